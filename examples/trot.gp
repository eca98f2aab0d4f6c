# The trotting quadruped's feet forces, motor torques and torso roll and pitch from trot's CSV.
#   gnuplot -e "csv='build/examples/trot.csv'; out='docs/figures'" examples/trot.gp
if (!exists("csv")) csv = 'trot.csv'
if (!exists("out")) out = '.'
set datafile separator ','
set terminal pngcairo size 720,480 font ',10' noenhanced
set grid
set key outside right
set xlabel 't (s)'

set output out.'/trot_forces.png'
set title 'The ground on each foot: normal force (solid) and forward force (dashed)'
set ylabel 'force (N)'
plot csv using 't_s':'FL_fz_N' with lines lw 2 lc 1 title 'FL', \
     csv using 't_s':'HR_fz_N' with lines lw 2 lc 4 title 'HR', \
     csv using 't_s':'FR_fz_N' with lines lw 2 lc 2 title 'FR', \
     csv using 't_s':'HL_fz_N' with lines lw 2 lc 3 title 'HL', \
     csv using 't_s':'FL_fx_N' with lines dt 2 lc 1 notitle, \
     csv using 't_s':'HR_fx_N' with lines dt 2 lc 4 notitle, \
     csv using 't_s':'FR_fx_N' with lines dt 2 lc 2 notitle, \
     csv using 't_s':'HL_fx_N' with lines dt 2 lc 3 notitle

set output out.'/trot_torques.png'
set title 'Hip flexion (solid) and knee (dashed) torques'
set ylabel 'torque (N m)'
plot csv using 't_s':'FL_HFE_Nm' with lines lw 2 lc 1 title 'FL', \
     csv using 't_s':'HR_HFE_Nm' with lines lw 2 lc 4 title 'HR', \
     csv using 't_s':'FR_HFE_Nm' with lines lw 2 lc 2 title 'FR', \
     csv using 't_s':'HL_HFE_Nm' with lines lw 2 lc 3 title 'HL', \
     csv using 't_s':'FL_KFE_Nm' with lines dt 2 lc 1 notitle, \
     csv using 't_s':'HR_KFE_Nm' with lines dt 2 lc 4 notitle, \
     csv using 't_s':'FR_KFE_Nm' with lines dt 2 lc 2 notitle, \
     csv using 't_s':'HL_KFE_Nm' with lines dt 2 lc 3 notitle

set output out.'/trot_roll.png'
set title 'The torso: roll and pitch (left), its angular acceleration about the support line (right)'
set ylabel 'angle (deg)'
set y2label 's (rad/s^2)'
set y2tics
set ytics nomirror
plot csv using 't_s':'roll_deg' with lines lw 2 lc 1 title 'roll', \
     csv using 't_s':'pitch_deg' with lines lw 2 lc 2 title 'pitch', \
     csv using 't_s':'s_rad_s2' axes x1y2 with lines dt 2 lc 7 title 's'
