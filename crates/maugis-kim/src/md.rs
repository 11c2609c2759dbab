//! The Maugis-Dugdale curve with the Kim non-contact extension, nondimensional (eq 7).
//!
//! **Contact branch** (a > 0), parametrised by s = sqrt(m^2 - 1) > 0, m = c/a, t = atan s.
//! Eq 8 is the quadratic P A^2 + Q A - 1 = 0 with
//! P = (lambda/2)[s + (m^2 - 2) t], Q = (4 lambda^2/3)[s t - m + 1], both positive,
//! so A = 2/(Q + sqrt(Q^2 + 4P)); then eq 9: Delta = A^2 - (4 lambda/3) A s and
//! eq 10: Fbar = A^3 - lambda A^2 [s + m^2 t]. s -> 0 is Hertz, s -> infinity the junction.
//!
//! **Non-contact branch** (a = 0, Kim et al. 1998), parametrised by C = c/(scale):
//! Delta = C^2/2 - (8 lambda/(3 pi)) C - 2/(pi lambda), Fbar = -(pi lambda/2) C^2,
//! for 0 <= C <= C_j, C_j the positive root of (pi lambda/4) C^2 + (4 lambda^2/3)(pi/2 - 1) C = 1.
//!
//! Walking from C = 0 through the junction to s -> 0, Delta falls to one minimum
//! Delta_t (the turning point) and then rises for ever; the part after Delta_t is stable
//! under displacement control. Derivations: `docs/theory.md`.

use crate::error::MkError;
use contact_core::numeric::{brent_from, expand_bracket, Expansion, Sample, Tolerance};
use contact_core::Path;
use contact_core::{finite, positive, CoreError};
use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::OnceLock;

/// lambda_c = (9 / (16 (1 - 1/pi)))^(1/3): the turning point sits exactly at the
/// junction of the two branches, (16/9)(1 - 1/pi) lambda_c^3 = 1.
pub const LAMBDA_CRITICAL: f64 = 0.937_947_457_210_712_3;

#[cfg(feature = "serde")]
fn is_infinite(v: &f64) -> bool {
    v.is_infinite()
}

/// Which branch a point lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum Branch {
    /// a = 0, c > 0 (Kim extension).
    NonContact,
    /// a > 0 (Maugis-Dugdale).
    Contact,
}

/// One point of the curve, nondimensional (eq 7).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct MdPoint {
    /// Contact radius A.
    pub a: f64,
    /// Radius of the cohesive zone C = m A.
    pub c: f64,
    /// Interference Delta.
    pub delta: f64,
    /// Force Fbar (compressive > 0).
    pub force: f64,
    /// The contact-branch parameter s = sqrt(m^2 - 1) (infinite on the non-contact
    /// branch, where it is left out of serialised points). Reported because m = c/a
    /// rounded to a double cannot resolve s < 1e-8.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "is_infinite"))]
    pub s: f64,
    /// Which branch the point lies on.
    pub branch: Branch,
    /// Stable under displacement control (after the turning point along the curve).
    pub stable: bool,
}

const MAX_ITER: usize = 300;
/// Bracket searches stop here in u = ln s; beyond, the contact branch is the junction
/// to every digit of a double (Delta - Delta_j = O(1/s^2)).
const U_MAX: f64 = 340.0;
const U_MIN: f64 = -340.0;

/// s - atan(s), by its series below s = 0.1 where the difference cancels (`t` = atan s,
/// computed once per point: atan is the costliest operation of a point).
fn s_minus_atan(s: f64, t: f64) -> f64 {
    if s < 0.1 {
        let x = s * s;
        // sum_{k>=1} (-1)^(k+1) s^(2k+1)/(2k+1)
        let mut term = s * x;
        let mut sum = 0.0;
        for k in 1..=10 {
            let sign = if k % 2 == 1 { 1.0 } else { -1.0 };
            sum += sign * term / (2 * k + 1) as f64;
            term *= x;
        }
        sum
    } else {
        s - t
    }
}

/// s/m^2 - atan(s), by its series below s = 0.1 (`t` = atan s).
fn s_over_m2_minus_atan(s: f64, t: f64) -> f64 {
    if s < 0.1 {
        let x = s * s;
        // sum_{k>=1} (-1)^k (2k/(2k+1)) s^(2k+1)
        let mut term = s * x;
        let mut sum = 0.0;
        for k in 1..=10 {
            let sign = if k % 2 == 1 { -1.0 } else { 1.0 };
            sum += sign * (2 * k) as f64 / (2 * k + 1) as f64 * term;
            term *= x;
        }
        sum
    } else {
        s / (1.0 + s * s) - t
    }
}

/// Everything the contact branch needs at one s, computed once.
#[derive(Debug, Clone, Copy)]
struct Contact {
    s: f64,
    m: f64,
    t: f64,
    p: f64,
    q: f64,
    a: f64,
    delta: f64,
    force: f64,
}

impl Contact {
    fn at(lambda: f64, s: f64) -> Self {
        let t = s.atan();
        // sqrt(1 + s^2) to an ulp or two, cheaper than hypot; hypot where s^2 overflows
        let m = if s < 1e150 {
            (1.0 + s * s).sqrt()
        } else {
            s.hypot(1.0)
        };
        let s_over = s / (1.0 + m); // (m - 1)/s, no overflow
                                    // g1 = s + (m^2 - 2) t = (s - t) + s^2 t
        let g1 = s_minus_atan(s, t) + s * s * t;
        // g2 = s t - (m - 1)
        let g2 = s * t - s * s_over;
        let p = 0.5 * lambda * g1;
        let q = 4.0 / 3.0 * lambda * lambda * g2;
        let a = 2.0 / (q + (q * q + 4.0 * p).sqrt());
        let delta = a * a - 4.0 / 3.0 * lambda * a * s;
        // g3 = s + m^2 t
        let force = a * a * (a - lambda * (s + (1.0 + s * s) * t));
        Self {
            s,
            m,
            t,
            p,
            q,
            a,
            delta,
            force,
        }
    }

    fn point(&self, stable: bool) -> MdPoint {
        MdPoint {
            a: self.a,
            c: self.m * self.a,
            delta: self.delta,
            force: self.force,
            s: self.s,
            branch: Branch::Contact,
            stable,
        }
    }

    /// dP/ds = lambda s (t + s/m^2) and dQ/ds = (4 lambda^2/3)(t + s/m^2 - s/m).
    fn d_pq(&self, lambda: f64) -> (f64, f64) {
        let (s, m, t) = (self.s, self.m, self.t);
        let u = t + s / (m * m);
        (lambda * s * u, 4.0 / 3.0 * lambda * lambda * (u - s / m))
    }

    /// The point at u + du (u = ln s), extrapolated linearly from this one: where Newton's
    /// next step is so small that its square is below rounding, this is the solution to
    /// rounding without another evaluation. Derivatives in u = ln s: with P A^2 + Q A = 1,
    /// A' = -A (P' A + Q')/(2 P A + Q); Delta = A^2 - (4 lambda/3) A s;
    /// Fbar = A^2 (A - lambda g3), g3 = s + m^2 t, g3' = 2 + 2 s t; C = m A, m' = s/m.
    fn extrapolated(&self, lambda: f64, du: f64) -> MdPoint {
        let (s, m, t, a, p, q) = (self.s, self.m, self.t, self.a, self.p, self.q);
        let (dp, dq) = self.d_pq(lambda);
        let da = -a * (dp * a + dq) / (2.0 * p * a + q);
        let g3 = s + m * m * t;
        let d_delta = 2.0 * a * da - 4.0 / 3.0 * lambda * (da * s + a);
        let d_force =
            2.0 * a * da * (a - lambda * g3) + a * a * (da - lambda * (2.0 + 2.0 * s * t));
        let dc = s / m * a + m * da;
        // d/du = s d/ds
        let h = s * du;
        MdPoint {
            a: a + da * h,
            c: m * a + dc * h,
            delta: self.delta + d_delta * h,
            force: self.force + d_force * h,
            s: s * du.exp(),
            branch: Branch::Contact,
            stable: true,
        }
    }

    /// A quantity with the sign of dDelta/ds (Delta'(s) D / A, D = 2PA + Q > 0).
    fn d_delta_sign(&self, lambda: f64) -> f64 {
        let (s, m, a) = (self.s, self.m, self.a);
        let l2 = lambda * lambda;
        let (dp, dq) = self.d_pq(lambda);
        let m_minus_1 = s * (s / (1.0 + m));
        let phi = -2.0 * a * (dp * a + dq) - 4.0 / 3.0 * l2 * s_over_m2_minus_atan(s, self.t) * a
            + 16.0 / 9.0 * l2 * lambda * m_minus_1 / (m * m);
        // Phi = O(1/s) at large s: rescale so the bracket search compares O(1) values.
        phi * m
    }

    /// dDelta/du with u = ln s: s Delta'(s), Delta'(s) = Phi A / D, D = 2PA + Q.
    fn d_delta_du(&self, lambda: f64) -> f64 {
        let d = 2.0 * self.p * self.a + self.q;
        self.s * self.d_delta_sign(lambda) / self.m * self.a / d
    }

    /// A quantity with the sign of dFbar/ds.
    fn d_force_sign(&self, lambda: f64) -> f64 {
        let (s, m, t, a, p, q) = (self.s, self.m, self.t, self.a, self.p, self.q);
        let (dp, dq) = self.d_pq(lambda);
        let g3 = s + m * m * t;
        let dg3 = 2.0 + 2.0 * s * t;
        let d = 2.0 * p * a + q;
        let gamma = -(dp * a + dq) * (3.0 * a - 2.0 * lambda * g3) - lambda * dg3 * d;
        gamma / (m * m)
    }
}

/// The Maugis-Kim curve for one lambda.
#[derive(Debug)]
pub struct MdCurve {
    lambda: f64,
    /// C of the minimum of Delta on the non-contact branch: 8 lambda/(3 pi).
    b: f64,
    c_j: f64,
    turning: OnceLock<Result<Turning, MkError>>,
}

#[derive(Debug, Clone, Copy)]
struct Turning {
    point: MdPoint,
    /// ln s of the turning point when it lies on the contact branch.
    u: Option<f64>,
}

impl MdCurve {
    /// The curve for transition parameter `lambda` (finite, > 0).
    pub fn new(lambda: f64) -> Result<Self, MkError> {
        positive("lambda", lambda)?;
        let qa = PI * lambda / 4.0;
        let qb = 4.0 / 3.0 * lambda * lambda * (FRAC_PI_2 - 1.0);
        // positive root of qa C^2 + qb C - 1 = 0, in the form without cancellation
        let c_j = 2.0 / (qb + (qb * qb + 4.0 * qa).sqrt());
        Ok(Self {
            lambda,
            b: 8.0 * lambda / (3.0 * PI),
            c_j,
            turning: OnceLock::new(),
        })
    }

    /// The transition parameter.
    pub fn lambda(&self) -> f64 {
        self.lambda
    }

    /// Jump-in interference on approach, Delta_in = -2/(pi lambda): the rigid gap at the
    /// centre equals the Dugdale range z0.
    pub fn jump_in_delta(&self) -> f64 {
        -2.0 / (PI * self.lambda)
    }

    /// A point of the non-contact branch at cohesive radius `c` in [0, C_j].
    pub fn noncontact_point(&self, c: f64) -> MdPoint {
        let l = self.lambda;
        MdPoint {
            a: 0.0,
            c,
            // C^2/2 - b C - 2/(pi lambda) rewritten about the junction, where the
            // terms cancel for small lambda: Delta_j = -(4 lambda/3) C_j.
            delta: (c - self.c_j) * (0.5 * (c + self.c_j) - self.b) - 4.0 / 3.0 * l * self.c_j,
            force: -0.5 * PI * l * c * c,
            s: f64::INFINITY,
            branch: Branch::NonContact,
            stable: l <= LAMBDA_CRITICAL && c >= self.b,
        }
    }

    /// A point of the contact branch at s = sqrt(m^2 - 1) > 0.
    pub fn contact_point(&self, s: f64) -> MdPoint {
        let c = Contact::at(self.lambda, s);
        let stable = match self.turning() {
            Ok(t) => t.u.is_none_or(|u| s.ln() <= u),
            Err(_) => false,
        };
        c.point(stable)
    }

    /// The junction of the two branches (A = 0, C = C_j, Delta_j = -(4 lambda/3) C_j).
    pub fn junction(&self) -> MdPoint {
        let mut p = self.noncontact_point(self.c_j);
        p.stable = self.lambda <= LAMBDA_CRITICAL;
        p
    }

    fn turning(&self) -> Result<Turning, MkError> {
        self.turning.get_or_init(|| self.find_turning()).clone()
    }

    fn find_turning(&self) -> Result<Turning, MkError> {
        let l = self.lambda;
        if l <= LAMBDA_CRITICAL {
            let mut point = self.noncontact_point(self.b);
            point.stable = true;
            return Ok(Turning { point, u: None });
        }
        let f = |u: f64| Contact::at(l, u.exp()).d_delta_sign(l);
        let bracket = turning_guess(l)
            .and_then(|g| tight_bracket(&f, g))
            .or_else(|| bracket_sign_change(&f, 0.0, U_MIN, U_MAX));
        let Some((lo, hi)) = bracket else {
            // lambda so close to lambda_c that the turning point is the junction to
            // double precision.
            let mut point = self.junction();
            point.stable = true;
            return Ok(Turning { point, u: None });
        };
        let u = brent_from(
            "turning point dDelta/ds = 0",
            |u| Ok::<_, CoreError>(f(u)),
            lo,
            hi,
            Tolerance::absolute(1e-14).with_max_iter(MAX_ITER),
        )?;
        let mut point = Contact::at(l, u.exp()).point(true);
        point.stable = true;
        Ok(Turning { point, u: Some(u) })
    }

    /// The turning point: the minimum Delta_t of the interference along the curve, where
    /// a retracting sphere jumps out of contact under displacement control.
    pub fn turning_point(&self) -> Result<MdPoint, MkError> {
        self.turning().map(|t| t.point)
    }

    /// Delta_t of the turning point, read from a table within
    /// [`crate::table::TURNING_ERROR`] of max(|Delta_t|, 1) where it holds lambda (lambda
    /// more than e^0.5 above lambda_c, up to 2e4), solved elsewhere.
    pub(crate) fn turning_delta_interpolated(&self) -> Result<f64, MkError> {
        match crate::table::turning_delta(self.lambda) {
            Some(d) => Ok(d),
            None => Ok(self.turning_point()?.delta),
        }
    }

    /// Pull-off under displacement control: the turning point, where a retracting
    /// sphere jumps out (force: JKR limit -5/6).
    pub fn pull_off_displacement_control(&self) -> Result<MdPoint, MkError> {
        self.turning_point()
    }

    /// Pull-off under load control: the point of minimum force on the stable branch
    /// (force: DMT limit -2, JKR limit -3/2).
    pub fn pull_off_load_control(&self) -> Result<MdPoint, MkError> {
        let l = self.lambda;
        let turning = self.turning()?;
        // The stable part of the contact branch is u <= u_t (all u if lambda <= lambda_c);
        // the non-contact stable part has Fbar decreasing towards the junction, so the
        // end point of the scan (turning point or junction) is always a candidate.
        let mut best = match turning.u {
            Some(_) => turning.point,
            None => self.junction(),
        };
        let u_hi = turning.u.unwrap_or(40.0);
        let f = |u: f64| Contact::at(l, u.exp()).d_force_sign(l);
        let step = 0.25;
        let mut u0 = (-30.0_f64).min(u_hi - 1.0);
        let mut f0 = f(u0);
        while u0 < u_hi {
            let u1 = (u0 + step).min(u_hi);
            let f1 = f(u1);
            if f0 < 0.0 && f1 >= 0.0 {
                let u = brent_from(
                    "pull-off dFbar/ds = 0",
                    |u| Ok::<_, CoreError>(f(u)),
                    Sample { x: u0, f: f0 },
                    Sample { x: u1, f: f1 },
                    Tolerance::absolute(1e-13).with_max_iter(MAX_ITER),
                )?;
                let p = Contact::at(l, u.exp()).point(true);
                if p.force < best.force {
                    best = p;
                }
            }
            u0 = u1;
            f0 = f1;
        }
        Ok(best)
    }

    /// The equilibrium on the stable branch at interference `delta` (Delta >= Delta_t).
    pub fn stable_point(&self, delta: f64) -> Result<MdPoint, MkError> {
        finite("delta", delta)?;
        let junction = self.junction();
        if delta > junction.delta {
            // One root on the whole contact branch (the unstable part lies below Delta_j).
            if let Some(p) = self.newton_contact(delta) {
                return Ok(p);
            }
            return self.solve_contact(delta, U_MAX);
        }
        let turning = self.turning()?;
        if delta < turning.point.delta {
            // within rounding of the turning point (at extreme lambda the jump-in and the
            // turning point differ by less than a few ulps): the turning point itself
            if turning.point.delta - delta
                <= 16.0 * f64::EPSILON * turning.point.delta.abs().max(1.0)
            {
                return Ok(turning.point);
            }
            return Err(MkError::BelowTurningPoint {
                delta,
                turning: turning.point.delta,
            });
        }
        match turning.u {
            // Stable part of the non-contact branch: C >= 8 lambda/(3 pi), closed form.
            None => {
                // (C - b)^2 = (C_j - b)^2 + 2 (Delta - Delta_j)
                let cj_b = self.c_j - self.b;
                let disc = (cj_b * cj_b + 2.0 * (delta - junction.delta)).max(0.0);
                let c = (self.b + disc.sqrt()).min(self.c_j);
                let mut p = self.noncontact_point(c);
                p.stable = true;
                Ok(p)
            }
            // Between Delta_t and Delta_j the stable root lies below the turning point.
            Some(u_t) => self.solve_below_turning(delta, u_t, turning.point.delta),
        }
    }

    /// Delta(s) = delta for Delta > Delta_j by Newton's method in u = ln s from the
    /// guide table's estimate; None (the caller then brackets and uses Brent) if the
    /// iteration leaves the stable side or does not converge in 12 steps. Converged means
    /// |Delta - delta| <= 4 eps max(1, |delta|) or a step below 1e-15 in u.
    fn newton_contact(&self, delta: f64) -> Option<MdPoint> {
        let l = self.lambda;
        let mut u = contact_guess(l, delta - self.junction().delta)?;
        let tol = 4.0 * f64::EPSILON * delta.abs().max(1.0);
        let mut last_step: Option<f64> = None;
        for _ in 0..12 {
            let c = Contact::at(l, u.exp());
            let g = c.delta - delta;
            if g.abs() <= tol {
                return Some(c.point(true));
            }
            let slope = c.d_delta_du(l);
            if !(slope < 0.0 && slope.is_finite()) {
                return None;
            }
            let step = (g / slope).clamp(-2.0, 2.0);
            // Newton converges quadratically: after this step the error in u is about
            // k step^2, k = |step| / last_step^2 measured on the last two steps. Once that
            // is within the tolerance (in u), the solution is this point moved by -step
            // to first order, whose own error is of the same (rounding) order.
            if let Some(last) = last_step {
                let k = step.abs() / (last * last);
                if step.abs() <= 1e-7 && k * step * step <= tol / slope.abs() {
                    return Some(c.extrapolated(l, -step));
                }
            }
            last_step = Some(step);
            u -= step;
            if step.abs() <= 1e-15 * u.abs().max(1.0) {
                let c = Contact::at(l, u.exp());
                return ((c.delta - delta).abs() <= 1e-13 * delta.abs().max(1.0))
                    .then(|| c.point(true));
            }
        }
        None
    }

    /// Delta(s) = delta on the stable part of the contact branch below the turning point,
    /// Delta_t <= delta <= Delta_j (lambda > lambda_c): Newton's method in u = ln s kept
    /// inside a bracket [lo, u_t] (Delta decreases in u there), started from the parabola
    /// Delta ~ Delta_t + c (u - u_t)^2 through the turning point and the bracket's lower
    /// end; a step leaving the bracket is a bisection. About 5 evaluations of the branch,
    /// where a bracket search and Brent's method took 25; the same root to rounding.
    fn solve_below_turning(&self, delta: f64, u_t: f64, delta_t: f64) -> Result<MdPoint, MkError> {
        let l = self.lambda;
        let tol = 4.0 * f64::EPSILON * delta.abs().max(1.0);
        // the lower end of the bracket: Delta(lo) > delta, stepping down from u_t - 1
        let mut step = 1.0;
        let mut lo = u_t - step;
        let mut c_lo = Contact::at(l, lo.exp());
        while c_lo.delta <= delta {
            step *= 2.0;
            lo = u_t - step;
            if lo < U_MIN {
                return self.solve_contact(delta, u_t);
            }
            c_lo = Contact::at(l, lo.exp());
        }
        let mut hi = u_t;
        let curvature = (c_lo.delta - delta_t) / (step * step);
        let mut u = u_t - ((delta - delta_t).max(0.0) / curvature).sqrt();
        if !(u > lo && u < hi) {
            u = 0.5 * (lo + hi);
        }
        for _ in 0..MAX_ITER {
            let c = Contact::at(l, u.exp());
            let g = c.delta - delta;
            if g.abs() <= tol {
                return Ok(c.point(true));
            }
            if g > 0.0 {
                lo = u;
            } else {
                hi = u;
            }
            let slope = c.d_delta_du(l);
            let mut next = u - g / slope;
            if !(slope < 0.0 && next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            if (next - u).abs() <= 1e-15 * u.abs().max(1.0) || hi - lo <= 1e-15 * u.abs().max(1.0) {
                return Ok(Contact::at(l, next.exp()).point(true));
            }
            u = next;
        }
        Err(CoreError::NoConvergence {
            what: "Maugis-Dugdale Delta(s) = Delta below the turning point",
            iterations: MAX_ITER,
        }
        .into())
    }

    /// Solve Delta(s) = delta for ln s <= u_top, where Delta decreases in s.
    fn solve_contact(&self, delta: f64, u_top: f64) -> Result<MdPoint, MkError> {
        let l = self.lambda;
        let g = |u: f64| Contact::at(l, u.exp()).delta - delta;
        // Hertz estimate A ~ sqrt(Delta), s ~ (3/(2 lambda A^2))^(1/3) as a starting point.
        let guess = if delta > 1.0 {
            ((1.5 / (l * delta)).cbrt()).ln().min(u_top)
        } else {
            0.0_f64.min(u_top)
        };
        let start = Sample {
            x: guess,
            f: g(guess),
        };
        if start.f == 0.0 {
            return Ok(Contact::at(l, guess.exp()).point(true));
        }
        let ok = |u: f64| Ok::<_, CoreError>(g(u));
        // Delta decreases in s: above the target, larger s; below it, smaller s
        let (lo, hi) = if start.f > 0.0 {
            match expand_bracket(
                "Maugis-Dugdale Delta(s)",
                ok,
                start,
                guess + 2.0,
                Expansion::Linear,
                u_top,
            )? {
                Some(b) => b,
                // target within rounding of the end of the branch
                None => return Ok(Contact::at(l, u_top.max(guess).exp()).point(true)),
            }
        } else {
            match expand_bracket(
                "Maugis-Dugdale Delta(s)",
                ok,
                start,
                guess - 2.0,
                Expansion::Linear,
                U_MIN,
            )? {
                Some((above, below)) => (below, above),
                None => return Err(MkError::Unresolvable { delta }),
            }
        };
        let (g_lo, g_hi) = (lo.f, hi.f);
        let (lo, hi) = (lo.x, hi.x);
        let u = brent_from(
            "Maugis-Dugdale Delta(s) = Delta",
            |u| Ok::<_, CoreError>(g(u)),
            Sample { x: lo, f: g_lo },
            Sample { x: hi, f: g_hi },
            Tolerance::absolute(1e-15).with_max_iter(MAX_ITER),
        )?;
        Ok(Contact::at(l, u.exp()).point(true))
    }

    /// Contact radius A on a path at interference `delta`, nondimensional (eq 7): the
    /// stable point's A where the sphere is attached as [`Self::force`] reads the path
    /// rule, 0 where it is detached or on the non-contact (Kim) branch, whose cohesive
    /// zone pulls without touching.
    pub fn contact_radius(&self, delta: f64, path: Path) -> Result<f64, MkError> {
        if delta.is_nan() {
            return Err(CoreError::Invalid {
                field: "delta",
                value: delta,
                allowed: "a number",
            }
            .into());
        }
        let d_in = self.jump_in_delta();
        let attached = delta >= d_in
            || match path {
                Path::Approach => false,
                Path::Retract { from } => from >= d_in && delta >= self.turning_point()?.delta,
            };
        Ok(if attached {
            self.stable_point(delta)?.a
        } else {
            0.0
        })
    }

    /// Force on a path at interference `delta`, all nondimensional; `Path::Retract { from }`
    /// gives the largest interference of the excursion.
    ///
    /// Approach: zero while Delta < Delta_in, then the stable branch (jump-in). Retract
    /// (after having reached Delta_in): the stable branch down to Delta_t, then zero.
    pub fn force(&self, delta: f64, path: Path) -> Result<f64, MkError> {
        self.force_with(delta, path, false)
    }

    /// [`Self::force`] with the stable force on the contact branch above the junction read
    /// from the interpolation table (within [`crate::INTERPOLATION_ERROR`] of max(|Fbar|, 1))
    /// where the table holds it, solved elsewhere.
    pub fn force_interpolated(&self, delta: f64, path: Path) -> Result<f64, MkError> {
        self.force_with(delta, path, true)
    }

    /// The stable point's force, from the table when `table` and it holds the point.
    fn stable_force(&self, delta: f64, table: bool) -> Result<f64, MkError> {
        if table {
            if let Some(f) = crate::table::force(self.lambda, delta - self.junction().delta) {
                return Ok(f);
            }
        }
        Ok(self.stable_point(delta)?.force)
    }

    fn force_with(&self, delta: f64, path: Path, table: bool) -> Result<f64, MkError> {
        let from = match path {
            Path::Retract { from } => from,
            Path::Approach => 0.0,
        };
        for (field, v) in [("delta", delta), ("from", from)] {
            if v.is_nan() {
                return Err(CoreError::Invalid {
                    field,
                    value: v,
                    allowed: "a number",
                }
                .into());
            }
        }
        let d_in = self.jump_in_delta();
        if delta >= d_in {
            return self.stable_force(delta, table);
        }
        match path {
            Path::Approach => Ok(0.0),
            Path::Retract { from } if from < d_in => Ok(0.0),
            Path::Retract { .. } => {
                // the table's Delta_t, except within its error bound of it, where the side
                // is decided by the solved turning point (a point the table puts on the
                // stable branch just below the true turning point has no stable solution)
                let t_delta = match table.then(|| crate::table::turning_delta(self.lambda)) {
                    Some(Some(d))
                        if (delta - d).abs()
                            > 4.0 * crate::table::TURNING_ERROR * d.abs().max(1.0) =>
                    {
                        d
                    }
                    _ => self.turning_point()?.delta,
                };
                if delta < t_delta {
                    Ok(0.0)
                } else {
                    self.stable_force(delta, table)
                }
            }
        }
    }

    /// The whole curve from C = 0 through the junction into the contact branch up to
    /// interference `delta_end`, `n` points (at least 4): a quarter on the non-contact
    /// branch, the rest log-spaced in s on the contact branch.
    pub fn curve(&self, n: usize, delta_end: f64) -> Result<Vec<MdPoint>, MkError> {
        finite("delta_end", delta_end)?;
        let n = n.max(4);
        let n_nc = n / 4;
        let mut out = Vec::with_capacity(n);
        for i in 0..n_nc {
            out.push(self.noncontact_point(self.c_j * i as f64 / n_nc as f64));
        }
        out.push(self.junction());
        let end = self.solve_contact(delta_end.max(self.junction().delta + 1e-6), U_MAX)?;
        let u_end = end.s.max(1e-300).ln();
        // A = C/m: beyond s = 1e3 the contact branch is the junction to 1e-3 of C_j
        let u_start = 1e3f64.ln().max(u_end + 1.0);
        let n_c = n - out.len();
        // half the points on the unstable part (junction to turning point), half on the
        // stable part, each log-spaced in s, so that large lambda (small s_t) is resolved
        let turning_u = self.turning()?.u.filter(|&u| u < u_start && u > u_end);
        // stability is known from the half being sampled, not re-derived from ln(exp(u))
        let l = self.lambda;
        let mut push = |from: f64, to: f64, k: usize, include_start: bool, stable: bool| {
            for i in 0..k {
                let f = if include_start {
                    i as f64 / k as f64
                } else {
                    (i + 1) as f64 / k as f64
                };
                out.push(Contact::at(l, (from + (to - from) * f).exp()).point(stable));
            }
        };
        match turning_u {
            Some(u_t) => {
                let k1 = n_c / 2;
                push(u_start, u_t, k1, true, false);
                push(u_t, u_end, n_c - k1, true, true);
            }
            None => push(u_start, u_end, n_c, false, true),
        }
        if let Some(last) = out.last_mut() {
            // end exactly at the requested interference
            *last = end;
        }
        Ok(out)
    }
}

/// ln lambda range of the turning-point guide table; outside it the wide search is used.
pub(crate) const GUIDE_LN_LO: f64 = -0.06; // just above ln lambda_c = -0.0641
pub(crate) const GUIDE_LN_HI: f64 = 9.3; // lambda ~ 1.1e4
pub(crate) const GUIDE_N: usize = 512;

/// ln s_t at grid point `i` of the turning-point guide (NaN where the search fails), by
/// the wide bracket search: how `guide_data::TURNING` was made (test
/// `the_committed_guides_are_the_solvers`, which also rewrites it).
#[cfg(test)]
pub(crate) fn turning_guide_entry(i: usize) -> f64 {
    let l = (GUIDE_LN_LO + (GUIDE_LN_HI - GUIDE_LN_LO) * i as f64 / (GUIDE_N - 1) as f64).exp();
    let f = |u: f64| Contact::at(l, u.exp()).d_delta_sign(l);
    bracket_sign_change(&f, 0.0, U_MIN, U_MAX)
        .and_then(|(a, b)| {
            brent_from(
                "turning guide",
                |u| Ok::<_, CoreError>(f(u)),
                a,
                b,
                Tolerance::absolute(1e-12).with_max_iter(MAX_ITER),
            )
            .ok()
        })
        .unwrap_or(f64::NAN)
}

/// ln s of the turning point on a grid of ln lambda (lambda > lambda_c), committed
/// (`guide_data.rs`; solving it at start-up cost every process about 4 M instructions,
/// with every thread waiting). It only seeds the bracket: the turning point is still
/// solved to 1e-14 in ln s, so results do not depend on the table.
fn guide() -> &'static [f64] {
    &crate::guide_data::TURNING
}

/// Interpolated ln s_t for lambda inside the guide table: 4-point Lagrange (cubic, the
/// stencil shifted inward at the ends), about 1e-8 in ln s away from lambda_c, where
/// ln s_t grows without bound and the first bracket is widened.
fn turning_guess(lambda: f64) -> Option<f64> {
    let x = (lambda.ln() - GUIDE_LN_LO) / (GUIDE_LN_HI - GUIDE_LN_LO) * (GUIDE_N - 1) as f64;
    if !(x >= 0.0 && x < (GUIDE_N - 1) as f64) {
        return None;
    }
    let g = guide();
    let (i0, w) = lagrange4(x, GUIDE_N);
    let u: f64 = w.iter().zip(&g[i0..i0 + 4]).map(|(w, g)| w * g).sum();
    u.is_finite().then_some(u)
}

/// The first index and the weights of the 4-point Lagrange stencil at fractional grid
/// position x on a grid of n >= 4 points (exact for cubics; shifted inward at the ends).
fn lagrange4(x: f64, n: usize) -> (usize, [f64; 4]) {
    let i0 = (x as usize).saturating_sub(1).min(n - 4);
    let f = x - (i0 + 1) as f64;
    (
        i0,
        [
            -f * (f - 1.0) * (f - 2.0) / 6.0,
            (f + 1.0) * (f - 1.0) * (f - 2.0) / 2.0,
            -(f + 1.0) * f * (f - 2.0) / 2.0,
            (f + 1.0) * f * (f - 1.0) / 6.0,
        ],
    )
}

/// Grid of the contact-solve guide: ln lambda and y = ln(Delta - Delta_j).
pub(crate) const CG_L: (f64, f64, usize) = (-7.2, 7.2, 49);
pub(crate) const CG_Y: (f64, f64, usize) = (-14.0, 10.0, 61);

/// Row `i` (one lambda) of the contact-solve guide (NaN where a solve fails), by the
/// bracketed solver: how `guide_data::CONTACT` was made (test
/// `the_committed_guides_are_the_solvers`).
#[cfg(test)]
pub(crate) fn contact_guide_row(i: usize) -> Vec<f64> {
    let l = (CG_L.0 + (CG_L.1 - CG_L.0) * i as f64 / (CG_L.2 - 1) as f64).exp();
    let c = MdCurve::new(l).expect("grid lambda is valid");
    let dj = c.junction().delta;
    (0..CG_Y.2)
        .map(|j| {
            let y = CG_Y.0 + (CG_Y.1 - CG_Y.0) * j as f64 / (CG_Y.2 - 1) as f64;
            c.solve_contact(dj + y.exp(), U_MAX)
                .map_or(f64::NAN, |p| p.s.ln())
        })
        .collect()
}

/// ln s of the contact-branch solution on a grid of (ln lambda, ln(Delta - Delta_j)),
/// committed (`guide_data.rs`; about 3000 bracketed solves, 17 M instructions at every
/// start-up before). Like the turning-point guide it only seeds Newton's method; results
/// are solved to rounding.
fn contact_guide() -> &'static [f64] {
    &crate::guide_data::CONTACT
}

/// Estimate of ln s for lambda and Delta - Delta_j > 0, inside the guide: 4 x 4-point
/// Lagrange interpolation (exact for bicubics; the stencil shifts inward at the edges of
/// the grid), bilinear where a stencil holds a failed solve.
fn contact_guess(lambda: f64, above_junction: f64) -> Option<f64> {
    if !(above_junction > 0.0) {
        return None;
    }
    let x = (lambda.ln() - CG_L.0) / (CG_L.1 - CG_L.0) * (CG_L.2 - 1) as f64;
    let y = (above_junction.ln() - CG_Y.0) / (CG_Y.1 - CG_Y.0) * (CG_Y.2 - 1) as f64;
    if !(x >= 0.0 && x < (CG_L.2 - 1) as f64 && y >= 0.0 && y < (CG_Y.2 - 1) as f64) {
        return None;
    }
    let g = contact_guide();
    let at = |i: usize, j: usize| g[i * CG_Y.2 + j];
    let (i0, wx) = lagrange4(x, CG_L.2);
    let (j0, wy) = lagrange4(y, CG_Y.2);
    let mut u = 0.0;
    // the 4 x 4 stencil as four row slices: one bounds check per row
    for (di, wi) in wx.iter().enumerate() {
        let start = (i0 + di) * CG_Y.2 + j0;
        for (wj, gij) in wy.iter().zip(&g[start..start + 4]) {
            u += wi * wj * gij;
        }
    }
    if u.is_finite() {
        return Some(u);
    }
    let (i, j) = (x as usize, y as usize);
    let (fx, fy) = (x - i as f64, y - j as f64);
    let u = (1.0 - fx) * ((1.0 - fy) * at(i, j) + fy * at(i, j + 1))
        + fx * ((1.0 - fy) * at(i + 1, j) + fy * at(i + 1, j + 1));
    u.is_finite().then_some(u)
}

/// A bracket of width 2w around the guess g (w from 1e-6, the cubic guide's accuracy),
/// widened eightfold up to six times if needed.
fn tight_bracket(f: &dyn Fn(f64) -> f64, g: f64) -> Option<(Sample, Sample)> {
    let mut w = 1e-6;
    for _ in 0..7 {
        let (a, b) = (g - w, g + w);
        let (fa, fb) = (f(a), f(b));
        if fa <= 0.0 && fb > 0.0 {
            return Some((Sample { x: a, f: fa }, Sample { x: b, f: fb }));
        }
        w *= 8.0;
    }
    None
}

/// Expands from u0 in both directions to find (lo, f(lo) < 0) and (hi, f(hi) > 0) with
/// lo < hi, for a function negative at small u and positive at large u.
fn bracket_sign_change(
    f: &dyn Fn(f64) -> f64,
    u0: f64,
    u_min: f64,
    u_max: f64,
) -> Option<(Sample, Sample)> {
    let start = Sample { x: u0, f: f(u0) };
    let ok = |u: f64| Ok::<_, CoreError>(f(u));
    if start.f >= 0.0 {
        expand_bracket("sign change", ok, start, u0 - 2.0, Expansion::Linear, u_min)
            .ok()
            .flatten()
            .map(|(above, below)| (below, above))
    } else {
        expand_bracket("sign change", ok, start, u0 + 2.0, Expansion::Linear, u_max)
            .ok()
            .flatten()
    }
}

#[cfg(test)]
mod guide_tests {
    use super::*;

    /// The committed file's text for the given guides: Rust's shortest round-trip form of
    /// each value, NaN where a solve failed.
    fn render(turning: &[f64], contact: &[f64]) -> String {
        let list = |v: &[f64], per_row: usize| -> String {
            v.chunks(per_row)
                .map(|row| {
                    let cells: Vec<String> = row
                        .iter()
                        .map(|x| {
                            if x.is_nan() {
                                "f64::NAN".to_owned()
                            } else {
                                format!("{x:?}")
                            }
                        })
                        .collect();
                    format!("    {},\n", cells.join(", "))
                })
                .collect()
        };
        format!(
            "//! The Newton guides of `md.rs`, solved once and committed: ln s of the turning point on\n\
             //! GUIDE_N points of ln lambda, and ln s of the contact-branch solution on CG_L x CG_Y\n\
             //! points of (ln lambda, ln(Delta - Delta_j)). They only seed the solves, so results do\n\
             //! not depend on them. Written by the test `the_committed_guides_are_the_solvers`\n\
             //! (`STICTION_WRITE_GUIDES=1 cargo test -p maugis-kim --release the_committed_guides`);\n\
             //! do not edit.\n\n\
             #[rustfmt::skip]\n\
             pub(crate) static TURNING: [f64; crate::md::GUIDE_N] = [\n{}];\n\n\
             #[rustfmt::skip]\n\
             pub(crate) static CONTACT: [f64; crate::md::CG_L.2 * crate::md::CG_Y.2] = [\n{}];\n",
            list(turning, 4),
            list(contact, 4)
        )
    }

    /// The committed guides are what the solvers give today, to 1e-9 in ln s (they were
    /// written on this platform to the last bit; another libm may differ in the last
    /// digits, and a guide only seeds a solve), and fail exactly where the solvers fail.
    #[test]
    fn the_committed_guides_are_the_solvers() {
        let turning: Vec<f64> = (0..GUIDE_N).map(turning_guide_entry).collect();
        let contact: Vec<f64> = (0..CG_L.2).flat_map(contact_guide_row).collect();
        if std::env::var_os("STICTION_WRITE_GUIDES").is_some() {
            let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/guide_data.rs");
            std::fs::write(path, render(&turning, &contact)).unwrap();
            return;
        }
        for (name, solved, committed) in [
            ("turning", &turning[..], &crate::guide_data::TURNING[..]),
            ("contact", &contact[..], &crate::guide_data::CONTACT[..]),
        ] {
            assert_eq!(solved.len(), committed.len(), "{name} guide length");
            for (i, (s, c)) in solved.iter().zip(committed).enumerate() {
                assert_eq!(s.is_nan(), c.is_nan(), "{name} guide entry {i}: {s} vs {c}");
                if !s.is_nan() {
                    assert!((s - c).abs() <= 1e-9, "{name} guide entry {i}: {s} vs {c}");
                }
            }
        }
        // the guides really seed: a contact solve inside the grid uses the guess
        assert!(contact_guess(2.0, 0.5).is_some());
        assert!(turning_guess(2.0).is_some());
    }
}
