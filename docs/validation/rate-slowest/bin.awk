# H [kPa] in h/r bins of width w from a dem-run series.csv: "h/r_mid H n"
NR > 1 && $2 == 3 && $7 != "nan" && $7 > 0 { b = int($7 / w); h[b] += $9; n[b]++; if (b > bm) bm = b }
END { for (b = 0; b <= bm; b++) if (n[b]) printf "%.4f %.4f %d\n", (b + 0.5) * w, h[b] / n[b] / 1e3, n[b] }
