# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
2.95 2.98279424 2.81444336
6.29 6.57075715 6.20654171
10.48 11.4416553 10.7778406
16.38 18.3281271 17.1999669
22.75 25.8300435 24.1530986
28.76 33.554056 31.2645724
36.09 42.3461859 39.3382261
46.5 55.5465573 51.3794369
56.31 67.7931354 62.5020531
67.99 82.7165544 75.9751924
97.1 119.638559 108.972866
EOD
$p1 << EOD
2944 7461.61266 7594.25376
3909 7755.2846 7964.34932
4678 7918.46901 8210.32598
5434 8025.89994 8413.28644
6040 8082.8401 8559.3875
6502 8058.35561 8617.69527
6968 8044.87361 8687.00553
7504 7964.78372 8721.55108
7921 7884.38686 8739.12144
8321 7600.93548 8711.52639
8999 6971.49626 8650.44528
EOD
$p2 << EOD
2.95 6.89435248 6.76573227
6.29 11.9312721 11.7928619
10.48 17.8189908 17.6723499
16.38 25.1626864 25.0076042
22.75 32.4991056 32.3368306
28.76 39.553652 39.3857455
36.09 47.1461581 46.9720988
46.5 57.9856966 57.8043342
56.31 67.57331 67.4004272
67.99 77.8034764 78.6332421
97.1 102.017687 105.949549
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
set title "DC current at the measured rpm\nMAE dynosize 14.4 %, plain DC 7.56 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:125.62]
set yrange [0:125.62]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 43.6 %, plain DC 47.8 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [0:9448.95]
set yrange [0:9448.95]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 47.5 %, plain DC 46.9 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:111.247]
set yrange [0:111.247]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
