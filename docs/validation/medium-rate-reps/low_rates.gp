# H against h/r at gamma* 0.03, 0.1 and 0.23 on the two x0.1 rate beds (the runs of
# dem-validate --tier medium --case strain-rate; data/run_XX.dat of its --out folder, columns
# h/r and H [Pa]). Usage: gnuplot -e "d='m2/data'" low_rates.gp
if (!exists("d")) d = 'm2/data'
set term pngcairo size 1000,420 font ',10'
set output 'H_low_rates.png'
set multiplot layout 1,2 title 'medium tier, x0.1 rate beds: H against depth at the three lowest rates (plateau window h/r 0.25-0.5)'
set yrange [0:10]; set xrange [0:0.55]; set grid
set xlabel 'h/r'; set ylabel 'H [kPa]'
set arrow 1 from 0.25, graph 0 to 0.25, graph 1 nohead dt 2
set title 'seed 1'
plot d.'/run_00.dat' u 1:($2/1000) w l lw 1.5 t 'gamma* 0.03', d.'/run_01.dat' u 1:($2/1000) w l lw 1.5 t '0.1', d.'/run_02.dat' u 1:($2/1000) w l t '0.23'
set title 'seed 2'
plot d.'/run_06.dat' u 1:($2/1000) w l lw 1.5 t 'gamma* 0.03', d.'/run_07.dat' u 1:($2/1000) w l lw 1.5 t '0.1', d.'/run_08.dat' u 1:($2/1000) w l t '0.23'
unset multiplot
