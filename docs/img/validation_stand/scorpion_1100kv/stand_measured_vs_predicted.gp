# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
6.6 3.35520345 3.24954245
11.2 6.56135509 6.35895501
17.3 11.645344 11.2584844
25.3 19.5304342 18.7949478
35.3 30.708327 29.3626837
46.7 46.0585362 43.7681214
58.5 63.5955498 60.0340583
EOD
$p1 << EOD
10231 9897.16786 10082.2909
12228 12072.6443 12363.2369
14114 14029.9587 14458.6662
15885 15763.0487 16375.0723
17285 17183.9143 18024.4554
18862 18408.6178 19510.3217
19862 18457.744 20797.6841
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
set title "DC current at the measured rpm\nMAE dynosize 24.2 %, plain DC 25.8 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:66.7753]
set yrange [0:66.7753]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 2.28 %, plain DC 2.93 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [8907.45:21837.6]
set yrange [8907.45:21837.6]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 24.1 %, plain DC 25 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:65.5011]
set yrange [0:65.5011]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
