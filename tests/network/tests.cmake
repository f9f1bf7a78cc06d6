# network tests (included by tests/CMakeLists.txt)

# Physics and vertex: flux consistency and monotonicity, Godunov and
# Engquist-Osher against brute force, the law in SIMD lanes against its
# scalar values, the stationary c_0 of Examples 7.1, 7.2, 7.4 (deviations
# printed, compared at 1e-12 abs).
granular_dg_unit_test(network/network_physics NUMDIFF -a 1e-12 -r 0)

# The engine is a template on the physics of an edge: a law of the test's
# own (linear advection, upwind) runs it and gives EdgeLaw's state and time
# steps bit for bit (differences printed, compared exactly).
granular_dg_unit_test(network/custom_law NUMDIFF -a 0 -r 0)
# (both laws in one unit at -O1: the check needs equal code, not fast code,
# and the unit compiles the whole engine)
target_compile_options(test_custom_law PRIVATE -O1)

# The initial projection's cell moments (add_cell_moments): smooth data in
# one level of adaptive Gauss integration in every cell of a fine mesh (the
# counts exactly), a jump inside a cell located to round-off.
granular_dg_unit_test(network/cell_moments NUMDIFF -a 0 -r 0)

# L1 contraction at every step and preservation of order between two runs
# with different data (Theorem 4.14), and their failure with a vertex 4
# times too narrow (the ratios to 1e-9 relative).
granular_dg_unit_test(network/network_contraction NUMDIFF -a 1e-14 -r 1e-9)

# The error tables of the five examples at levels 3-8 (degree 0: the paper's
# scheme), against the independent numpy implementation of (4.1) in
# tests/network/fv_reference.py, which wrote the .output files:
# L1 error over edges and vertex, EOC, number of steps; 1e-9 relative
# (round-off: the two codes agree to ~1e-13), 1e-15 absolute for the
# vertex part, which is round-off once the vertex is stationary.
set(table_columns convergence.csv:level,time_steps,l1_error,eoc,l1_error_vertex)
set(table_levels "Convergence/cells=8,16,32,64,128,256")
foreach(e 1 2 3 4 5)
  granular_dg_test(network/example_7_${e}_table PRM ../prm/network_example_7_${e}.prm
    ARGS --set Convergence/enabled=true --set ${table_levels}
    COMPARE ${table_columns} NUMDIFF -r 1e-9 -a 1e-15)
  # the stored tables are what the numpy implementation computes today
  # (its own round-off: 1e-12 relative)
  granular_dg_test(network/example_7_${e}_fv_reference EXE ${TEST_PYTHON}
    ARGS ${CMAKE_CURRENT_SOURCE_DIR}/network/fv_reference.py --examples 7.${e} --csv out
    KEEP_OUTPUT COMPARE example_7_${e}_table.output EXPECTED network/example_7_${e}_table.output
    NUMDIFF -r 1e-12 -a 1e-15)
endforeach()

# The tables must notice a wrong vertex: a full cell per edge end (width
# factor 2, dx_0 = N dx) in 7.3 and the paper's typo c_0 = sqrt(3/2) in 7.4
# run to completion but differ from the reference tables (the .output files
# are links to them); the test passes only when run_test reports the
# difference.
granular_dg_test(network/wrong_vertex_width PRM ../prm/network_example_7_3.prm
  ARGS --set Convergence/enabled=true --set ${table_levels}
       --set "Network/vertex width factor=2"
  COMPARE ${table_columns} NUMDIFF -r 1e-9 -a 1e-15)
granular_dg_test(network/wrong_c0 PRM ../prm/network_example_7_4.prm
  ARGS --set Convergence/enabled=true --set ${table_levels}
       --set "Network/vertex initial value=sqrt(3/2)"
  COMPARE ${table_columns} NUMDIFF -r 1e-9 -a 1e-15)
set_tests_properties(network/wrong_vertex_width PROPERTIES
  PASS_REGULAR_EXPRESSION "wrong_vertex_width.result differs from")
set_tests_properties(network/wrong_c0 PROPERTIES
  PASS_REGULAR_EXPRESSION "wrong_c0.result differs from")

# The discrete stationary states of 7.2 (traffic) and 7.4 (Burgers) are kept
# to round-off: L1, L2 and Linf distance to the initial data (edges and
# vertex) at T, at degree 0 and at degree 2 with the limiter (1e-13 abs).
foreach(s 7_2 7_4)
  granular_dg_test(network/stationary_${s} PRM network/stationary_${s}.prm
    COMPARE summary.json:errors/component_0_l1_l2_linf NUMDIFF -a 1e-13 -r 0)
  granular_dg_test(network/stationary_${s}_dg PRM network/stationary_${s}.prm
    ARGS --set Discretization/degree=2 --set "Time stepping/CFL number=0.18"
    COMPARE summary.json:errors/component_0_l1_l2_linf NUMDIFF -a 1e-13 -r 0)
endforeach()

# Mass conservation at every step: R = (mass(t) - mass(0) - far-end inflow)
# / ||u(0)||_L1 over edges + vertex; max |R| over the steps (the drift) and
# the largest change of R in one step are <= 1e-13 (compared with 0 at
# 1e-13 abs) for the roundabout (7.1, degree 0), the traffic fluxes (7.2,
# degree 1 + limiter) and the shock through the vertex (7.5, degree 2 +
# limiter), level 8. (The drift is accumulated round-off: it grows with the
# number of steps, to 1e-12 after 41000 steps at level 12; one step stays
# below 1e-15.)
granular_dg_test(network/mass_7_1 PRM ../prm/network_example_7_1.prm
  ARGS --set "Output/write vtu=false"
  COMPARE summary.json:diagnostics/mass_balance_residual_max,diagnostics/mass_step_residual_max NUMDIFF -a 1e-13 -r 0)
granular_dg_test(network/mass_7_2_dg PRM ../prm/network_example_7_2.prm
  ARGS --set "Output/write vtu=false" --set Discretization/degree=1
       --set "Time stepping/CFL number=0.3" --set Limiter/scheme=componentwise
  COMPARE summary.json:diagnostics/mass_balance_residual_max,diagnostics/mass_step_residual_max NUMDIFF -a 1e-13 -r 0)
granular_dg_test(network/mass_7_5_dg PRM ../prm/network_example_7_5.prm
  ARGS --set "Output/write vtu=false" --set Discretization/degree=2
       --set "Time stepping/CFL number=0.18" --set Limiter/scheme=componentwise
  COMPARE summary.json:diagnostics/mass_balance_residual_max,diagnostics/mass_step_residual_max NUMDIFF -a 1e-13 -r 0)

# A single run of 7.1 at level 6 with output: the L1 error equals the numpy
# reference's (1e-9 rel), the vertex ends at sqrt(5/3), the mass balance;
# its solution.pvd is read by ParaView below.
granular_dg_test(network/example_7_1_run PRM ../prm/network_example_7_1.prm
  ARGS --set "Network/cells per unit length=64"
  COMPARE summary.json:diagnostics/l1_error,diagnostics/vertex_value_final,diagnostics/vertex_exact_final,diagnostics/mass_balance_residual_max
  NUMDIFF -r 1e-9 -a 1e-13
  FIXTURES_SETUP network_7_1_output WORKDIR ${CMAKE_CURRENT_BINARY_DIR}/network_7_1_run)
if(PVPYTHON_EXECUTABLE)
  # ParaView opens the network's solution.pvd by absolute path: 7 steps at
  # t = 0, 0.125, ..., 0.625, 0.7; the arrays; 4 edges x 64 cells x 2 points
  # + the vertex (a line patch of length 0 at the origin: 2 points) = 514
  # points; no NaN.
  granular_dg_test(network/paraview_pvd EXE ${PVPYTHON_EXECUTABLE}
    ARGS --no-mpi ${CMAKE_CURRENT_SOURCE_DIR}/paraview/read_pvd.py
         ${CMAKE_CURRENT_BINARY_DIR}/network_7_1_run/out/solution.pvd
    COMPARE stdout NUMDIFF -a 0 -r 0 KEEP_OUTPUT FIXTURES_REQUIRED network_7_1_output)
endif()

# Order of accuracy through the vertex (smooth linear advection): with the
# vertex without volume every degree 1-3 converges at p + 1 (EOC of levels
# 5-6 within 0.15; degree 3 at CFL 0.03 so that SSPRK3's time error stays
# below h^4); with the paper's vertex cell the O(dx) lag of its value limits
# every degree to first order (EOC 1 within 0.1).
granular_dg_test(network/smooth_eoc_zero_width PRM ../prm/network_smooth.prm
  ARGS --set Convergence/enabled=true --set "Network/vertex width factor=0"
       --set "Convergence/degrees=1,2,3" --set "Convergence/CFL numbers=0.3,0.18,0.03"
       --set "Convergence/cells=8,16,32,64"
  COMPARE convergence-rates.csv NUMDIFF -a 0.15 -r 0)
granular_dg_test(network/smooth_eoc_vertex_cell PRM ../prm/network_smooth.prm
  ARGS --set Convergence/enabled=true --set "Convergence/degrees=1,2,3"
       --set "Convergence/CFL numbers=0.3,0.18,0.1" --set "Convergence/cells=32,64,128"
  COMPARE convergence-rates.csv NUMDIFF -a 0.1 -r 0)

# Bad input: exit 2, one line naming the parameter, its value and what is
# allowed (verbatim), nothing written.
granular_dg_test(network/bad_direction PRM network/bad_direction.prm EXIT 2 KEEP_OUTPUT)
granular_dg_test(network/bad_flux PRM ../prm/network_example_7_4.prm
  ARGS --set "Network/Edge 3/flux=burger" EXIT 2 KEEP_OUTPUT)
granular_dg_test(network/negative_length PRM ../prm/network_example_7_4.prm
  ARGS --set "Network/Edge 5/length=-1" EXIT 2 KEEP_OUTPUT)
granular_dg_test(network/alpha_swap PRM ../prm/network_example_7_2.prm
  ARGS --set "Network/Edge 3/alpha=4" --set "Network/Edge 5/alpha=2" EXIT 2 KEEP_OUTPUT)
# An example's exact solution lives on edges of length 1: another length would
# measure the errors against the wrong solution.
granular_dg_test(network/wrong_length PRM ../prm/network_example_7_5.prm
  ARGS --set "Network/Edge 1/length=3" EXIT 2 KEEP_OUTPUT)
# An edge given by from/to that is not the example's is blamed on the entry
# the user set (from), not on direction.
granular_dg_test(network/wrong_from PRM ../prm/network_two_stars.prm
  ARGS --set "Network/Edge 4/from=1" EXIT 2 KEEP_OUTPUT)
granular_dg_test(network/wrong_initial_data PRM ../prm/network_example_7_5.prm
  ARGS --set "Network/Edge 1/initial data=if(x < 0.5, 2, 1)" EXIT 2 KEEP_OUTPUT)
granular_dg_test(network/bad_vertex_value PRM ../prm/network_example_7_4.prm
  ARGS --set "Network/vertex initial value=c0" EXIT 2 KEEP_OUTPUT)
# a Network-wide vertex value that no vertex takes (every vertex without
# volume) is refused, not ignored
granular_dg_test(network/vertex_value_never_taken PRM ../prm/network_example_7_4.prm
  ARGS --set "Network/vertex width factor=0" --set "Network/vertex initial value=0.3"
  EXIT 2 KEEP_OUTPUT)
granular_dg_test(network/bad_initial_expression PRM ../prm/network_example_7_4.prm
  ARGS --set "Network/Edge 2/initial data=1 + y" EXIT 2 KEEP_OUTPUT)
# The edges run in one line engine (EdgeLines): the MatrixFree engine is refused.
granular_dg_test(network/engine_matrix_free PRM ../prm/network_example_7_3.prm
  ARGS --set Discretization/engine=matrix_free EXIT 2 KEEP_OUTPUT)
# Skipping quiet cells is not built for the network: a skip tolerance > 0
# is refused (it was ignored).
granular_dg_test(network/skip_tolerance PRM ../prm/network_example_7_4.prm
  ARGS --set "Time stepping/skip tolerance=1e-15" EXIT 2 KEEP_OUTPUT)
# A network that cannot fit (5 edges of 2 10^9 cells) is refused before
# anything is allocated: one line with the estimate, the memory available and
# what to change. MemAvailable varies between runs: -r 1 on the numbers.
granular_dg_test(network/memory_does_not_fit PRM ../prm/network_example_7_4.prm
  ARGS --set "Network/cells per unit length=2000000000" EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 1)
granular_dg_test(network/no_edges PRM ../prm/network_example_7_4.prm
  ARGS --set "Network/Edge 1/direction=none" --set "Network/Edge 2/direction=none"
       --set "Network/Edge 3/direction=none" --set "Network/Edge 4/direction=none"
       --set "Network/Edge 5/direction=none" --set "Network/exact solution=none"
  EXIT 2 KEEP_OUTPUT)

# ---------------------------------------------------------------- general graphs
# Two star vertices joined by an edge (prm/network_two_stars.prm): L1 error
# against the exact solution built from the stationary construction at each
# vertex (shocks into the connecting edge, then out of the second vertex), per
# level and degree 0-2, and the vertex part (exact to round-off: both vertex
# states are stationary between the shock arrivals). The errors fall at rate
# ~1 (shocks); 1e-9 relative, vertex errors to 1e-14 absolute.
granular_dg_test(network/two_stars_table PRM ../prm/network_two_stars.prm
  ARGS --set Convergence/enabled=true --set "Convergence/cells=16,32,64,128,256"
  COMPARE convergence.csv:degree,level,l1_error,eoc,l1_error_vertex NUMDIFF -r 1e-9 -a 1e-14)

# A smooth solution through two vertices without volume: the EOC of the two
# finest levels (64, 128 cells per unit length) is p + 1 for p = 0..3
# (0.93, 2.03, 3.00, 3.91), compared to 1e-6.
granular_dg_test(network/smooth_two_vertices_eoc PRM network/smooth_two_vertices.prm
  ARGS --set Convergence/enabled=true
  COMPARE convergence-rates.csv NUMDIFF -a 1e-6 -r 0)

# A chain of three edges through two vertices without volume equals the same
# problem on one line (tests/network/chain_equals_line.py): degree 0 exactly,
# degree 2 to the 12 digits of the profile files (1e-12 relative).
set(chain_equals_line ${CMAKE_CURRENT_SOURCE_DIR}/network/chain_equals_line.py)
granular_dg_test(network/chain_equals_line_p0 EXE ${TEST_PYTHON}
  ARGS ${chain_equals_line} $<TARGET_FILE:granular_dg> ${CMAKE_CURRENT_SOURCE_DIR}/network/chain.prm
       --set Discretization/degree=0 --set "Time stepping/CFL number=0.5"
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(network/chain_equals_line_p2 EXE ${TEST_PYTHON}
  ARGS ${chain_equals_line} $<TARGET_FILE:granular_dg> ${CMAKE_CURRENT_SOURCE_DIR}/network/chain.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# Mass over a graph read from CSV files (tests/network/ring.prm: a ring of
# three junctions, traffic in at one and out at another) is conserved to
# round-off at every step, at degree 0 (which also checks the maximum
# principle in every stage) and degree 2 with the limiter: the drift and the
# largest change in one step, compared with 0 at 1e-13 abs (the degree-2 run
# stops at t = 1 after 587 steps, drift 4.2e-14: the drift is accumulated round-off, 1.1e-13
# after the 1141 steps to t = 2, with 9.6e-16 per step).
set(ring_files COPY network/ring.csv network/ring_vertices.csv)
granular_dg_test(network/ring_mass PRM network/ring.prm ${ring_files}
  COMPARE summary.json:diagnostics/mass_balance_residual_max,diagnostics/mass_step_residual_max NUMDIFF -a 1e-13 -r 0)
granular_dg_test(network/ring_mass_dg PRM network/ring.prm ${ring_files}
  ARGS --set Discretization/degree=2 --set "Time stepping/CFL number=0.18"
       --set Limiter/scheme=componentwise --set "Time stepping/final time=1"
       --set "Output/output times=1"
  COMPARE summary.json:diagnostics/mass_balance_residual_max,diagnostics/mass_step_residual_max NUMDIFF -a 1e-13 -r 0)

# Graph validation: one line naming the file, line, edge or vertex; exit 2
# (hex_id: a vertex id written 0x1 is not an integer id; fractional_edge_id:
# an edge id 2.5 is not an integer edge id; subnormal: a flux
# parameter of 1e-308 is not of normal magnitude; isolated_vertex: a
# vertex only the vertex file lists is blamed on that file and its line;
# burgers_parameter: a parameter on a burgers road, which has none;
# unclosed_quote: a field in double quotes without its closing quote;
# unquoted_commas: an expression with a comma outside double quotes, which
# splits it, blamed on its unbalanced parenthesis).
foreach(bad duplicate_id fractional_edge_id negative_length nonfinite subnormal self_loop
        bad_header hex_id burgers_parameter unclosed_quote unquoted_commas)
  granular_dg_test(network/graph_${bad} PRM network/ring.prm
    COPY network/ring_${bad}.csv network/ring_vertices.csv
    ARGS --set "Network/graph file=ring_${bad}.csv" EXIT 2 KEEP_OUTPUT)
endforeach()
foreach(bad missing_vertex isolated_vertex)
  granular_dg_test(network/graph_${bad} PRM network/ring.prm
    COPY network/ring.csv network/ring_${bad}.csv
    ARGS --set "Network/vertex file=ring_${bad}.csv" EXIT 2 KEEP_OUTPUT)
endforeach()
# A graph file that is not a regular file (a device that never ends, such as
# /dev/zero, or a directory) is refused instead of read.
granular_dg_test(network/graph_not_a_file PRM network/ring.prm
  ARGS --set "Network/graph file=/dev/zero" EXIT 2 KEEP_OUTPUT)
# Graph and vertex files written as users' tools write them read as the
# plain ring: the run completes with the ring's cells, vertices and final
# vertex values (1e-12 relative; the four outputs are the same file).
#   bom: saved as "CSV UTF-8" (a byte-order mark, CRLF line ends, no
#        comment line);
#   cr: the line ends of an old Mac (CR alone, "CSV (Macintosh)");
#   irregular: columns in another order, vertex ids 10, 20, 30 and vertex
#        rows out of order, blanks and a tab around fields, blank and
#        indented comment lines between rows, empty last fields, no line end
#        after the last row;
#   quoted: every field in double quotes (as spreadsheets and pandas'
#        QUOTE_ALL write them), blanks around quotes, empty fields as "",
#        and expressions with commas in them (min, max) that give the ring's
#        constants.
foreach(form bom cr irregular quoted)
  granular_dg_test(network/graph_${form} PRM network/ring.prm
    COPY network/ring_${form}.csv network/ring_vertices_${form}.csv
    ARGS --set "Network/graph file=ring_${form}.csv"
         --set "Network/vertex file=ring_vertices_${form}.csv"
         --set "Time stepping/final time=1" --set "Output/output times=1"
    COMPARE summary.json:n_cells,diagnostics/n_vertices,diagnostics/vertex_values_final
    NUMDIFF -r 1e-12 -a 0)
endforeach()
# Network/edge profiles = auto (the default): one CSV file per edge and
# snapshot for a graph of up to 100 edges (chain100.csv: the last edge's
# profile is written), none for a larger one (chain101.csv: the VTU only).
granular_dg_test(network/profiles_auto_100 PRM network/ring.prm COPY network/chain100.csv
  ARGS --set "Network/graph file=chain100.csv" --set "Network/vertex file="
       --set "Time stepping/final time=0.5" --set "Output/output times=0.5"
  COMPARE profile-0001-edge-100.csv NUMDIFF -a 1e-12)
granular_dg_test(network/profiles_auto_101 PRM network/ring.prm COPY network/chain101.csv
  ARGS --set "Network/graph file=chain101.csv" --set "Network/vertex file="
       --set "Time stepping/final time=0.5" --set "Output/output times=0.5"
  COMPARE summary.json:n_cells
  ABSENT_FILES out/profile-0001-edge-1.csv out/profile-0001-edge-101.csv out/profile-0001.csv)
granular_dg_test(network/graph_file_and_vertex_section PRM network/ring.prm ${ring_files}
  ARGS --set "Network/Vertex 2/width factor=0" EXIT 2 KEEP_OUTPUT)
# An Edge N entry beside a graph file would be ignored (the file's length
# kept): refused, naming the entry the user set.
granular_dg_test(network/graph_file_and_edge_section PRM network/ring.prm ${ring_files}
  ARGS --set "Network/Edge 2/length=3" EXIT 2 KEEP_OUTPUT)
# An Edge N section with entries but no direction and no from/to describes
# no edge: refused instead of ignored.
granular_dg_test(network/edge_section_without_ends PRM ../prm/network_two_stars.prm
  ARGS --set "Network/Edge 7/length=3" EXIT 2 KEEP_OUTPUT)
# Edge N sections number their vertices from 1 without gaps: a star numbered
# 3 is refused naming the gap (it had blamed Vertex 1 for having no edges).
granular_dg_test(network/vertex_numbers_gap PRM network/chain.prm
  ARGS --set "Network/Edge 1/to=3" --set "Network/Edge 2/from=3" EXIT 2 KEEP_OUTPUT)
# Far-end data on an edge between two vertices could never act: refused (it
# had been ignored).
granular_dg_test(network/far_end_without_free_end PRM network/chain.prm
  ARGS --set "Network/Edge 2/far end data=5" EXIT 2 KEEP_OUTPUT)
# A convergence study whose runs fail (Example 7.3 at CFL 1.2, the stability
# check off, a vertex wide enough not to bound the step) ends with exit 3 and
# summary.json's status naming the run; a benchmark of the same case fails
# with the one line of a run (time, step, position, state, test).
granular_dg_test(network/study_failure_summary PRM ../prm/network_example_7_3.prm
  ARGS --set Convergence/enabled=true --set "Convergence/cells=8, 16"
       --set "Time stepping/CFL number=1.2" --set "Time stepping/check stability limit=false"
       --set "Network/vertex width factor=3"
  EXIT 3 COMPARE summary.json:status NUMDIFF -a 0 -r 0)
granular_dg_test(network/benchmark_failure PRM ../prm/network_example_7_3.prm
  ARGS --benchmark --set "Time stepping/CFL number=1.2"
       --set "Time stepping/check stability limit=false" --set "Network/vertex width factor=3"
  EXIT 3 NUMDIFF -a 0 -r 0)
granular_dg_test(network/edge_self_loop PRM ../prm/network_two_stars.prm
  ARGS --set "Network/Edge 3/to=1" EXIT 2 KEEP_OUTPUT)
granular_dg_test(network/edge_direction_and_from PRM ../prm/network_two_stars.prm
  ARGS --set "Network/Edge 3/direction=in" EXIT 2 KEEP_OUTPUT)
# A Vertex N section beyond the vertices the edges name: the message names
# the entry set (Vertex 5 of a two-vertex graph had been blamed on Vertex 3).
granular_dg_test(network/vertex_without_edges PRM ../prm/network_two_stars.prm
  ARGS --set "Network/Vertex 5/width factor=0" EXIT 2 KEEP_OUTPUT)
granular_dg_test(network/edge_unknown_vertex PRM ../prm/network_two_stars.prm
  ARGS --set "Network/Edge 3/to=9" EXIT 2 KEEP_OUTPUT)

# One edge of length 1e-9 in the ring at 32 cells per unit length gets one
# cell of width 1e-9: one warning line at set-up names the edge, the factor
# (3.1e7) and what it does to the time step; the run goes on (to t = 1e-9).
granular_dg_test(network/short_edge_warning PRM network/ring.prm
  COPY network/ring_short_edge.csv network/ring_vertices.csv
  ARGS --set "Network/graph file=ring_short_edge.csv"
       --set "Time stepping/final time=1e-9" --set "Output/output times=1e-9"
  EXPECT_FILES out/summary.json)

# Resuming with a graph or vertex file whose content changed since the
# checkpoint (an edge reversed with another flux law and another inflow; a
# width factor) is refused like a changed parameter: exit 2, one line naming
# the file; with the files restored the run resumes and completes
# (tests/network/resume_changed_graph.py).
granular_dg_test(network/resume_changed_graph EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/network/resume_changed_graph.py $<TARGET_FILE:granular_dg>
       ring.prm
  COPY network/ring.prm network/ring.csv network/ring_vertices.csv
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# The shipped city grid (prm/network_city_grid.prm: 84 roads, 36 junctions
# from CSV files) at 8 cells per unit length: mass conserved to round-off at
# every step at degree 2 with the limiter (to t = 3, through the rush hour:
# the drift to t = 6 is 9.5e-14, accumulated round-off), and at degree 0 (where every stage
# also checks the maximum principle); compared with 0 at 1e-13 abs.
set(city_files COPY ../prm/network_city_grid.csv ../prm/network_city_grid_vertices.csv)
granular_dg_test(network/city_grid_mass PRM ../prm/network_city_grid.prm ${city_files}
  ARGS --set "Network/cells per unit length=8" --set "Output/write vtu=false"
       --set "Network/edge profiles=none"
       --set "Time stepping/final time=3" --set "Output/output times=3"
  COMPARE summary.json:diagnostics/mass_balance_residual_max,diagnostics/mass_step_residual_max NUMDIFF -a 1e-13 -r 0)
granular_dg_test(network/city_grid_mass_p0 PRM ../prm/network_city_grid.prm ${city_files}
  ARGS --set "Network/cells per unit length=8" --set "Output/write vtu=false"
       --set "Network/edge profiles=one_file" --set Discretization/degree=0
       --set "Time stepping/CFL number=0.5"
  COMPARE summary.json:diagnostics/mass_balance_residual_max,diagnostics/mass_step_residual_max NUMDIFF -a 1e-13 -r 0
  EXPECT_FILES profile-0006.csv)

# Edges over MPI ranks: the solution does not depend on the number
# of ranks, bit for bit (tests/network/rank_equivalence.py prints the number
# of profile and VTU files that differ from the one-rank run: 0; and the
# column-scaled difference of timeseries.csv without the round-off column
# mass_balance_residual, compared with 0 at 1e-12). The city grid at degree 2
# with the limiter, 16 cells per unit length to t = 2, on 1, 2 and 3 ranks
# (and stopped on 2 ranks, resumed on 3): every edge ends in a full SIMD batch,
# also the last edge of a rank (a line engine that computed that batch cell
# by cell differed in the last bits from t = 1.3 on); the chain, whose
# vertices have no volume (their traces are exchanged after the limiter
# too), stopped on 3 and resumed on 2; the city grid at degree 0, whose
# maximum-principle bounds are reduced over the ranks.
# RUN_SERIAL: three processes on two cores.
set(rank_equivalence ${TEST_PYTHON} ARGS ${CMAKE_CURRENT_SOURCE_DIR}/network/rank_equivalence.py
  $<TARGET_FILE:granular_dg>)
set(city_small --set "Network/cells per unit length=8" --set "Time stepping/final time=1"
  --set "Output/output times=0.5, 1")
granular_dg_test(network/rank_equivalence_city EXE ${rank_equivalence}
  ${CMAKE_CURRENT_SOURCE_DIR}/../prm/network_city_grid.prm 1 2 3 --resume 60:2:3
  --set "Network/cells per unit length=16" --set "Time stepping/final time=2"
  --set "Output/output times=1, 2"
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 1e-12 -r 0 LABELS mpi)
granular_dg_test(network/rank_equivalence_chain EXE ${rank_equivalence}
  ${CMAKE_CURRENT_SOURCE_DIR}/network/chain.prm 1 2 3 --resume 50:3:2
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 1e-12 -r 0 LABELS mpi)
granular_dg_test(network/rank_equivalence_city_p0 EXE ${rank_equivalence}
  ${CMAKE_CURRENT_SOURCE_DIR}/../prm/network_city_grid.prm 1 3 ${city_small}
  --set Discretization/degree=0 --set "Time stepping/CFL number=0.5" --set Limiter/scheme=none
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 1e-12 -r 0 LABELS mpi)
set_tests_properties(network/rank_equivalence_city network/rank_equivalence_chain
  network/rank_equivalence_city_p0 PROPERTIES RUN_SERIAL TRUE)

# A vertex cell 5 times narrower than the paper's (width factor 0.2 < 2 x
# CFL 0.5): the edges' time step would make its update (4.1b) non-monotone
# (Example 7.3 then grows to 1e61 by t = 0.5); the time step also keeps
# dt sum max|f'| <= dx_0 there (1280 steps instead of 256), and the run
# stays stable: the vertex reaches its exact value 1 and the L1 error
# against the exact solution is 0.0335 (0.0251 with the paper's cell).
granular_dg_test(network/narrow_vertex_7_3 PRM ../prm/network_example_7_3.prm
  ARGS --set "Network/vertex width factor=0.2" --set "Output/write vtu=false"
  COMPARE summary.json:status,diagnostics/vertex_value_final,diagnostics/l1_error NUMDIFF -r 1e-6)
# ... and says so at set-up, in one line naming the vertex and its factor.
granular_dg_test(network/narrow_vertex_warning PRM ../prm/network_two_stars.prm
  ARGS --set "Network/Vertex 2/width factor=0.3" --set "Time stepping/final time=0.01"
       --set "Output/output times=0.01" EXPECT_FILES out/summary.json)

# A failure found on rank 1 of 2 (the partition puts Edge 22 there): the
# city grid at degree 0 whose Edge 22 inflow data turn NaN at t = 0.35
# (network/city_grid_nan_inflow.csv); every rank stops with the one-rank
# run's status (the edge, position, time, step and value), exit 3, the last
# good state written.
granular_dg_test(network/failure_on_rank_1 PRM ../prm/network_city_grid.prm MPI 2 EXIT 3
  COPY network/city_grid_nan_inflow.csv ../prm/network_city_grid_vertices.csv
  ARGS --set "Network/cells per unit length=8" --set Discretization/degree=0
       --set "Time stepping/CFL number=0.5" --set Limiter/scheme=none
       --set "Network/graph file=city_grid_nan_inflow.csv"
  COMPARE summary.json:status,final_time NUMDIFF -r 1e-9 LABELS mpi)
# Subcell blending on every edge (Limiter/subcell blending, no limiter):
# Burgers' shock through the vertex, P2; mass is conserved to round-off
# as with the limiter (measured 2.4e-14 / 5.0e-16; L1 error 5.2e-3 between the
# unlimited 5.7e-3 and the limited 4.7e-3).
granular_dg_test(network/mass_7_5_blending PRM ../prm/network_example_7_5.prm
  ARGS --set "Output/write vtu=false" --set Discretization/degree=2
       --set "Time stepping/CFL number=0.18" --set Limiter/scheme=none
       --set "Limiter/subcell blending=true"
  COMPARE summary.json:diagnostics/mass_balance_residual_max,diagnostics/mass_step_residual_max NUMDIFF -a 1e-13 -r 0)
# The same run's timeseries.csv has the column blended_cells (cells of all
# edges with a blending factor > 0): none at t = 0, the shock's cells
# afterwards.
granular_dg_test(network/blended_cells_7_5 PRM ../prm/network_example_7_5.prm
  ARGS --set "Output/write vtu=false" --set Discretization/degree=2
       --set "Time stepping/CFL number=0.18" --set Limiter/scheme=none
       --set "Limiter/subcell blending=true"
  COMPARE timeseries.csv:time,blended_cells NUMDIFF -a 0 -r 0)

# A junction without a stationary value (two roads in, none out) under the
# default vertex initial value = stationary: exit 3 at set-up, advice to give
# the vertex an initial value (it has volume: "use a vertex with volume"
# would be wrong), summary.json with that status; and an initial value that
# makes it run.
granular_dg_test(network/stationary_dead_end PRM network/dead_end.prm
  COPY network/dead_end.csv EXIT 3 EXPECT_FILES out/parameters.prm out/summary.json
  NUMDIFF -a 0 -r 0)
granular_dg_test(network/dead_end_filling PRM network/dead_end.prm
  COPY network/dead_end.csv ARGS --set "Network/vertex initial value=1"
  COMPARE summary.json:status NUMDIFF -a 0 -r 0)

# A junction of traffic roads of unequal capacity (network/unequal_capacity.prm:
# alpha = 2 and 1 in at capacity, alpha = 1 out) fills up; its single vertex
# value must stay within [0, 1], the densities of the alpha = 1 roads (beyond,
# their flux turns negative). The run stops where it passes 1 (exit 3, the
# status names the vertex, the road and the time); the same at degree 2,
# where the cell means are checked too.
granular_dg_test(network/unequal_capacity PRM network/unequal_capacity.prm EXIT 3
  COMPARE summary.json:status,final_time NUMDIFF -r 1e-9)
granular_dg_test(network/unequal_capacity_dg PRM network/unequal_capacity.prm EXIT 3
  ARGS --set Discretization/degree=2 --set "Time stepping/CFL number=0.15"
       --set Limiter/scheme=componentwise
  COMPARE summary.json:status,final_time NUMDIFF -r 1e-9)
# Started from its discrete stationary value (Definition 4.4) instead, the
# junction is refused at t = 0: that value, 1.19, lies beyond 1, since at every
# value up to 1 more flows in than out; the status says that the program
# found the value and which parameter gives one (exit 3).
granular_dg_test(network/unequal_capacity_stationary PRM network/unequal_capacity.prm EXIT 3
  ARGS --set "Network/vertex initial value=stationary"
  COMPARE summary.json:status NUMDIFF -r 1e-9)
# Traffic data outside [0, alpha] are refused at t = 0 (exit 3, initial state
# written): initial data 1.5 on a road of capacity 1.
granular_dg_test(network/traffic_initial_jammed PRM network/unequal_capacity.prm EXIT 3
  ARGS --set "Network/Edge 3/initial data=1.5"
  COMPARE summary.json:status NUMDIFF -a 0 -r 0)
# A source vertex (network/source_vertex.prm): no false alarm, neither at
# set-up (its stationary value is 0 within round-off) nor while a congested
# road drains it from u_0 = 0.1 (the scheme undershoots 0 there by 8e-6).
granular_dg_test(network/source_vertex PRM network/source_vertex.prm
  COMPARE summary.json:status NUMDIFF -a 0 -r 0)
granular_dg_test(network/source_vertex_draining PRM network/source_vertex.prm
  ARGS --set "Network/Edge 1/initial data=0.8" --set "Network/vertex initial value=0.1"
  COMPARE summary.json:status NUMDIFF -a 0 -r 0)
# The parameter of another flux law on an Edge N section (it had been
# accepted and ignored): alpha on a linear edge.
granular_dg_test(network/edge_alpha_on_linear PRM ../prm/network_example_7_3.prm
  ARGS --set "Network/Edge 1/alpha=2" EXIT 2 KEEP_OUTPUT)
# The pieces of a VTU snapshot are compressed by one thread per core the
# rank may use, and written in order: the 6 x 6 city grid at 17,000 cells per
# unit length and p = 2 (4,284,072 points: two pieces of 2,193,000 and 2,091,072)
# writes the same file, byte for byte, bound to one core (taskset -c 0: one
# writer thread) and on all cores (tests/network/vtu_threads.py).
granular_dg_test(network/vtu_threads EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/network/vtu_threads.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/network_city_grid.prm
       --set "Network/cells per unit length=17000" --set "Network/edge profiles=none"
       --set "Time stepping/final time=5e-6" --set "Output/output times=5e-6"
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
