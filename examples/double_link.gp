# The paper's Figs. 5-8 from double_link's CSV.
#   gnuplot -e "csv='build/double_link.csv'; out='docs/figures'" examples/double_link.gp
if (!exists("csv")) csv = 'double_link.csv'
if (!exists("out")) out = '.'
set datafile separator ','
set terminal pngcairo size 720,480 font ',10'
set grid
set key top left

set output out.'/double_link_fig5_tau2.png'
set title 'Fig. 5: driving torque at joint 2'
set xlabel 't (s)'; set ylabel 'tau_2 (N m)'
plot csv using 't_s':'tau2_Nm' with lines lw 2 title 'vtdyn', \
     csv using 't_s':(-245.25*cos(column('theta_rad'))) every 6 with points pt 6 title '-245.25 cos(theta) (exact)'

set output out.'/double_link_fig6_tip.png'
set title 'Fig. 6: tip of link 2 in the XY plane'
set xlabel 'x (m)'; set ylabel 'y (m)'
set size ratio -1
plot csv using 'tip_x_m':'tip_y_m' with lines lw 2 title 'driven (joint 2 locked)', \
     csv using 'tip_x_fwd_m':'tip_y_fwd_m' every 6 with points pt 6 title 'forward: torque applied'
set size noratio

set output out.'/double_link_fig7_f1x.png'
set title 'Fig. 7: reaction at joint 1, X'
set xlabel 't (s)'; set ylabel 'f_{1x} (N)'
plot csv using 't_s':'f1x_N' with lines lw 2 title 'driven', \
     csv using 't_s':'f1x_fwd_N' every 6 with points pt 6 title 'forward', \
     csv using 't_s':'f1x_exact_N' every 6 with points pt 2 title 'exact (29)'

set output out.'/double_link_fig8_f1y.png'
set title 'Fig. 8: reaction at joint 1, Y'
set ylabel 'f_{1y} (N)'
plot csv using 't_s':'f1y_N' with lines lw 2 title 'driven', \
     csv using 't_s':'f1y_fwd_N' every 6 with points pt 6 title 'forward', \
     csv using 't_s':'f1y_exact_N' every 6 with points pt 2 title 'exact (29)'
