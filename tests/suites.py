"""Runs test suites, each a make target, and ends with a summary a person reads: per suite its result, what it
counted (tests passed, inputs replayed, scripts run) and its time. `make test` and `make check` call it.

    python3 -B tests/suites.py --title "make test" --logs build/tests/logs --make make build=all c=test-c ...

Each suite's output is shown as it runs and kept in LOGS/NAME.log. A failed suite does not stop the others (the
summary shows every failure at once), except the first, which builds what the rest need. Exit status 1 when any
suite failed. Standard library only: it runs before the project's virtual environment is needed.
"""
import argparse
import re
import subprocess
import sys
import time
from pathlib import Path

# What each runner prints about its own count; every match of a pattern adds to the suite's figure.
COUNTERS = [
    # Criterion: "Synthesis: Tested: 295 | Passing: 295 | Failing: 0 | Crashing: 0"
    (re.compile(r"Synthesis: Tested: (\d+) \| Passing: (\d+) \| Failing: (\d+) \| Crashing: (\d+)"),
     lambda m: {"tests": int(m[1]), "passed": int(m[2]), "failed": int(m[3]) + int(m[4])}),
    # pytest: "193 passed, 2 skipped in 0.65s" (with -q) or "=== 3 failed, 190 passed in 1.2s ==="
    (re.compile(r"^=*\s*((?:\d+ (?:passed|failed|skipped|errors?|xfailed|xpassed)(?:, )?)+) in [\d.]+s"),
     lambda m: _pytest_counts(m[1])),
    # unittest: "Ran 12 tests in 3.1s"
    (re.compile(r"^Ran (\d+) tests? in "), lambda m: {"tests": int(m[1])}),
    # make test-fuzz: "fuzz_png: replayed 40 inputs"
    (re.compile(r"^fuzz_\w+: replayed (\d+) inputs"), lambda m: {"inputs": int(m[1])}),
    # Godot test scripts and the demo: their own PASS lines
    (re.compile(r"^RESULT: PASS$"), lambda m: {"scripts": 1}),
    # the public headers' compile check: two headers, C11 and C++17
    (re.compile(r"^public headers compile as C11 and C\+\+17"), lambda m: {"headers": 2}),
    # ThreadSanitizer's and valgrind's programs
    (re.compile(r"^tsan_worlds: \d+ threads"), lambda m: {"programs": 1}),
    (re.compile(r"ERROR SUMMARY: 0 errors"), lambda m: {"programs": 1}),
]


def _pytest_counts(text):
    counts = {"tests": 0}
    for number, word in re.findall(r"(\d+) (\w+)", text):
        key = {"error": "failed", "errors": "failed", "xfailed": "skipped", "xpassed": "passed"}.get(word, word)
        counts[key] = counts.get(key, 0) + int(number)
        counts["tests"] += int(number)
    return counts


def count(lines):
    """The figures a suite's output reports, summed over every runner it ran."""
    total = {}
    for line in lines:
        for pattern, read in COUNTERS:
            m = pattern.search(line)
            if m:
                for key, value in read(m).items():
                    total[key] = total.get(key, 0) + value
    return total


def describe(figures):
    """'295 passed, 2 skipped' for tests; '160 inputs' or '3 scripts' for the others; '' when nothing counted."""
    if "tests" in figures:
        words = [f"{figures.get('passed', figures['tests'])} passed"]
        words += [f"{figures[k]} {k}" for k in ("failed", "skipped") if figures.get(k)]
        return ", ".join(words)
    return ", ".join(f"{v} {k}" for k, v in figures.items())


def run_suite(make, name, target, logs):
    """Runs `make TARGET`, echoing and logging its output; returns (ok, seconds, figures)."""
    log_path = logs / f"{name}.log"
    print(f"\n=== {name}: {make} {target}", flush=True)
    start = time.monotonic()
    lines = []
    with open(log_path, "w", encoding="utf-8", errors="replace") as log:
        proc = subprocess.Popen([make, "--no-print-directory", target], stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True, errors="replace", bufsize=1)
        for line in proc.stdout:
            sys.stdout.write(line)
            log.write(line)
            lines.append(line.rstrip("\n"))
        rc = proc.wait()
    return rc == 0, time.monotonic() - start, count(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--title", default="tests")
    parser.add_argument("--logs", type=Path, required=True)
    parser.add_argument("--make", default="make")
    parser.add_argument("suites", nargs="+", metavar="NAME=TARGET")
    args = parser.parse_args()
    args.logs.mkdir(parents=True, exist_ok=True)
    suites = [s.split("=", 1) for s in args.suites]
    started = time.monotonic()
    rows = []
    for i, (name, target) in enumerate(suites):
        ok, seconds, figures = run_suite(args.make, name, target, args.logs)
        rows.append((name, target, ok, seconds, figures))
        if not ok and i == 0:
            break  # nothing else can run without the build
    total = time.monotonic() - started
    failed = [r for r in rows if not r[2]]
    skipped = [name for name, _ in suites[len(rows):]]

    print(f"\n{args.title}: summary (logs in {args.logs}/)")
    print(f"  {'suite':<10} {'target':<15} {'result':<7} {'counted':<32} {'time':>8}")
    for name, target, ok, seconds, figures in rows:
        print(f"  {name:<10} {target:<15} {'ok' if ok else 'FAILED':<7} {describe(figures):<32} {seconds:7.1f}s")
    for name in skipped:
        print(f"  {name:<10} {'':<15} {'not run':<7}")
    tests = sum(r[4].get("tests", 0) for r in rows)
    print(f"  {'total':<10} {'':<15} {'FAILED' if failed or skipped else 'ok':<7} {f'{tests} tests':<32} {total:7.1f}s")
    for name, target, *_ in failed:
        print(f"{args.title}: {name} FAILED; its output: {args.logs / (name + '.log')}")
    return 1 if failed or skipped else 0


if __name__ == "__main__":
    sys.exit(main())
