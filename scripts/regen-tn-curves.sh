#!/usr/bin/env bash
# Regenerate reference_data/thornton_ning_curves/: force-overlap curves of the `thornton-ning`
# law (thesis 3.4.4.1, eqs 3.55-3.59) in a normal impact of an ammonium fluorescein sphere on a
# silicon wall at 2, 5 and 10 m/s (thesis Table 4.1 set), from build/bin/dem-impact --trace.
#
#   bash scripts/regen-tn-curves.sh [--bin DIR] [--out DIR]    # write the three CSV files
#   bash scripts/regen-tn-curves.sh [--bin DIR] --check DIR    # regenerate into a temporary
#                                                              # folder and compare with DIR
#
# Each curve is dem-impact's own trace (printf "%.10e", velocity Verlet, dt = 0.01 x the
# Rayleigh step), thinned to about SAMPLES = 400 rows evenly spaced in path length sum |d alpha|,
# always keeping the first row, the row of the largest overlap and the last row: the same rows,
# by the same rule, as calibrate/generate.c picks for an in-program `reference_law` target, so
# the committed curves give the built-in calibration the very same reference points. The kept
# rows are copied as text (never re-formatted), so the output is byte-for-byte dem-impact's.
# Only the header is rewritten into the reference_data convention (`name [unit]`, SI units).
#
# --check: identical bytes pass; otherwise every field must agree within
# TOL = 1e-9 x the largest |value| of its column (same header, same number of rows), because
# the last printed digit may flip between builds (Release vs Debug/ASan, another compiler,
# FMA contraction); that is reported. Exit status: 0 same, 1 different, 2 usage or run error.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN="$here/build/bin"
OUT="$here/reference_data/thornton_ning_curves"
CHECK=""
SAMPLES=400
TOL=1e-9
while [ $# -gt 0 ]; do
  case "$1" in
    --bin) BIN=${2:?--bin needs a folder}; shift 2 ;;
    --out) OUT=${2:?--out needs a folder}; shift 2 ;;
    --check) CHECK=${2:?--check needs a folder}; shift 2 ;;
    -h|--help) sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "regen-tn-curves: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
IMPACT="$BIN/dem-impact"
[ -x "$IMPACT" ] || { echo "regen-tn-curves: $IMPACT not found (build first)" >&2; exit 2; }

# The thornton-ning reference set (thesis Table 4.1; docs/contact-laws.md; the same numbers as
# the former in-program reference_set of calibrate/builtin/pasha-simplified-tn.cfg).
SET=(--set R=2.45e-6 --set rho=1350 --set E=1.2e9 --set nu=0.3 --set wall_E=1.82e11
     --set wall_nu=0.3 --set gamma=0.2 --set py=35.3e6)
VELOCITIES=(2 5 10)

work=$(mktemp -d "${TMPDIR:-/tmp}/regen-tn-curves.XXXXXX")
trap 'rm -rf "$work"' EXIT
dest=$OUT
[ -n "$CHECK" ] && dest="$work/new"
mkdir -p "$dest"

for v in "${VELOCITIES[@]}"; do
  "$IMPACT" --law thornton-ning "${SET[@]}" --integrator verlet --dt-factor 0.01 \
    --velocity "$v" --trace "$work/trace.csv" > /dev/null ||
    { echo "regen-tn-curves: dem-impact failed at $v m/s" >&2; exit 2; }
  # Thinning, statement for statement calibrate/generate.c (want = SAMPLES): rows k = 0 .. n-1,
  # s = path length up to row k; keep k if k == 0, k == kmax (first largest alpha), k == n-1 or
  # s >= next, then advance next by ds = len / want past s; at most want + 2 rows.
  LC_ALL=C awk -F, -v want="$SAMPLES" '
    NR == 1 {
      if ($0 != "t,alpha,alpha_dot,f,f_el,f_damp") { print "unexpected trace header: " $0 > "/dev/stderr"; exit 3 }
      next
    }
    { n++; line[n - 1] = $0; a[n - 1] = $2 + 0 }
    END {
      if (n < 2) { print "trace has " n " rows" > "/dev/stderr"; exit 3 }
      len = 0; kmax = 0
      for (k = 1; k < n; k++) {
        d = a[k] - a[k - 1]; len += (d < 0 ? -d : d)
        if (a[k] > a[kmax]) kmax = k
      }
      print "t [s],alpha [m],alpha_dot [m/s],f [N],f_el [N],f_damp [N]"
      m = 0; s = 0; next_s = 0; ds = len / want
      for (k = 0; k < n && m < want + 2; k++) {
        if (k > 0) { d = a[k] - a[k - 1]; s += (d < 0 ? -d : d) }
        if (k == 0 || k == kmax || k == n - 1 || s >= next_s) {
          print line[k]; m++
          while (next_s <= s) next_s += ds
        }
      }
    }' "$work/trace.csv" > "$dest/curve_${v}ms.csv.tmp"
  mv "$dest/curve_${v}ms.csv.tmp" "$dest/curve_${v}ms.csv"
  [ -z "$CHECK" ] && echo "regen-tn-curves: wrote $dest/curve_${v}ms.csv ($(($(wc -l < "$dest/curve_${v}ms.csv") - 1)) rows)"
done
[ -z "$CHECK" ] && exit 0

status=0
for v in "${VELOCITIES[@]}"; do
  f="curve_${v}ms.csv"
  if [ ! -f "$CHECK/$f" ]; then
    echo "regen-tn-curves: $CHECK/$f is missing"; status=1; continue
  fi
  if cmp -s "$work/new/$f" "$CHECK/$f"; then
    echo "regen-tn-curves: $f: identical bytes ($(($(wc -l < "$CHECK/$f") - 1)) rows)"
    continue
  fi
  if LC_ALL=C awk -F, -v tol="$TOL" -v name="$f" '
      FNR == NR { ref[FNR] = $0; nref = FNR; next }
      FNR == 1 {
        if ($0 != ref[1]) { print "regen-tn-curves: " name ": header differs"; exit 1 }
        next
      }
      {
        new[FNR] = $0; nnew = FNR
      }
      END {
        if (nnew != nref) { print "regen-tn-curves: " name ": " nref - 1 " committed rows, " nnew - 1 " regenerated"; exit 1 }
        for (r = 2; r <= nref; r++) {
          nc = split(ref[r], x, ","); if (split(new[r], y, ",") != nc) { print "regen-tn-curves: " name ":" r ": field count"; exit 1 }
          for (c = 1; c <= nc; c++) { v = x[c] + 0; if (v < 0) v = -v; if (v > big[c]) big[c] = v }
        }
        worst = 0
        for (r = 2; r <= nref; r++) {
          split(ref[r], x, ","); split(new[r], y, ",")
          for (c = 1; c <= nc; c++) {
            d = x[c] - y[c]; if (d < 0) d = -d
            e = big[c] > 0 ? d / big[c] : d
            if (e > worst) worst = e
            if (e > tol) { printf "regen-tn-curves: %s:%d: column %d: committed %s, regenerated %s (%.3g of the column maximum > %g)\n", name, r, c, x[c], y[c], e, tol; bad = 1 }
          }
        }
        if (bad) exit 1
        printf "regen-tn-curves: %s: bytes differ, all fields within %g of their column maximum (largest %.3g)\n", name, tol, worst
      }' "$CHECK/$f" "$work/new/$f"; then
    :
  else
    status=1
  fi
done
[ $status -eq 0 ] && echo "regen-tn-curves: $CHECK agrees with a fresh regeneration" ||
  echo "regen-tn-curves: $CHECK differs from a fresh regeneration (rerun without --check to update)"
exit $status
