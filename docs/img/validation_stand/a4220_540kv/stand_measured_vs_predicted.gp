# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
2.95 2.87557694 2.73708576
6.29 6.29320203 6.00339508
10.48 10.8891296 10.3706757
16.38 17.3395465 16.4684276
22.75 24.3192514 23.0324944
28.76 31.4555296 29.7056847
36.09 39.5560006 37.263237
46.5 51.634896 48.4671394
56.31 62.7911162 58.775326
67.99 76.3040553 71.1945782
97.1 109.397689 101.330526
101.2 115.767555 107.126699
EOD
$p1 << EOD
2944 2663.60134 2763.45475
3909 3641.78036 3799.16616
4678 4401.4539 4621.16646
5434 5134.55968 5426.18773
6040 5729.61434 6088.36351
6502 6140.95008 6562.02601
6968 6595.89082 7079.2935
7504 7081.36375 7651.06502
7921 7476.08933 8117.70609
8321 7834.54875 8557.66972
8999 8149.83765 9531.52173
9204 8152.5926 9578.94961
EOD
$p2 << EOD
2.95 2.6327948 2.58367769
6.29 5.92078163 5.8520969
10.48 10.344879 10.2597461
16.38 16.5499548 16.4479544
22.75 23.3059654 23.1895937
28.76 30.0637181 29.9360967
36.09 37.8973902 37.7574765
46.5 49.3976887 49.2431871
56.31 60.119872 59.9530729
67.99 72.9849459 72.8054294
97.1 102.017687 105.949549
101.2 106.365157 110.473442
EOD
set terminal pngcairo size 1200,1200 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 2,2 title "A4220_540kv_stand_test.csv: A-4220 540KV + Castle Phoenix 125 (measured torque as the load)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 8.34 %, plain DC 3.72 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:121.556]
set yrange [0:121.556]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 6.81 %, plain DC 2.58 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [0:10057.9]
set yrange [0:10057.9]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 5.12 %, plain DC 5.86 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:115.997]
set yrange [0:115.997]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
