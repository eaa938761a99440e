#!/bin/sh
# ctest entry for the GUI tests: installs the package into a fresh temporary KLAYOUT_HOME whose
# klayoutrc hides the first-start tips (they are modal and would block), runs KLayout under
# Xvfb and keeps the screenshots.
#   run_gui.sh BUILD_DIR INPUT LAYER SCREENSHOT [-e] [name=value ...]
# -e: editor mode, else viewer mode. name=value: passed to the script as -rd name=value, except
# script=FILE (the test script in tests/klayout, default gui_menu.py) and seconds=N (the time
# limit, default 120).
set -e
build="$1"; input="$2"; layer="$3"; shot="$4"
shift 4
mode=""
if [ "${1:-}" = "-e" ]; then mode="-e"; shift; fi
here="$(cd "$(dirname "$0")" && pwd)"
script="gui_menu.py"; seconds=120
home="$(mktemp -d)"
trap 'rm -rf "$home"' EXIT
extra="$home/extra.args"
: > "$extra"
for a in "$@"; do
  case "$a" in
    script=*) script="${a#script=}" ;;
    seconds=*) seconds="${a#seconds=}" ;;
    *) printf '%s\n' "$a" >> "$extra" ;;
  esac
done
cmake --install "$build" --prefix "$home/salt/linf_opc" > /dev/null
cat > "$home/klayoutrc" <<'RC'
<?xml version="1.0" encoding="utf-8"?>
<config>
 <full-hierarchy-new-cell>true</full-hierarchy-new-cell>
 <tip-window-hidden>only-top-level-shown-by-default=-1,editor-mode=4</tip-window-hidden>
</config>
RC
mkdir -p "$(dirname "$shot")"
set --
while IFS= read -r a; do set -- "$@" -rd "$a"; done < "$extra"
status=0
# KLayout ignores SIGTERM while a modal dialog is up: KILL after the deadline.
KLAYOUT_HOME="$home" timeout -s KILL "$seconds" xvfb-run -a -s "-screen 0 1600x1000x24" \
  klayout -x $mode -rr "$here/$script" -rd input="$input" -rd layer="$layer" -rd shot="$shot" \
  -rd log="$home/gui.log" "$@" || status=$?
cat "$home/gui.log" 2>/dev/null || echo "no log: KLayout did not run the test script"
[ "$status" -eq 137 ] && echo "KLayout was killed after $seconds s (a modal dialog?)"
exit $status
