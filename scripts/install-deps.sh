#!/usr/bin/env bash
# Installs the Debian 12 packages mechflow needs, then three.js from the npm
# registry (graphics/web, pinned by its package-lock.json: version and sha512).
#   scripts/install-deps.sh main   what `mechflow` needs to build, run and plot
#                                  (scripts/run-example.sh: the first run stays short)
#   scripts/install-deps.sh [all]  that and what the tests and benchmarks need too
#                                  (GoogleTest, lld, OpenMPI, Simbody, Chromium, graphviz,
#                                  the glTF validator, pybind11 and Python's numpy, pandas,
#                                  scipy, matplotlib for the Python module)
# Does nothing when all is present; the packages need root (or passwordless
# sudo), and it says so clearly when it has neither.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-all}
case "$mode" in
  main | all) ;;
  *)
    echo "usage: scripts/install-deps.sh [main|all]" >&2
    exit 2
    ;;
esac

# the `mechflow` target: compiler, CMake, the libraries it links, gnuplot for its plots
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libsundials-dev libsuitesparse-dev libtinyxml2-dev liblua5.4-dev
  libudunits2-dev libudunits2-data
  gnuplot-nox libfftw3-dev
  libceres-dev libnlopt-dev libnlopt-cxx-dev   # `mechflow fit`: its optimisers
  libzip-dev                    # `mechflow export-fmu`: the .fmu archive
  curl ca-certificates          # three.js's archive from the npm registry
)
if [ "$mode" = all ]; then
  packages+=(
    lld                           # links the test programs ten times faster than GNU ld
    libgtest-dev                  # the test suite
    libopenmpi-dev openmpi-bin    # `mechflow sweep` over MPI ranks (its tests)
    libsimbody-dev                # a contender of the pendulum-chain benchmark
    chromium                      # the browser tests of the animation viewer
    graphviz                      # `dot`, which draws `mechflow graph` (README tour)
    pybind11-dev python3-dev      # the Python module (python/) and its tests
    python3-numpy python3-pandas python3-scipy python3-matplotlib
    python3-venv python3-setuptools python3-wheel   # its `pip install .` test
  )
fi
# Node.js and npm install the viewer's development dependencies (the glTF
# validator); a machine may have them from elsewhere. The main job does without:
# they are some 360 Debian packages, most of a fresh machine's install time.
if [ "$mode" = all ] && ! command -v npm >/dev/null 2>&1; then packages+=(nodejs npm); fi
# more for one script (scripts/fuzz.sh: clang and its libFuzzer runtime)
read -r -a extra <<< "${MECHFLOW_EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

# three.js for the animation viewer, embedded into the binary at build time.
# `main` fetches its archive from the npm registry with curl and checks it against
# the sha512 that package-lock.json pins (what `npm ci` checks); `all` runs npm ci,
# which also installs the glTF validator the tests run.
fetch_three() {
  local lock=graphics/web/package-lock.json version integrity registry url tgz want got
  version=$(sed -n '/"node_modules\/three"/,/}/s/.*"version": "\([^"]*\)".*/\1/p' "$lock")
  integrity=$(sed -n '/"node_modules\/three"/,/}/s/.*"integrity": "sha512-\([^"]*\)".*/\1/p' "$lock")
  if [ -z "$version" ] || [ -z "$integrity" ]; then
    echo "mechflow: $lock names no three.js version with a sha512 integrity" >&2
    exit 1
  fi
  registry=${npm_config_registry:-https://registry.npmjs.org}
  url="${registry%/}/three/-/three-${version}.tgz"
  tgz=$(mktemp)
  echo "mechflow: fetching three.js ${version} ($url)"
  curl -fsSL --retry 3 -o "$tgz" "$url"
  want=$(printf '%s' "$integrity" | base64 -d | od -An -tx1 | tr -d ' \n')
  got=$(sha512sum "$tgz" | cut -d' ' -f1)
  if [ "$want" != "$got" ]; then
    rm -f "$tgz"
    echo "mechflow: $url does not match the sha512 in $lock; not installed" >&2
    exit 1
  fi
  rm -rf graphics/web/node_modules/three
  mkdir -p graphics/web/node_modules/three
  tar xzf "$tgz" -C graphics/web/node_modules/three --strip-components=1
  rm -f "$tgz"
}
install_three() {
  if [ "$mode" = main ]; then
    [ -f graphics/web/node_modules/three/build/three.min.js ] && return 0
    fetch_three
  else
    [ -f graphics/web/node_modules/three/build/three.min.js ] &&
      [ -d graphics/web/node_modules/gltf-validator ] && return 0
    echo "mechflow: installing three.js and the glTF validator (npm ci in graphics/web)"
    (cd graphics/web && npm ci --no-audit --no-fund --loglevel=error)
  fi
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
# --force-unsafe-io: dpkg skips its fsync after every file. The main set alone is
# some 300 packages (SUNDIALS' MPI/PETSc dependencies among them), 670 with Node.js;
# without the syncs dpkg took 13 min instead of 15 for the 670 on a loaded 2-core machine. An install
# cut short is simply run again.
"${as_root[@]}" apt-get install -y -qq --no-install-recommends -o Dpkg::Options::=--force-unsafe-io "${missing[@]}"
install_three
