# H over an h/r window of a dem-run series.csv (column 7 h_over_r, 9 hardness, 2 stage):
# mean, sd, and the standard error from 8 consecutive blocks (the series is correlated).
# awk -F, -v lo=0.2 -v hi=0.5 -f hwin.awk series.csv
NR > 1 && $2 == 3 && $7 != "nan" && $7 >= lo && $7 <= hi { h[n++] = $9 / 1e3 }
END {
  for (i = 0; i < n; i++) s += h[i]; m = s / n;
  for (i = 0; i < n; i++) v += (h[i] - m)^2;
  nb = 8; for (b = 0; b < nb; b++) { t = 0; c = 0; for (i = int(b*n/nb); i < int((b+1)*n/nb); i++) { t += h[i]; c++ } bm[b] = t / c; }
  for (b = 0; b < nb; b++) w += (bm[b] - m)^2;
  printf "H %.2f +- %.2f kPa (sd %.2f, n %d)", m, sqrt(w / (nb - 1) / nb), sqrt(v / (n - 1)), n
}
