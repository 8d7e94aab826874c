# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
11.21 9.45066703 9.01551128
13.58 11.7094568 11.1594677
16.21 14.0587989 13.3846657
19.14 16.6448827 15.8293556
23.2 20.2928446 19.2699459
27.69 24.6937887 23.4104475
32.79 29.2770821 27.71187
38.58 34.3222641 32.4356787
45.8 40.1756696 37.9037383
52.89 45.850993 43.192169
62.57 50.9058074 47.893399
72.77 56.8849721 53.4445647
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
11.21 10.1200181 9.63903487
13.58 12.6255655 12.0101498
16.21 15.4086132 14.6341799
19.14 18.5885856 17.6231087
23.2 23.1893674 21.9328777
27.69 28.2768014 26.6934943
32.79 34.1757126 32.1848421
38.58 40.9496669 38.4664006
45.8 48.9612668 45.8706224
52.89 57.0319929 53.2997771
62.57 68.0127169 63.294753
72.77 79.2546455 73.5149148
EOD
$p3 << EOD
4943 4183.32494 4322.91253
5313 4646.26358 4810.38574
5650 5105.83676 5295.4099
5978 5554.52314 5771.36571
6382 5994.31633 6238.83701
6806 6424.57197 6698.11027
7193 6846.75597 7149.70323
7571 7260.63218 7593.52936
7963 7666.76374 8030.32838
8301 8065.42808 8457.92425
8577 8454.7729 8878.8373
8879 8920.70811 9699.50248
EOD
$p4 << EOD
11.21 5.85320929 6.13683262
13.58 7.91650836 8.35000355
16.21 10.4107079 11.0509349
19.14 13.3624665 14.2561937
23.2 16.7816076 17.9960919
27.69 20.7075451 22.3032392
32.79 25.1493746 27.2036658
38.58 30.1383038 32.7338971
45.8 35.6922242 38.9111381
52.89 41.8319552 45.8225401
62.57 48.6201694 53.4414559
72.77 57.748835 70.9555651
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT4125_540kv.csv: T-Motor AT4125 540KV + Castle Phoenix 125 + APC 15x8E (PER3, computed)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 13.9 %, plain DC 18.5 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:76.4085]
set yrange [0:76.4085]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 5.83 %, plain DC 5.83 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:5813.85]
set yrange [0:5813.85]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 5.79 %, plain DC 4.79 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:83.2174]
set yrange [0:83.2174]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 6.14 %, plain DC 4.33 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3764.99:10184.5]
set yrange [3764.99:10184.5]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 28.3 %, plain DC 21.7 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:76.4085]
set yrange [0:76.4085]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
