# skeleton tests (included by tests/CMakeLists.txt): the minimal scene's
# convergence to the exact solution u0(x - a t) and its bad input. A scene
# copied from it (contrib/new_scene.sh) starts with these tests renamed.

# Smooth advection: DG of degree p converges at p + 1 (EOC of the two finest
# meshes, L2 and L1; within 0.1 of the theory, the stored values are p + 1)
granular_dg_test(skeleton/eoc_1d PRM skeleton/base.prm
  ARGS --set Convergence/enabled=true --set "Convergence/degrees=1,2,3"
       --set "Convergence/cells=8,16,32"
  COMPARE convergence-rates.csv:degree,eoc_finest,eoc_l1_finest NUMDIFF -a 0.1)
granular_dg_test(skeleton/eoc_2d PRM skeleton/base.prm
  ARGS --set Mesh/dimension=2 --set Convergence/enabled=true --set "Convergence/degrees=1,2"
       --set "Convergence/cells=8,16,32"
       --set "Initial condition/u=sin(2*pi*x)*sin(2*pi*y)"
  COMPARE convergence-rates.csv:degree,eoc_finest,eoc_l1_finest NUMDIFF -a 0.1)
# Inflow data instead of periodicity: the same rates
granular_dg_test(skeleton/eoc_inflow PRM skeleton/base.prm
  ARGS --set Mesh/periodic=false --set Convergence/enabled=true
       --set "Convergence/degrees=1,2,3" --set "Convergence/cells=8,16,32"
  COMPARE convergence-rates.csv:degree,eoc_finest NUMDIFF -a 0.1)

# Bad input: exit 2, one line naming the parameter, its value and what is allowed
granular_dg_test(skeleton/bad_velocity PRM skeleton/bad_velocity.prm EXIT 2)
granular_dg_test(skeleton/zero_velocity PRM skeleton/zero_velocity.prm EXIT 2)

# deal.II's low-storage schemes (Time stepping/scheme) keep the rates p + 1
# at CFL numbers SSP-RK3 would refuse (0.6, 0.3, 0.2 for p = 1, 2, 3 against
# its 0.4095, 0.2097, 0.13; lsrk_5_4 allows 0.6754, 0.3505, 0.2193)
foreach(scheme lsrk_5_4 lsrk_9_5)
  granular_dg_test(skeleton/eoc_${scheme} PRM skeleton/base.prm
    ARGS --set Convergence/enabled=true --set "Convergence/degrees=1,2,3"
         --set "Convergence/cells=8,16,32" --set "Time stepping/scheme=${scheme}"
         --set "Convergence/CFL numbers=0.6,0.3,0.2"
    COMPARE convergence-rates.csv:degree,eoc_finest,eoc_l1_finest NUMDIFF -a 0.1)
endforeach()

# A single run writes its VTU snapshots (deal.II hands the values of a system
# of one component to the derived fields' scalar path)
granular_dg_test(skeleton/run_1d PRM skeleton/base.prm
  EXPECT_FILES out/solution.pvd out/solution-0001.vtu
  COMPARE summary.json:status,final_time NUMDIFF -r 1e-12)
