#!/usr/bin/env bash
# Configures and builds mechflow (Release, with MPI for `mechflow sweep`) in build/,
# installing dependencies first.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMECHFLOW_MPI=ON >/dev/null
cmake --build build -j "$(nproc)"
