# pairs.awk: case 10's flatness pairs by hand, from strain-rate_dynamic.png.dat (every run:
# gamma*, v, rho_b v^2, H, se, sd; seed 1's rates, then seed 2's, ...; a run that failed is
# not listed, and a bed starts at its gamma* 0.03 line). Per pair: the difference on each
# bed (its own z), Cochran's Q (heterogeneous above chi^2_(k-1)(0.95): 3.841, 5.991, 7.815
# for k = 2, 3, 4 beds) and the paired statistic dem_compare_paired uses: z = dbar /
# (sqrt(sum s_i^2) / k) on the runs' errors, or t = dbar / (sd(d) / sqrt(k)) on k - 1 dof.
# Usage: awk -f pairs.awk strain-rate_dynamic.png.dat
BEGIN { split("0.03 0.1 0.23 0.46 1 2.3", g, " "); for (i = 1; i <= 6; i++) col[g[i]] = i - 1; k = 0
        q95[2] = 3.841; q95[3] = 5.991; q95[4] = 7.815 }
!/^#/ { if ($1 == "0.03") k++; H[k - 1, col[$1]] = $4; S[k - 1, col[$1]] = $5 }
END {
  split("0.03 0.1 0.23 0.46", nm, " ")
  for (a = 0; a < 4; a++) for (b = a + 1; b < 4; b++) {
    line = ""; sw = 0; sdw = 0; ss = 0; db = 0
    for (j = 0; j < k; j++) {
      d[j] = H[j, a] - H[j, b]; s2[j] = S[j, a]^2 + S[j, b]^2
      line = line sprintf("%s%.0f (z %.2f)", j ? ", " : "", d[j], d[j] / sqrt(s2[j]))
      sw += 1 / s2[j]; sdw += d[j] / s2[j]; ss += s2[j]; db += d[j] / k
    }
    dw = sdw / sw; Q = 0; v = 0
    for (j = 0; j < k; j++) { Q += (d[j] - dw)^2 / s2[j]; v += (d[j] - db)^2 / (k - 1) }
    if (Q > q95[k]) { se = sqrt(v / k); lt = "t" } else { se = sqrt(ss) / k; lt = "z" }
    printf "%s vs %s: difference per bed [Pa] %s; Q %.2f; paired %s = %.2f\n",
      nm[a + 1], nm[b + 1], line, Q, lt, db / se
  }
}
