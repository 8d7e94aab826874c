# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
11.21 9.45066703 9.4502996
13.58 11.7094568 11.7089793
16.21 14.0587989 14.0582014
19.14 16.6448827 16.6441478
23.2 20.2928446 20.291907
27.69 24.6937887 24.6925954
32.79 29.2770821 29.2756112
38.58 34.3222641 34.3204758
45.8 40.1756696 40.1735
52.89 45.850993 45.8484399
62.57 50.9058074 50.9029034
72.77 56.8849721 56.8816431
EOD
$p1 << EOD
1674 1594.20996 1594.20996
1929 1845.16027 1845.16027
2205 2090.19799 2090.19799
2492 2343.78388 2343.78388
2864 2677.60367 2677.60367
3233 3052.8163 3052.8163
3655 3418.35214 3418.35214
4081 3797.04908 3797.04908
4541 4211.87385 4211.87385
4951 4589.41582 4589.41582
5163 4910.66205 4910.66205
5537 5275.44526 5275.44526
EOD
$p2 << EOD
11.21 10.1200181 10.1196054
13.58 12.6255655 12.6250231
16.21 15.4086132 15.4079162
19.14 18.5885856 18.5877018
23.2 23.1893674 23.1881977
27.69 28.2768014 28.2753099
32.79 34.1757126 34.1738182
38.58 40.9496669 40.9472849
45.8 48.9612668 48.9582823
52.89 57.0319929 57.0283712
62.57 68.0127169 68.008115
72.77 79.2546455 79.2490274
EOD
$p3 << EOD
4943 4183.32494 4183.45142
5313 4646.26358 4646.41244
5650 5105.83676 5106.00862
5978 5554.52314 5554.71961
6382 5994.31633 5994.53812
6806 6424.57197 6424.81914
7193 6846.75597 6847.02961
7571 7260.63218 7260.93198
7963 7666.76374 7667.09077
8301 8065.42808 8065.78006
8577 8454.7729 8455.15251
8879 8920.70811 9213.31715
EOD
$p4 << EOD
11.21 5.85320929 5.8535066
13.58 7.91650836 7.91694272
16.21 10.4107079 10.4113278
19.14 13.3624665 13.3633125
23.2 16.7816076 16.7827291
27.69 20.7075451 20.7090088
32.79 25.1493746 25.1512328
38.58 30.1383038 30.1406363
45.8 35.6922242 35.6950912
52.89 41.8319552 41.8354828
62.57 48.6201694 48.6244064
72.77 57.748835 64.10781
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT4125_540kv.csv: T-Motor AT4125 540KV + Castle Phoenix 125 + APC 15x8E (PER3, computed)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, datasheet R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 13.9 %, plain DC 13.9 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:76.4085]
set yrange [0:76.4085]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 5.83 %, plain DC 5.83 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:5813.85]
set yrange [0:5813.85]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 5.79 %, plain DC 5.79 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:83.2174]
set yrange [0:83.2174]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 6.14 %, plain DC 6.41 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3764.99:9673.98]
set yrange [3764.99:9673.98]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 28.3 %, plain DC 27.6 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:76.4085]
set yrange [0:76.4085]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
