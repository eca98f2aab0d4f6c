# MuJoCo's Stewart–Gough platform (soft equality constraints) against vtdyn's exact forces.
#   gnuplot -e "csv='build/stewart_mujoco.csv'; out='docs/figures'" bench/peers/stewart_mujoco.gp
if (!exists("csv")) csv = 'stewart_mujoco.csv'
if (!exists("out")) out = '.'
set datafile separator ','
set terminal pngcairo size 720,480 font ',10' noenhanced
set grid
set key outside right
set xlabel 't (s)'
set logscale y
set format y '%.0e'

set output out.'/stewart_mujoco_diff.png'
set title 'MuJoCo (connect and joint equalities) minus vtdyn (exact): leg (solid) and spherical (dashed) forces'
set ylabel '|difference| (N)'
plot for [i=1:6] csv using 't_s':(abs(column('df'.i.'_N'))) with lines lw 2 lc i title 'leg '.i, \
     for [i=1:6] csv using 't_s':'dS'.i.'_N' with lines lw 1 dt 2 lc i title 'S '.i
