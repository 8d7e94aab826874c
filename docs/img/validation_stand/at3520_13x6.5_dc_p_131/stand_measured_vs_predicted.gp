# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
4.96 4.96506201 4.7353249
6 6.10161499 5.81455844
7.26 7.53435513 7.17212791
8.88 9.45307528 8.98575149
10.87 11.7097613 11.1113221
13.47 15.0452044 14.2391779
16.12 18.4193118 17.3919295
19.27 22.3429616 21.0459212
22.6 26.5137091 24.9178346
30.77 37.2934176 34.8770525
34.89 42.1970701 39.3888197
EOD
$p1 << EOD
912 905.84456 905.84456
1053 1040.56107 1040.56107
1208 1197.50538 1197.50538
1396 1390.894 1390.894
1619 1603.89918 1603.89918
1890 1899.97162 1899.97162
2140 2174.51421 2174.51421
2412 2470.85468 2470.85468
2711 2763.66804 2763.66804
3289 3446.81917 3446.81917
3575 3728.90778 3728.90778
EOD
$p2 << EOD
4.96 4.67843765 4.46729307
6 5.77268332 5.50786104
7.26 7.11404495 6.7814056
8.88 8.8886212 8.46278727
10.87 11.1338422 10.5798269
13.47 14.1640736 13.4297655
16.12 17.2034839 16.27937
19.27 20.8596601 19.693995
22.6 25.0243195 23.5656238
30.77 34.6581447 32.5012163
34.89 39.9966863 37.4114713
EOD
$p3 << EOD
4834 4277.87091 4420.94573
5181 4751.90345 4920.52882
5558 5214.18744 5409.60326
5990 5665.49845 5888.75379
6404 6101.80762 6349.2541
6895 6515.81568 6788.95376
7313 6911.52256 7214.64942
7732 7295.8948 7629.37191
8119 7666.83764 8030.68656
8940 8375.46673 8800.09751
9252 8792.07129 9552.92918
EOD
$p4 << EOD
4.96 3.47642028 3.6492071
6 4.72531451 4.99321698
7.26 6.22424594 6.61598913
8.88 7.98840229 8.53639251
10.87 10.0169827 10.7994379
13.47 12.4321263 13.5196763
16.12 15.2016624 16.6163707
19.27 18.313757 20.1136765
22.6 21.7611901 24.0057273
30.77 29.7059115 33.0327661
34.89 35.2912716 44.0098843
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT3520_550kv.csv: T-Motor AT3520 550KV + Castle Phoenix 125 + APC E 13.0x6.5\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 11 %, plain DC 6.51 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:44.3069]
set yrange [0:44.3069]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 1.79 %, plain DC 1.79 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:3915.35]
set yrange [0:3915.35]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 6.56 %, plain DC 4.79 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:41.9965]
set yrange [0:41.9965]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 6.33 %, plain DC 2.63 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3850.08:10030.6]
set yrange [3850.08:10030.6]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 10 %, plain DC 9.47 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:46.2104]
set yrange [0:46.2104]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
