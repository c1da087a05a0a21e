#!/usr/bin/env bash
# Runs one libFuzzer target for SECONDS: scripts/fuzz.sh TARGET SECONDS
#   TARGET: diagram_loader | time_function | lua | table | results_table | set_file | scene
#   (tests/fuzz/fuzz_TARGET.cc)
# Builds the project with clang, AddressSanitizer, UndefinedBehaviorSanitizer
# and libFuzzer in build-fuzz/ (installing clang's runtime from Debian if it
# is missing), keeps the growing corpus in build-fuzz/corpus/TARGET and writes
# any crashing input to build-fuzz/findings/TARGET/. A finding, once fixed,
# goes into tests/fuzz/regressions/TARGET/, which CTest replays.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -ne 2 ]; then
  echo "usage: scripts/fuzz.sh diagram_loader|time_function|lua|table|results_table|set_file|scene SECONDS" >&2
  exit 2
fi
target=$1
seconds=$2
if [ ! -f "tests/fuzz/fuzz_${target}.cc" ]; then
  echo "scripts/fuzz.sh: no fuzz target '${target}' (have: diagram_loader, time_function, lua, table, results_table, set_file, scene)" >&2
  exit 2
fi
MECHFLOW_EXTRA_PACKAGES="clang libclang-rt-14-dev" bash scripts/install-deps.sh
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMECHFLOW_FUZZ=ON \
    -DMECHFLOW_BUILD_BENCH=OFF >/dev/null
fi
cmake --build build-fuzz -j "$(nproc)" --target "fuzz_${target}"
case "$target" in
  diagram_loader | scene) seeds=diagrams/examples ;;
  *) seeds=tests/fuzz/seeds/${target} ;;
esac
corpus=build-fuzz/corpus/${target}
findings=build-fuzz/findings/${target}
mkdir -p "$corpus" "$findings"
# in the examples folder, so that the seed diagrams find the files they name
cd diagrams/examples
dict=
[ -f "../../tests/fuzz/${target}.dict" ] && dict="../../tests/fuzz/${target}.dict"
exec ../../build-fuzz/fuzz_"${target}" "../../${corpus}" "../../${seeds}" "../../tests/fuzz/regressions/${target}" \
  ${dict:+-dict="$dict"} -max_total_time="${seconds}" -timeout=10 -rss_limit_mb=2048 \
  -max_len=16384 -artifact_prefix="../../${findings}/" -print_final_stats=1
