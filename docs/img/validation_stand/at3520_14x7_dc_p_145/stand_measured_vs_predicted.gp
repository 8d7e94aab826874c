# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
5.15 4.45555505 4.19778686
6.71 6.28491359 5.90353177
8.5 8.42231183 7.8857616
11.18 11.4267247 10.6567872
13.7 14.6180525 13.5842874
16.9 19.1525913 17.7218462
20.26 23.7098442 21.8591206
24.56 29.1720191 26.7952445
29.2 35.0110228 32.0494172
38.47 47.983245 43.6550597
44.28 54.5967503 49.5441503
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
4423 4076.89503 4244.09766
4888 4488.07263 4684.98813
5313 4881.0221 5108.48485
5785 5251.85859 5509.92147
6192 5612.7676 5902.13015
6664 5955.7696 6276.15717
7056 6283.59194 6634.70525
7454 6597.01763 6978.41463
7818 6896.73491 7307.86009
8481 7467.02747 7936.60521
8762 7794.20959 8540.42563
EOD
$p4 << EOD
5.15 3.38949867 3.65559656
6.71 4.68831095 5.10698494
8.5 6.26224646 6.88159189
11.18 8.10772606 8.97859667
13.7 10.271374 11.4550897
16.9 12.7303819 14.2874882
20.26 15.4944492 17.4894977
24.56 18.5643637 21.0641432
29.2 21.9385215 25.0113238
38.47 29.6709848 34.1151988
44.28 35.008074 45.0139529
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT3520_550kv.csv: T-Motor AT3520 550KV + Castle Phoenix 125 + APC E 14.0x7.0\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, same R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 13.3 %, plain DC 9.11 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:57.3266]
set yrange [0:57.3266]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 3.13 %, plain DC 3.13 %"
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
set title "speed from the throttle\nMAE dynosize 10.1 %, plain DC 5.01 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3669.21:9200.1]
set yrange [3669.21:9200.1]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 25.9 %, plain DC 16.2 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:47.2647]
set yrange [0:47.2647]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
