# The knee four-bar's angles, torques and bearing loads from knee's CSV.
#   gnuplot -e "csv='build/knee.csv'; out='docs/figures'" examples/knee.gp
if (!exists("csv")) csv = 'knee.csv'
if (!exists("out")) out = '.'
set datafile separator ','
set terminal pngcairo size 720,480 font ',10' noenhanced
set grid
set key outside right
set xlabel 't (s)'

set output out.'/knee_angles.png'
set title 'Hip, motor (crank from thigh) and knee (shank from thigh) angles'
set ylabel 'angle (rad)'
plot csv using 't_s':'hip_rad' with lines lw 2 title 'hip', \
     csv using 't_s':'motor_rad' with lines lw 2 title 'motor', \
     csv using 't_s':'knee_rad' with lines lw 2 title 'knee'

set output out.'/knee_torques.png'
set title 'Hip and knee-motor torques'
set ylabel 'torque (N m)'
plot csv using 't_s':'tau_hip_Nm' with lines lw 2 title 'hip', \
     csv using 't_s':'tau_motor_Nm' with lines lw 2 title 'knee motor'

set output out.'/knee_bearings.png'
set title 'Bearing loads'
set ylabel '|force| (N)'
plot csv using 't_s':(sqrt(column('hip_fx_N')**2 + column('hip_fy_N')**2)) with lines lw 2 title 'hip', \
     csv using 't_s':(sqrt(column('motor_fx_N')**2 + column('motor_fy_N')**2)) with lines lw 2 title 'motor (crank)', \
     csv using 't_s':(sqrt(column('knee_fx_N')**2 + column('knee_fy_N')**2)) with lines lw 2 title 'knee', \
     csv using 't_s':(sqrt(column('crank_fx_N')**2 + column('crank_fy_N')**2)) with lines lw 2 title 'crank-coupler', \
     csv using 't_s':(sqrt(column('lever_fx_N')**2 + column('lever_fy_N')**2)) with lines lw 2 dt 2 title 'coupler-lever (planar revolute cut)'
