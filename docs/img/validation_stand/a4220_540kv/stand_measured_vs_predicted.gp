# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
2.95 2.87557694 2.8757502
6.29 6.29320203 6.29365262
10.48 10.8891296 10.8900295
16.38 17.3395465 17.3411606
22.75 24.3192514 24.3217219
28.76 31.4555296 31.4589655
36.09 39.5560006 39.5605729
46.5 51.634896 51.641313
56.31 62.7911162 62.7993278
67.99 76.3040553 76.31459
97.1 109.397689 109.414536
101.2 115.767555 115.785632
EOD
$p1 << EOD
2944 2663.60134 2663.39525
3909 3641.78036 3641.44892
4678 4401.4539 4400.98665
5434 5134.55968 5133.93573
6040 5729.61434 5728.84414
6502 6140.95008 6140.04407
6968 6595.89082 6594.849
7504 7081.36375 7080.1339
7921 7476.08933 7474.70278
8321 7834.54875 7832.9846
8999 8149.83765 8624.25373
9204 8152.5926 8633.24311
EOD
$p2 << EOD
2.95 2.6327948 2.63279005
6.29 5.92078163 5.92077096
10.48 10.344879 10.3448603
16.38 16.5499548 16.549925
22.75 23.3059654 23.3059234
28.76 30.0637181 30.0636639
36.09 37.8973902 37.8973219
46.5 49.3976887 49.3975997
56.31 60.119872 60.1197636
67.99 72.9849459 72.9848143
97.1 102.017687 106.157652
101.2 106.365157 110.681545
EOD
set terminal pngcairo size 1200,1200 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 2,2 title "A4220_540kv_stand_test.csv: A-4220 540KV + Castle Phoenix 125 (measured torque as the load)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, datasheet R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 8.34 %, plain DC 8.35 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:121.575]
set yrange [0:121.575]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 6.81 %, plain DC 5.95 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [0:9664.2]
set yrange [0:9664.2]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 5.12 %, plain DC 5.83 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:116.216]
set yrange [0:116.216]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
