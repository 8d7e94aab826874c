# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
11.21 13.9503699 13.0283517
13.58 17.4856217 16.2923391
16.21 21.1984538 19.7088922
19.14 25.3271793 23.4967406
23.2 31.1733106 28.8427359
27.69 38.2951131 35.3319406
32.79 45.7581578 42.1089245
38.58 54.0103681 49.5790735
45.8 63.6527538 58.2808686
52.89 72.9177553 66.6184907
62.57 81.1776351 74.0343788
72.77 90.9706057 82.8078817
EOD
$p1 << EOD
1674 1711.50676 1711.50676
1929 2018.84554 2018.84554
2205 2323.86185 2323.86185
2492 2644.12158 2644.12158
2864 3070.86259 3070.86259
3233 3557.73634 3557.73634
3655 4037.61855 4037.61855
4081 4539.58254 4539.58254
4541 5095.3622 5095.3622
4951 5603.77227 5603.77227
5163 6039.21336 6039.21336
5537 6536.7927 6536.7927
EOD
$p2 << EOD
11.21 10.6456587 10.0270664
13.58 13.3178005 12.5221314
16.21 16.3002438 15.2946491
19.14 19.7215218 18.4634011
23.2 24.6921609 23.0489726
27.69 30.1961496 28.1203927
32.79 36.6175894 34.0017971
38.58 44.0250657 40.7564574
45.8 52.8201588 48.7459809
52.89 61.7204483 56.7950315
62.57 73.9808106 67.7464819
72.77 86.5498218 78.9588207
EOD
$p3 << EOD
4943 3860.43105 4046.27562
5313 4261.9785 4477.76323
5650 4656.79575 4903.76839
5978 5040.06263 5318.84293
6382 5412.73719 5723.78741
6806 5775.65193 6119.3092
7193 6129.53571 6506.03696
7571 6475.03094 6884.53242
7963 6812.70729 7255.29996
8301 7143.07273 7618.79444
8577 7466.58253 7975.42779
8879 7852.57311 8669.57601
EOD
$p4 << EOD
11.21 6.58946587 7.1165707
13.58 8.88255197 9.66317859
16.21 11.6322002 12.7374843
19.14 14.8418726 16.3476827
23.2 18.5311574 20.5199537
27.69 22.7177815 25.27823
32.79 27.4178824 30.6444926
38.58 32.6462279 36.6390172
45.8 38.4163968 43.2805788
52.89 44.7409272 50.5866243
62.57 51.6314414 58.5734189
72.77 60.8199791 76.6491415
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
set title "DC current at the measured rpm\nMAE dynosize 33.3 %, plain DC 22.9 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:95.5191]
set yrange [0:95.5191]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 9.82 %, plain DC 9.82 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:6863.63]
set yrange [0:6863.63]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 10.1 %, plain DC 5.8 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:90.8773]
set yrange [0:90.8773]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 15.6 %, plain DC 10.3 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3474.39:9322.95]
set yrange [3474.39:9322.95]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 21.8 %, plain DC 12.9 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:80.4816]
set yrange [0:80.4816]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
