# The humanoid's feet forces, centres of pressure and leg torques from balance's CSV.
#   gnuplot -e "csv='build/examples/balance.csv'; out='docs/figures'" examples/balance.gp
if (!exists("csv")) csv = 'balance.csv'
if (!exists("out")) out = '.'
set datafile separator ','
set terminal pngcairo size 720,480 font ',10' noenhanced
set grid
set key outside right
set xlabel 't (s)'

set output out.'/balance_forces.png'
set title 'Each foot: the ground''s normal force (left axis) and its centre of pressure y (right)'
set ylabel 'force (N)'
set y2label 'y (m)'
set y2tics
set y2range [-0.2:0.2]
plot csv using 't_s':'L_fz_N' with lines lw 2 lc 1 title 'left fz', \
     csv using 't_s':'R_fz_N' with lines lw 2 lc 2 title 'right fz', \
     csv using 't_s':'L_cop_y_m' axes x1y2 with lines dt 2 lc 1 title 'left CoP y', \
     csv using 't_s':'R_cop_y_m' axes x1y2 with lines dt 2 lc 2 title 'right CoP y'
unset y2tics
unset y2label

set output out.'/balance_torques.png'
set title 'Left (solid) and right (dashed) leg torques'
set ylabel 'torque (N m)'
plot csv using 't_s':'L_hip_roll_Nm' with lines lw 2 lc 1 title 'hip roll', \
     csv using 't_s':'L_knee_Nm' with lines lw 2 lc 2 title 'knee', \
     csv using 't_s':'L_ankle_roll_Nm' with lines lw 2 lc 3 title 'ankle roll', \
     csv using 't_s':'R_hip_roll_Nm' with lines dt 2 lc 1 notitle, \
     csv using 't_s':'R_knee_Nm' with lines dt 2 lc 2 notitle, \
     csv using 't_s':'R_ankle_roll_Nm' with lines dt 2 lc 3 notitle
