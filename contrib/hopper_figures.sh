#!/bin/bash
# Regenerates every hopper figure of doc/hopper.md from scratch:
#   bash contrib/hopper_figures.sh [BUILD]          (BUILD = build directory, default build)
# Runs the prm/hopper_*.prm cases into output/, the perturbation runs, the
# Fig. 9 bar (contrib/hopper_runs.py range), the work-precision runs
# (contrib/hopper_runs.py precision), then the matplotlib figures and the
# ParaView picture. About 30 min of CPU on one core (the work-precision runs
# are two thirds of it).
set -e
BUILD=${1:-build}
cd "$(dirname "$0")/.."
for c in radial_wedge radial_cone cone_30_25 wedge_30_25 wedge_30_35 cone_30_31 \
         cone_30_24_p1 cone_30_24_p2 fig9_scan; do
  "$BUILD"/granular_dg prm/hopper_$c.prm --set Output/overwrite=true
done
# the cone 30 -> 35 stops with exit code 2 (loss of hyperbolicity): expected
"$BUILD"/granular_dg prm/hopper_cone_30_35.prm --set Output/overwrite=true || test $? -eq 2
"$BUILD"/granular_dg prm/hopper_fig9_scan.prm --set Output/overwrite=true \
  --set Hopper/geometry=wedge --set Output/directory=output/hopper_fig9_scan_wedge
for g in wedge cone; do
  "$BUILD"/granular_dg prm/hopper_radial_$g.prm --set Output/overwrite=true \
    --set "Hopper/initial perturbation=1e-3" --set "Output/write vtu=false" \
    --set Output/directory=output/hopper_perturbed_$g
done
/usr/bin/python3 contrib/hopper_runs.py range "$BUILD"
/usr/bin/python3 contrib/hopper_runs.py precision "$BUILD"
/usr/bin/python3 contrib/hopper_figures.py output doc/figures
xvfb-run -a pvpython --no-mpi contrib/hopper_paraview.py \
  "$PWD/output/hopper_cone_30_25/hopper-field.pvd" doc/figures/hopper_paraview_cone_30_25.png \
  T_rr_over_r "cone 30 -> 25 deg, r from 1.5 r0 to 0.05 r0: T_rr/r, white: psi every 5 deg"
xvfb-run -a pvpython --no-mpi contrib/hopper_paraview.py \
  "$PWD/output/hopper_wedge_30_35/hopper-field.pvd" doc/figures/hopper_paraview_wedge_30_35.png \
  T_rr_over_r "wedge 30 -> 35 deg: T_rr/r, white: psi every 5 deg"
