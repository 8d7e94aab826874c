# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
6.6 3.35520345 3.35524289
11.2 6.56135509 6.56145947
17.3 11.645344 11.6455827
25.3 19.5304342 19.5309386
35.3 30.708327 30.7093099
46.7 46.0585362 46.0602681
58.5 63.5955498 63.5983012
EOD
$p1 << EOD
10231 9897.16786 9897.01954
12228 12072.6443 12072.4077
14114 14029.9587 14029.6066
15885 15763.0487 15762.5432
17285 17183.9143 17183.2176
18862 18408.6178 18407.7027
19862 18457.744 19426.1441
EOD
$p2 << EOD
6.6 3.25279972 3.25279385
11.2 6.48503036 6.48501866
17.3 11.5833704 11.5833495
25.3 19.4002402 19.4002052
35.3 30.5576762 30.5576211
46.7 45.1593511 45.1592697
58.5 60.064993 62.5024815
EOD
set terminal pngcairo size 1200,1200 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 2,2 title "Scorpion_1100kv.csv: Scorpion 1100KV + Castle Phoenix 125 (measured torque as the load)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, datasheet R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 24.2 %, plain DC 24.2 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:66.7782]
set yrange [0:66.7782]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 2.28 %, plain DC 1.59 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [8907.32:20855.1]
set yrange [8907.32:20855.1]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 24.1 %, plain DC 24.7 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:65.6276]
set yrange [0:65.6276]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
