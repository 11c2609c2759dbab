//! An analytic law with the qualitative shape of an adhesive elasto-plastic rough surface,
//! for tests, benches, examples and for trying the crate without the model.
//!
//! In u = d/sigma and x = (d - d_min)/sigma, with cut-offs C_L(t) = (1 - t/L)^3 for t < L and
//! 0 beyond (reaches U = 6, X_A = 3, X_R = 2.5):
//!
//! * virgin envelope: p_V = P0 C_U(u) e^-u (1 - u/1.5), compressive below u = 1.5, a shallow
//!   tensile region above, zero beyond 6 sigma;
//! * retract branch: p_R = [p_V(u_min) e^(-x/0.02) - W(u_min) g(x/x_w)] C_XR(x), a steep
//!   elastic drop from the envelope into a narrow tensile well (g(t) = t e^(1-t), x_w =
//!   0.12 + 0.02 (u_min - 0.5)) whose depth W = 0.05 P0 (1 - u_min/6)^2 (1 + 0.3 (6 - u_min))
//!   grows as d_min decreases;
//! * approach branch: p_A = [p_V(u_min) e^(-x/0.3) - 0.2 W(u_min) g(x/0.8)] C_XA(x), a
//!   gentler reload with a small tensile pull-in well.
//!
//! Every branch starts on the envelope, p_A = p_R = p_V(d_min) at d = d_min.

use crate::tabulate::{Branch, LawSource, ReloadSource};
use std::convert::Infallible;

/// The analytic toy law (SI: `sigma` in m, `p0` in Pa).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToyLaw {
    /// Length scale (m).
    pub sigma: f64,
    /// Pressure scale (Pa).
    pub p0: f64,
}

const U_TOP: f64 = 6.0;
const X_APPROACH: f64 = 3.0;
const X_RETRACT: f64 = 2.5;
const EPS_RETRACT: f64 = 0.02;
const EPS_APPROACH: f64 = 0.3;
const X_PULL_IN: f64 = 0.8;

fn cutoff(t: f64, len: f64) -> f64 {
    if t < len {
        let s = 1.0 - t / len;
        s * s * s
    } else {
        0.0
    }
}

fn well(t: f64) -> f64 {
    t * (1.0 - t).exp()
}

impl Default for ToyLaw {
    /// sigma = 3 nm, P0 = 1 GPa.
    fn default() -> Self {
        ToyLaw {
            sigma: 3e-9,
            p0: 1e9,
        }
    }
}

impl ToyLaw {
    /// Virgin envelope p_V(d) (Pa).
    pub fn virgin(&self, d: f64) -> f64 {
        let u = d / self.sigma;
        self.p0 * cutoff(u, U_TOP) * (-u).exp() * (1.0 - u / 1.5)
    }

    fn depth(&self, d_min: f64) -> f64 {
        let u = d_min / self.sigma;
        let s = (1.0 - u / U_TOP).max(0.0);
        0.05 * self.p0 * s * s * (1.0 + 0.3 * (U_TOP - u).max(0.0))
    }

    fn well_width(&self, d_min: f64) -> f64 {
        0.12 + 0.02 * (d_min / self.sigma - 0.5)
    }

    /// Retract branch p_R(d; d_min) (Pa), d >= d_min.
    pub fn retract(&self, d: f64, d_min: f64) -> f64 {
        let x = (d - d_min) / self.sigma;
        let xw = self.well_width(d_min);
        cutoff(x, X_RETRACT)
            * (self.virgin(d_min) * (-x / EPS_RETRACT).exp() - self.depth(d_min) * well(x / xw))
    }

    /// Approach branch p_A(d; d_min) (Pa), d >= d_min.
    pub fn approach(&self, d: f64, d_min: f64) -> f64 {
        let x = (d - d_min) / self.sigma;
        cutoff(x, X_APPROACH)
            * (self.virgin(d_min) * (-x / EPS_APPROACH).exp()
                - 0.2 * self.depth(d_min) * well(x / X_PULL_IN))
    }

    /// The pull-out of the retract branch from `d_min`, by a scan and golden section.
    pub fn pull_out_point(&self, d_min: f64) -> (f64, f64) {
        let len = X_RETRACT * self.sigma;
        let f = |x: f64| self.retract(d_min + x, d_min);
        let n: usize = 2000;
        let mut k: usize = 0;
        let mut best = f(0.0);
        for i in 1..=n {
            let v = f(len * i as f64 / n as f64);
            if v < best {
                best = v;
                k = i;
            }
        }
        let (mut a, mut b) = (
            len * (k.saturating_sub(1)) as f64 / n as f64,
            len * ((k + 1).min(n)) as f64 / n as f64,
        );
        let g = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..200 {
            let c = b - g * (b - a);
            let e = a + g * (b - a);
            if f(c) < f(e) {
                b = e;
            } else {
                a = c;
            }
        }
        let x = 0.5 * (a + b);
        (d_min + x, f(x))
    }
}

impl LawSource for ToyLaw {
    type Error = Infallible;

    fn pressure(&self, d: f64, d_min: f64, branch: Branch) -> Result<f64, Infallible> {
        Ok(match branch {
            Branch::Virgin => self.virgin(d),
            Branch::Approach => self.approach(d, d_min),
            Branch::Retract => self.retract(d, d_min),
        })
    }

    fn reach(&self, d_min: f64, branch: Branch) -> Result<f64, Infallible> {
        Ok(match branch {
            Branch::Virgin => U_TOP * self.sigma,
            Branch::Approach => d_min + X_APPROACH * self.sigma,
            Branch::Retract => d_min + X_RETRACT * self.sigma,
        })
    }

    fn pull_out(&self, d_min: f64) -> Result<(f64, f64), Infallible> {
        Ok(self.pull_out_point(d_min))
    }

    fn length_scale(&self) -> f64 {
        self.sigma
    }
}

impl ReloadSource for ToyLaw {
    /// The retraction starts on the reload curve at d_turn and relaxes onto the retract
    /// branch of d_min over 0.02 sigma.
    fn retract_after_reload(&self, d: f64, d_min: f64, d_turn: f64) -> Result<f64, Infallible> {
        let gap = self.approach(d_turn, d_min) - self.retract(d_turn, d_min);
        Ok(self.retract(d, d_min) + gap * (-(d - d_turn) / (EPS_RETRACT * self.sigma)).exp())
    }
}
