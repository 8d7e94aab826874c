# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
5.15 4.99132103 4.99241639
6.71 7.04413917 7.04584919
8.5 9.43785905 9.44035241
11.18 12.7952593 12.7989438
13.7 16.353654 16.3586962
16.9 21.3983821 21.4054796
20.26 26.4573342 26.4666162
24.56 32.5087376 32.520765
29.2 38.9654777 38.9805654
38.47 53.2734511 53.2957115
44.28 60.5526601 60.57873
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
5.15 4.99112687 4.99222216
6.71 6.68056089 6.68212389
8.5 8.73718462 8.73937571
11.18 11.7160551 11.7192406
13.7 14.7833556 14.787632
16.9 18.6420442 18.6477271
20.26 22.6413288 22.6485688
24.56 27.8801756 27.889616
29.2 33.8107571 33.8228493
38.47 45.4148502 45.4322775
44.28 52.7325165 52.7536432
EOD
$p3 << EOD
4423 4149.93682 4149.15278
4888 4588.45479 4587.58593
5313 4995.49524 4994.48571
5785 5380.41993 5379.26968
6192 5755.713 5754.41901
6664 6112.94872 6111.5124
7056 6454.84572 6453.26858
7454 6782.12409 6780.40828
7818 7095.42262 7093.57078
8481 7692.37411 7690.25506
8762 8035.28727 8262.20718
EOD
$p4 << EOD
5.15 4.14030047 4.13891978
6.71 5.66506119 5.66267803
8.5 7.60712676 7.60366426
11.18 9.89299061 9.8881792
13.7 12.5824992 12.576014
16.9 15.6484281 15.6399485
20.26 19.1040821 19.0932664
24.56 22.9514329 22.9379276
29.2 27.1892871 27.172731
38.47 36.930215 36.906366
44.28 43.6718828 48.51118
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT3520_550kv.csv: T-Motor AT3520 550KV + Castle Phoenix 125 + APC E 14.0x7.0\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, datasheet R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 22.8 %, plain DC 22.9 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:63.6077]
set yrange [0:63.6077]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 3.13 %, plain DC 3.13 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:4321.8]
set yrange [0:4321.8]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 9.78 %, plain DC 9.8 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:55.3913]
set yrange [0:55.3913]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 7.72 %, plain DC 7.51 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3734.24:9200.1]
set yrange [3734.24:9200.1]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 8.84 %, plain DC 9.63 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:50.9367]
set yrange [0:50.9367]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
