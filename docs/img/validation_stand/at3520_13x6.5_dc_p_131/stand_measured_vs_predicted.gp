# Written by dynosize; run 'gnuplot stand_measured_vs_predicted.gp' to redraw.
$p0 << EOD
4.96 4.85536699 4.58946017
6 6.09145107 5.74882862
7.26 7.68881722 7.24199854
8.88 9.88592185 9.28791755
10.87 12.4184046 11.6368197
13.47 16.0208439 14.9637606
16.12 19.6811923 18.330079
19.27 23.9549636 22.2454251
22.6 28.5148965 26.4079636
30.77 40.367218 37.1685499
34.89 45.7844481 42.0641519
EOD
$p1 << EOD
912 841.559185 841.559185
1053 986.560004 986.560004
1208 1158.97753 1158.97753
1396 1376.00624 1376.00624
1619 1603.89918 1603.89918
1890 1899.97162 1899.97162
2140 2174.51421 2174.51421
2412 2470.85468 2470.85468
2711 2763.66804 2763.66804
3289 3446.81917 3446.81917
3575 3728.90778 3728.90778
EOD
$p2 << EOD
4.96 4.89815787 4.62890453
6 6.0584876 5.71855703
7.26 7.4842088 7.05482652
8.88 9.37589822 8.82336945
10.87 11.7843517 11.0619984
13.47 15.0456536 14.0841945
16.12 18.3297173 17.1162948
19.27 22.2988653 20.7644932
22.6 26.8448798 24.9208514
30.77 37.3897479 34.5369944
34.89 43.2897021 39.8667856
EOD
$p3 << EOD
4834 4169.01354 4326.89336
5181 4609.18871 4795.34179
5558 5033.51313 5249.10867
5990 5443.21147 5689.1353
6404 5835.16449 6111.73476
6895 6214.14275 6521.76331
7313 6578.73986 6917.46477
7732 6931.90511 7301.83977
8119 7271.87061 7672.79249
8940 7919.1712 8381.45898
9252 8298.51596 9071.92028
EOD
$p4 << EOD
4.96 3.03098014 3.22548902
6 4.16885068 4.47652525
7.26 5.54714848 6.00416451
8.88 7.1808482 7.82814074
10.87 9.06937047 9.95037851
13.47 11.2319894 12.395261
16.12 13.6677874 15.1639567
19.27 16.3914827 18.2755055
22.6 19.3952584 21.7226755
30.77 26.2751387 29.6677521
34.89 31.0833712 39.2542821
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
set title "DC current at the measured rpm\nMAE dynosize 17.2 %, plain DC 11.1 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:48.0737]
set yrange [0:48.0737]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p0 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p0 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "thrust at the measured rpm\nMAE dynosize 3.28 %, plain DC 3.28 %"
set xlabel 'measured [gf]'
set ylabel 'predicted [gf]'
set xrange [0:3915.35]
set yrange [0:3915.35]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p1 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p1 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current at the measured rpm and torque\nMAE dynosize 11.3 %, plain DC 6.53 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:45.4542]
set yrange [0:45.4542]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p2 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p2 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "speed from the throttle\nMAE dynosize 10.4 %, plain DC 5.74 %"
set xlabel 'measured [rpm]'
set ylabel 'predicted [rpm]'
set xrange [3752.11:9714.6]
set yrange [3752.11:9714.6]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p3 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p3 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
set title "DC current from the throttle\nMAE dynosize 19.6 %, plain DC 12.5 %"
set xlabel 'measured [A]'
set ylabel 'predicted [A]'
set xrange [0:41.217]
set yrange [0:41.217]
plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', 0.9*x with lines dt 2 lc rgb 'gray50' notitle, $p4 using 1:2 with points pt 7 ps 1.2 lc rgb '#d95f0e' title 'dynosize', $p4 using 1:3 with points pt 5 ps 1.0 lc rgb '#1f3b99' title 'plain DC'
unset multiplot

unset output
