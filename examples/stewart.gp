# The Stewart–Gough platform's leg lengths, leg forces and bearing loads from stewart's CSV.
#   gnuplot -e "csv='build/stewart.csv'; out='docs/figures'" examples/stewart.gp
if (!exists("csv")) csv = 'stewart.csv'
if (!exists("out")) out = '.'
set datafile separator ','
set terminal pngcairo size 720,480 font ',10' noenhanced
set grid
set key outside right
set xlabel 't (s)'
mag(a, b, c) = sqrt(a * a + b * b + c * c)

set output out.'/stewart_lengths.png'
set title 'Leg lengths (the drives, from the pose inverse kinematics)'
set ylabel 'length (m)'
plot for [i=1:6] csv using 't_s':'L'.i.'_m' with lines lw 2 title 'leg '.i

set output out.'/stewart_forces.png'
set title 'Leg (actuator) forces, positive pushing the platform away'
set ylabel 'force (N)'
plot for [i=1:6] csv using 't_s':'f'.i.'_N' with lines lw 2 title 'leg '.i

set output out.'/stewart_bearings.png'
set title 'Bearing loads: universal joints at the base (solid), spherical joints at the platform (dashed)'
set ylabel '|force| (N)'
plot for [i=1:6] csv using 't_s':(mag(column('U'.i.'x_N'), column('U'.i.'y_N'), column('U'.i.'z_N'))) \
       with lines lw 2 lc i title 'U '.i, \
     for [i=1:6] csv using 't_s':(mag(column('S'.i.'x_N'), column('S'.i.'y_N'), column('S'.i.'z_N'))) \
       with lines lw 2 dt 2 lc i title 'S '.i
