#!/usr/bin/env python3
"""Reference values of the "by hand" tests, computed independently of the Rust code from
the equations as written in docs/theory.md (plain Python, double precision, no shared code).

Run: python3 docs/derivations/by_hand.py
Each block names the test that pins its numbers.
"""
from math import exp, expm1, pi, sqrt, gamma

# Table 1: Ru film, sphere of radius R
E, NU, SY, R = 410e9, 0.3, 3.42e9, 4e-6
W, Z0 = 1.0, 0.169e-9

# --- asperity-plastic: yield_onset_of_table_1_ru_by_hand (rigid flat) ---------------
E_STAR = E / (1 - NU**2)                      # rigid flat: E* = E/(1 - nu^2) = 410e9/0.91
CV = 1.295 * exp(0.736 * NU)                   # eq 1
def delta_cp(e1):                              # eq 1 with the modulus e1
    return R * (pi * CV * SY / (2 * e1)) ** 2
DCP = delta_cp(E_STAR)                         # composite reading
A_CP = sqrt(R * DCP)                           # eq 2 (Hertz form)
F_CP = 2 / 3 * pi * CV * SY * R * DCP          # eq 3
print("yield onset (composite): C_v", repr(CV), "delta_CP", repr(DCP), "a_CP", repr(A_CP), "F_CP", repr(F_CP))
print("yield onset (as printed): delta_CP", repr(delta_cp(E)))

# --- asperity-plastic: residual_state_of_fig2_cases_by_hand -------------------------
K_RES = 1.275 * (SY / E) ** 0.216              # eqs 5 and 12, the material's own S_Y/E
def c1(om): return 0.22 + 0.6242 * exp(-0.092 * om)           # eq 13
def c2(om): return 10 / (1 + (om / 10) ** 2) - 5              # eq 13
def shape(c, x): return x if c == 0 else expm1(-c * x) / expm1(-c)   # eq 12's f(x)
for dmax in (17e-9, 34e-9, 51e-9):
    om = dmax / DCP
    dres = dmax * (1 - om ** -0.28) * (1 - om ** -0.69)                 # eq 4
    rres = R * (1 + K_RES * (om - 1))                                   # eq 5
    def r_eff(d):                                                       # eq 12
        x = min((d - dres) / (dmax - dres), 1.0)
        return rres - K_RES * (1 - c1(om)) * (om - 1) * R * shape(c2(om), x)
    print(f"Fig 2 case {dmax * 1e9:.0f} nm: omega {om!r} delta_res {dres!r} R_res {rres!r} "
          f"R_eff(load) {r_eff(dmax)!r} R_eff(mid) {r_eff(0.5 * (dres + dmax))!r}")

# --- gw-surface: Hertz surface at d = 0 (crate root example, README) -----------------
F32_0 = 2 ** 0.25 * gamma(1.25) / sqrt(2 * pi)  # integral of s^(3/2) phi(s), s > 0
print("F_3/2(0)", repr(F32_0))

# --- maugis-kim: critical lambda (16/9)(1 - 1/pi) lambda^3 = 1 -----------------------
print("lambda_c", repr((9 / (16 * (1 - 1 / pi))) ** (1 / 3)))

# --- switch-1d: stiffness_for_impact_energy_closes_the_energy_balance_at_pull_in -----
D0, T_D, EPS_R, EPS0, E_I = 2e-6, 0.15e-6, 7.6, 8.854e-12, 0.5      # Table 2
G = D0 + T_D / EPS_R                                                 # effective gap
K_S = E_I / ((4 * G**3 / 27) * (EPS_R / T_D - 1 / G) - D0**2 / 2)    # drive A
V_PI = sqrt(8 * K_S * G**3 / (27 * EPS0))
print("switch: g", repr(G), "K_s", repr(K_S), "V_PI", repr(V_PI), "K_s d0", repr(K_S * D0))
