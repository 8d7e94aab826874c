# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
11.63 10.9288989 10.2532131
13.82 13.2834821 12.4357354
15.84 15.5884787 14.5695994
18.17 18.0545625 16.8365627
20.4 20.6452103 19.2094078
22.93 23.8409067 22.1278118
26 27.8067186 25.7430145
30.26 33.1694253 30.603072
34.78 39.1640108 36.0361314
45.13 51.7360157 47.3646672
49.57 57.0980545 52.1760358
EOD
$p1 << EOD
8205 4910.29644 5506.40896
8704 5497.54962 6168.18817
9162 6117.28142 6854.60114
9519 6711.17391 7519.09723
9844 7300.2664 8178.79332
10207 7837.64098 8798.53875
10630 8306.49763 9361.53354
11085 8649.67914 9826.31014
11611 8984.46066 10282.6867
12479 9643.3416 11172.9906
12788 10255.7096 12552.3022
EOD
$p2 << EOD
11.63 7.51350533 7.47143303
13.82 9.52712012 9.47978684
15.84 11.6538324 11.601238
18.17 14.0632886 14.0054325
20.4 16.6989399 16.6358216
22.93 19.8058309 19.7374497
26 23.4405104 23.3668653
30.26 28.036519 27.9576083
34.78 33.0220858 32.9379088
45.13 43.8226014 43.7278902
49.57 49.5703498 51.4768099
EOD
set terminal pngcairo size 1200,1200 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 2,2 title "TMotor_AT2814_1200kv.csv: T-Motor AT2814 1200KV + Castle Phoenix 125 (measured torque as the load)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 6.94 %, plain DC 5.68 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:59.953]
set yrange [0:59.953]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 27.1 %, plain DC 16.9 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [0:13427.4]
set yrange [0:13427.4]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 15.7 %, plain DC 16.3 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:54.0507]
set yrange [0:54.0507]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
