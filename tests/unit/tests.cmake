# Unit tests of the physics: small programs printing to stdout.
granular_dg_unit_test(unit/elasticity_physics NUMDIFF -a 1e-7 -r 0)
