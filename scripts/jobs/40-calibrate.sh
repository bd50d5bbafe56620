#!/usr/bin/env bash
# The built-in calibrations of issue 4 (calibrate/builtin/*.cfg, listed by
# `dem-calibrate --list-builtins`): pasha-simplified fitted to thornton-ning impact curves,
# nan fitted to Wall et al. (1990) sticking velocities (p_y alone; p_y and Gamma), luding and
# pasha fitted to Ning's unloading points, and the round-trip case. Each writes
# OUT_DIR/calibrate/<case>/ (summary.txt, results.h5, residual tables, trace, PNG plots) and
# its --json summary. A case whose law is not in this build is skipped with the message.
#
# Usage: bash scripts/jobs/40-calibrate.sh BIN_DIR OUT_DIR
set -euo pipefail
BIN=${1:?usage: $0 BIN_DIR OUT_DIR}
OUT=${2:?usage: $0 BIN_DIR OUT_DIR}/calibrate
mkdir -p "$OUT"
CAL="$BIN/dem-calibrate"
mapfile -t CASES < <("$CAL" --list-builtins | awk '{print $1}')
skipped=()
for c in "${CASES[@]}"; do
  start=$(date +%s.%N)
  if "$CAL" --builtin "$c" --out "$OUT/$c" --json --quiet > "$OUT/$c.json" 2> "$OUT/$c.err"; then
    t=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.1f", b - a}')
    mre=$(grep -o '"mean_relative_error": [^,]*' "$OUT/$c.json" | cut -d' ' -f2)
    echo "calibrate: $c done in $t s, mean relative error $mre"
    [ -s "$OUT/$c.err" ] && sed 's/^/calibrate:   /' "$OUT/$c.err"
    rm -f "$OUT/$c.err"
  else
    echo "calibrate: skip $c: $(head -1 "$OUT/$c.err")"
    rm -f "$OUT/$c.json"
    skipped+=("$c")
  fi
done
if [ ${#skipped[@]} -gt 0 ]; then echo "calibrate: skipped: ${skipped[*]}"; fi
echo "calibrate: results in $OUT"
