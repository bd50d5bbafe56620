#!/usr/bin/env bash
# Install the Debian 12 packages the suite needs, if any is missing (apt-get; root or sudo).
set -euo pipefail
PKGS=(build-essential cmake pkg-config libgsl-dev libhdf5-dev libnlopt-dev check
      libjansson-dev libconfig-dev gnuplot-nox libopenmpi-dev openmpi-bin)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
