# Written by dynosize; run 'gnuplot carpet_battery_capacity_ah_vehicle_mass_kg.gp' to redraw.
$b << EOD
0 23.0890765
1 31.0877474
2 36.125712


0.5 17.7080164
1.5 24.652699
2.5 28.9490015


1 13.9545381
2 19.8777874
3 24.0316704
EOD
$a << EOD
0 23.0890765
0.5 17.7080164
1 13.9545381


1 31.0877474
1.5 24.652699
2 19.8777874


2 36.125712
2.5 28.9490015
3 24.0316704
EOD
set terminal pngcairo size 1000,700 font 'DejaVu Sans,11' noenhanced
if (!exists('outfile')) outfile = 'carpet_battery_capacity_ah_vehicle_mass_kg.png'
set output outfile
set encoding utf8
set grid lc rgb '#dddddd'
set key outside right top
set title "1.5 kg quadcopter, hover and cruise: carpet of endurance [min], best pick per point\nover battery.capacity_ah (red) and vehicle.mass_kg (blue)"
set ylabel 'endurance [min]'
unset xtics
set xlabel 'carpet: each vehicle.mass_kg step shifts the lines right by half a battery.capacity_ah step'
unset key
set offsets 1.2, 1.2, 0.5, 0.5
set label 'vehicle.mass_kg = 0.5' at 2,36.1257 offset 1,0 left tc rgb '#1f77b4'
set label 'vehicle.mass_kg = 0.75' at 2.5,28.949 offset 1,0 left tc rgb '#1f77b4'
set label 'vehicle.mass_kg = 1.0' at 3,24.0317 offset 1,0 left tc rgb '#1f77b4'
set label 'battery.capacity_ah = 3' at 0,23.0891 offset -0.8,0 right tc rgb '#d62728'
set label 'battery.capacity_ah = 5' at 1,31.0877 offset -0.8,0 right tc rgb '#d62728'
set label 'battery.capacity_ah = 7' at 2,36.1257 offset -0.8,0 right tc rgb '#d62728'
plot $b using 1:2 with linespoints pt 7 lw 2 lc rgb '#1f77b4', $a using 1:2 with lines lw 1 dt 2 lc rgb '#d62728'

unset output
