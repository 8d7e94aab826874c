#!/usr/bin/env bash
# Installs what dynosize needs on Debian 12 (as root, or with sudo when available).
# Package names and versions: ../shared/docs/ecosystem-notes.md. The python3-* packages are the
# Python module's (docs/python.md): pybind11 and numpy to build it, pytest to test it, distributed
# (dask) for trade studies on a cluster. libcpp-httplib-dev and libjs-chart.js are `dynosize serve`'s
# (docs/web.md); chromium, chromium-driver and python3-selenium its browser test.
set -euo pipefail
packages=(cmake g++ make pkg-config libeigen3-dev libnlopt-cxx-dev coinor-libipopt-dev
          nlohmann-json3-dev libcli11-dev googletest libgtest-dev libbenchmark-dev gnuplot-nox jq
          clang libclang-rt-14-dev
          python3 python3-dev python3-pybind11 pybind11-dev python3-numpy python3-pytest python3-distributed
          libcpp-httplib-dev libjs-chart.js chromium chromium-driver python3-selenium)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null && SUDO=sudo
  echo "installing: ${missing[*]}" >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
