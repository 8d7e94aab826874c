# Written by dynosize; run 'gnuplot objective_vs_battery_capacity_ah.gp' to redraw.
$d << EOD
3 23.0890765 9.14073005 24.531303
5 31.0877474 13.1223661 34.5934181
7 36.125712 14.7311935 39.7457297


3 17.7080164 NaN 19.6680282
5 24.652699 9.93883063 27.1553752
7 28.9490015 11.920203 31.997715


3 13.9545381 NaN 15.3806415
5 19.8777874 8.10718131 22.0076342
7 24.0316704 9.73380102 26.7338157
EOD
set terminal pngcairo size 1000,700 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'objective_vs_battery_capacity_ah.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set title "1.5 kg quadcopter, hover and cruise: endurance [min] vs battery.capacity_ah\nbest pick per point; band: its objective range (pessimistic to optimistic data; none where an end cannot fly)"
set xlabel 'battery.capacity_ah'
set ylabel 'endurance [min]'
set key inside bottom left
plot $d index 0 using 1:3:4 with filledcurves fs transparent solid 0.15 lc rgb '#1f77b4' notitle, $d index 0 using 1:2 with linespoints pt 7 lw 2 lc rgb '#1f77b4' title 'vehicle.mass_kg = 0.5', $d index 1 using 1:3:4 with filledcurves fs transparent solid 0.15 lc rgb '#d62728' notitle, $d index 1 using 1:2 with linespoints pt 7 lw 2 lc rgb '#d62728' title 'vehicle.mass_kg = 0.75', $d index 2 using 1:3:4 with filledcurves fs transparent solid 0.15 lc rgb '#2ca02c' notitle, $d index 2 using 1:2 with linespoints pt 7 lw 2 lc rgb '#2ca02c' title 'vehicle.mass_kg = 1.0'

unset output
