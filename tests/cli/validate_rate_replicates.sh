#!/bin/sh
# Case 10 (strain-rate) over replicate rate beds (validate/cases.c, c_rate), on the smoke
# tier's rate bed at stiffness x0.01 (the cheapest scene with every path; not a validation).
#   1. --replicates 1: the single-bed criteria; --replicates 2 on the same folder prepares
#      only the seed-2 rate bed, reuses the six seed-1 runs and makes six seed-2 runs.
#   2. The printed values are recomputed here from the runs' plateau means and standard
#      errors (strain-rate_dynamic.png.dat lists every run: gamma*, v, rho_b v^2, H, se, sd):
#      - flatness: the mean H per rate over the beds, and the pair furthest beyond its
#        critical value by the paired two-sided test at 0.05 / 6 (Cochran's Q against
#        chi^2_1(0.95) = 3.841; z with crit 2.638, or t on 1 dof with crit
#        1 / tan(pi 0.05 / 12) = 76.39);
#      - the rise: the one-sided z of H(2.3) over H(0.1) on each bed (crit 1.645), the least
#        printed, PASS only if every bed's exceeds it;
#      - the sd ratio: mean sd(0.46) / mean sd(0.1) and mean sd(1) / mean sd(0.1);
#      - the rate fit uses all 12 runs.
#   3. --replicates 1 again reads the seed-1 runs only and prints what step 1 printed.
# usage: validate_rate_replicates.sh DEM_VALIDATE
set -e
V=$1
rm -rf v_rr
"$V" --tier smoke --case strain-rate --stiffness-scale 0.01 --threads 2 --beds v_rr/beds \
  --out v_rr/r1 > v_rr1.txt 2> v_rr1.err || test $? -eq 3
"$V" --tier smoke --case strain-rate --stiffness-scale 0.01 --replicates 2 --threads 2 \
  --beds v_rr/beds --out v_rr/r2 > v_rr2.txt 2> v_rr2.err || test $? -eq 3
"$V" --tier smoke --case strain-rate --stiffness-scale 0.01 --threads 2 --beds v_rr/beds \
  --out v_rr/r3 > v_rr3.txt 2> v_rr3.err || test $? -eq 3

# 1. what was made and reused
test "$(grep -c ': preparing' v_rr1.err)" -eq 1
test "$(grep -c ': preparing' v_rr2.err)" -eq 1
grep -q 'seed2_.*: preparing' v_rr2.err
test "$(grep -c ': cached (' v_rr2.err)" -eq 6
test "$(grep -c 'samples to h/r' v_rr2.err)" -eq 6
grep -q 'gamma\* 0.1, .*, seed 2' v_rr2.err
grep -q '"replicates": 2' v_rr/r2/summary.json
test "$(grep -c 'mean over 2 replicate beds' v_rr2.txt)" -eq 3
grep -q 'paired over the replicate beds, two-sided, Bonferroni' v_rr/r2/summary.json
grep -q 'z, one-sided, level 0.05, on every replicate bed' v_rr/r2/summary.json
grep -q 'over the 12 runs made on 2 replicate beds' v_rr/r2/report.md
test "$(grep -vc '^#' v_rr/r2/strain-rate_dynamic.png.dat)" -eq 12

# 2. the printed values against the runs
D=v_rr/r2/strain-rate_dynamic.png.dat
flat=$(grep 'four rates agree pairwise' v_rr2.txt)
rise=$(grep 'H(2.3) > H(0.1)' v_rr2.txt)
sdr=$(grep 'fluctuation grows' v_rr2.txt)
awk -v flat="$flat" -v rise="$rise" -v sdr="$sdr" '
  !/^#/ { j = int(n / 6); o = n % 6; H[j, o] = $4; S[j, o] = $5; SD[j, o] = $6; n++ }
  function near(a, b, tol) { return a - b < tol && b - a < tol }
  function grab(s, re,   t) { if (!match(s, re)) return "none"; t = substr(s, RSTART, RLENGTH);
    sub(/.*[^0-9.-]/, "", t); return t + 0 }
  END {
    if (n != 12) { print "runs " n; exit 1 }
    split("0.03 0.1 0.23 0.46", nm, " ")
    # mean H per rate, as printed
    for (o = 0; o < 4; o++) {
      m = (H[0, o] + H[1, o]) / 2 / 1000
      if (!near(grab(flat, " " nm[o + 1] " [0-9.]+"), m, 0.0051)) { print "mean " nm[o + 1]; exit 1 }
    }
    # the paired test of every pair; the worst by |z| / crit
    worst = -1
    for (a = 0; a < 4; a++) for (b = a + 1; b < 4; b++) {
      for (j = 0; j < 2; j++) { d[j] = H[j, a] - H[j, b]; s2[j] = S[j, a]^2 + S[j, b]^2 }
      dw = (d[0] / s2[0] + d[1] / s2[1]) / (1 / s2[0] + 1 / s2[1])
      Q = (d[0] - dw)^2 / s2[0] + (d[1] - dw)^2 / s2[1]
      db = (d[0] + d[1]) / 2
      if (Q > 3.841) { se = (d[0] > d[1] ? d[0] - d[1] : d[1] - d[0]) / 2; crit = 76.39; lt = "t" }
      else { se = sqrt(s2[0] + s2[1]) / 2; crit = 2.638; lt = "z" }
      z = db / se; if (z < 0) z = -z
      if (z / crit > worst) { worst = z / crit; wz = z; wc = crit; wl = lt; wp = nm[a + 1] " vs " nm[b + 1] }
      if (z > crit) bad = 1
    }
    if (index(flat, "max |" wl "| = ") == 0) { print "letter " wl; exit 1 }
    if (!near(grab(flat, "max [|][zt][|] = [0-9.]+"), wz, 0.0051)) { print "z " wz; exit 1 }
    if (index(flat, "(" wp ")") == 0) { print "pair " wp; exit 1 }
    if (!near(grab(flat, "crit [0-9.]+"), wc, 0.011)) { print "crit " wc; exit 1 }
    if ((index(flat, " PASS ") > 0) != !bad) { print "flat status"; exit 1 }
    # the rise on every bed
    zmin = 1e300; all = 1
    for (j = 0; j < 2; j++) {
      zj[j] = (H[j, 5] - H[j, 1]) / sqrt(S[j, 5]^2 + S[j, 1]^2)
      if (zj[j] < zmin) zmin = zj[j]
      if (zj[j] <= 1.645) all = 0
    }
    if (!near(grab(rise, "; z = [0-9.-]+"), zmin, 0.0051)) { print "rise z " zmin; exit 1 }
    if (!match(rise, "per bed [0-9.-]+ [0-9.-]+")) { print "per bed"; exit 1 }
    split(substr(rise, RSTART + 8, RLENGTH - 8), pb, " ")
    if (!near(pb[1], zj[0], 0.0051) || !near(pb[2], zj[1], 0.0051)) { print "per bed z"; exit 1 }
    if ((index(rise, " PASS ") > 0) != all) { print "rise status"; exit 1 }
    # the sd ratios of the beds means
    r3 = (SD[0, 3] + SD[1, 3]) / (SD[0, 1] + SD[1, 1])
    r4 = (SD[0, 4] + SD[1, 4]) / (SD[0, 1] + SD[1, 1])
    if (!near(grab(sdr, "ratios [0-9.]+"), r3, 0.0051)) { print "sd ratio 0.46"; exit 1 }
    if (!match(sdr, "[0-9.]+ [(]1.0[)]")) { print "sd ratio 1 missing"; exit 1 }
    if (!near(substr(sdr, RSTART, RLENGTH - 6) + 0, r4, 0.0051)) { print "sd ratio 1"; exit 1 }
  }' "$D"

# 3. one bed again: the single-bed criteria as before
grep -q 'z, two-sided, Bonferroni' v_rr/r3/summary.json
grep -q '"statistic": "z, one-sided, level 0.05"' v_rr/r3/summary.json
test "$(grep -c 'replicate beds' v_rr3.txt)" -eq 0
grep 'strain-rate' v_rr1.txt | sed 's/(.*made in [0-9]* s)//' > v_rr1.cmp
grep 'strain-rate' v_rr3.txt | sed 's/(.*made in [0-9]* s)//' > v_rr3.cmp
cmp v_rr1.cmp v_rr3.cmp
