#!/bin/sh
# Runs tests/godot in godot3-server against the freshly built adapter (make test-godot).
# Copies the project to $BUILD/godot/project with bin/ holding the two libraries, runs test.gd
# under timeout, and passes only on exit code 0 together with the line "RESULT: PASS".
set -u
cd "$(dirname "$0")/../.." || exit 1
BUILD=${BUILD:-build}
GODOT=${GODOT:-godot3-server}
TIMEOUT=${GODOT_TIMEOUT:-60}
root=$(cd "$BUILD" && pwd)/godot || exit 1
project=$root/project

fail() { echo "test-godot: FAIL: $*"; exit 1; }

command -v "$GODOT" >/dev/null || fail "$GODOT not found; run 'make deps' (Debian package godot3-server)"
for f in "$BUILD/libphyspix_godot.so" "$BUILD/libphyspix.so.0"; do
    [ -e "$f" ] || fail "$f is missing; run 'make all $BUILD/libphyspix_godot.so'"
done

rm -rf "$root"
mkdir -p "$project/bin" "$root/home" "$root/xdg/config" "$root/xdg/data" "$root/xdg/cache" || exit 1
cp tests/godot/project.godot plugin/godot/physpix.gdnlib plugin/godot/physpix_world.gdns tests/godot/test.gd \
    "$project/" || exit 1
# -L: the soname is a symlink in build/; the project needs the file itself.
cp -L "$BUILD/libphyspix_godot.so" "$BUILD/libphyspix.so.0" "$project/bin/" || exit 1

# Godot takes its locale from LANG alone (no C library locale needed); under C or C.UTF-8 it prints
# "Unsupported locale" errors, so the value is fixed rather than taken from `locale -a`.

log=$root/output.txt
start=$(date +%s.%N)
env LANG=en_US.UTF-8 HOME="$root/home" XDG_CONFIG_HOME="$root/xdg/config" \
    XDG_DATA_HOME="$root/xdg/data" XDG_CACHE_HOME="$root/xdg/cache" \
    timeout "$TIMEOUT" "$GODOT" --path "$project" -s test.gd >"$log" 2>&1
rc=$?
end=$(date +%s.%N)
cat "$log"
echo "test-godot: $GODOT exited $rc after $(awk "BEGIN { printf \"%.2f\", $end - $start }") s"

[ $rc -eq 124 ] && fail "timed out after $TIMEOUT s (the engine hung: a script that errors before any quit() does this)"
[ $rc -gt 128 ] && fail "$GODOT was killed by signal $((rc - 128)) (a crash in the adapter or in PhysPix?)"
[ $rc -eq 0 ] || fail "exit code $rc (1 is the script's guard: it stopped before quit(0); see the errors above)"
grep -qx 'RESULT: PASS' "$log" ||
    fail "exit code 0 but no 'RESULT: PASS' line (a GDScript parse error exits 0 silently)"
echo "test-godot: PASS"
