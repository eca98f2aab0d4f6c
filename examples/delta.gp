# The Delta robot's motor torques and bearing loads over one turn of its path, from delta's CSV.
#   gnuplot -e "csv='build/delta.csv'; out='docs/figures'" examples/delta.gp
if (!exists("csv")) csv = 'delta.csv'
if (!exists("out")) out = '.'
set datafile separator ','
set terminal pngcairo size 720,480 font ',10' noenhanced
set grid
set xlabel 't (s)'
set key top right

set output out.'/delta_torques.png'
set title 'Delta robot: motor torques that move the platform along its path'
set ylabel 'torque (N m)'
plot for [i=1:3] csv using 't_s':'tau'.i.'_Nm' with lines lw 2 title 'motor '.i

# |f| of a joint's reaction force from its three columns
mag(p) = sqrt(column(p.'x_N')**2 + column(p.'y_N')**2 + column(p.'z_N')**2)
set terminal pngcairo size 720,900 font ',10' noenhanced
set output out.'/delta_bearings.png'
set multiplot layout 3,1 title 'Delta robot: bearing loads (magnitude of the reaction force)'
set ylabel 'force (N)'
set key outside right
set title 'motor bearings (revolute: the base on the upper arm)'
plot for [i=1:3] csv using 't_s':(mag('mot'.i.'_f')) with lines lw 2 title 'motor '.i
set title 'elbows (universal: the upper arm on each rod)'
plot for [i=1:3] csv using 't_s':(mag('elb'.i.'a_f')) with lines lw 2 lc i title 'arm '.i.', rod a', \
     for [i=1:3] csv using 't_s':(mag('elb'.i.'b_f')) with lines lw 2 dt 2 lc i title 'arm '.i.', rod b'
set title 'ball joints (spherical: the platform on each rod)'
plot for [i=1:3] csv using 't_s':(mag('ball'.i.'a_f')) with lines lw 2 lc i title 'arm '.i.', rod a', \
     for [i=1:3] csv using 't_s':(mag('ball'.i.'b_f')) with lines lw 2 dt 2 lc i title 'arm '.i.', rod b'
unset multiplot
