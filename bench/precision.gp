# Charts of bench_precision: work-precision (CPU time against achieved error) and drift.
#   gnuplot -e "dir='build/bench'" bench/precision.gp
if (!exists("dir")) dir = '.'
wp = dir.'/work_precision.csv'
dr = dir.'/drift.csv'
set datafile separator ','
set terminal pngcairo size 1100,480 font ',10' noenhanced
set grid
forms = 'index1 baumgarte projection ggl ode'
sel(scene, form) = sprintf("< awk -F, 'NR==1 || ($1==\"%s\" && $2==\"%s\")' %s", scene, form, wp)
# MuJoCo's curves (bench_precision built with -Dmujoco_dir): whichever of mujoco_rk4 and
# mujoco_euler the CSV has, on the double-link panel; their rtol column is the time step
mj = system(sprintf("awk -F, '$1==\"double_link\" && $2 ~ /^mujoco_/ {print $2}' %s | sort -ru | tr '\n' ' '", wp))
mjtitle(f) = f eq 'mujoco_rk4' ? 'MuJoCo RK4, soft lock' : 'MuJoCo Euler (default), soft lock'
mjcolor(f) = f eq 'mujoco_rk4' ? 0x000000 : 0xb22222
mjpoint(f) = f eq 'mujoco_rk4' ? 4 : 6

set output dir.'/work_precision.png'
set multiplot layout 1,2 title 'CPU time against achieved error (IDA rtol 1e-3 .. 1e-12'.(words(mj) > 0 ? '; MuJoCo: time step 1e-2 .. 1e-5 s)' : ')')
set logscale xy
set xlabel 'error'
set ylabel 'CPU time (s)'
set key top left
set title 'double link: reaction vs (29) and first integral, relative'
set offsets 0, 0, graph 0.3, 0  # room above the curves for the key
plot for [f in forms] sel('double_link', f) using 'error':'cpu_s' with linespoints lw 2 title f, \
     for [f in mj] sel('double_link', f) using 'error':'cpu_s' with linespoints lw 2 dt 2 pt mjpoint(f) \
         lc rgb mjcolor(f) title mjtitle(f)
set key top right
set offsets 0, 0, 0, 0
set title 'five-link arm: forward-check tip deviation, m'
plot for [f in forms] sel('five_link', f) using 'error':'cpu_s' with linespoints lw 2 title f
unset multiplot

dsel(scene, form) = sprintf("< awk -F, 'NR==1 || ($1==\"%s\" && $2==\"%s\")' %s", scene, form, dr)
set terminal pngcairo size 1100,800 font ',10' noenhanced
set output dir.'/drift.png'
set multiplot layout 3,2 title 'Constraint drift and energy error at IDA rtol 1e-6'
set logscale y
unset logscale x
set xlabel 't (s)'
set format y '%.0e'
set key bottom right
set title 'four-bar (free, ~100 crank revolutions): max |Phi|'
set ylabel '|Phi|'
plot for [f in forms] dsel('fourbar', f) using 't_s':(column('phi_norm') + 1e-18) with lines lw 1.5 title f
set title 'four-bar: max |Phi_q qdot + Phi_t|'
set ylabel '|Phi dot|'
plot for [f in forms] dsel('fourbar', f) using 't_s':(column('phidot_norm') + 1e-18) with lines lw 1.5 title f
set title 'double link, 100 s (linear lock: no drift): max |Phi|'
set ylabel '|Phi|'
plot for [f in forms] dsel('double_link', f) using 't_s':(column('phi_norm') + 1e-22) with lines lw 1.5 title f
set title 'energy error |E(t) - E(0)|, four-bar'
set ylabel 'J'
plot for [f in forms] dsel('fourbar', f) using 't_s':(abs(column('energy_error')) + 1e-16) with lines lw 1.5 title f
set title 'energy error, double link'
plot for [f in forms] dsel('double_link', f) using 't_s':(abs(column('energy_error')) + 1e-16) with lines lw 1.5 title f
set title 'energy error, IFToMM A01 pendulum, 2000 s'
plot for [f in forms] dsel('pendulum', f) using 't_s':(abs(column('energy_error')) + 1e-16) with lines lw 1.5 title f
unset multiplot
