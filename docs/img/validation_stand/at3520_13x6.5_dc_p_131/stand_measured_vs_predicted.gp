# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
4.96 5.05204941 5.05303142
6 6.18018713 6.18144498
7.26 7.59474957 7.59637019
8.88 9.47836738 9.48049571
10.87 11.7097613 11.7125353
13.47 15.0452044 15.0490256
16.12 18.4193118 18.4242559
19.27 22.3429616 22.3492796
22.6 26.5137091 26.5215547
30.77 37.2934176 37.3054744
34.89 42.1970701 42.2111439
EOD
$p1 << EOD
912 875.209111 875.209111
1053 1014.96338 1014.96338
1208 1179.34115 1179.34115
1396 1383.91573 1383.91573
1619 1603.89918 1603.89918
1890 1899.97162 1899.97162
2140 2174.51421 2174.51421
2412 2470.85468 2470.85468
2711 2763.66804 2763.66804
3289 3446.81917 3446.81917
3575 3728.90778 3728.90778
EOD
$p2 << EOD
4.96 4.67843765 4.67929587
6 5.77268332 5.77380022
7.26 7.11404495 7.11549217
8.88 8.8886212 8.89052716
10.87 11.1338422 11.1363879
13.47 14.1640736 14.1675253
16.12 17.2034839 17.2078951
19.27 20.8596601 20.8652992
22.6 25.0243195 25.0314553
30.77 34.6581447 34.6688566
34.89 39.9966863 40.0096029
EOD
$p3 << EOD
4834 4266.21104 4265.50872
5181 4741.82737 4741.00148
5558 5206.44275 5205.48824
5990 5660.79007 5659.7027
6404 6100.75353 6099.53127
6895 6515.81568 6514.51165
7313 6911.52256 6910.07838
7732 7295.8948 7294.30942
8119 7666.83764 7665.11157
8940 8375.46673 8373.46068
9252 8792.07129 9063.57807
EOD
$p4 << EOD
4.96 3.53692611 3.53591524
6 4.7841376 4.78266222
7.26 6.27448221 6.27241551
8.88 8.02199752 8.01919812
10.87 10.0251876 10.0215073
13.47 12.4321263 12.4267615
16.12 15.2016624 15.194772
19.27 18.313757 18.3050821
22.6 21.7611901 21.7504677
30.77 29.7059115 29.6902438
34.89 35.2912716 39.2687235
EOD
set terminal pngcairo size 1200,1800 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'stand_measured_vs_predicted.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set multiplot layout 3,2 title "TMotor_AT3520_550kv.csv: T-Motor AT3520 550KV + Castle Phoenix 125 + APC E 13.0x6.5\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, datasheet R and Io)"
set grid
set key left top inside
set size ratio -1
set title "DC current at the measured rpm\nMAE dynosize 11.4 %, plain DC 11.4 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:44.3217]
set yrange [0:44.3217]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 2.49 %, plain DC 2.49 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:3915.35]
set yrange [0:3915.35]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 6.56 %, plain DC 6.57 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:42.0101]
set yrange [0:42.0101]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 6.39 %, plain DC 6.14 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3838.96:9714.6]
set yrange [3838.96:9714.6]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 9.7 %, plain DC 10.8 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:41.2322]
set yrange [0:41.2322]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
