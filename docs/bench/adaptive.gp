set terminal pngcairo size 720,400 font "sans,10" noenhanced
set output "docs/bench/adaptive.png"
set datafile separator ","
set title "ball_on_board, 0.3 s: CPU ms per 600 steps by board dynamics (2026-11-26, 2-core VM)"
set style data histograms
set style fill solid 0.8 border -1
set boxwidth 0.7
set ylabel "ms per 600 steps (CPU)"
set yrange [0:*]
set grid ytics
unset key
plot "docs/bench/adaptive.csv" every ::1 using 2:xtic(1) lc rgb "#4a7ab0", '' every ::1 using 0:($2+2):(sprintf("%.1f", $2)) with labels
