#!/usr/bin/env bash
# The main job: build the `mechflow` command if needed (only it, with only the
# packages it needs: scripts/build.sh main), then run the stick-slip example headless.
# Writes results/stick_slip_blocks.csv and results/stick_slip_blocks.png.
# Extra arguments go to `mechflow run` (e.g. --set mu_s=0.5).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh main
./build/mechflow run diagrams/examples/stick_slip_blocks.xml --out results "$@"
