# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
11.21 13.2574984 13.2568495
13.58 16.4786135 16.4777688
16.21 19.8362356 19.8351774
19.14 23.6368583 23.6355471
23.2 28.9999563 28.9982729
27.69 35.5088958 35.5067407
32.79 42.3056488 42.3029813
38.58 49.7968785 49.7936263
45.8 58.5225486 58.5185927
52.89 66.882538 66.8778878
62.57 74.3180019 74.3127195
72.77 83.1143616 83.1083154
EOD
$p1 << EOD
1674 1745.35991 1745.35991
1929 2036.47108 2036.47108
2205 2323.86185 2323.86185
2492 2644.12158 2644.12158
2864 3070.86259 3070.86259
3233 3557.73634 3557.73634
3655 4037.61855 4037.61855
4081 4539.58254 4539.58254
4541 5095.3622 5095.3622
4951 5603.77227 5603.77227
5163 6004.50336 6004.50336
5537 6434.79009 6434.79009
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
4943 4026.88529 4027.03246
5313 4460.13935 4460.31141
5650 4888.69826 4888.89637
5978 5307.03918 5307.26399
6382 5714.92413 5715.17343
6806 6110.06569 6110.34258
7193 6496.40129 6496.70607
7571 6874.49466 6874.82756
7963 7244.85187 7245.21304
8301 7607.92919 7608.31875
8577 7964.13975 7964.55776
8879 8389.96072 8657.90444
EOD
$p4 << EOD
11.21 7.260304 7.26076015
13.58 9.7998623 9.80052365
16.21 12.8520203 12.8529435
19.14 16.4232052 16.4244511
23.2 20.5510927 20.5527673
27.69 25.3043829 25.3065393
32.79 30.664082 30.666802
38.58 36.6503846 36.6537553
45.8 43.2819878 43.2861013
52.89 50.576264 50.5812172
62.57 58.5494072 58.5553012
72.77 69.2178934 76.6000061
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT4125_540kv.csv: T-Motor AT4125 540KV + Castle Phoenix 125 + APC E 15.0x8.0\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, datasheet R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 23.7 %, plain DC 23.7 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:87.2701]
set yrange [0:87.2701]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 9.85 %, plain DC 9.85 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:6756.53]
set yrange [0:6756.53]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 5.79 %, plain DC 5.79 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:83.2174]
set yrange [0:83.2174]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 10.7 %, plain DC 10.5 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3624.2:9322.95]
set yrange [3624.2:9322.95]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 12.6 %, plain DC 12.6 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:80.43]
set yrange [0:80.43]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
