# MuJoCo's soft constraints against vtdyn's exact reactions on the Delta robot (delta_mujoco's CSV).
#   gnuplot -e "dir='build/bench'" bench/peers/delta_mujoco.gp
if (!exists("dir")) dir = '.'
csv = dir.'/delta_mujoco.csv'
set datafile separator ','
set terminal pngcairo size 720,720 font ',10' noenhanced
set output dir.'/delta_mujoco.png'
set grid
set xlabel 't (s)'
set multiplot layout 2,1 title 'Delta robot: MuJoCo (equality connect, soft) against vtdyn (exact), same state and motor torques'
set title 'largest reaction error (|f_MuJoCo - f_vtdyn|)'
set ylabel 'force error (N)'
set logscale y
set format y '%.0e'
set key outside right
plot csv using 't_s':'ball_err_N_tight' with lines lw 2 lc 1 title 'ball joints, tight', \
     csv using 't_s':'mot_err_N_tight' with lines lw 2 dt 2 lc 1 title 'motor bearings, tight', \
     csv using 't_s':'ball_err_N_default' with lines lw 2 lc 2 title 'ball joints, default', \
     csv using 't_s':'mot_err_N_default' with lines lw 2 dt 2 lc 2 title 'motor bearings, default'
unset logscale y
set format y '%g'
set title 'ball joint 1a: |force| in each'
set ylabel 'force (N)'
plot csv using 't_s':'vt_ball1a_N' with lines lw 3 lc rgb 'black' title 'vtdyn', \
     csv using 't_s':'mj_ball1a_N_tight' with lines lw 1 lc 1 title 'MuJoCo, tight', \
     csv using 't_s':'mj_ball1a_N_default' with lines lw 1 lc 2 title 'MuJoCo, default'
unset multiplot
