# column tests (included by tests/CMakeLists.txt)

# The exact solution of the linear case checked against its PDE, boundary,
# front and Rankine-Hugoniot conditions and an independent SciPy computation
# of the first stop time (1e-8 absolute on that number, 1e-5 on residuals).
granular_dg_unit_test(column/closed_form NUMDIFF -a 1e-5 -r 0)

# Convergence to the exact solution of the linear case at t = 1, 2 and 4
# (t = 4 is after the first stop at the wall, t_s(0) = 3.25, with the frozen
# region behind the stopping front): P2 on 50, 100, 200, 400 cells of (0, 5).
# The front is a discontinuity, so the L1 error converges at first order; the
# test requires an L1 EOC in [0.6, 1.4] on the finest pair (.output: 1,
# tolerance 0.4), i.e. an error that decreases at the rate a discontinuity allows.
foreach(t 1 2 4)
  granular_dg_test(column/m1_convergence_t${t} PRM column/m1_base.prm
    ARGS --set Convergence/enabled=true --set "Time stepping/final time=${t}"
         --set "Output/output times="
    COMPARE convergence-rates.csv:degree,eoc_l1_finest NUMDIFF -a 0.4 -r 0)
endforeach()

# The pressure front of the linear case: strain -e^{-t/2} and velocity
# e^{-t/2} just behind it at t = 1, 2, 4 (section 2; hand-computed .output),
# within 2% (numdiff -r 0.02), at the paper's dx = 0.025.
granular_dg_test(column/m1_front PRM column/m1_base.prm
  COMPARE timeseries.csv:time,front_strain,front_velocity NUMDIFF -r 0.02 -a 1e-12)

# The shipped shock capturing of prm/column_m1.prm (the characteristic limiter
# on the cells the modal-energy indicator flags, threshold 0.2) at
# the paper's dx = 0.025 on (0, 5), t = 4: the strain error at (z, t) = (3, 4)
# against the closed form must be at most half of the 5.09e-4 that the limiter
# in every cell leaves (.output 1.2725e-4 with -a 1.2725e-4: passes iff the
# error is in [0, 2.545e-4]; it is 1.77e-4), and v = 0 exactly in every stuck
# cell (the flag 1; a 0 fails the tolerance).
granular_dg_test(column/point_error EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/column/point_error.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/column_m1.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 1.2725e-4 -r 0)

# Stuck material (t = 8, after the stopping front has frozen z < 6.92): the
# velocity is exactly 0 in every stuck cell after every stage (also after the
# characteristic limiter), the friction multiplier stays in [-1, 1], the
# strain at z = 0.5 (stuck since t = 3.32) does not drift (to round-off,
# -a 1e-12), and no velocity sign flips (chatter) occur.
granular_dg_test(column/m1_stuck PRM column/m1_stuck.prm
  COMPARE summary.json:diagnostics/max_stuck_velocity,diagnostics/stuck_multiplier_in_bounds,diagnostics/probe_strain_drift,diagnostics/velocity_chatter_detected
  NUMDIFF -a 1e-12 -r 0)
# ... and the stopping front sits at the exact z_s(8) = 6.9230 within two
# cells (-a 0.05; .output from the SciPy computation in closed_form.cc).
granular_dg_test(column/m1_stop_front PRM column/m1_stuck.prm
  COMPARE summary.json:diagnostics/stop_front NUMDIFF -a 0.05 -r 0)

# The naive explicit friction (sgn(v) of the current state) on the same case:
# the velocity of stopped material chatters around 0 (sign flips) and its
# strain creeps; the test expects both (chatter detected = 1, and a probe
# strain drift of -5.4e-3 where the projection keeps 0: |drift| > 1e-3 is
# enforced by the tolerance, .output -5.4e-3 with -a 4.4e-3).
granular_dg_test(column/naive_explicit_friction PRM column/m1_stuck.prm
  ARGS --set Physics/friction=explicit_sign
  COMPARE summary.json:diagnostics/velocity_chatter_detected,diagnostics/probe_strain_drift
  NUMDIFF -a 4.4e-3 -r 0)

# Rankine-Hugoniot at the pressure front (2.10)-(2.11) for m = 3/2 and m = 2 at
# t = 20: front speed / |u_L|^{(m-1)/2} and v_L^2 / |u_L|^{m+1}, both 1
# exactly; measured within 3% (-r 0.03).
foreach(m 15 2)
  granular_dg_test(column/rankine_hugoniot_m${m} PRM column/m${m}_t20.prm
    COMPARE summary.json:diagnostics/front_speed_over_rankine_hugoniot,diagnostics/front_velocity_squared_over_rankine_hugoniot
    NUMDIFF -r 0.03 -a 0)
endforeach()

# Regression of the m = 3/2 strain and velocity profiles at t = 20 (cell
# centres) from a reviewed run (doc/column.md), 1e-8 absolute.
granular_dg_test(column/m15_profile_t20 PRM column/m15_t20.prm
  ARGS --set "Output/profile points per cell=1"
  COMPARE profile-0001.csv NUMDIFF -a 1e-8 -r 1e-6)

# Bad input: one line naming the parameter, its value and what is allowed.
granular_dg_test(column/bad_exponent PRM column/m1_stuck.prm
  ARGS "--set" "Physics/stress exponent m=0.5" EXIT 2 KEEP_OUTPUT)
granular_dg_test(column/bad_wall_strain PRM column/m1_stuck.prm
  ARGS "--set" "Physics/wall strain=0.5" EXIT 2 KEEP_OUTPUT)
granular_dg_test(column/bad_closed_form PRM column/m1_stuck.prm
  ARGS "--set" "Physics/stress exponent m=2" "--set" "Diagnostics/closed form=true" EXIT 2 KEEP_OUTPUT)
granular_dg_test(column/bad_friction PRM column/m1_stuck.prm
  ARGS "--set" "Physics/friction=implicit" EXIT 2 KEEP_OUTPUT)

# Skipping quiet cells (Time stepping/skip tolerance = 1e-15; doc/engine.md)
# changes no result: m = 3/2 on (0, 10), 400 P2 cells, to t = 60, snapshots
# every 2. Every profile (31 snapshots and the final one) of the skipping run
# equals the full computation's to 1e-12 of each quantity's scale over the
# run (measured 1e-14: the print resolution). The run comes to rest at
# t = 29.06 and then keeps stepping without computing the steps of the
# CFL size (those that land on the snapshot times are computed): it takes
# the full run's 14 700 steps and writes the full run's rows of
# timeseries.csv (time, step, dt and values) and of history.csv (every sample
# time); 78 % of the cell updates are skipped (the .output has the fraction,
# the steps and the time of rest, so a run that stops skipping fails too).
# The case is well conditioned: the full run with the wall strain moved by
# one ulp agrees with it to 1e-12 as well (doc/column.md, "Run time", shows
# cases where round-off grows to 1e-6).
granular_dg_test(column/skip_quiet_cells EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/column/skip_agrees.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/column/m15_rest.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# The same case at the largest skip tolerance allowed, 1e-14: the results
# still agree with the full computation to 1e-12 (measured 1e-14), and the
# run is at rest from t = 29.07.
granular_dg_test(column/skip_largest_tolerance EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/column/skip_agrees.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/column/m15_rest.prm --skip 1e-14
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# A larger skip tolerance is refused (exit 2, one line naming the range): at
# 1e-6 the column to t = 300 comes to a false rest at t = 120 with a
# velocity 20 times the full computation's (doc/engine.md).
granular_dg_test(column/skip_tolerance_too_large PRM column/m15_rest.prm
  ARGS --set "Time stepping/skip tolerance=1e-6" EXIT 2 KEEP_OUTPUT)

# A skipping run stopped at max steps = 10000 (t = 41), while it is at rest
# and steps of the CFL size are not computed (checkpoints every 1000 steps,
# all in that stretch), and resumed: every file equals the uninterrupted
# run's byte for byte (summary.json's at_rest_from, the skipped fraction and
# the step counter included; tests/checkpoint/resume_test.py).
granular_dg_test(column/skip_resume_at_rest EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint/resume_test.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/column/m15_rest.prm stop:10000 --every 1000
       --set "Time stepping/skip tolerance=1e-15"
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
