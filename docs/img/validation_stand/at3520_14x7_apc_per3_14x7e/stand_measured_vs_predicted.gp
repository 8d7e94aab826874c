# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
5.15 4.94934377 4.64972729
6.71 6.63897273 6.22574938
8.5 8.53714313 7.9897249
11.18 11.0944864 10.3576895
13.7 13.6965832 12.7586623
16.9 17.2507099 16.0268625
20.26 20.6899005 19.1792264
24.56 24.7007801 22.8442794
29.2 28.8594166 26.6340009
38.47 37.7987651 34.7483095
44.28 42.2286144 38.756727
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
5.15 5.27109362 4.94297538
6.71 7.07987932 6.62577532
8.5 9.29668034 8.67558289
11.18 12.5290391 11.6459189
13.7 15.8743107 14.7054358
16.9 20.0913361 18.5550807
20.26 24.4871996 22.5458752
24.56 30.2863238 27.7746135
29.2 36.8919394 33.6946034
38.47 49.8539018 45.2793925
44.28 58.1128292 52.5858265
EOD
$p3 << EOD
4423 3998.02328 4184.80372
4888 4425.26104 4642.2113
5313 4840.45437 5087.74025
5785 5236.28912 5513.21087
6192 5625.29411 5934.23904
6664 5999.81996 6340.03142
7056 6361.24786 6733.41308
7454 6710.72265 7114.2977
7818 7048.30652 7482.18564
8481 7697.58996 8193.24594
8762 8074.99425 8885.18582
EOD
$p4 << EOD
5.15 3.69646177 3.96361703
6.71 4.96332634 5.35697944
8.5 6.45960479 7.01629709
11.18 8.19104456 8.9551009
13.7 10.1982456 11.2048906
16.9 12.4517906 13.74829
20.26 14.9655446 16.5921538
24.56 17.7346169 19.7406068
29.2 20.7587102 23.2001492
38.47 27.6519869 31.115502
44.28 32.3826377 40.5365478
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT3520_550kv.csv: T-Motor AT3520 550KV + Castle Phoenix 125 + APC 14x7E (PER3, computed)\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 1.68 %, plain DC 7.78 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:46.494]
set yrange [0:46.494]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 5.55 %, plain DC 5.55 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:4321.8]
set yrange [0:4321.8]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 17.8 %, plain DC 9.53 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:61.0185]
set yrange [0:61.0185]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 9.39 %, plain DC 4.24 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3598.22:9329.45]
set yrange [3598.22:9329.45]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 26.8 %, plain DC 18.5 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:46.494]
set yrange [0:46.494]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
