# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
11.63 10.330082 10.3289165
13.82 12.5207376 12.5192542
15.84 14.6621943 14.6603938
18.17 16.9367922 16.9346208
20.4 19.3173881 19.3148102
22.93 22.2450732 22.2419767
26 25.8715564 25.8678034
30.26 30.7464052 30.7417091
34.78 36.1956126 36.1898622
45.13 47.5572052 47.549116
49.57 52.3824791 52.3733532
EOD
$p1 << EOD
8205 5487.95292 5489.05927
8704 6148.63234 6149.87932
9162 6834.0613 6835.43411
9519 7497.51549 7499.02153
9844 8156.16969 8157.80894
10207 8774.69958 8776.49427
10630 9336.30517 9338.27749
11085 9799.28739 9801.48916
11611 10253.8696 10256.3008
12479 11140.7583 11143.6263
12788 11842.0107 12521.7768
EOD
$p2 << EOD
11.63 7.51350533 7.51349178
13.82 9.52712012 9.52710294
15.84 11.6538324 11.6538114
18.17 14.0632886 14.0632633
20.4 16.6989399 16.6989098
22.93 19.8058309 19.8057952
26 23.4405104 23.4404681
30.26 28.036519 28.0364685
34.78 33.0220858 33.0220263
45.13 43.8226014 43.8225224
49.57 49.5703498 51.5819567
EOD
set terminal pngcairo size 1200,1200 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 2,2 title "TMotor_AT2814_1200kv.csv: T-Motor AT2814 1200KV + Castle Phoenix 125 (measured torque as the load)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, datasheet R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 5.48 %, plain DC 5.49 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:55.0016]
set yrange [0:55.0016]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 17.6 %, plain DC 17.1 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [4939.16:13427.4]
set yrange [4939.16:13427.4]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 15.7 %, plain DC 16 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:54.1611]
set yrange [0:54.1611]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
