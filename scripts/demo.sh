#!/usr/bin/env bash
# Installs dependencies, builds, and runs the main job on the built-in dataset.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/tspplay demo "$@"
