#!/usr/bin/env python3
"""Instructions per step, per awake body and per contact point, stage by stage (issue 40).

Runs build/bench/bench_instr under callgrind once per scene, reads the callgrind.out file itself and charges
every instruction of the measured steps to a stage: a function's own instructions to the stage of its source
file in lib/ (STAGES below) or to ODE (libode), and a call into libc, libm or ld.so at its inclusive cost to the
caller's stage, so qsort from carry.c is carry's and sqrt from ODE is ODE's. So is a call into lib/'s shared
helpers: raster.c (the narrowphase reads masks through it, an erase writes them) and the headers' out-of-line
functions. Instruction counts do not depend on a noisy machine. Standard library only.

    report.py [--binary build/bench/bench_instr] [--scene NAME]... [--csv PATH] [--keep DIR]
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import tempfile
from collections import defaultdict

SCENES = ["pyramid20", "rain500", "destruction", "sleep1000"]

# lib/ source files by stage; a file not named here is a stage of its own, called by its name.
STAGES = {
    "broadphase.c": "broadphase",
    "narrowphase.c": "narrowphase", "narrow_cpu.c": "narrowphase", "narrow_tiled.c": "narrowphase",
    "workers.c": "narrowphase", "corner.c": "narrowphase",
    "carry.c": "carry/held pairs",
    "contact_table.c": "contact table/events",
    "pair_map.c": "pair maps",
    "crowd.c": "crowd budget",
    "island.c": "islands+sleep",
    "contact_solve.c": "contact building",
    "solver_ode.c": "solver glue",
    "step.c": "step loop+pose sync",
    "awake.c": "awake set",
    "continuous.c": "continuous",
    "step_undo.c": "step_undo",
    "forces.c": "forces",
}
ODE = "ODE"
SYSTEM = "(system)"  # libc, libm, ld.so: charged to whoever called them
HELPER = "(helper)"  # lib/'s shared helpers: raster.c and the headers' out-of-line functions, charged likewise
HELPER_FILES = {"raster.c"}  # the narrowphase reads masks through it, an erase writes them
BENCH = "(benchmark program)"  # bench_instr's own code: not a stage
NOT_BOOKKEEPING = {ODE, "narrowphase"}
LIB_FILE = re.compile(r"(?:^|/)lib/(core|collide|dynamics|edit|query|io)/([^/]+)$")


def stage_of(obj, path, binary_name):
    """The stage a function's own instructions belong to, from its object file and source file."""
    if "libode" in os.path.basename(obj):
        return ODE
    if os.path.basename(obj) != binary_name:
        return SYSTEM
    m = LIB_FILE.search(path)
    if not m:
        return BENCH
    folder, name = m.groups()
    if name.endswith(".h") or name in HELPER_FILES:
        return HELPER
    if folder == "edit":
        return "edits"
    if name.startswith("joint"):
        return "joints"
    return STAGES.get(name, name.rsplit(".", 1)[0] if name.endswith(".c") else name)


class Profile:
    """A callgrind.out file: each function's own Ir, each call edge's inclusive Ir, and the file's total."""

    SPEC = re.compile(r"^(ob|fl|fi|fe|fn|cob|cfi|cfl|cfn|calls)=(.*)$")
    NAME = re.compile(r"^\((\d+)\)(?: (.*))?$")

    def __init__(self, path):
        self.self_ir = defaultdict(int)  # (object, file, function) -> Ir
        self.calls = defaultdict(int)    # (caller key, callee key) -> inclusive Ir
        self.total = None
        # Name compression: "(id) name" defines an id, "(id)" refers to it; ob/cob share one table,
        # fl/fi/fe/cfi/cfl another, fn/cfn a third.
        tables = {"ob": {}, "fl": {}, "fn": {}}
        table_of = {"ob": "ob", "cob": "ob", "fl": "fl", "fi": "fl", "fe": "fl", "cfi": "fl", "cfl": "fl",
                    "fn": "fn", "cfn": "fn"}
        ir_col = npos = None
        obj = cur_file = fn_file = None
        fn_key = None
        callee = {}
        in_call = False
        with open(path, encoding="utf-8", errors="replace") as f:
            for line in f:
                line = line.rstrip("\n")
                if not line or line[0] == "#":
                    continue
                if line[0].isdigit() or line[0] in "+-*":
                    fields = line.split()
                    ir = int(fields[npos + ir_col]) if len(fields) > npos + ir_col else 0
                    if in_call:  # the line after calls=: that call's inclusive cost
                        key = (callee.get("cob", obj), callee.get("cfl", cur_file), callee["cfn"])
                        self.calls[(fn_key, key)] += ir
                        in_call, callee = False, {}
                    else:
                        self.self_ir[fn_key] += ir
                    continue
                m = self.SPEC.match(line)
                if m:
                    kind, value = m.groups()
                    if kind == "calls":
                        in_call = True
                        continue
                    n = self.NAME.match(value)
                    table = tables[table_of[kind]]
                    if n and n.group(2) is not None:
                        table[n.group(1)] = n.group(2)
                    name = table[n.group(1)] if n else value
                    if kind == "ob":
                        obj = name
                    elif kind in ("fl", "fi", "fe"):
                        cur_file = name
                        if kind == "fl":
                            fn_file = name
                    elif kind == "fn":
                        fn_key = (obj, fn_file, name)
                    else:  # cob, cfl (cfi is its older spelling), cfn: valid for the next calls= only
                        callee["cfl" if kind == "cfi" else kind] = name
                    continue
                if line.startswith("positions:"):
                    npos = len(line.split()[1:])
                elif line.startswith("events:"):
                    ir_col = line.split()[1:].index("Ir")
                elif line.startswith("totals:") or (line.startswith("summary:") and self.total is None):
                    self.total = int(line.split()[1 + ir_col])


def charge(profile, binary_name):
    """Ir by stage. Own instructions go to their function's stage. A call from outside the system libraries and
    the helpers into them is charged, inclusive, to the caller; a call back out of them (qsort's comparator) is
    taken off its callee's stage, which already has it as own instructions, so each instruction is counted
    once."""
    stage = {}

    def of(key):
        if key not in stage:
            stage[key] = stage_of(key[0], key[1] or "", binary_name)
        return stage[key]

    def shared(key):
        return of(key) in (SYSTEM, HELPER)

    ir = defaultdict(int)
    for key, n in profile.self_ir.items():
        if not shared(key):
            ir[of(key)] += n
    for (caller, callee), n in profile.calls.items():
        if not shared(caller) and shared(callee):
            ir[of(caller)] += n
        elif shared(caller) and not shared(callee):
            ir[of(callee)] -= n
    return ir


def run_scene(binary, scene, out_dir):
    out = os.path.join(out_dir, f"{scene}.callgrind.out")
    # LD_BIND_NOW: no lazy symbol binding inside the measured steps, whose resolver would charge a first call's
    # callee to its caller.
    cmd = ["valgrind", "--tool=callgrind", "--instr-atstart=no", "--collect-atstart=no",
           f"--callgrind-out-file={out}", binary, "--scene", scene]
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, LD_BIND_NOW="1"))
    except FileNotFoundError:
        sys.exit("report.py: no valgrind on PATH (make deps installs it)")
    line = next((l for l in r.stdout.splitlines() if l.startswith("instr ")), None)
    if r.returncode != 0 or line is None:
        sys.exit(f"report.py: {' '.join(cmd)} failed ({r.returncode}):\n{r.stdout}{r.stderr}")
    counts = dict(field.split("=", 1) for field in line.split()[1:])
    return out, int(counts["steps"]), int(counts["awake_sum"]), int(counts["contacts_sum"])


def human(x):
    if x != x:  # NaN: nothing to divide by
        return "-"
    return f"{x / 1e6:.2f} M" if abs(x) >= 1e6 else f"{x / 1e3:.1f} k" if abs(x) >= 1e3 else f"{x:.0f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--binary", default="build/bench/bench_instr")
    ap.add_argument("--scene", action="append", choices=SCENES, help="a scene (default: all)")
    ap.add_argument("--csv", help="also write the tables as CSV")
    ap.add_argument("--keep", help="keep the callgrind.out files in this folder (for callgrind_annotate)")
    args = ap.parse_args()

    print("bench_instr under callgrind: instructions (Ir) of the measured steps only, PhysPix BALANCED, CPU\n"
          "backend, one thread. /step: per measured step; /awake body: over the sum of pp_step_stats.awake_bodies\n"
          "over those steps; /contact: over the sum of contact points (last substep's) over them. Calls into libc,\n"
          "libm, ld.so, raster.c and lib/'s headers count toward their caller's stage.\n")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        out_dir = args.keep or tmp
        os.makedirs(out_dir, exist_ok=True)
        for scene in args.scene or SCENES:
            out, steps, awake, contacts = run_scene(args.binary, scene, out_dir)
            profile = Profile(out)
            ir = charge(profile, os.path.basename(args.binary))
            bench = ir.pop(BENCH, 0)
            staged = sum(ir.values())
            # Each instruction is charged once: the stages and the program's own code add up to callgrind's total
            # for the measured steps (within rounding of recursive calls through libc, which these scenes lack).
            off = abs(staged + bench - profile.total) / max(profile.total, 1)
            if off > 0.001:
                sys.exit(f"report.py: {scene}: stages sum to {staged + bench} Ir, callgrind says {profile.total}")
            print(f"{scene}: {steps} steps, {awake / steps:.1f} awake bodies and {contacts / steps:.1f} contact points"
                  f" a step; callgrind total {profile.total:,} Ir, stages {staged:,} (program {bench:,}, "
                  f"unmatched {off * 100:.4f} %)")
            print(f"  {'stage':<44} {'/step':>10} {'/awake body':>12} {'/contact':>10} {'share':>7}")
            bookkeeping = sum(n for s, n in ir.items() if s not in NOT_BOOKKEEPING)
            lines = sorted(ir.items(), key=lambda kv: -kv[1])
            lines += [("total", staged), ("bookkeeping outside ODE and the narrowphase", bookkeeping)]
            for i, (stage, n) in enumerate(lines):
                per = [n / steps, n / awake if awake else float("nan"), n / contacts if contacts else float("nan")]
                share = 100.0 * n / staged if staged else float("nan")
                if i == len(lines) - 2:
                    print("  " + "-" * 86)
                print(f"  {stage:<44} {human(per[0]):>10} {human(per[1]):>12} {human(per[2]):>10} {share:6.1f}%")
                rows.append([scene, stage, n, steps, awake, contacts, *(f"{x:.1f}" for x in per), f"{share:.2f}"])
            print()
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["scene", "stage", "ir", "steps", "awake_sum", "contacts_sum", "ir_per_step",
                        "ir_per_awake_body", "ir_per_contact", "share_pct"])
            w.writerows(rows)
        print(f"wrote {args.csv}")


if __name__ == "__main__":
    main()
