# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
11.21 13.1309776 12.421684
13.58 16.4075057 15.4929089
16.21 19.8362356 18.6976453
19.14 23.6368583 22.2407454
23.2 28.9999563 27.2262486
27.69 35.5088958 33.2578605
32.79 42.3056488 39.5371747
38.58 49.7968785 46.4387591
45.8 58.5225486 54.4554561
52.89 66.882538 62.1165828
62.57 74.3180019 68.9161238
72.77 83.1143616 76.9444433
EOD
$p1 << EOD
1674 1776.67009 1776.67009
1929 2052.60415 2052.60415
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
4943 4038.75279 4199.23474
5313 4469.94208 4658.17767
5650 4895.61953 5113.0857
5978 5310.34551 5557.92476
6382 5714.92413 5993.33526
6806 6110.06569 6419.89246
7193 6496.40129 6838.11541
7571 6874.49466 7248.47433
7963 7244.85187 7651.39683
8301 7607.92919 8047.27311
8577 7964.13975 8436.4604
8879 8389.96072 9196.05413
EOD
$p4 << EOD
11.21 7.15356198 7.62164904
13.58 9.70067042 10.4057581
16.21 12.7742036 13.7870566
19.14 16.3823145 17.7795901
23.2 20.5510927 22.4171573
27.69 25.3043829 27.7309833
32.79 30.664082 33.7500214
38.58 36.6503846 40.501208
45.8 43.2819878 48.0096804
52.89 50.576264 56.2989631
62.57 58.5494072 65.3911291
72.77 69.2178934 86.0659664
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT4125_540kv.csv: T-Motor AT4125 540KV + Castle Phoenix 125 + APC E 15.0x8.0\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 23.5 %, plain DC 15.6 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:87.2701]
set yrange [0:87.2701]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 10.1 %, plain DC 10.1 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:6756.53]
set yrange [0:6756.53]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 5.79 %, plain DC 4.79 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:83.2174]
set yrange [0:83.2174]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 10.7 %, plain DC 6.42 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3634.88:9655.86]
set yrange [3634.88:9655.86]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 12.8 %, plain DC 10.2 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:90.3693]
set yrange [0:90.3693]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
