#!/bin/sh
# Installs the Debian packages the project needs, only those missing (needs root or sudo).
set -e
PKGS="klayout libcgal-dev libgmp-dev libmpfr-dev libboost-dev zlib1g-dev pybind11-dev python3-dev cmake g++ make
      libgtest-dev xvfb xauth python3 clang libclang-rt-14-dev libfftw3-dev libeigen3-dev python3-distributed"
missing=""
for p in $PKGS; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "installing:$missing"
SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing
