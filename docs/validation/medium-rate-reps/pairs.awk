# pairs.awk: case 10's flatness pairs by hand, from strain-rate_dynamic.png.dat (every run:
# gamma*, v, rho_b v^2, H, se, sd; seed 1's rates, then seed 2's; a run that failed is not
# listed, and a bed starts at its gamma* 0.03 line). Per pair: the
# difference on each bed and its own z, Cochran's Q (heterogeneous above chi^2_1(0.95) =
# 3.841) and the paired statistic dem_compare_paired uses (z on the runs' errors, or t on
# 1 dof on the beds' spread). Usage: awk -f pairs.awk strain-rate_dynamic.png.dat
BEGIN { split("0.03 0.1 0.23 0.46 1 2.3", g, " "); for (i = 1; i <= 6; i++) col[g[i]] = i - 1; j = -1 }
!/^#/ { if ($1 == "0.03") j++; H[j, col[$1]] = $4; S[j, col[$1]] = $5 }
END {
  split("0.03 0.1 0.23 0.46", nm, " ")
  for (a = 0; a < 4; a++) for (b = a + 1; b < 4; b++) {
    for (j = 0; j < 2; j++) { d[j] = H[j, a] - H[j, b]; s2[j] = S[j, a]^2 + S[j, b]^2; zj[j] = d[j] / sqrt(s2[j]) }
    dw = (d[0] / s2[0] + d[1] / s2[1]) / (1 / s2[0] + 1 / s2[1])
    Q = (d[0] - dw)^2 / s2[0] + (d[1] - dw)^2 / s2[1]
    db = (d[0] + d[1]) / 2
    if (Q > 3.841) { se = (d[0] > d[1] ? d[0] - d[1] : d[1] - d[0]) / 2; lt = "t" }
    else { se = sqrt(s2[0] + s2[1]) / 2; lt = "z" }
    printf "%s vs %s: difference per bed %.0f, %.0f Pa (z %.2f, %.2f); Q %.2f; paired %s = %.2f\n",
      nm[a + 1], nm[b + 1], d[0], d[1], zj[0], zj[1], Q, lt, db / se
  }
}
