# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
5.15 4.70307644 4.70406509
6.71 6.28776043 6.28916986
8.5 8.06051064 8.06242265
11.18 10.4393308 10.4419579
13.7 12.8505162 12.8539076
16.9 16.1318112 16.1362945
20.26 19.2961974 19.3017801
24.56 22.9746639 22.9815762
29.2 26.7778027 26.7861365
38.47 34.9196462 34.9311679
44.28 38.9413179 38.9544708
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
4423 4178.05308 4177.28709
4888 4635.35472 4634.45655
5313 5080.81591 5079.78918
5785 5506.15985 5504.99533
6192 5927.04638 5925.73938
6664 6332.7043 6331.25716
7056 6725.92928 6724.33888
7454 7106.67841 7104.95093
7818 7474.40206 7472.53267
8481 8185.16018 8183.01686
8762 8598.15643 8874.31204
EOD
$p4 << EOD
5.15 3.99439858 3.99311618
6.71 5.39126451 5.38941227
8.5 7.05369037 7.05106697
11.18 8.99581115 8.9922811
13.7 11.2488651 11.2442346
16.9 13.7953373 13.7893853
20.26 16.642328 16.6348694
24.56 19.7935784 19.7843387
29.2 23.2560595 23.2448569
38.47 31.1765525 31.1605519
44.28 36.6545141 40.5807294
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT3520_550kv.csv: T-Motor AT3520 550KV + Castle Phoenix 125 + APC 14x7E (PER3, computed)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, datasheet R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 7.12 %, plain DC 7.09 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:46.494]
set yrange [0:46.494]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 5.55 %, plain DC 5.55 %"
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
set title "speed from the throttle\nMAE dynosize 4.39 %, plain DC 4.35 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3759.56:9318.03]
set yrange [3759.56:9318.03]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 19 %, plain DC 18.2 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:46.494]
set yrange [0:46.494]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
