# Unit tests of the physics: small programs printing to stdout.
granular_dg_unit_test(unit/elasticity_physics NUMDIFF -a 1e-7 -r 0)
# Interface-aware flux at a material interface: errors ~0.
granular_dg_unit_test(unit/layered_interface NUMDIFF -a 1e-7 -r 0)
# The CFL stability limit of every Time stepping/scheme and degree 0-4,
# computed from the program's integrators (Fourier analysis of upwind DG),
# and the check that the table the program enforces lies within [0.98, 1] of
# them (the test fails itself otherwise); the orders of the schemes read off
# their stability functions. Limits printed to 4 digits: -a 2e-4.
granular_dg_unit_test(unit/rk_stability_limits NUMDIFF -a 2e-4 -r 0)
# The SIMD exponential (base/vectorized_math.h, used by the exponential stress
# law) within 2 ulp of std::exp over the finite range, lane- and
# width-independent, special values right; and the lane tests all_finite,
# all_positive of the admissibility checks equal the lane-by-lane std::isfinite
# and > 0 for NaN, +-inf, +-0, subnormals in any lane (native width, 4, 1); it
# fails itself otherwise.
granular_dg_unit_test(unit/vectorized_exp NUMDIFF -r 1e-15)
# The byte transport of checkpoints (gather_bytes, broadcast_bytes) in chunks
# of 7 bytes on 3 ranks: every byte arrives (an empty part too); fails itself
# otherwise. RUN_SERIAL: three processes on two cores.
granular_dg_unit_test(unit/gather_bytes MPI 3 NUMDIFF -a 0 -r 0 LABELS mpi)
set_tests_properties(unit/gather_bytes PROPERTIES RUN_SERIAL TRUE)
# Checkpoints written and read per rank: 3 ranks write their pieces of two
# shared blocks through MPI-IO; each reads back its own, rank 0 each whole
# block in rank order; a flipped byte in a block is caught by the combined
# CRC-32 (fallback to the older checkpoint, then none). Fails itself otherwise.
granular_dg_unit_test(unit/shared_blocks MPI 3 NUMDIFF -a 0 -r 0 LABELS mpi)
set_tests_properties(unit/shared_blocks PROPERTIES RUN_SERIAL TRUE)
# Subcell blending in the line engine: the blending factors (the
# jump cell alpha_max, its neighbours half, smooth cells 0 with their rates
# bitwise those of the cell-by-cell kernel), conservation to round-off, and with alpha = 1 the FV
# rate of the subcells (checked by quadrature, not by the engine's tables);
# degrees 1-4, linear advection, periodic. Fails itself otherwise.
granular_dg_unit_test(unit/subcell_blending NUMDIFF -a 0 -r 0)
# Subcell blending in the 2D MatrixFree engine: the blending
# factors (the jump cell alpha_max, its four face neighbours half, smooth
# cells 0 with their rates bitwise unchanged), every mean rate the DG one and
# conservation to round-off, and with alpha = 1 the FV rate of the subcells
# plus the DG mean's correction (checked by quadrature, not by the engine's
# tables); degrees 1-3, 2D linear advection, periodic. Fails itself otherwise.
granular_dg_unit_test(unit/subcell_blending_2d NUMDIFF -a 0 -r 0)
# SIMD batches of the line engine: rates with batches equal the
# cell-by-cell kernel to 1e-14 of their size (elasticity quadratic/impedance
# and exponential/LLF with two materials, the column with gravity, periodic
# advection; degrees 0-4), and a stage written in place equals it written
# out of place, bit for bit. Fails itself otherwise.
granular_dg_unit_test(unit/line_batches NUMDIFF -a 0 -r 0)
# The limiter's SIMD batches: in 1D the analysis and TVB test of
# every cell run on batches of interior cells; the flags and the limited
# states equal those of the cell-by-cell limiter, bit for bit (elasticity
# flux_variables and characteristic with two materials, the column
# characteristic, periodic advection componentwise; degrees 1-4, smooth and
# rough cells, so both outcomes occur). Fails itself otherwise.
granular_dg_unit_test(unit/limiter_batches NUMDIFF -a 0 -r 0)
# The writers on a full disk (/dev/full) and beside a user's files: a
# RunError naming the file instead of a silent success, and a file the output
# directory's manifest does not list refused before it is touched. Fails
# itself otherwise.
granular_dg_unit_test(unit/output_files NUMDIFF -a 0 -r 0)
# A SIGINT or SIGTERM outside a time loop (during set-up, after the loop):
# exit 128 + signal at once and one line saying when (none on a rank that
# does not report), each in a child process; fails itself otherwise.
granular_dg_unit_test(unit/interrupt_outside_loop NUMDIFF -a 0 -r 0)
# The modal-energy indicator's measure at solution scales 1e-300 ... 1e300:
# the same share as at scale 1 (its squares had overflowed beyond ~1e154 and
# underflowed below ~1e-154: no cell flagged); fails itself otherwise.
granular_dg_unit_test(unit/modal_energy_scale NUMDIFF -r 1e-12)
