#!/bin/sh
# phi of the unloaded bed, H over h/r windows, bin phi before indentation, phi of top 8 d (Rc 8 d)
# Run in the folder holding crate.log (both dem-run outputs, in order g 0.1, g 0.04) and
# out_g0.1/, out_g0.04/; PHIPROF: the built ../full-hertz-jkr-bh/phiprof.c.
for g in 0.1 0.04; do
  sf=$(grep -o 'surface [0-9.e-]* m' crate.log | sed -n "$([ $g = 0.1 ] && echo 1 || echo 2)p" | awk '{print $2}')
  line=$(grep '^particles' crate.log | sed -n "$([ $g = 0.1 ] && echo 1 || echo 2)p")
  echo "g $g: $line"
  awk -F, 'NR>1 && $2==3 && $7!="nan" { if($7>=0.2&&$7<=0.5){h+=$9;n++} if($7>=0.3&&$7<=0.5){h3+=$9;n3++} if($7<=0.05 && $15!="nan"){p+=$15;np++} }
     END{printf "  H 0.2-0.5 %.2f kPa (n %d), 0.3-0.5 %.2f; bin phi0 %.4f\n", h/n/1e3, n, h3/n3/1e3, p/np}' out_g$g/series.csv
  ${PHIPROF:-../full-hertz-jkr-bh/phiprof} out_g$g/checkpoint_unloaded.h5 8 $sf | awk '!/^#/{n++; if(n<=8){s+=$2;c++}; a+=$2; ca++} END{printf "  phi top 8 d (Rc 8) %.4f, whole column %.4f\n", s/c, a/ca}'
done
