#!/usr/bin/python3
"""Independent reference for the radial (Jenike) field of the hopper scene.

Solves the BVP (16)-(17) of Gremaud & Matthews (On the computation of steady
hopper flows I) by shooting from the
axis with SciPy's DOP853 (rtol 1e-13) and Brent's method, and writes the
columns the tests compare (theta,sigma,psi,T_rr,T_rtheta,T_thetatheta,T_phiphi
per unit rho g r) at the points of radial-field.csv. It shares no code with
source/equations/hopper/radial_field.cc (Boost.odeint Dormand-Prince
5(4) and TOMS 748).

  /usr/bin/python3 tests/hopper/radial_reference.py cone 30 61 > tests/hopper/radial_cone.output
"""
import sys
import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

deg = np.pi / 180


def radial_field(geometry, theta_w_deg, delta_deg=32.1, phi_deg=11.7):
    s = np.sin(delta_deg * deg)
    phi = phi_deg * deg
    psi_w = 0.5 * (phi + np.arcsin(np.sin(phi) / s))
    theta_w = theta_w_deg * deg
    cone = geometry == 'cone'
    k = 4 if cone else 2

    def rhs(th, y):
        sig, psi = y
        c2, s2 = np.cos(2 * psi), np.sin(2 * psi)
        A = np.array([[-s * s2, -2 * s * sig * c2], [1 + s * c2, -2 * s * sig * s2]])
        if cone:
            ct = 1 / np.tan(th)
            B = [-np.cos(th) + sig * (4 * s * c2 - 1 + s + s * ct * s2),
                 np.sin(th) + sig * (4 * s * s2 - s * (c2 - 1) * ct)]
        else:
            B = [-np.cos(th) + sig * (3 * s * c2 - 1), np.sin(th) + sig * 3 * s * s2]
        return np.linalg.solve(A, B)

    th0 = 1e-8 if cone else 0.0

    def shoot(sig0, dense=False):
        dpsi0 = (1 - sig0 * ((k + 1) * s - 1)) / (k * s * sig0)
        return solve_ivp(rhs, [th0, theta_w], [sig0, dpsi0 * th0], method='DOP853',
                         rtol=1e-13, atol=1e-15, dense_output=dense)

    sig0 = brentq(lambda x: shoot(x).y[1, -1] - psi_w, 0.05, 2.0, xtol=1e-15, rtol=1e-15)
    return shoot(sig0, True), s, theta_w


def main():
    geometry, theta_w_deg, n = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
    sol, s, theta_w = radial_field(geometry, theta_w_deg)
    print('theta,sigma,psi,T_rr,T_rtheta,T_thetatheta,T_phiphi')
    for i in range(n):
        th = theta_w * i / (n - 1)
        sig, psi = sol.sol(max(th, sol.t[0]))
        if i == 0:
            psi = 0.0
        T = [sig * (1 - s * np.cos(2 * psi)), -sig * s * np.sin(2 * psi),
             sig * (1 + s * np.cos(2 * psi)), sig * (1 + s) if geometry == 'cone' else sig]
        print(','.join('%.12g' % (v + 0.0) for v in [th, sig, psi] + T))


if __name__ == '__main__':
    main()
