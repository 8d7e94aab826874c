# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
5.15 4.70307644 4.46951504
6.71 6.28776043 5.96790748
8.5 8.06051064 7.63896153
11.18 10.4393308 9.87449431
13.7 12.8505162 12.1336959
16.9 16.1318112 15.1991179
20.26 19.2961974 18.1470953
24.56 22.9746639 21.5647758
29.2 26.7778027 25.0898237
38.47 34.9196462 32.6100373
44.28 38.9413179 36.3142648
EOD
$p1 << EOD
973 932.905406 932.905406
1169 1141.40771 1141.40771
1408 1351.01269 1351.01269
1689 1605.13773 1605.13773
1954 1842.64299 1842.64299
2247 2139.73561 2139.73561
2529 2404.07076 2404.07076
2863 2689.5526 2689.5526
3216 2965.30893 2965.30893
3787 3505.78385 3505.78385
4116 3749.60634 3749.60634
EOD
$p2 << EOD
5.15 4.99112687 4.73661601
6.71 6.68056089 6.33066243
8.5 8.73718462 8.26121664
11.18 11.7160551 11.0426384
13.7 14.7833556 13.8948269
16.9 18.6420442 17.4770457
20.26 22.6413288 21.1717378
24.56 27.8801756 25.9819816
29.2 33.8107571 31.3975841
38.47 45.4148502 41.9673957
44.28 52.7325165 48.570063
EOD
$p3 << EOD
4423 4178.05308 4337.56325
4888 4635.35472 4822.32516
5313 5080.81591 5294.86943
5785 5506.15985 5749.20037
6192 5927.04638 6199.84652
6664 6332.7043 6635.68317
7056 6725.92928 7059.27388
7454 7106.67841 7469.68046
7818 7474.40206 7867.88811
8481 8185.16018 8638.03237
8762 8598.15643 9389.63746
EOD
$p4 << EOD
5.15 3.99439858 4.22674802
6.71 5.39126451 5.73915461
8.5 7.05369037 7.56173658
11.18 8.99581115 9.69261557
13.7 11.2488651 12.1802959
16.9 13.7953373 15.0033712
20.26 16.642328 18.1730439
24.56 19.7935784 21.7054486
29.2 23.2560595 25.5904677
38.47 31.1765525 34.5555994
44.28 36.6545141 45.313637
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT3520_550kv.csv: T-Motor AT3520 550KV + Castle Phoenix 125 + APC 14x7E (PER3, computed)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 7.12 %, plain DC 12.5 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:46.494]
set yrange [0:46.494]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 5.55 %, plain DC 5.55 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:4321.8]
set yrange [0:4321.8]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 9.78 %, plain DC 5.38 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:55.3691]
set yrange [0:55.3691]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 4.39 %, plain DC 1.34 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3760.25:9859.12]
set yrange [3760.25:9859.12]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 19 %, plain DC 11.4 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:47.5793]
set yrange [0:47.5793]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
