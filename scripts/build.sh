#!/usr/bin/env bash
# Configures and builds mechflow in build/ (Release), installing dependencies first.
#   scripts/build.sh main   only the `mechflow` command (scripts/run-example.sh): the
#                           main job's packages, no tests, no benchmarks, no MPI, so a
#                           fresh machine reaches its first plot in minutes. A build/
#                           configured before (by the full build) keeps its options.
#   scripts/build.sh [all]  everything (scripts/test.sh): the tests, the benchmarks and
#                           MPI for `mechflow sweep`, turned on in a build/ that `main` made.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-all}
case "$mode" in
  main)
    bash scripts/install-deps.sh main
    if [ ! -f build/CMakeCache.txt ]; then
      cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMECHFLOW_BUILD_TESTS=OFF -DMECHFLOW_BUILD_BENCH=OFF \
        -DMECHFLOW_MPI=OFF >/dev/null
    fi
    cmake --build build -j "$(nproc)" --target mechflow
    ;;
  all)
    bash scripts/install-deps.sh all
    # -U: a build/ that `main` configured checked for lld before it was installed
    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMECHFLOW_BUILD_TESTS=ON -DMECHFLOW_BUILD_BENCH=ON \
      -DMECHFLOW_MPI=ON -UMECHFLOW_HAVE_LLD >/dev/null
    cmake --build build -j "$(nproc)"
    ;;
  *)
    echo "usage: scripts/build.sh [main|all]" >&2
    exit 2
    ;;
esac
