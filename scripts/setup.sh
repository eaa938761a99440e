#!/bin/sh
# Quick start, step 1: dependencies, build, install as a KLayout package, and the main job on
# the bundled sample. The package goes to $KLAYOUT_HOME/salt/linf_opc (default ~/.klayout).
set -e
cd "$(dirname "$0")/.."
./scripts/deps.sh
./scripts/build.sh
home="${KLAYOUT_HOME:-$HOME/.klayout}"
cmake --install build --prefix "$home/salt/linf_opc" > /dev/null
echo "installed the KLayout package in $home/salt/linf_opc (menu: Tools > L-inf Voronoi OPC)"
out="${1:-out/sample}"
# The main job: the whole flow (diagram, gauges, pattern selection against the sample's
# markers on 100/0, calibration/verification split) on the sample's metal layer.
python3 macros/linf_opc.py -rd cmd=flow -rd input=samples/metal.oas -rd layer=1/0 -rd markers=100/0 -rd out="$out"
echo "open the results with: klayout $out/windows.oas -m $out/flow.lyrdb   (report: $out/report.html;"
echo "  clip libraries: $out/calibration.oas, $out/verification.oas)"
