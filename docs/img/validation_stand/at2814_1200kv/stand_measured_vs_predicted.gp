# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
11.63 10.330082 9.80959211
13.82 12.5207376 11.8699543
15.84 14.6621943 13.8818806
18.17 16.9367922 16.0060098
20.4 19.3173881 18.2221148
22.93 22.2450732 20.9404613
26 25.8715564 24.3022944
30.26 30.7464052 28.7979594
34.78 36.1956126 33.8235431
45.13 47.5572052 44.2474371
49.57 52.3824791 48.6575469
EOD
$p1 << EOD
8205 5487.95292 5936.7635
8704 6148.63234 6653.55325
9162 6834.0613 7389.18619
9519 7497.51549 8105.79753
9844 8156.16969 8817.60887
10207 8774.69958 9498.15543
10630 9336.30517 10130.6372
11085 9799.28739 10685.1679
11611 10253.8696 11231.2985
12479 11140.7583 12292.4246
12788 11842.0107 13738.3279
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
set title "DC current at the measured rpm\nMAE dynosize 5.48 %, plain DC 8.3 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:55.0016]
set yrange [0:55.0016]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 17.6 %, plain DC 11.2 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [0:14425.2]
set yrange [0:14425.2]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 15.7 %, plain DC 16.3 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:54.0507]
set yrange [0:54.0507]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
