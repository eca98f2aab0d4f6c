# MuJoCo's knee four-bar (soft equality constraints) against vtdyn's exact torques and forces.
#   gnuplot -e "csv='build/knee_mujoco.csv'; out='docs/figures'" bench/peers/knee_mujoco.gp
if (!exists("csv")) csv = 'knee_mujoco.csv'
if (!exists("out")) out = '.'
set datafile separator ','
set terminal pngcairo size 720,480 font ',10' noenhanced
set grid
set key outside right
set xlabel 't (s)'
set logscale y
set format y '%.0e'

set output out.'/knee_mujoco_diff.png'
set title 'MuJoCo (connect and joint equalities) minus vtdyn (exact)'
set ylabel '|difference| (N m, N)'
plot csv using 't_s':(abs(column('dtau_hip_Nm'))) with lines lw 2 title 'hip torque', \
     csv using 't_s':(abs(column('dtau_motor_Nm'))) with lines lw 2 title 'motor torque', \
     csv using 't_s':'dlever_N' with lines lw 1 dt 2 title 'coupler-lever force', \
     csv using 't_s':'dknee_N' with lines lw 1 dt 2 title 'knee force', \
     csv using 't_s':'dhip_N' with lines lw 1 dt 2 title 'hip force'
