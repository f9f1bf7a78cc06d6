#!/bin/bash
# The network scene's studies behind doc/network.md: the EOC tables of the
# five examples of Musch, Fjordholm & Risebro Section 7 at grid levels 3-12
# (degree 0, the paper's scheme) and, for Examples 7.3 and 7.5, degrees 1-3
# with the limiter (the work-precision chart); the smooth order study.
#   bash contrib/network_studies.sh [BUILD_DIR] [OUTPUT_DIR]
# Takes about 40 min on one core (degree 3 at level 12 dominates).
set -e
build=${1:-build}
out=${2:-output/network_studies}
exe="$build/granular_dg"
levels="8,16,32,64,128,256,512,1024,2048,4096"
mkdir -p "$out"
for e in 1 2 4; do
  "$exe" prm/network_example_7_$e.prm --set Output/overwrite=true --set Output/directory="$out/example_7_$e" \
    --set Convergence/enabled=true --set "Convergence/cells=$levels"
done
for e in 3 5; do
  "$exe" prm/network_example_7_$e.prm --set Output/overwrite=true --set Output/directory="$out/example_7_$e" \
    --set Convergence/enabled=true --set "Convergence/cells=$levels" \
    --set "Convergence/degrees=0,1,2,3" --set "Convergence/CFL numbers=0.5,0.3,0.18,0.1" \
    --set Limiter/scheme=componentwise
done
for w in 1 0; do
  "$exe" prm/network_smooth.prm --set Output/overwrite=true --set Output/directory="$out/smooth_width_$w" \
    --set Convergence/enabled=true --set "Network/vertex width factor=$w" \
    --set "Convergence/CFL numbers=0.5,0.3,0.18,0.03" --set "Convergence/cells=8,16,32,64,128,256,512"
done
