#!/bin/sh
# The fill-height series (docs/validation.md, "The fill height of a glass-bead bed"): per fill
# fraction, the scene's solids fraction, the settled and unloaded bed's phi in the column
# under the ball (top 8 d and whole, 8 d cylinder), and H over h/r 0.2-0.5 and 0.3-0.5.
# Run in the folder holding settle.log (seed 1), settle_s2.log (seed 2), settle_s34.log
# (seeds 3, 4: the same configs with seed = 2, 3, 4), hwin.awk and out_f*/; PHIPROF: the built
# ../full-hertz-jkr-bh/phiprof.c.
P=${PHIPROF:-../full-hertz-jkr-bh/phiprof}
for f in 0.36 0.2 0.144 0.087 0.36_s2 0.144_s2 0.36_s3 0.144_s3 0.36_s4 0.144_s4; do
  [ -f out_f$f/series.csv ] || continue
  ff=${f%_s*}; sd=1; [ "$ff" != "$f" ] && sd=${f#*_s}
  line=$(awk -v f="$ff" -v sd=$sd '$1=="=="&&$3==f&&($4=="seed"?$5:1)==sd{on=1;next} on&&/^particles/{print;exit}' settle*.log)
  sf=$(echo "$line" | grep -o 'surface [0-9.e-]* m' | awk '{print $2}')
  echo "f $f: $(echo "$line" | grep -o 'bed after unloading [^)]*)')"
  awk -F, 'NR>1 && $2==3 && $7!="nan" { if($7>=0.2&&$7<=0.5){h+=$9;n++} if($7>=0.3&&$7<=0.5){h3+=$9;n3++} }
     NR>1 && $2==0 {ts=$1} NR>1 && $2==1 && !tc {tc=$1}
     END{printf "  settle ends t %.4f s; H 0.2-0.5 %.2f kPa (n %d), 0.3-0.5 %.2f\n", tc, h/n/1e3, n, h3/n3/1e3}' out_f$f/series.csv
  echo "  $(awk -F, -v lo=0.2 -v hi=0.5 -f hwin.awk out_f$f/series.csv) over 0.2-0.5; $(awk -F, -v lo=0.3 -v hi=0.5 -f hwin.awk out_f$f/series.csv) over 0.3-0.5"
  for st in settled unloaded; do
    $P out_f$f/checkpoint_$st.h5 8 $([ $st = unloaded ] && echo $sf) | awk -v st=$st '!/^#/{n++; if(n<=8){s+=$2;c++}; if(n>1&&n<=12){m+=$2;cm++}; a+=$2; ca++} END{printf "  %-9s phi top 8 d (Rc 8) %.4f, 1-12 d %.4f, whole column %.4f (%d slabs)\n", st, s/c, m/cm, a/ca, ca}'
  done
done
