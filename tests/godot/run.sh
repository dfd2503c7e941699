#!/bin/sh
# Runs the Godot tests in godot3-server against the freshly built addon (make test-godot): test.gd (the
# native PhysPixWorld), test_nodes.gd (the PhysPixWorld2D and PhysPixBody2D nodes) and test_joint.gd (the
# PhysPixJoint2D node), test_character.gd (the PhysPixCharacter2D node), test_editor.gd (the world's overlay in the editor) in tests/godot, and test_example.gd and test_example_hero.gd (its hero played by scripted input) in a copy of the example `make godot-example` made.
# Each project is copied under $BUILD/godot with addons/physpix from $BUILD/addons/physpix; each script runs under timeout and passes only on exit code 0,
# the line "RESULT: PASS" and no "SCRIPT ERROR" (a runtime error in a frame does not stop the engine).
set -u
cd "$(dirname "$0")/../.." || exit 1
BUILD=${BUILD:-build}
GODOT=${GODOT:-godot3-server}
TIMEOUT=${GODOT_TIMEOUT:-60}
root=$(cd "$BUILD" && pwd)/godot || exit 1

fail() { echo "test-godot: FAIL: $*"; exit 1; }

command -v "$GODOT" >/dev/null || fail "$GODOT not found; run 'make deps' (Debian package godot3-server)"
[ -e "$BUILD/addons/physpix/libphyspix_godot.so" ] || fail "$BUILD/addons/physpix is missing; run 'make all'"

rm -rf "$root"
mkdir -p "$root/home" "$root/xdg/config" "$root/xdg/data" "$root/xdg/cache" || exit 1

# $1 the project folder to copy, $2 its name under $root; then any files to add beside its project.godot.
make_project() {
    src=$1 project=$root/$2
    shift 2
    mkdir -p "$project/addons" || exit 1
    cp -R "$src/." "$project/" && cp -R "$BUILD/addons/physpix" "$project/addons/" || exit 1
    [ $# -eq 0 ] || cp "$@" "$project/" || exit 1
}

# Godot takes its locale from LANG alone (no C library locale needed); under C or C.UTF-8 it prints
# "Unsupported locale" errors, so the value is fixed rather than taken from `locale -a`.
godot() {
    env LANG=en_US.UTF-8 HOME="$root/home" XDG_CONFIG_HOME="$root/xdg/config" \
        XDG_DATA_HOME="$root/xdg/data" XDG_CACHE_HOME="$root/xdg/cache" timeout "$TIMEOUT" "$GODOT" "$@"
}

# $1 project name, $2 script; $3 "strict" also fails on any engine ERROR line (the example prints none).
# --fixed-fps 60: every frame steps 1/60 s of game time, run as fast as the machine goes.
run_script() {
    log=$root/$2.txt
    start=$(date +%s.%N)
    godot --path "$root/$1" --fixed-fps 60 -s "$2" >"$log" 2>&1
    rc=$?
    end=$(date +%s.%N)
    cat "$log"
    echo "test-godot: $2: $GODOT exited $rc after $(awk "BEGIN { printf \"%.2f\", $end - $start }") s"
    [ $rc -eq 124 ] && fail "$2 timed out after $TIMEOUT s (the engine hung: a script that errors before any quit() does this)"
    [ $rc -gt 128 ] && fail "$2: $GODOT was killed by signal $((rc - 128)) (a crash in the adapter or in PhysPix?)"
    [ $rc -eq 0 ] || fail "$2: exit code $rc (1 is the script's guard: it stopped before quit(0); see the errors above)"
    grep -qx 'RESULT: PASS' "$log" ||
        fail "$2: exit code 0 but no 'RESULT: PASS' line (a GDScript parse error exits 0 silently)"
    ! grep -q 'SCRIPT ERROR' "$log" || fail "$2: a script error (above)"
    if [ "${3:-}" = strict ]; then
        ! grep -q 'ERROR' "$log" || fail "$2: the engine printed an error (above)"
    fi
}

make_project tests/godot tests
run_script tests test.gd
run_script tests test_nodes.gd
run_script tests test_joint.gd
run_script tests test_character.gd
run_script tests test_editor.gd

# The example as `make godot-example` left it, imported and ready to run: no import step here, so a target that
# forgot it fails ("No loader found for resource: res://terrain.png").
[ -e "$BUILD/godot-example/project.godot" ] || fail "$BUILD/godot-example is missing; run 'make godot-example'"
make_project "$BUILD/godot-example" example tests/godot/test_example.gd tests/godot/test_example_hero.gd \
    tests/godot/checks.gd
run_script example test_example.gd strict
run_script example test_example_hero.gd strict
echo "test-godot: PASS"
