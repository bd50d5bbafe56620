# H against h/r (bins of 0.025) of the slowest-rate runs: x0.3 beds (seeds 1-3) and the x0.01 bed
set terminal pngcairo size 1200,480 font ",10"
set output "H_slowest.png"
set multiplot layout 1,2
set xlabel "h/r"; set ylabel "H [kPa] (bins of 0.025 in h/r)"; set grid
set xrange [0:0.5]; set yrange [0:12]; set key top right
set title "stiffness x0.3 (three beds)"
plot "s1_g0.1.dat" w lp pt 7 ps 0.5 lc rgb "#1b9e77" t "seed 1, gamma* 0.1", \
     "s1_aged.dat" w lp pt 6 ps 0.5 lc rgb "#66c2a5" t "seed 1, gamma* 0.1 after 45 ms rest", \
     "s1_g0.03.dat" w lp pt 7 ps 0.5 lc rgb "#d95f02" t "seed 1, gamma* 0.03", \
     "s2_g0.1.dat" w lp pt 5 ps 0.5 lc rgb "#7570b3" t "seed 2, gamma* 0.1", \
     "s2_g0.03.dat" w lp pt 5 ps 0.5 lc rgb "#e7298a" t "seed 2, gamma* 0.03", \
     "s3_g0.1.dat" w lp pt 9 ps 0.5 lc rgb "#666666" t "seed 3, gamma* 0.1", \
     "s3_g0.03.dat" w lp pt 9 ps 0.5 lc rgb "#e6ab02" t "seed 3, gamma* 0.03"
set title "stiffness x0.01 (one bed, seed 1)"
plot "k001_g0.1.dat" w lp pt 7 ps 0.5 lc rgb "#1b9e77" t "gamma* 0.1", \
     "k001_g0.03.dat" w lp pt 7 ps 0.5 lc rgb "#d95f02" t "gamma* 0.03", \
     "k001_g0.01.dat" w lp pt 7 ps 0.5 lc rgb "#7570b3" t "gamma* 0.01", \
     "k001_g0.003.dat" w lp pt 7 ps 0.5 lc rgb "#e7298a" t "gamma* 0.003"
unset multiplot
