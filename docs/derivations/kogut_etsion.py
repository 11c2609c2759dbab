#!/usr/bin/env python3
"""Reference values of the Kogut-Etsion / Etsion-Kligerman-Kadin law (asperity_plastic::KogutEtsion),
computed independently of the Rust code from the published formulas as written in docs/theory.md
section 2.7 (plain Python, double precision, no shared code).

  Kogut & Etsion 2002 (KE), J. Appl. Mech. 69:657-662, with omega = delta/delta_c:
    P/Pc = omega^1.5,            A/Ac = omega              (omega <= 1, Hertz)
    P/Pc = 1.03 omega^1.425,     A/Ac = 0.93 omega^1.136   (1 < omega <= 6)
    P/Pc = 1.40 omega^1.263,     A/Ac = 0.94 omega^1.146   (6 < omega <= 110)
    P = 2.8 S_Y 2 pi R delta,    A = 2 pi R delta          (omega > 110, fully plastic)
    Pc = (4/3) E* R^1/2 delta_c^3/2, Ac = pi R delta_c (Hertz at delta_c)
  Etsion, Kligerman & Kadin 2005 (EKK), Int. J. Solids Struct. 42:3716-3729:
    delta_res/delta_max = [1 - omega^-0.28][1 - omega^-0.69]
    R_res/R = 1 + 1.275 (S_Y/E)^0.216 (omega - 1)
    P/Pmax = x^n, x = (delta - delta_res)/(delta_max - delta_res), n = 1.5 omega^-0.0331
  Derived (theory.md 2.7): R_L = [3 P / (4 E* (delta_max - delta_res)^1.5)]^2,
    R_eff(x) = min(R_L x^(2n-3), R_res) where R_L < R_res, else R_res + (R_L - R_res) x.

Run: python3 docs/derivations/kogut_etsion.py
Each block names the test that pins its numbers.
"""
from math import exp, pi, sqrt

# Table 1: Ru film, sphere of radius R, rigid flat
E, NU, SY, R = 410e9, 0.3, 3.42e9, 4e-6


def e_star(e1, nu1, e2=None, nu2=None):
    c = (1 - nu1 ** 2) / e1
    if e2 is not None:
        c += (1 - nu2 ** 2) / e2
    return 1 / c


def cv(nu):                       # the paper's eq 1 coefficient
    return 1.295 * exp(0.736 * nu)


def c_ke(nu):                     # KE 2002: K H / S_Y, K = 0.454 + 0.41 nu, H = 2.8 S_Y
    return 2.8 * (0.454 + 0.41 * nu)


def dc(r, c, sy, e1):             # delta_c = R (pi C S_Y / (2 E1))^2
    return r * (pi * c * sy / (2 * e1)) ** 2


def p_ratio(w, c):                # KE P/Pc
    if w <= 0:
        return 0.0
    if w <= 1:
        return w ** 1.5
    if w <= 6:
        return 1.03 * w ** 1.425
    if w <= 110:
        return 1.40 * w ** 1.263
    return 8.4 * w / c            # 2.8 S_Y 2 pi R delta / ((2/3) pi C S_Y R delta_c)


def a_ratio(w):                   # KE A/Ac
    if w <= 0:
        return 0.0
    if w <= 1:
        return w
    if w <= 6:
        return 0.93 * w ** 1.136
    if w <= 110:
        return 0.94 * w ** 1.146
    return 2 * w


def g(w):                         # EKK delta_res/delta_max, 0 at and below yield
    return 0.0 if w <= 1 else (1 - w ** -0.28) * (1 - w ** -0.69)


def n_exp(w):                     # EKK unloading exponent
    return 1.5 * w ** -0.0331 if w > 1 else 1.5


ES = e_star(E, NU)
C = cv(NU)
DC = dc(R, C, SY, ES)             # composite reading
DC_P = dc(R, C, SY, E)            # as printed
PC = 4 / 3 * ES * sqrt(R) * DC ** 1.5
PC_P = 4 / 3 * ES * sqrt(R) * DC_P ** 1.5
K_RES = 1.275 * (SY / E) ** 0.216

# --- kogut_etsion::tests::critical_values_of_table_1_ru_by_hand ----------------------
print("critical: delta_c", repr(DC), "Pc", repr(PC), "Ac", repr(pi * R * DC),
      "(2/3) pi C S_Y R delta_c", repr(2 / 3 * pi * C * SY * R * DC))
print("critical (as printed): delta_c", repr(DC_P), "Pc", repr(PC_P))
print("KE 2002 onset: C", repr(c_ke(NU)), "delta_c", repr(dc(R, c_ke(NU), SY, ES)))

# --- kogut_etsion::tests::published_fits_at_chosen_omega -----------------------------
for w in (0.5, 1.0, 2.0, 6.0, 20.0, 110.0, 500.0):
    print(f"fits at omega {w}: P/Pc {p_ratio(w, C)!r} A/Ac {a_ratio(w)!r}")
print("upper branches at the boundaries: P/Pc(6+)", repr(1.40 * 6 ** 1.263), "A/Ac(6+)",
      repr(0.94 * 6 ** 1.146), "P/Pc(110+)", repr(8.4 * 110 / C), "A/Ac(110+)", repr(220.0))

# --- kogut_etsion::tests::declared_jumps_have_the_published_sizes --------------------
print("force jumps: omega 1", repr(1.03), "omega 6", repr(1.40 * 6 ** 1.263 / (1.03 * 6 ** 1.425)),
      "omega 110", repr(8.4 * 110 / C / (1.40 * 110 ** 1.263)))
print("area jumps: omega 1", repr(0.93), "omega 6", repr(0.94 * 6 ** 1.146 / (0.93 * 6 ** 1.136)),
      "omega 110", repr(220 / (0.94 * 110 ** 1.146)))
print("mean pressure / S_Y just below 110:", repr(PC * p_ratio(110, C) / (pi * R * DC * a_ratio(110)) / SY))

# --- kogut_etsion::tests::ekk_residual_state_and_loading_radius_by_hand --------------
for w in (2.0, 10.0, 34.4, 100.0):
    RL = p_ratio(w, C) ** 2 / (w * (1 - g(w))) ** 3
    Rres = 1 + K_RES * (w - 1)
    x_k = (Rres / RL) ** (1 / (2 * n_exp(w) - 3)) if Rres > RL else None
    print(f"omega {w}: g {g(w)!r} n {n_exp(w)!r} R_res/R {Rres!r} R_L/R {RL!r} x_kink {x_k!r}")

# --- tests/kogut_etsion.rs: composed_asperity_reproduces_ke_loading_and_ekk_unloading -
# Ru composite, delta_max = 10 delta_c; the forces in N through the Hertz law
w = 10.0
dmax = w * DC
dres = g(w) * dmax
RL = R * p_ratio(w, C) ** 2 / (w * (1 - g(w))) ** 3
rr = R * (1 + K_RES * (w - 1))
assert RL < rr
n = n_exp(w)
K = 4 / 3 * ES
def f_unload(x):
    d = dres + x * (dmax - dres)
    reff = min(RL * x ** (2 * n - 3), rr)
    return K * sqrt(reff) * (d - dres) ** 1.5
print("omega 10: P_max", repr(PC * p_ratio(w, C)), "F(x=0.5)", repr(f_unload(0.5)),
      "EKK x^n at 0.5", repr(PC * p_ratio(w, C) * 0.5 ** n), "F(x=0.01)", repr(f_unload(0.01)),
      "EKK at 0.01", repr(PC * p_ratio(w, C) * 0.01 ** n))

# --- tests/kogut_etsion.rs: ke_over_ek_loading_force_for_ru ---------------------------
def c1(w): return 0.22 + 0.6242 * exp(-0.092 * w)
for w in (2.0, 5.0, 10.0, 30.0, 100.0):
    r_ek = 1 + K_RES * (w - 1) * c1(w)            # paper eq 12 at x = 1
    f_ek = sqrt(r_ek) * (w * (1 - g(w))) ** 1.5   # EK loading force / Pc through Hertz
    print(f"KE/EK loading force at omega {w}: {p_ratio(w, C) / f_ek!r}")

# --- tests/kogut_etsion.rs: both_readings_of_eq_1 -------------------------------------
# the same interference 50 nm in both readings (regime 2 in both)
d = 50e-9
f_c = PC * p_ratio(d / DC, C)
f_p = PC_P * p_ratio(d / DC_P, C)
print("50 nm: omega composite", repr(d / DC), "as printed", repr(d / DC_P), "P composite", repr(f_c),
      "P as printed", repr(f_p), "ratio", repr(f_p / f_c), "= (DC_P/DC)^0.237", repr((DC_P / DC) ** 0.237))

# --- kogut_etsion::tests::the_near_yield_band_of_table_1_ru ---------------------------
def gap(w): return p_ratio(w, C) ** 2 / (w * (1 - g(w))) ** 3 - (1 + K_RES * (w - 1))
lo, hi = 1 + 1e-9, 6.0
for _ in range(200):
    m = 0.5 * (lo + hi)
    if gap(m) > 0:
        lo = m
    else:
        hi = m
print("Ru: R_L = R_res at omega", repr(0.5 * (lo + hi)))

# --- tests/kogut_etsion.rs: a second material (held out from the Ru values above) -----
# a steel-like sphere on a Ru counter-surface, both able to yield
E2, NU2, SY2 = 200e9, 0.29, 1.0e9
ES2 = e_star(E2, NU2, E, NU)
d_steel = dc(R, cv(NU2), SY2, ES2)
d_ru = dc(R, cv(NU), SY, ES2)
print("steel on Ru (composite): delta_c steel", repr(d_steel), "Ru", repr(d_ru))
K2 = 1.275 * (SY2 / E2) ** 0.216
PC2 = 4 / 3 * ES2 * sqrt(R) * d_steel ** 1.5
for w in (3.0, 40.0):
    RL2 = R * p_ratio(w, cv(NU2)) ** 2 / (w * (1 - g(w))) ** 3
    print(f"steel omega {w}: P {PC2 * p_ratio(w, cv(NU2))!r} delta_res {g(w) * w * d_steel!r} "
          f"r_res {R * (1 + K2 * (w - 1))!r} R_L {RL2!r}")
