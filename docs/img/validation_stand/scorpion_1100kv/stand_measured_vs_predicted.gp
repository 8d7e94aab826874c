# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
6.6 3.42662294 3.30147572
11.2 6.74379168 6.49310778
17.3 12.0529397 11.5600528
25.3 20.3775549 19.424099
35.3 32.3381631 30.5760552
46.7 48.9077281 45.8924783
58.5 68.094662 63.3917806
EOD
$p1 << EOD
10231 9664.34308 9910.44411
12228 11701.3025 12087.6139
14114 13477.2255 14047.1457
15885 14969.5596 15783.1789
17285 16090.305 17207.7135
18862 16972.0139 18436.61
19862 16668.2514 19459.5902
EOD
$p2 << EOD
6.6 3.25279972 3.20460154
11.2 6.48503036 6.42477826
17.3 11.5833704 11.511061
25.3 19.4002402 19.3158686
35.3 30.5576762 30.4612364
46.7 45.1593511 45.050837
58.5 60.064993 62.3820007
EOD
set terminal pngcairo size 1200,1200 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 2,2 title "Scorpion_1100kv.csv: Scorpion 1100KV + Castle Phoenix 125 (measured torque as the load)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 23.9 %, plain DC 24.6 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:71.4994]
set yrange [0:71.4994]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 7.59 %, plain DC 1.45 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [8697.91:20855.1]
set yrange [8697.91:20855.1]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 24.1 %, plain DC 25 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:65.5011]
set yrange [0:65.5011]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
