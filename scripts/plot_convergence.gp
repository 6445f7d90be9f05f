# The convergence plot of `vkrt converge`: RMSE against the reference over render
# seconds, log-log, one curve per backend and estimator, and a 1/sqrt(t) guide: the
# rate at which an unbiased Monte Carlo estimator's error falls, so a curve that
# runs parallel to it converges as it should and one that flattens has a bias.
#
# vkrt converge runs it (docs/cli.md); by hand:
#   gnuplot -e "csv='c.csv'; png='c.png'; curves='vulkan/path:cosine cpu/path:cosine'" scripts/plot_convergence.gp
# csv: the CSV vkrt converge wrote (columns backend,estimator,spp,seconds,rmse,...)
# png: the image to draw
# curves: the curves to draw, backend/estimator, separated by spaces

if (!exists("csv") || !exists("png") || !exists("curves")) {
    print "plot_convergence.gp: set csv, png and curves with -e (see the comment at the top)"
    exit status 1
}

set datafile separator ","
set terminal pngcairo size 900,600 noenhanced font ",11"
set output png
set logscale xy
set format x "%g"
set format y "%g"
set xlabel "render seconds"
set ylabel "RMSE against the reference"
set title "vkrt converge: ".csv
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key outside right top title "backend/estimator"

# A log scale cannot show an error of 0 (a scene without randomness matches its
# reference exactly); vkrt converge does not call this script then.
stats csv skip 1 using 5 nooutput
if (STATS_max <= 0) {
    print "plot_convergence.gp: every RMSE in ".csv." is 0: nothing to draw on a log scale"
    exit status 1
}

# The guide goes through the first row (the first curve at 1 spp), or where that
# is 0, through the largest error.
# One column at a time: stats on two would fit a line and warn about one point.
stats csv skip 1 every ::0::0 using 4 nooutput
t0 = STATS_min
stats csv skip 1 every ::0::0 using 5 nooutput
e0 = STATS_min
if (e0 <= 0) {
    stats csv skip 1 using 5 nooutput
    e0 = STATS_max
}
guide(t) = e0 * sqrt(t0 / t)

# Each curve its own colour and its own mark, so that none can be mistaken for
# another in print or for a reader who does not tell colours apart.
colours = "#1f77b4 #ff7f0e #2ca02c #d62728 #9467bd #8c564b #e377c2 #17becf #bcbd22 #000000 " . \
          "#7f7f7f #aec7e8 #ffbb78 #98df8a #ff9896 #c5b0d5"
colour(i) = word(colours, (i - 1) % words(colours) + 1)
mark(i) = (i - 1) % 15 + 1
row(i) = strcol(1)."/".strcol(2) eq word(curves, i)
plot for [i = 1:words(curves)] csv skip 1 using 4:(row(i) ? $5 : NaN) \
         with linespoints lw 2 lc rgb colour(i) pt mark(i) ps 1.1 title word(curves, i), \
     guide(x) with lines dt 2 lw 1.5 lc rgb "#888888" title "1/sqrt(t)"
