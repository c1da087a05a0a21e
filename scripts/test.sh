#!/usr/bin/env bash
# Installs everything the tests need (scripts/install-deps.sh all: GoogleTest,
# OpenMPI, Simbody, Chromium, graphviz, ...), builds mechflow with its tests and
# benchmarks and runs the whole test suite through CTest, then builds
# it again with AddressSanitizer and UndefinedBehaviorSanitizer (assertions
# on) and runs the same suite there (scripts/test-sanitizers.sh).
# MECHFLOW_SKIP_SANITIZERS=1 skips the second part (for a quick local run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh all
(cd build && ctest --output-on-failure -j "$(nproc)")
if [ "${MECHFLOW_SKIP_SANITIZERS:-0}" != 1 ]; then
  bash scripts/test-sanitizers.sh
fi
