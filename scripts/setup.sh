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
klayout -b -r macros/linf_opc.py -rd cmd=voronoi -rd input=samples/metal.oas -rd layer=1/0 -rd out="$out"
klayout -b -r macros/linf_opc.py -rd cmd=gauges -rd input=samples/metal.oas -rd layer=1/0 -rd out="$out"
echo "open the results with: klayout $out/voronoi.oas   or, with the gauges in the marker browser:"
echo "  klayout $out/gauges.oas -m $out/gauges.lyrdb"
