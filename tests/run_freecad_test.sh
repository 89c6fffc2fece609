#!/usr/bin/env bash
# Runs one unittest module inside FreeCAD against the add-on staged in the build tree.
#   usage: run_freecad_test.sh cmd|gui MODDIR TESTMODULE
#   cmd: freecadcmd -t TESTMODULE; gui: freecad -t TESTMODULE under Xvfb.
# The user's FreeCAD configuration is never touched: FreeCAD runs with a throw-away HOME whose
# add-on folder ($HOME/.local/share/FreeCAD/Mod, where 0.20 looks for user add-ons) links to
# MODDIR/MultiAxisSlicer. FreeCAD then loads it exactly as an installed add-on (package.xml,
# Init.py, InitGui.py). (`freecadcmd -M DIR -t X` segfaults on 0.20.2, and -M skips package.xml.)
# Fails on a non-zero exit code, on any "Traceback" or "FAILED" in the output (FreeCAD swallows
# exceptions raised in GUI commands and still exits 0), and unless the output shows tests ran and
# passed ("Ran N tests" with N > 0, then "OK").
set -u
if [ $# -ne 3 ] || { [ "$1" != cmd ] && [ "$1" != gui ]; }; then
  echo "usage: $0 cmd|gui MODDIR TESTMODULE" >&2
  exit 2
fi
mode=$1
addon=$(cd "$2/MultiAxisSlicer" 2>/dev/null && pwd) || { echo "no add-on in $2/MultiAxisSlicer" >&2; exit 2; }
module=$3
[ -f "$addon/Init.py" ] && [ -f "$addon/package.xml" ] || { echo "$addon is not a staged add-on" >&2; exit 2; }

home=$(mktemp -d "${TMPDIR:-/tmp}/mas-freecad-home.XXXXXX")
trap 'rm -rf "$home"' EXIT
mkdir -p "$home/.local/share/FreeCAD/Mod" "$home/.config" "$home/.cache" "$home/tmp"
ln -s "$addon" "$home/.local/share/FreeCAD/Mod/MultiAxisSlicer"
# Temporary files go with the HOME too: FreeCAD's Start page leaves a FreeCADStartThumbnails*
# folder in the temporary directory on every GUI start.
export HOME="$home" XDG_DATA_HOME="$home/.local/share" XDG_CONFIG_HOME="$home/.config" \
  XDG_CACHE_HOME="$home/.cache" TMPDIR="$home/tmp"
unset FREECAD_USER_HOME FREECAD_USER_DATA FREECAD_USER_TEMP
log="$home/output.log"

case $mode in
  cmd)
    timeout 560 freecadcmd -t "$module" >"$log" 2>&1
    status=$? ;;
  gui)
    QTWEBENGINE_DISABLE_SANDBOX=1 timeout 560 \
      xvfb-run -a -s "-screen 0 1280x1024x24" freecad -t "$module" >"$log" 2>&1
    status=$? ;;
esac
cat "$log"

fail() { echo "run_freecad_test: $module ($mode): $*" >&2; exit 1; }
[ "$status" -eq 0 ] || fail "FreeCAD exited with status $status"
! grep -q "Traceback" "$log" || fail "a Python traceback in the output"
! grep -q "FAILED" "$log" || fail "FAILED in the output"
ran=$(sed -n 's/^Ran \([0-9][0-9]*\) tests\{0,1\} in .*/\1/p' "$log" | tail -n 1)
[ -n "$ran" ] && [ "$ran" -gt 0 ] || fail "no tests ran"
grep -Eq '^OK( \(.*\))?$' "$log" || fail "no OK from unittest"
echo "run_freecad_test: $module ($mode): $ran tests passed"
