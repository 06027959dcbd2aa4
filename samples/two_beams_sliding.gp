# Force-displacement curve of the two-beam sliding test (samples/two_beams_sliding.json):
#   fibra run samples/two_beams_sliding.json --out out/two_beams
#   gnuplot -e "dir='out/two_beams'; png='two_beams_sliding.png'" samples/two_beams_sliding.gp
# x: y displacement of B's middle node (mm); y: horizontal force of B's end holds on B (N).
if (!exists("dir")) dir = 'out/two_beams'
if (!exists("png")) png = dir.'/two_beams_sliding.png'
set datafile separator ','
set terminal pngcairo size 800,520
set output png
set xlabel 'displacement of beam B (mm)'
set ylabel 'horizontal force on beam B (N)'
set grid
set key bottom right
mu_RN = 0.2 * 0.2
plot dir.'/history.csv' every ::0::24 using 'probe.B_middle.y':(column('reaction.B.start.fy') + column('reaction.B.end.fy')) with linespoints pt 7 ps 0.5 title 'first translation', \
     '' every ::25::74 using 'probe.B_middle.y':(column('reaction.B.start.fy') + column('reaction.B.end.fy')) with linespoints pt 7 ps 0.5 title 'cycle 1', \
     '' every ::75::124 using 'probe.B_middle.y':(column('reaction.B.start.fy') + column('reaction.B.end.fy')) with lines lw 2 dt 2 title 'cycle 2', \
     mu_RN with lines lc 'gray' title '±μ R_N', -mu_RN with lines lc 'gray' notitle
