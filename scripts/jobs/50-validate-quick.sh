#!/usr/bin/env bash
# The quick tier of the ball-indentation validation (issue 6; docs/validation.md): the
# hardness plateau, the bed-height and the indenter-size conclusions of thesis chapter 5 on a
# reduced geometry. Writes OUT_DIR/validation-quick/ (report.md, report.html, summary.json,
# PNG figures, data/, beds/). A failed criterion is reported (exit status 3 of dem-validate)
# but does not stop the main job; a run that fails does.
#
# Usage: bash scripts/jobs/50-validate-quick.sh BIN_DIR OUT_DIR
set -euo pipefail
BIN=${1:?usage: $0 BIN_DIR OUT_DIR}
OUT=${2:?usage: $0 BIN_DIR OUT_DIR}/validation-quick
THREADS=$(nproc 2>/dev/null || echo 2)
rc=0
"$BIN/dem-validate" --tier quick --threads "$THREADS" --out "$OUT" || rc=$?
case $rc in
  0) echo "validate: every quick-tier criterion passed; report in $OUT/report.md" ;;
  3) echo "validate: some quick-tier criteria FAILED (see $OUT/report.md)" ;;
  *) echo "validate: dem-validate failed with status $rc" >&2; exit "$rc" ;;
esac
