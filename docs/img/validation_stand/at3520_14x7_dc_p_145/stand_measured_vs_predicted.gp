# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
5.15 4.99132103 4.7367958
6.71 7.04413917 6.66551102
8.5 9.43785905 8.90302529
11.18 12.7952593 12.024982
13.7 16.353654 15.3167788
16.9 21.3983821 19.9598341
20.26 26.4573342 24.5934075
24.56 32.5087376 30.1115772
29.2 38.9654777 35.9751283
38.47 53.2734511 48.8959792
44.28 60.5526601 55.4395194
EOD
$p1 << EOD
973 1022.57904 1022.57904
1169 1248.8935 1248.8935
1408 1475.51165 1475.51165
1689 1749.32191 1749.32191
1954 2004.12546 2004.12546
2247 2321.30917 2321.30917
2529 2602.43657 2602.43657
2863 2904.30208 2904.30208
3216 3194.87846 3194.87846
3787 3759.73414 3759.73414
4116 4013.00321 4013.00321
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
4423 4152.00008 4313.98588
4888 4588.45479 4771.36638
5313 4995.49524 5208.49922
5785 5380.41993 5623.73936
6192 5755.713 6030.19889
6664 6112.94872 6418.4691
7056 6454.84572 6791.22657
7454 6782.12409 7149.0323
7818 7095.42262 7492.39594
8481 7692.37411 8148.71487
8762 8035.28727 8780.13712
EOD
$p4 << EOD
5.15 4.12959374 4.39005452
6.71 5.66506119 6.13623601
8.5 7.60712676 8.30953059
11.18 9.89299061 10.8874823
13.7 12.5824992 13.9428687
16.9 15.6484281 17.448205
20.26 19.1040821 21.4221022
24.56 22.9514329 25.8697105
29.2 27.1892871 30.7920908
38.47 36.930215 42.1813267
44.28 43.6718828 55.8677554
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT3520_550kv.csv: T-Motor AT3520 550KV + Castle Phoenix 125 + APC E 14.0x7.0\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 22.8 %, plain DC 15.5 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:63.5803]
set yrange [0:63.5803]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 3.13 %, plain DC 3.13 %"
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
set title "speed from the throttle\nMAE dynosize 7.72 %, plain DC 2.91 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3736.8:9219.14]
set yrange [3736.8:9219.14]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 8.86 %, plain DC 7.77 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:58.6611]
set yrange [0:58.6611]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
