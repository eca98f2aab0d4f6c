# Time per inverse-dynamics instant against the chain's length, log-log, one curve per method.
#   gnuplot -e "dir='build/bench'" bench/inverse_speed.gp
if (!exists("dir")) dir = '.'
csv = dir.'/inverse_speed.csv'
out = dir.'/inverse_speed.png'
set datafile separator ','
set terminal pngcairo size 800,520 font ',10' noenhanced
set output out
set title 'Joint torques + every joint reaction, spatial chain of n revolute joints'
set xlabel 'n (joints)'
set ylabel 'median time per call (us)'
set logscale xy
set grid
set key top left
methods = system("awk -F, 'NR>1 && $1==\"chain\" {print $3}' ".csv." | awk '!seen[$0]++' | tr '\\n' ' '")
plot for [mth in methods] '< awk -F, -v m='.mth.' ''NR==1 || ($1=="chain" && $3==m)'' '.csv \
     using 'n':'median_us' with linespoints lw 2 title mth
