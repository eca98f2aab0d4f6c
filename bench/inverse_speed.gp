# Time per inverse-dynamics instant against the chain's length, log-log, one curve per method:
# every joint driven (left) and the tip driven with every joint free (right).
#   gnuplot -e "dir='build/bench'" bench/inverse_speed.gp
if (!exists("dir")) dir = '.'
csv = dir.'/inverse_speed.csv'
out = dir.'/inverse_speed.png'
set datafile separator ','
set terminal pngcairo size 1200,520 font ',10' noenhanced
set output out
set multiplot layout 1,2 title 'Joint torques + every joint reaction, spatial chain of n revolute joints'
set xlabel 'n (joints)'
set ylabel 'median time per call (us)'
set logscale xy
set grid
set key top left
set title 'every joint driven (chain)'
methods = system("awk -F, 'NR>1 && $1==\"chain\" {print $3}' ".csv." | awk '!seen[$0]++' | tr '\\n' ' '")
plot for [mth in methods] '< awk -F, -v m='.mth.' ''NR==1 || ($1=="chain" && $3==m)'' '.csv \
     using 'n':'median_us' with linespoints lw 2 title mth
set title 'tip y driven, every joint free (chain_tip)'
methods = system("awk -F, 'NR>1 && $1==\"chain_tip\" {print $3}' ".csv." | awk '!seen[$0]++' | tr '\\n' ' '")
plot for [mth in methods] '< awk -F, -v m='.mth.' ''NR==1 || ($1=="chain_tip" && $3==m)'' '.csv \
     using 'n':'median_us' with linespoints lw 2 title mth
unset multiplot
