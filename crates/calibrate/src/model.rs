//! The forward model: the workspace's elasto-plastic adhesive asperity with trial constants
//! of eq 13, evaluated on the finite-element data points, and its derivatives.

use crate::constants::Constant;
use crate::data::{Branch, Curve, FeData};
use crate::error::CalibError;
use asperity_plastic::{EffectiveRadiusFit, ElastoPlasticAsperity, EtsionKadin};
use contact_core::{AdhesionLaw, AsperityHistory, AsperityModel, LawError, Path, PlasticityLaw};
use serde::Serialize;

/// Relative step of the central differences in c1 and c2: h = 1e-5 max(|c|, 1).
///
/// The asperity force is solved to about 1e-13 relative, so the rounding part of the
/// derivative error is about 1e-13/1e-5 = 1e-8 relative and the truncation part
/// (h^2/6) F''' about 1e-11: h = 1e-5 balances them near 1e-8.
pub const FD_STEP: f64 = 1e-5;

/// The model of one asperity whose eq-13 constants are to be identified: the scene's
/// Etsion-Kadin law (material, radius, reading of eq 1; its own constants are the default
/// starting point) and adhesion law.
///
/// Predicted force at a data point (eqs 4, 5, 12, then the adhesion law with R_eff at
/// delta - delta_res):
/// * loading: the virgin loading force at delta, `force(delta, VIRGIN, Approach)` (the
///   asperity has been loaded to delta, so delta_max = delta and x = 1, f(x) = 1: only
///   c1(delta/delta_CP) enters);
/// * unloading: the retraction force from the curve's delta_max,
///   `force(delta, {delta_max}, Retract { from: delta_max })` (c1 and c2 at
///   omega = delta_max/delta_CP).
#[derive(Debug, Clone, PartialEq)]
pub struct Calibrator<A> {
    plasticity: EtsionKadin,
    adhesion: A,
}

/// A data point flattened out of its curve, with its weight.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Point {
    pub curve: usize,
    pub branch: Branch,
    pub delta_max: f64,
    pub delta: f64,
    pub force: f64,
    /// 1/(F_peak(curve) sqrt(n_curve)).
    pub weight: f64,
    pub line: usize,
}

pub(crate) fn flatten(data: &FeData) -> Vec<Point> {
    let mut out = Vec::with_capacity(data.len());
    for (k, c) in data.curves().iter().enumerate() {
        let w = 1.0 / (c.peak_force() * (c.points.len() as f64).sqrt());
        for p in &c.points {
            out.push(Point {
                curve: k,
                branch: c.branch,
                delta_max: c.delta_max,
                delta: p.delta,
                force: p.force,
                weight: w,
                line: p.line,
            });
        }
    }
    out
}

/// Model and data of one curve on a fine grid, for an overlay plot.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OverlayCurve {
    /// The curve's delta_max (m).
    pub delta_max_m: f64,
    /// The branch.
    pub branch: Branch,
    /// The data points, [delta (m), force (N)].
    pub data: Vec<[f64; 2]>,
    /// The model on an even grid over the data's delta range, [delta (m), force (N)].
    pub model: Vec<[f64; 2]>,
}

impl<A: AdhesionLaw + Clone> Calibrator<A> {
    /// The model of the scene's asperity: `plasticity` (its constants of eq 13 are the
    /// default start of a fit) composed with `adhesion`.
    pub fn new(plasticity: EtsionKadin, adhesion: A) -> Self {
        Self {
            plasticity,
            adhesion,
        }
    }

    /// The plasticity law as given.
    pub fn plasticity(&self) -> &EtsionKadin {
        &self.plasticity
    }

    /// The adhesion law.
    pub fn adhesion(&self) -> &A {
        &self.adhesion
    }

    /// delta_CP (m), eq 1.
    pub fn delta_cp(&self) -> f64 {
        self.plasticity.delta_cp()
    }

    /// The asperity with the constants `fit`.
    pub fn asperity(&self, fit: EffectiveRadiusFit) -> ElastoPlasticAsperity<EtsionKadin, A> {
        ElastoPlasticAsperity::new(self.plasticity.with_fit(fit), self.adhesion.clone())
    }

    /// Predicted force (N) at interference `delta` (m) of the `branch` curve to `delta_max`.
    pub fn force(
        &self,
        fit: EffectiveRadiusFit,
        branch: Branch,
        delta_max: f64,
        delta: f64,
    ) -> Result<f64, LawError> {
        Evaluator::new(self, fit).force(branch, delta_max, delta)
    }

    /// Predicted forces (N) at every data point, curve by curve. Errors name the data line.
    pub fn predict(
        &self,
        fit: EffectiveRadiusFit,
        data: &FeData,
    ) -> Result<Vec<Vec<f64>>, CalibError> {
        let ev = Evaluator::new(self, fit);
        data.curves()
            .iter()
            .map(|c| {
                c.points
                    .iter()
                    .map(|p| {
                        ev.force(c.branch, c.delta_max, p.delta).map_err(|source| {
                            CalibError::Model {
                                line: p.line,
                                delta_max: c.delta_max,
                                branch: c.branch,
                                delta: p.delta,
                                source,
                            }
                        })
                    })
                    .collect()
            })
            .collect()
    }

    /// Data and model at `fit` on `points` evenly spaced interferences over each curve's
    /// data range (loading: from the smallest delta up to delta_max; unloading: from
    /// delta_max down to the smallest delta), for an overlay plot.
    pub fn overlay(
        &self,
        fit: EffectiveRadiusFit,
        data: &FeData,
        points: usize,
    ) -> Result<Vec<OverlayCurve>, CalibError> {
        let ev = Evaluator::new(self, fit);
        let n = points.max(2);
        data.curves()
            .iter()
            .map(|c| {
                let lo = c.points.iter().fold(c.delta_max, |m, p| m.min(p.delta));
                let grid: Vec<f64> = match c.branch {
                    Branch::Loading => {
                        contact_core::numeric::linspace(lo, c.delta_max, n).collect()
                    }
                    Branch::Unloading => {
                        contact_core::numeric::linspace(c.delta_max, lo, n).collect()
                    }
                };
                let model = grid
                    .into_iter()
                    .map(|d| {
                        ev.force(c.branch, c.delta_max, d)
                            .map(|f| [d, f])
                            .map_err(|source| CalibError::Overlay {
                                delta_max: c.delta_max,
                                branch: c.branch,
                                delta: d,
                                source,
                            })
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                Ok(OverlayCurve {
                    delta_max_m: c.delta_max,
                    branch: c.branch,
                    data: c.points.iter().map(|p| [p.delta, p.force]).collect(),
                    model,
                })
            })
            .collect()
    }

    /// delta_max/delta_CP of a curve.
    pub fn omega(&self, curve: &Curve) -> f64 {
        curve.delta_max / self.delta_cp()
    }
}

/// One asperity whose constants are swapped without cloning the adhesion law.
pub(crate) struct Evaluator<A> {
    base: EtsionKadin,
    asp: ElastoPlasticAsperity<EtsionKadin, A>,
}

/// A fit holding c1 and c2 constant in omega at the values `c1`, `c2`
/// (a1 = c1, a2 = a3 = 0; b1 = 0, b2 = 1, b3 = -c2): R_eff at any point then equals that
/// of a fit with c1(omega) = c1 and c2(omega) = c2 there, bit for bit.
fn frozen(c1: f64, c2: f64) -> Option<EffectiveRadiusFit> {
    EffectiveRadiusFit::new([c1, 0.0, 0.0], [0.0, 1.0, -c2]).ok()
}

impl<A: AdhesionLaw + Clone> Evaluator<A> {
    pub fn new(cal: &Calibrator<A>, fit: EffectiveRadiusFit) -> Self {
        Self {
            base: cal.plasticity,
            asp: cal.asperity(fit),
        }
    }

    pub fn set_fit(&mut self, fit: EffectiveRadiusFit) {
        self.asp.plasticity = self.base.with_fit(fit);
    }

    pub fn force(&self, branch: Branch, delta_max: f64, delta: f64) -> Result<f64, LawError> {
        match branch {
            Branch::Loading => self
                .asp
                .force(delta, AsperityHistory::VIRGIN, Path::Approach),
            Branch::Unloading => self.asp.force(
                delta,
                AsperityHistory { delta_max },
                Path::Retract { from: delta_max },
            ),
        }
    }

    /// Derivatives (N) of the force at a point with respect to the six constants
    /// [a1, a2, a3, b1, b2, b3] at `fit`, given the force `f0` there (its value at `fit`).
    ///
    /// The constants enter only through c1 and c2 at the point's omega (delta/delta_CP on
    /// loading, delta_max/delta_CP on unloading), so dF/dc1 and dF/dc2 are taken by central
    /// differences of step [`FD_STEP`] (second-order one-sided in c1 when c1 < h, to stay in
    /// c1 >= 0) with c1, c2 frozen, and eq 13 is differentiated analytically:
    /// dc1/d(a1, a2, a3) = (1, e, -a2 omega e), e = exp(-a3 omega);
    /// dc2/d(b1, b2, b3) = (q, 2 b1 omega^2 q^2/b2^3, -1), q = 1/(1 + (omega/b2)^2).
    /// Exact zeros: where R_eff = R_res (not yielded, or delta <= delta_res), and dF/dc2 on
    /// loading (f(1) = 1 for every c2).
    pub fn gradient(
        &mut self,
        fit: EffectiveRadiusFit,
        branch: Branch,
        delta_max: f64,
        delta: f64,
        f0: f64,
    ) -> Result<[f64; 6], LawError> {
        let dmax = match branch {
            Branch::Loading => delta.max(0.0),
            Branch::Unloading => delta_max,
        };
        let st = self.base.state(dmax);
        if st.delta_res <= 0.0 || delta <= st.delta_res {
            return Ok([0.0; 6]);
        }
        let omega = dmax / self.base.delta_cp();
        let (c1, c2) = (fit.c1(omega), fit.c2(omega));
        let diffs = self.c_derivatives(branch, delta_max, delta, f0, c1, c2);
        self.set_fit(fit);
        let (d_c1, d_c2) = diffs?;
        let [_, a2, a3] = fit.c1;
        let [b1, b2, _] = fit.c2;
        let e = (-a3 * omega).exp();
        let q = 1.0 / (1.0 + (omega / b2).powi(2));
        let mut g = [0.0; 6];
        g[Constant::A1.index()] = d_c1;
        g[Constant::A2.index()] = d_c1 * e;
        g[Constant::A3.index()] = -d_c1 * a2 * omega * e;
        g[Constant::B1.index()] = d_c2 * q;
        g[Constant::B2.index()] = d_c2 * 2.0 * b1 * omega * omega * q * q / (b2 * b2 * b2);
        g[Constant::B3.index()] = -d_c2;
        Ok(g)
    }

    /// (dF/dc1, dF/dc2) by differences with c1, c2 frozen (leaves a frozen fit set).
    fn c_derivatives(
        &mut self,
        branch: Branch,
        delta_max: f64,
        delta: f64,
        f0: f64,
        c1: f64,
        c2: f64,
    ) -> Result<(f64, f64), LawError> {
        let mut eval = |a: f64, b: f64| -> Result<f64, LawError> {
            let fz = frozen(a, b).ok_or(LawError::Core(contact_core::CoreError::Invalid {
                field: "c1",
                value: a,
                allowed: ">= 0",
            }))?;
            self.set_fit(fz);
            self.force(branch, delta_max, delta)
        };
        let h1 = FD_STEP * c1.abs().max(1.0);
        let d_c1 = if c1 - h1 >= 0.0 {
            (eval(c1 + h1, c2)? - eval(c1 - h1, c2)?) / (2.0 * h1)
        } else {
            (-3.0 * f0 + 4.0 * eval(c1 + h1, c2)? - eval(c1 + 2.0 * h1, c2)?) / (2.0 * h1)
        };
        let d_c2 = match branch {
            Branch::Loading => 0.0,
            Branch::Unloading => {
                let h2 = FD_STEP * c2.abs().max(1.0);
                (eval(c1, c2 + h2)? - eval(c1, c2 - h2)?) / (2.0 * h2)
            }
        };
        Ok((d_c1, d_c2))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::{from_array, to_array};
    use asperity_plastic::YieldModulus;
    use contact_core::{paper, Material, Pair};
    use maugis_kim::{DugdaleParams, MaugisKim};

    fn ru(modulus: YieldModulus) -> Calibrator<MaugisKim> {
        let pair = Pair::new(Material::new(paper::RU).unwrap(), None, paper::RADIUS).unwrap();
        Calibrator::new(
            EtsionKadin::new(&pair, modulus).unwrap(),
            MaugisKim::new(DugdaleParams::for_pair(
                &pair,
                paper::WORK_OF_ADHESION,
                paper::Z0,
            ))
            .unwrap(),
        )
    }

    /// The chain-rule gradient against brute-force central differences on each of the six
    /// constants (step 1e-4 relative: truncation ~1e-8, rounding ~1e-9 of the force).
    #[test]
    fn gradient_matches_differences_on_the_constants() {
        let fit = EffectiveRadiusFit::new([0.3, 0.5, 0.12], [8.0, 12.0, 4.0]).unwrap();
        for modulus in [YieldModulus::AsPrinted, YieldModulus::Composite] {
            let cal = ru(modulus);
            let dcp = cal.delta_cp();
            let mut ev = Evaluator::new(&cal, fit);
            for (branch, omega, x) in [
                (Branch::Loading, 7.0, 1.0),
                (Branch::Loading, 33.0, 1.0),
                (Branch::Unloading, 6.0, 0.8),
                (Branch::Unloading, 25.0, 0.97),
                (Branch::Unloading, 25.0, 0.3),
            ] {
                let dmax = omega * dcp;
                let st = cal.plasticity().state(dmax);
                let delta = st.delta_res + x * (dmax - st.delta_res);
                let f0 = ev.force(branch, dmax, delta).unwrap();
                let g = ev.gradient(fit, branch, dmax, delta, f0).unwrap();
                // the evaluator is left at `fit`
                assert_eq!(ev.force(branch, dmax, delta).unwrap(), f0);
                let gmax = g.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let t = to_array(&fit);
                for k in 0..6 {
                    let h = 1e-4 * t[k].abs().max(1e-3);
                    let mut up = t;
                    let mut dn = t;
                    up[k] += h;
                    dn[k] -= h;
                    let f = |a: &[f64; 6]| {
                        cal.force(from_array(a).unwrap(), branch, dmax, delta)
                            .unwrap()
                    };
                    let fd = (f(&up) - f(&dn)) / (2.0 * h);
                    assert!(
                        (fd - g[k]).abs() <= 1e-6 * gmax,
                        "{modulus:?} {branch} omega {omega} x {x} constant {k}: {} vs {fd}",
                        g[k]
                    );
                }
                if branch == Branch::Loading {
                    assert_eq!(&g[3..], &[0.0; 3], "c2 has no effect on loading");
                }
            }
            // below yield and out of contact the constants have no effect at all
            let dmax = 20.0 * dcp;
            let st = cal.plasticity().state(dmax);
            for (branch, delta) in [
                (Branch::Loading, 0.5 * dcp),
                (Branch::Unloading, st.delta_res),
                (Branch::Unloading, st.delta_res - 0.1e-9),
            ] {
                let f0 = ev.force(branch, dmax, delta).unwrap();
                assert_eq!(ev.gradient(fit, branch, dmax, delta, f0).unwrap(), [0.0; 6]);
            }
        }
    }

    /// The frozen fit reproduces the force of the real fit bit for bit, which the
    /// one-sided difference and the chain rule rely on.
    #[test]
    fn frozen_constants_reproduce_the_force_exactly() {
        let cal = ru(YieldModulus::AsPrinted);
        let fit = EffectiveRadiusFit::PAPER;
        for omega in [3.0, 10.0, 42.0] {
            let dmax = omega * cal.delta_cp();
            let fz = frozen(fit.c1(omega), fit.c2(omega)).unwrap();
            for branch in [Branch::Loading, Branch::Unloading] {
                let d = 0.93 * dmax;
                let om = if branch == Branch::Loading {
                    d / cal.delta_cp()
                } else {
                    omega
                };
                let fz = if branch == Branch::Loading {
                    frozen(fit.c1(om), fit.c2(om)).unwrap()
                } else {
                    fz
                };
                assert_eq!(
                    cal.force(fit, branch, dmax, d).unwrap(),
                    cal.force(fz, branch, dmax, d).unwrap()
                );
            }
        }
    }
}
