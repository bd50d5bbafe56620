#!/bin/sh
# Case 10's slowest rate (docs/validation.md, "The slowest rate of case 10 on more beds"):
# H over h/r 0.25-0.5 (the medium tier's plateau window) and 0.2-0.5 of each run (hwin.awk:
# mean +- the standard error of 8 blocks), the rest's drift (agetest), and the binned curves
# for plot.gp (bin.awk). Run in the folder holding the dem-run outputs s1/, s1_g003/ (and
# s2-s4), k001/, k001_g0.03/, k001_g0.01/, k001_g0.003/ and agetest's s1_aged.csv/.txt, with
# bin.awk and ../fill-height/hwin.awk copied there.
win() { printf "0.25-0.5: %s; 0.2-0.5: %s\n" "$(awk -F, -v lo=0.25 -v hi=0.5 -f hwin.awk $1)" \
  "$(awk -F, -v lo=0.2 -v hi=0.5 -f hwin.awk $1)"; }
for s in 1 2 3 4; do
  for r in "0.1:s$s/series.csv" "0.03:s${s}_g003/series.csv" "0.1 aged:s${s}_aged.csv"; do
    f=${r#*:}; [ -f "$f" ] || continue
    printf "x0.3 seed %s gamma* %-8s %s" $s "${r%%:*}" "$(win $f)"; echo
  done
  awk -F, -v w=0.025 -f bin.awk s$s/series.csv > s${s}_g0.1.dat
  awk -F, -v w=0.025 -f bin.awk s${s}_g003/series.csv > s${s}_g0.03.dat
  [ -f s${s}_aged.txt ] && awk '/^#/{print "  " $0; next} $1%5==0{printf "  rest %2d ms: KE %.3g J, dz_com %.3f um, dz_top %.3f um\n", $1, $2, $3, $4}' s${s}_aged.txt
done
awk -F, -v w=0.025 -f bin.awk s1_aged.csv > s1_aged.dat
for g in 0.1 0.03 0.01 0.003; do
  f=k001_g$g/series.csv; [ $g = 0.1 ] && f=k001/series.csv; [ -f $f ] || continue
  printf "x0.01 seed 1 gamma* %-5s %s" $g "$(win $f)"; echo
  awk -F, -v w=0.025 -f bin.awk $f > k001_g$g.dat
done
