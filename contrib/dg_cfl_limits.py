#!/usr/bin/python3
"""Linear stability limits of the CFL number nu = a dt / h of SSP-RK3 with
upwind DG of degree p = 0..4 (Legendre modes) for u_t + u_x = 0: Fourier
analysis of the semi-discrete operator, the largest nu with
|R(nu z)| <= 1 for all its eigenvalues z, R(z) = 1 + z + z^2/2 + z^3/6.
The values are the ssp_rk3 row of dg::cfl_limit() in source/dg/parameters.cc
(rounded down there; tests/unit/rk_stability_limits computes every scheme's
row from the program's integrators and checks the table).

    /usr/bin/python3 contrib/dg_cfl_limits.py
"""
import numpy as np
from numpy.polynomial import legendre as L


def symbol(p, theta):
    """h times the semi-discrete operator on one cell for the Fourier mode
    exp(i j theta): M^{-1} (volume term - outflow trace + inflow trace)."""
    n = p + 1
    x, w = L.leggauss(n + 2)
    P = np.array([L.legval(x, [0] * k + [1]) for k in range(n)])
    dP = np.array([L.legval(x, L.legder([0] * k + [1])) for k in range(n)])
    D = np.array([[np.sum(w * P[m] * dP[k]) for m in range(n)] for k in range(n)])
    s = np.array([(-1.) ** k for k in range(n)])
    one = np.ones(n)
    A = D - np.outer(one, one) + np.exp(-1j * theta) * np.outer(s, one)
    return np.diag([2 * k + 1. for k in range(n)]) @ A


def R(z):
    return 1 + z + z ** 2 / 2 + z ** 3 / 6


thetas = np.linspace(0, 2 * np.pi, 2001)
for p in range(5):
    z = np.concatenate([np.linalg.eigvals(symbol(p, t)) for t in thetas])
    lo, hi = 0., 2.
    for _ in range(60):
        nu = (lo + hi) / 2
        lo, hi = (nu, hi) if np.max(np.abs(R(nu * z))) <= 1 + 1e-13 else (lo, nu)
    print(f'degree {p}: CFL limit {lo:.6f}')
