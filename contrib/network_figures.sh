#!/bin/bash
# The figures of doc/network.md: the five examples at grid level 8 (the
# prm/ files as they ship) with their profiles against the exact solutions,
# the ParaView picture of Example 7.1 (xvfb-run + pvpython), and the charts
# of the studies of contrib/network_studies.sh (run that first).
#   bash contrib/network_figures.sh [BUILD_DIR] [STUDIES_DIR]
set -e
build=${1:-build}
studies=${2:-output/network_studies}
figures=doc/figures
for e in 1 2 3 4 5; do
  "$build/granular_dg" prm/network_example_7_$e.prm --set Output/overwrite=true
  /usr/bin/python3 contrib/network_plot_profiles.py output/network_example_7_$e \
    $figures/network_example_7_$e.png --title "Example 7.$e, level 8, degree 0"
done
"$build/granular_dg" prm/network_example_7_5.prm --set Output/overwrite=true \
  --set Output/directory=output/network_example_7_5_dg2 --set Discretization/degree=2 \
  --set "Time stepping/CFL number=0.18" --set Limiter/scheme=componentwise
/usr/bin/python3 contrib/network_plot_profiles.py output/network_example_7_5_dg2 \
  $figures/network_example_7_5_dg2.png --title "Example 7.5, level 8, degree 2 + limiter"
xvfb-run -a pvpython --no-mpi contrib/network_paraview.py output/network_example_7_1 \
  $figures/network_paraview_7_1.png 0.625
/usr/bin/python3 contrib/network_charts.py "$studies" $figures
