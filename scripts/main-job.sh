#!/usr/bin/env bash
# README command 1: install what is missing, build, and run the main job on the embedded
# reference data. Output: out/ (CSV, HDF5, PNG plots, summaries).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
JOBS=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$JOBS"
OUT=${1:-out}
mkdir -p "$OUT"
for job in scripts/jobs/*.sh; do
  [ -e "$job" ] || continue
  echo "== $job"
  bash "$job" build/bin "$OUT"
done
echo "main job done: results in $OUT/"
