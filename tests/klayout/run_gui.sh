#!/bin/sh
# ctest entry for the GUI test: installs the package into a fresh temporary KLAYOUT_HOME whose
# klayoutrc hides the first-start tips (they are modal and would block), runs KLayout under
# Xvfb and keeps the screenshot.
#   run_gui.sh BUILD_DIR INPUT LAYER SCREENSHOT [-e]     (-e: editor mode, else viewer mode)
set -e
build="$1"; input="$2"; layer="$3"; shot="$4"; mode="${5:-}"
here="$(cd "$(dirname "$0")" && pwd)"
home="$(mktemp -d)"
trap 'rm -rf "$home"' EXIT
cmake --install "$build" --prefix "$home/salt/linf_opc" > /dev/null
cat > "$home/klayoutrc" <<'RC'
<?xml version="1.0" encoding="utf-8"?>
<config>
 <full-hierarchy-new-cell>true</full-hierarchy-new-cell>
 <tip-window-hidden>only-top-level-shown-by-default=-1,editor-mode=4</tip-window-hidden>
</config>
RC
mkdir -p "$(dirname "$shot")"
status=0
# KLayout ignores SIGTERM while a modal dialog is up: KILL after the deadline.
KLAYOUT_HOME="$home" timeout -s KILL 120 xvfb-run -a -s "-screen 0 1600x1000x24" \
  klayout -x $mode -rr "$here/gui_menu.py" -rd input="$input" -rd layer="$layer" -rd shot="$shot" \
  -rd log="$home/gui.log" || status=$?
cat "$home/gui.log" 2>/dev/null || echo "no log: KLayout did not run the test script"
[ "$status" -eq 137 ] && echo "KLayout was killed after 120 s (a modal dialog?)"
exit $status
