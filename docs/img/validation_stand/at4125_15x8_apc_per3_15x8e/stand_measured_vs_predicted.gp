# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
11.21 9.9175223 9.35983496
13.58 12.3175318 11.6088151
16.21 14.8211267 13.9488315
19.14 17.5841545 16.525318
23.2 21.493369 20.1606247
27.69 26.224373 24.5472728
32.79 31.1665826 29.1164933
38.58 36.6225018 34.1468867
45.8 42.9699185 39.9838164
52.89 49.1425751 45.6437041
62.57 54.6527408 50.6851087
72.77 61.1839213 56.648739
EOD
$p1 << EOD
1674 1594.20996 1594.20996
1929 1845.16027 1845.16027
2205 2090.19799 2090.19799
2492 2343.78388 2343.78388
2864 2677.60367 2677.60367
3233 3052.8163 3052.8163
3655 3418.35214 3418.35214
4081 3797.04908 3797.04908
4541 4211.87385 4211.87385
4951 4589.41582 4589.41582
5163 4910.66205 4910.66205
5537 5275.44526 5275.44526
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
4943 4025.12855 4190.88257
5313 4460.89832 4654.10095
5650 4892.3167 5113.94789
5978 5312.04384 5562.96108
6382 5721.58234 6003.09281
6806 6121.79711 6433.69431
7193 6512.65704 6856.25329
7571 6895.51632 7270.49059
7963 7269.97879 7677.01796
8301 7636.89111 8076.00896
8577 7996.97886 8465.75968
8879 8423.53641 9224.66086
EOD
$p4 << EOD
11.21 5.47482535 5.81027487
13.58 7.36802014 7.87112856
16.21 9.63975045 10.3641837
19.14 12.3108885 13.3155015
23.2 15.3958519 16.7353278
27.69 18.9109867 20.6632723
32.79 22.8803244 25.1081007
38.58 27.3104225 30.1017854
45.8 32.2269485 35.6614641
52.89 37.6390364 41.8099229
62.57 43.5547992 48.6073236
72.77 51.5363152 64.1133501
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT4125_540kv.csv: T-Motor AT4125 540KV + Castle Phoenix 125 + APC 15x8E (PER3, computed)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 8.5 %, plain DC 14.4 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:76.4085]
set yrange [0:76.4085]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 5.83 %, plain DC 5.83 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:5813.85]
set yrange [0:5813.85]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 10.1 %, plain DC 5.8 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:90.8773]
set yrange [0:90.8773]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 10.5 %, plain DC 6.3 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3622.62:9685.89]
set yrange [3622.62:9685.89]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 34.7 %, plain DC 27.7 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:76.4085]
set yrange [0:76.4085]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
