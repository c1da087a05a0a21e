#!/usr/bin/env bash
# Installs the Debian 12 packages mechflow needs to build, test and plot.
# Does nothing when they are all present; needs root (or passwordless sudo)
# otherwise, and says so clearly.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libsundials-dev libsuitesparse-dev libtinyxml2-dev liblua5.4-dev libgtest-dev
  gnuplot-nox libfftw3-dev
  libopenmpi-dev openmpi-bin
)
# more for one script (scripts/fuzz.sh: clang and its libFuzzer runtime)
read -r -a extra <<< "${MECHFLOW_EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "mechflow: installing Debian packages: ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  as_root=(sudo -n)
else
  echo "mechflow: these packages are missing and installing them needs root:" >&2
  echo "  sudo apt-get install -y --no-install-recommends ${missing[*]}" >&2
  echo "Run that (or this script as root), then try again." >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
