//! The result of a fit: constants, uncertainty, identifiability, misfit, the scene
//! fragment, and a plain-text rendering.

use crate::constants::{from_array, Constant};
use crate::data::Branch;
use asperity_plastic::{EffectiveRadiusFit, YieldModulus};
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Why the iteration stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// The residual is orthogonal to the determined columns of the Jacobian.
    Gradient,
    /// An accepted step reduced the cost, and was predicted to, by less than the cost
    /// tolerance.
    Cost,
    /// The step fell below the step tolerance.
    Step,
    /// The curves are reproduced to the model's own accuracy (RMS below 1e-12 of each
    /// curve's peak).
    Exact,
    /// Not converged: the iteration cap was reached.
    IterationCap,
    /// Not converged: the damping grew without bound (no trial step reduced the cost).
    Damping,
    /// Not converged: the step shrank to nothing while trial evaluations failed.
    Stalled,
    /// Not converged: the data determine none of the selected constants.
    NothingDetermined,
}

impl StopReason {
    /// True for the convergence criteria (gradient, cost, step, exact).
    pub fn converged(self) -> bool {
        matches!(
            self,
            StopReason::Gradient | StopReason::Cost | StopReason::Step | StopReason::Exact
        )
    }
}

/// Standard errors of the fitted and determined constants (absent ones omitted).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct StandardErrors {
    /// Of a1, a2, a3 (keys `a1`, `a2`, `a3`).
    pub c1: BTreeMap<Constant, f64>,
    /// Of b1, b2, b3 (keys `b1`, `b2`, `b3`).
    pub c2: BTreeMap<Constant, f64>,
}

impl StandardErrors {
    pub(crate) fn insert(&mut self, c: Constant, v: f64) {
        if c.index() < 3 {
            self.c1.insert(c, v);
        } else {
            self.c2.insert(c, v);
        }
    }

    /// The standard error of `c`, if it was fitted and is determined.
    pub fn get(&self, c: Constant) -> Option<f64> {
        self.c1.get(&c).or_else(|| self.c2.get(&c)).copied()
    }
}

/// Correlation matrix of the fitted and determined constants.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Correlation {
    /// The constants, in the order of the rows and columns.
    pub names: Vec<Constant>,
    /// The matrix (symmetric, unit diagonal).
    pub matrix: Vec<Vec<f64>>,
}

/// One component of an undetermined direction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DirectionComponent {
    /// The constant.
    pub constant: Constant,
    /// Its component in the unit direction (scaled coordinates: each constant in units of
    /// its own column norm of the Jacobian).
    pub component: f64,
}

/// A direction in constant space the data do not determine: a right singular vector of
/// the column-scaled Jacobian with a singular value below the rank tolerance, or a
/// constant the data do not see at all.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Direction {
    /// Its singular value relative to the largest (0 for an unseen constant).
    pub relative_singular_value: f64,
    /// Its components of magnitude >= 1e-3, largest first.
    pub components: Vec<DirectionComponent>,
}

/// Misfit on one curve.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CurveReport {
    /// The curve's delta_max (m).
    pub delta_max_m: f64,
    /// delta_max/delta_CP.
    pub omega: f64,
    /// The branch.
    pub branch: Branch,
    /// Its number of points.
    pub points: usize,
    /// max |F| on the curve (N).
    pub peak_force_n: f64,
    /// RMS of F_model - F_data (N).
    pub rms_n: f64,
    /// `rms_n` / `peak_force_n`.
    pub rms_relative: f64,
}

/// The result of [`crate::Calibrator::fit`]. Serialises without null or NaN: absent
/// values are omitted.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitReport {
    /// Fitted [a1, a2, a3].
    pub c1: [f64; 3],
    /// Fitted [b1, b2, b3].
    pub c2: [f64; 3],
    /// Starting [a1, a2, a3].
    pub start_c1: [f64; 3],
    /// Starting [b1, b2, b3].
    pub start_c2: [f64; 3],
    /// The constants selected for fitting.
    pub fitted: Vec<Constant>,
    /// Standard errors from s^2 (J^T J)^+ over the determined subspace,
    /// s^2 = (weighted residual sum of squares)/(n - rank); only fitted and determined
    /// constants.
    pub standard_errors: StandardErrors,
    /// Correlation of the fitted and determined constants.
    pub correlation: Correlation,
    /// RMS of F_model - F_data over all points (N).
    pub residual_rms_n: f64,
    /// Weighted cost 1/2 sum r_i^2 at the start.
    pub start_cost: f64,
    /// Weighted cost at the end.
    pub cost: f64,
    /// Accepted steps.
    pub iterations: usize,
    /// Model evaluations on the whole data set (residual vectors; Jacobians not counted).
    pub evaluations: usize,
    /// True when a convergence criterion was met (see `stop`).
    pub converged: bool,
    /// Why the iteration stopped.
    pub stop: StopReason,
    /// Numerical rank of the column-scaled Jacobian over the fitted constants.
    pub rank: usize,
    /// The relative singular value threshold of the rank.
    pub rank_tolerance: f64,
    /// Singular values of the column-scaled Jacobian relative to the largest (zeros for
    /// unseen constants), one per fitted constant.
    pub singular_values: Vec<f64>,
    /// Fitted constants the data do not determine (held at their starting values, up to
    /// the motion of the determined combinations).
    pub not_determined: Vec<Constant>,
    /// When some constants are not determined: a subset of the fitted constants, as many as
    /// the rank, that the data determine together (greedy column pivoting on the scaled
    /// Jacobian): a `--fit` selection to try. Empty otherwise.
    pub suggested_fit: Vec<Constant>,
    /// The undetermined directions.
    pub undetermined_directions: Vec<Direction>,
    /// Fitted constants that ended on a bound of the domain of eq 13.
    pub at_bound: Vec<Constant>,
    /// n - rank.
    pub degrees_of_freedom: usize,
    /// The reading of eq 1 used.
    pub yield_modulus: YieldModulus,
    /// delta_CP (m).
    pub delta_cp_m: f64,
    /// Misfit per curve.
    pub curves: Vec<CurveReport>,
    /// The `[contact.effective_radius]` table of a scene file with the fitted constants.
    pub scene_fragment: String,
}

/// Shortest form of `x` rounded to 8 significant digits (TOML float syntax).
fn short(x: f64) -> f64 {
    format!("{x:.7e}").parse().unwrap_or(x)
}

/// The scene fragment: constants to 8 significant digits (full precision if rounding would
/// leave the domain of eq 13), written as TOML floats.
pub fn scene_fragment(fit: &EffectiveRadiusFit) -> String {
    let t = crate::constants::to_array(fit);
    let rounded = t.map(short);
    let v = if from_array(&rounded).is_ok() {
        rounded
    } else {
        t
    };
    format!(
        "[contact.effective_radius]\nc1 = [{:?}, {:?}, {:?}]\nc2 = [{:?}, {:?}, {:?}]\n",
        v[0], v[1], v[2], v[3], v[4], v[5]
    )
}

impl FitReport {
    /// The fitted constants.
    pub fn fit(&self) -> EffectiveRadiusFit {
        EffectiveRadiusFit {
            c1: self.c1,
            c2: self.c2,
        }
    }

    /// A plain-text table: constants with their standard errors, the stop, the
    /// identifiability, and the per-curve misfit.
    pub fn to_table(&self) -> String {
        let mut s = String::new();
        let dcp = self.delta_cp_m;
        let _ = writeln!(
            s,
            "Effective-radius constants (eq 13), yield modulus {}, delta_CP = {:.4} nm",
            self.yield_modulus.as_str(),
            dcp * 1e9
        );
        let _ = writeln!(
            s,
            "{:<9} {:>13} {:>13}  standard error",
            "constant", "start", "fitted"
        );
        let start = [self.start_c1, self.start_c2].concat();
        let fitted = [self.c1, self.c2].concat();
        for c in Constant::ALL {
            let i = c.index();
            let note = if !self.fitted.contains(&c) {
                "held (not fitted)".to_string()
            } else if self.not_determined.contains(&c) {
                "not determined by the data".to_string()
            } else {
                match self.standard_errors.get(c) {
                    Some(se) => format!("± {se:.3e}"),
                    None => "none (no degrees of freedom)".to_string(),
                }
            };
            let bound = if self.at_bound.contains(&c) {
                " (at bound)"
            } else {
                ""
            };
            let _ = writeln!(
                s,
                "{:<9} {:>13.6e} {:>13.6e}  {note}{bound}",
                c.name(),
                start[i],
                fitted[i]
            );
        }
        let _ = writeln!(
            s,
            "stop: {:?} ({}), {} iterations, {} evaluations; cost {:.3e} -> {:.3e}",
            self.stop,
            if self.converged {
                "converged"
            } else {
                "NOT converged"
            },
            self.iterations,
            self.evaluations,
            self.start_cost,
            self.cost
        );
        let sv: Vec<String> = self
            .singular_values
            .iter()
            .map(|x| format!("{x:.2e}"))
            .collect();
        let _ = writeln!(
            s,
            "rank {} of {} (relative singular values {}; tolerance {:.0e})",
            self.rank,
            self.fitted.len(),
            sv.join(", "),
            self.rank_tolerance
        );
        if !self.not_determined.is_empty() {
            let names: Vec<&str> = self.not_determined.iter().map(|c| c.name()).collect();
            let suggested: Vec<&str> = self.suggested_fit.iter().map(|c| c.name()).collect();
            let _ = writeln!(
                s,
                "not determined: {}. The data fix only combinations of them (directions below, \
                 scaled coordinates); their values above depend on the start. \
                 Add curves at other delta_max, or fit a subset such as {}",
                names.join(", "),
                suggested.join(",")
            );
            for d in &self.undetermined_directions {
                let comps: Vec<String> = d
                    .components
                    .iter()
                    .map(|c| format!("{:+.3} {}", c.component, c.constant))
                    .collect();
                let _ = writeln!(
                    s,
                    "  direction {} (relative singular value {:.1e})",
                    comps.join(" "),
                    d.relative_singular_value
                );
            }
        }
        let _ = writeln!(s, "residual RMS {:.4e} N", self.residual_rms_n);
        let _ = writeln!(
            s,
            "{:>15} {:>8} {:>10} {:>7} {:>12} {:>12} {:>10}",
            "delta_max (nm)", "omega", "branch", "points", "peak (N)", "RMS (N)", "RMS/peak"
        );
        for c in &self.curves {
            let _ = writeln!(
                s,
                "{:>15.4} {:>8.3} {:>10} {:>7} {:>12.4e} {:>12.4e} {:>10.3e}",
                c.delta_max_m * 1e9,
                c.omega,
                c.branch.as_str(),
                c.points,
                c.peak_force_n,
                c.rms_n,
                c.rms_relative
            );
        }
        s.push('\n');
        s.push_str(&self.scene_fragment);
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_fragment_is_toml_with_floats() {
        let fit = EffectiveRadiusFit::new([0.3, 0.123456789012, 0.12], [8.0, 12.0, -4.0]).unwrap();
        assert_eq!(
            scene_fragment(&fit),
            "[contact.effective_radius]\nc1 = [0.3, 0.12345679, 0.12]\nc2 = [8.0, 12.0, -4.0]\n"
        );
        let tiny = EffectiveRadiusFit::new([1e-20, 0.5, 0.0], [1.0, 1e3, 0.0]).unwrap();
        assert!(scene_fragment(&tiny).contains("c1 = [1e-20, 0.5, 0.0]"));
    }
}
