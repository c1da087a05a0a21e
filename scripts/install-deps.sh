#!/usr/bin/env bash
# Installs the Debian 12 packages mechflow needs to build, test and plot,
# then three.js from the npm registry (graphics/web, pinned by its
# package-lock.json). Does nothing when all is present; the packages need
# root (or passwordless sudo), and it says so clearly when it has neither.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config lld
  libeigen3-dev libsundials-dev libsuitesparse-dev libtinyxml2-dev liblua5.4-dev libgtest-dev
  libudunits2-dev libudunits2-data
  gnuplot-nox libfftw3-dev
  libopenmpi-dev openmpi-bin
  libsimbody-dev
  chromium
)
# Node.js and npm fetch three.js; a machine may have them from elsewhere
command -v npm >/dev/null 2>&1 || packages+=(nodejs npm)
# more for one script (scripts/fuzz.sh: clang and its libFuzzer runtime)
read -r -a extra <<< "${MECHFLOW_EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

# three.js for the animation viewer, embedded into the binary at build time
install_three() {
  [ -f graphics/web/node_modules/three/build/three.min.js ] && return 0
  echo "mechflow: installing three.js (npm ci in graphics/web)"
  (cd graphics/web && npm ci --no-audit --no-fund --loglevel=error)
}

if [ ${#missing[@]} -eq 0 ]; then
  install_three
  exit 0
fi

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
install_three
