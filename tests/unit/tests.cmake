# Unit tests of the physics: small programs printing to stdout.
granular_dg_unit_test(unit/elasticity_physics NUMDIFF -a 1e-7 -r 0)
# Interface-aware flux at a material interface (issue 4): errors ~0.
granular_dg_unit_test(unit/layered_interface NUMDIFF -a 1e-7 -r 0)
