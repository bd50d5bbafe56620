#!/usr/bin/env bash
# README command 2: install what is missing, build with warnings as errors, run the whole test
# suite (CTest over the Check executables); then the same suite under AddressSanitizer and
# UndefinedBehaviorSanitizer in a second build tree.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
JOBS=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDEM_WERROR=ON
cmake --build build -j "$JOBS"
(cd build && ctest --output-on-failure -j "$JOBS")
if [ "${DEM_SKIP_SANITIZE:-0}" != "1" ]; then
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DDEM_WERROR=ON -DDEM_SANITIZE=ON
  cmake --build build-asan -j "$JOBS"
  # Sanitized code runs 4-10x slower: Check's per-test timeouts are scaled to match.
  (cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
     CK_TIMEOUT_MULTIPLIER=6 \
     ctest --output-on-failure -j "$JOBS" -LE slow)
fi
