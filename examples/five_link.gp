# The paper's Fig. 10 (and the joint torques) from five_link's CSV.
#   gnuplot -e "csv='build/five_link.csv'; out='docs/figures'" examples/five_link.gp
if (!exists("csv")) csv = 'five_link.csv'
if (!exists("out")) out = '.'
set datafile separator ','
set terminal pngcairo size 720,480 font ',10' noenhanced
set grid

set output out.'/five_link_fig10_tip.png'
set title 'Fig. 10: tip of link 5 in the XY plane'
set xlabel 'x (m)'; set ylabel 'y (m)'
set size ratio -1
set key outside bottom center
plot csv using 'tip_x_m':'tip_y_m' with lines lw 2 title 'driven (five point drives)', \
     csv using 'tip_x_fwd_m':'tip_y_fwd_m' every 8 with points pt 6 title 'forward: joint torques applied'
set size noratio

set output out.'/five_link_torques.png'
set title 'Joint torques that draw the circle'
set key top right
set xlabel 't (s)'; set ylabel 'torque (N m)'
plot for [j=1:5] csv using 't_s':'tau'.j.'_Nm' with lines lw 2 title 'joint '.j
