# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
2.95 2.98279424 2.81444336
6.29 6.57075715 6.20654171
10.48 11.4416553 10.7778406
16.38 18.3281271 17.1999669
22.75 25.8300435 24.1530986
28.76 33.554056 31.2645724
36.09 42.3461859 39.3382261
46.5 55.5465573 51.3794369
56.31 67.7931354 62.5020531
67.99 82.7165544 75.9751924
97.1 119.638559 108.972866
101.2 126.754139 115.32685
EOD
$p1 << EOD
2944 2539.77186 2672.41296
3909 3442.6286 3651.69332
4678 4120.70301 4412.55998
5434 4759.65594 5147.04244
6040 5266.8346 5743.382
6502 5596.57121 6155.91087
6968 5969.91281 6612.04473
7504 6342.40232 7099.16968
7921 6642.97505 7495.27194
8321 6894.7279 7855.29159
8999 6971.49626 8650.44528
9204 6924.03635 8660.25246
EOD
$p2 << EOD
2.95 2.6327948 2.58367769
6.29 5.92078163 5.8520969
10.48 10.344879 10.2597461
16.38 16.5499548 16.4479544
22.75 23.3059654 23.1895937
28.76 30.0637181 29.9360967
36.09 37.8973902 37.7574765
46.5 49.3976887 49.2431871
56.31 60.119872 59.9530729
67.99 72.9849459 72.8054294
97.1 102.017687 105.949549
101.2 106.365157 110.473442
EOD
set terminal pngcairo size 1200,1200 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 2,2 title "A4220_540kv_stand_test.csv: A-4220 540KV + Castle Phoenix 125 (measured torque as the load)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 15.3 %, plain DC 8.09 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:133.092]
set yrange [0:133.092]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 15.6 %, plain DC 5.69 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [0:9664.2]
set yrange [0:9664.2]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 5.12 %, plain DC 5.86 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:115.997]
set yrange [0:115.997]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
