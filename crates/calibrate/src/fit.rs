//! Levenberg-Marquardt on the weighted residuals, each step from the singular value
//! decomposition (faer) of the column-scaled Jacobian, restricted to the directions the
//! data determine; identifiability and standard errors at the optimum.

use crate::constants::{from_array, to_array, Constant, Selection};
use crate::data::FeData;
use crate::error::{CalibError, DataProblem};
use crate::model::{flatten, Calibrator, Evaluator, Point};
use crate::report::{
    scene_fragment, Correlation, CurveReport, Direction, DirectionComponent, FitReport,
    StandardErrors, StopReason,
};
use asperity_plastic::EffectiveRadiusFit;
use contact_core::{AdhesionLaw, LawError};
use faer::Mat;

/// Options of [`Calibrator::fit`]. `Default` gives the values documented on each field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    /// Starting constants; `None`: those of the calibrator's plasticity law (the paper's
    /// eq 13 unless the scene sets others). Constants not selected stay at these values.
    pub start: Option<EffectiveRadiusFit>,
    /// The constants to fit (default all six).
    pub select: Selection,
    /// Cap on accepted steps (default 100).
    pub max_iterations: usize,
    /// Numerical rank: singular values of the column-scaled Jacobian below
    /// `rank_tolerance * s_max` count as zero (default 1e-7: ten times the 1e-8 accuracy of
    /// the finite-difference derivatives, so that a direction the data do not see cannot
    /// pass for one they do).
    pub rank_tolerance: f64,
    /// Stop when an accepted step reduces the cost by less than this fraction, and the
    /// linear model predicted no more (default 1e-10).
    pub cost_tolerance: f64,
    /// Stop when the scaled step |D dtheta| is below this fraction of |D theta| (default
    /// 1e-10).
    pub step_tolerance: f64,
    /// Stop when the residual is orthogonal to the determined columns of the Jacobian:
    /// max_i |u_i . r| <= this * |r| (default 1e-10).
    pub gradient_tolerance: f64,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            start: None,
            select: Selection::ALL,
            max_iterations: 100,
            rank_tolerance: 1e-7,
            cost_tolerance: 1e-10,
            step_tolerance: 1e-10,
            gradient_tolerance: 1e-10,
        }
    }
}

/// A constant is "not determined" when more than this fraction of its unit vector (in
/// squared norm, scaled coordinates) lies in the null space of the Jacobian.
pub const NULL_WEIGHT: f64 = 1e-6;

/// Smallest b2 a step may reach (eq 13 needs b2 > 0).
pub const B2_MIN: f64 = 1e-6;

/// Largest ratio (either way) between a curve's peak data force and the model's peak force
/// on the same points at the starting constants. A loading curve does not depend on the
/// constants at all and an unloading curve starts from the loading force at delta_max, so
/// data further off than this are in other units or of another asperity: refused, naming
/// the line of the curve's peak (rather than fitted into a meaningless, overflowing report).
pub const FORCE_SCALE_LIMIT: f64 = 1e6;

/// Refuses data whose force scale is not the model's (see [`FORCE_SCALE_LIMIT`]);
/// `model` is the model's force at each of `points`.
fn check_force_scale(data: &FeData, points: &[Point], model: &[f64]) -> Result<(), CalibError> {
    for (k, c) in data.curves().iter().enumerate() {
        let model_peak = points
            .iter()
            .zip(model)
            .filter(|(p, _)| p.curve == k)
            .fold(0.0f64, |m, (_, f)| m.max(f.abs()));
        let Some(peak) = c
            .points
            .iter()
            .max_by(|a, b| a.force.abs().total_cmp(&b.force.abs()))
        else {
            continue;
        };
        let ratio = peak.force.abs() / model_peak;
        // a model without force on the curve gives no scale to compare with
        if model_peak > 0.0 && !(1.0 / FORCE_SCALE_LIMIT..=FORCE_SCALE_LIMIT).contains(&ratio) {
            return Err(CalibError::Data {
                line: peak.line,
                column: crate::data::COLUMNS[2].to_string(),
                problem: DataProblem::ForceScale {
                    force: peak.force,
                    delta_max: c.delta_max,
                    branch: c.branch,
                    model_peak,
                },
            });
        }
    }
    Ok(())
}

/// Euclidean norm without overflow or underflow of the squares.
fn norm(v: impl Iterator<Item = f64> + Clone) -> f64 {
    let m = v.clone().fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * v.map(|x| (x / m).powi(2)).sum::<f64>().sqrt()
}

/// Initial damping, relative to the largest squared singular value.
const MU0: f64 = 1e-3;
/// Damping beyond which trial steps are abandoned, relative to s_max^2.
const MU_MAX: f64 = 1e32;
/// Accept a step when the actual reduction is at least this fraction of the predicted.
const ACCEPT: f64 = 1e-4;
/// Per-curve RMS relative misfit regarded as exact (the model's own accuracy is ~1e-13).
const EXACT_RMS: f64 = 1e-12;

/// The weighted least-squares problem over the free constants.
struct Problem<'a, A> {
    eval: Evaluator<A>,
    points: &'a [Point],
    free: Vec<Constant>,
    evaluations: usize,
}

type Failure = (usize, LawError);

/// (relative singular value, [(free position, component)]).
type RawDirection = (f64, Vec<(usize, f64)>);

impl<A: AdhesionLaw + Clone> Problem<'_, A> {
    fn forces(&mut self, theta: &[f64; 6]) -> Result<Vec<f64>, Failure> {
        let fit = from_array(theta).map_err(|e| (0, LawError::law(e)))?;
        self.eval.set_fit(fit);
        self.evaluations += 1;
        self.points
            .iter()
            .enumerate()
            .map(
                |(i, p)| match self.eval.force(p.branch, p.delta_max, p.delta) {
                    Ok(f) if f.is_finite() => Ok(f),
                    Ok(_) => Err((
                        i,
                        LawError::Core(contact_core::CoreError::NotFinite {
                            what: "asperity force",
                            x: p.delta,
                        }),
                    )),
                    Err(e) => Err((i, e)),
                },
            )
            .collect()
    }

    /// Weighted residuals r_i = (F_model - F_data) w_i and the model forces.
    fn residuals(&mut self, theta: &[f64; 6]) -> Result<(Vec<f64>, Vec<f64>), Failure> {
        let f = self.forces(theta)?;
        let r = self
            .points
            .iter()
            .zip(&f)
            .map(|(p, f)| (f - p.force) * p.weight)
            .collect();
        Ok((r, f))
    }

    /// The weighted Jacobian dr/dtheta over the free constants (n x p).
    fn jacobian(&mut self, theta: &[f64; 6], forces: &[f64]) -> Result<Mat<f64>, Failure> {
        let fit = from_array(theta).map_err(|e| (0, LawError::law(e)))?;
        self.eval.set_fit(fit);
        let mut jac = Mat::<f64>::zeros(self.points.len(), self.free.len());
        for (i, (p, f0)) in self.points.iter().zip(forces).enumerate() {
            let g = self
                .eval
                .gradient(fit, p.branch, p.delta_max, p.delta, *f0)
                .map_err(|e| (i, e))?;
            for (j, c) in self.free.iter().enumerate() {
                jac[(i, j)] = g[c.index()] * p.weight;
            }
        }
        Ok(jac)
    }
}

/// The column-scaled Jacobian J D^-1 (D = column norms, zero columns left out) and its
/// thin SVD.
struct Scaled {
    /// Column norms of J (0 for a column the data do not see at all).
    d: Vec<f64>,
    /// Free-constant positions of the nonzero columns.
    nz: Vec<usize>,
    s: Vec<f64>,
    u: Mat<f64>,
    v: Mat<f64>,
    rank: usize,
}

impl Scaled {
    fn new(jac: &Mat<f64>, tol: f64) -> Result<Self, CalibError> {
        let (n, p) = (jac.nrows(), jac.ncols());
        let d: Vec<f64> = (0..p).map(|j| norm((0..n).map(|i| jac[(i, j)]))).collect();
        let nz: Vec<usize> = (0..p).filter(|&j| d[j] > 0.0 && d[j].is_finite()).collect();
        let js = Mat::<f64>::from_fn(n, nz.len(), |i, k| jac[(i, nz[k])] / d[nz[k]]);
        let (s, u, v) = if nz.is_empty() {
            (Vec::new(), Mat::zeros(n, 0), Mat::zeros(0, 0))
        } else {
            let svd = js.thin_svd().map_err(|_| CalibError::Svd {
                rows: n,
                cols: nz.len(),
            })?;
            let s: Vec<f64> = (0..svd.S().dim()).map(|i| svd.S()[i]).collect();
            (s, svd.U().to_owned(), svd.V().to_owned())
        };
        let smax = s.first().copied().unwrap_or(0.0);
        let rank = s.iter().filter(|&&x| x > tol * smax).count();
        Ok(Self {
            d,
            nz,
            s,
            u,
            v,
            rank,
        })
    }

    /// u_i . r for the determined directions.
    fn ur(&self, r: &[f64]) -> Vec<f64> {
        (0..self.rank)
            .map(|i| r.iter().enumerate().map(|(k, x)| self.u[(k, i)] * x).sum())
            .collect()
    }

    /// The damped step in the free constants: dtheta = D^-1 z,
    /// z = -sum_{i < rank} s_i/(s_i^2 + mu) (u_i . r) v_i, i.e. the solution of
    /// min |J dtheta + r|^2 + mu |D dtheta|^2 restricted to the determined subspace.
    fn step(&self, ur: &[f64], mu: f64, p: usize) -> Vec<f64> {
        let mut dtheta = vec![0.0; p];
        for (k, &j) in self.nz.iter().enumerate() {
            let z: f64 = (0..self.rank)
                .map(|i| -self.s[i] / (self.s[i] * self.s[i] + mu) * ur[i] * self.v[(k, i)])
                .sum();
            dtheta[j] = z / self.d[j];
        }
        dtheta
    }

    /// `rank` free constants whose columns are well determined together, in the order
    /// a1 ... b3: greedy column pivoting (modified Gram-Schmidt) on J D^-1, taking at each
    /// step the column with the largest remaining norm; near-ties (within 1e-6) go to the
    /// first constant in the order a1 ... b3, so that the suggestion does not depend on
    /// rounding.
    fn pivoted_subset(&self, jac: &Mat<f64>) -> Vec<usize> {
        let n = jac.nrows();
        let mut cols: Vec<Vec<f64>> = self
            .nz
            .iter()
            .map(|&j| (0..n).map(|i| jac[(i, j)] / self.d[j]).collect())
            .collect();
        let mut chosen: Vec<usize> = Vec::new();
        for _ in 0..self.rank.min(cols.len()) {
            let norms: Vec<f64> = cols.iter().map(|c| dot(c, c).sqrt()).collect();
            let best = (0..cols.len())
                .filter(|k| !chosen.contains(k))
                .fold(0.0f64, |m, k| m.max(norms[k]));
            let Some(pick) = (0..cols.len())
                .find(|k| !chosen.contains(k) && norms[*k] >= (1.0 - 1e-6) * best && best > 0.0)
            else {
                break;
            };
            chosen.push(pick);
            let q: Vec<f64> = cols[pick].iter().map(|x| x / norms[pick]).collect();
            for (k, c) in cols.iter_mut().enumerate() {
                if !chosen.contains(&k) {
                    let a = dot(&q, c);
                    for (x, qi) in c.iter_mut().zip(&q) {
                        *x -= a * qi;
                    }
                }
            }
        }
        let mut out: Vec<usize> = chosen.into_iter().map(|k| self.nz[k]).collect();
        out.sort_unstable();
        out
    }

    /// A basis of the undetermined directions in scaled coordinates, one per free constant
    /// outside `subset` (the pivoted, determined columns): for a seen column j,
    /// v = e_j - sum_{s in subset} c_s e_s with c the least-squares solution (faer QR) of
    /// J_S c = J_j, normalised (the move of constant j that the subset compensates, to
    /// first order); for an unseen column, e_j. Each with |J D^-1 v|/s_max.
    fn directions(
        &self,
        jac: &Mat<f64>,
        subset: &[usize],
        smax: f64,
    ) -> Result<Vec<RawDirection>, CalibError> {
        use faer::linalg::solvers::SolveLstsq;
        let n = jac.nrows();
        let p = jac.ncols();
        let scaled = |i: usize, j: usize| jac[(i, j)] / self.d[j];
        let mut out = Vec::new();
        let others: Vec<usize> = (0..p).filter(|j| !subset.contains(j)).collect();
        if others.is_empty() {
            return Ok(out);
        }
        let js_s = Mat::<f64>::from_fn(n, subset.len(), |i, k| scaled(i, subset[k]));
        let qr = (!subset.is_empty()).then(|| js_s.qr());
        for j in others {
            if !self.nz.contains(&j) {
                out.push((0.0, vec![(j, 1.0)]));
                continue;
            }
            let rhs = Mat::<f64>::from_fn(n, 1, |i, _| scaled(i, j));
            let c = match &qr {
                Some(qr) => qr.solve_lstsq(&rhs),
                None => Mat::zeros(0, 1),
            };
            let mut v: Vec<(usize, f64)> = vec![(j, 1.0)];
            v.extend(subset.iter().enumerate().map(|(k, &s)| (s, -c[(k, 0)])));
            let norm = v.iter().map(|(_, x)| x * x).sum::<f64>().sqrt();
            for (_, x) in v.iter_mut() {
                *x /= norm;
            }
            // |J D^-1 v|
            let jv = (0..n)
                .map(|i| {
                    v.iter()
                        .map(|&(col, x)| scaled(i, col) * x)
                        .sum::<f64>()
                        .powi(2)
                })
                .sum::<f64>()
                .sqrt();
            let rel = if smax > 0.0 { jv / smax } else { 0.0 };
            if !(rel.is_finite() && v.iter().all(|(_, x)| x.is_finite())) {
                return Err(CalibError::Svd { rows: n, cols: p });
            }
            out.push((rel, v));
        }
        Ok(out)
    }

    /// Null-space weight of each free constant: sum over undetermined directions of the
    /// squared component (1 for a column the data do not see).
    fn null_weights(&self, p: usize) -> Vec<f64> {
        let mut w = vec![1.0; p];
        for (k, &j) in self.nz.iter().enumerate() {
            w[j] = (self.rank..self.nz.len())
                .map(|i| {
                    if i < self.v.ncols() {
                        self.v[(k, i)].powi(2)
                    } else {
                        0.0
                    }
                })
                .sum::<f64>();
            if self.v.ncols() < self.nz.len() {
                // fewer rows than columns: the missing directions are null too
                w[j] += 1.0
                    - (0..self.v.ncols())
                        .map(|i| self.v[(k, i)].powi(2))
                        .sum::<f64>();
            }
        }
        w
    }
}

/// Clamp the free constants back into the domain of eq 13 (a3 >= 0, a1 >= 0,
/// a1 + a2 e^-a3 >= 0, b2 >= [`B2_MIN`]).
fn project(t: &mut [f64; 6], free: &[Constant]) {
    let is_free = |c: Constant| free.contains(&c);
    if is_free(Constant::A3) {
        t[2] = t[2].max(0.0);
    }
    if is_free(Constant::A1) {
        t[0] = t[0].max(0.0);
    }
    if t[0] + t[1] * (-t[2]).exp() < 0.0 {
        if is_free(Constant::A2) {
            t[1] = -t[0] * t[2].exp() * (1.0 - 4.0 * f64::EPSILON);
        } else if is_free(Constant::A1) {
            t[0] = -t[1] * (-t[2]).exp() * (1.0 + 4.0 * f64::EPSILON);
        }
    }
    if is_free(Constant::B2) {
        t[4] = t[4].max(B2_MIN);
    }
}

/// Free constants sitting on a bound of the domain.
fn at_bound(t: &[f64; 6], free: &[Constant]) -> Vec<Constant> {
    free.iter()
        .copied()
        .filter(|c| match c {
            Constant::A1 => t[0] == 0.0,
            Constant::A2 => {
                t[0] + t[1] * (-t[2]).exp() <= 1e-12 * (t[0].abs() + t[1].abs()) && t[1] < 0.0
            }
            Constant::A3 => t[2] == 0.0,
            Constant::B2 => t[4] <= B2_MIN,
            _ => false,
        })
        .collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

impl<A: AdhesionLaw + Clone> Calibrator<A> {
    /// Fit the constants selected by `options.select` to `data` (the method is in
    /// `docs/calibration.md`).
    ///
    /// Minimises C = 1/2 sum r_i^2 with r_i = (F_model - F_data)/(F_peak sqrt(n_curve))
    /// (each curve counts alike) by Levenberg-Marquardt: the step solves
    /// min |J dtheta + r|^2 + mu |D dtheta|^2 (D the column norms of J) through the SVD
    /// of J D^-1, keeping only singular values above `rank_tolerance * s_max`, so that
    /// directions the data do not determine keep their starting values. Trial points are
    /// clamped into the domain of eq 13; a trial whose model evaluation fails, or that does
    /// not reduce the cost, is rejected and the damping raised. Errors: bad options or
    /// start, too few points, a model failure at the start (naming the data line).
    pub fn fit(&self, data: &FeData, options: &FitOptions) -> Result<FitReport, CalibError> {
        for (field, v) in [
            ("rank_tolerance", options.rank_tolerance),
            ("cost_tolerance", options.cost_tolerance),
            ("step_tolerance", options.step_tolerance),
            ("gradient_tolerance", options.gradient_tolerance),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(CalibError::Option {
                    field,
                    value: v,
                    allowed: "finite and >= 0",
                });
            }
        }
        let start = match options.start {
            Some(f) => from_array(&to_array(&f))?,
            None => from_array(&to_array(&self.plasticity().fit()))?,
        };
        let free = options.select.constants();
        if free.is_empty() {
            return Err(CalibError::Selection {
                text: String::new(),
                reason: "no constant selected".into(),
            });
        }
        let points = flatten(data);
        if points.len() < free.len() {
            return Err(CalibError::TooFewPoints {
                line: points.iter().map(|p| p.line).max().unwrap_or(1),
                points: points.len(),
                constants: free.len(),
            });
        }
        let mut pb = Problem {
            eval: Evaluator::new(self, start),
            points: &points,
            free: free.clone(),
            evaluations: 0,
        };
        // points is not empty here (at least one constant, as many points)
        let at_start = |(i, source): Failure| match points.get(i).or(points.first()) {
            Some(p) => CalibError::Model {
                line: p.line,
                delta_max: p.delta_max,
                branch: p.branch,
                delta: p.delta,
                source,
            },
            None => CalibError::TooFewPoints {
                line: 1,
                points: 0,
                constants: free.len(),
            },
        };
        let p = free.len();
        let mut theta = to_array(&start);
        let (mut r, mut f) = pb.residuals(&theta).map_err(at_start)?;
        check_force_scale(data, &points, &f)?;
        let mut jac = pb.jacobian(&theta, &f).map_err(at_start)?;
        let mut cost = 0.5 * dot(&r, &r);
        let start_cost = cost;
        let cost_floor = 0.5 * data.curves().len() as f64 * EXACT_RMS * EXACT_RMS;
        let mut mu: Option<f64> = None;
        let mut nu = 2.0;
        let mut iterations = 0;
        let stop = 'outer: loop {
            let sc = Scaled::new(&jac, options.rank_tolerance)?;
            if sc.rank == 0 {
                break StopReason::NothingDetermined;
            }
            if cost <= cost_floor {
                break StopReason::Exact;
            }
            let ur = sc.ur(&r);
            let rn = dot(&r, &r).sqrt();
            if ur.iter().fold(0.0f64, |m, x| m.max(x.abs())) <= options.gradient_tolerance * rn {
                break StopReason::Gradient;
            }
            if iterations >= options.max_iterations {
                break StopReason::IterationCap;
            }
            let s1sq = sc.s[0] * sc.s[0];
            let mu_now = mu.get_or_insert(MU0 * s1sq);
            let mut failed = false;
            loop {
                let dtheta = sc.step(&ur, *mu_now, p);
                let mut trial = theta;
                for (j, c) in free.iter().enumerate() {
                    trial[c.index()] += dtheta[j];
                }
                project(&mut trial, &free);
                let dt: Vec<f64> = free
                    .iter()
                    .map(|c| trial[c.index()] - theta[c.index()])
                    .collect();
                let step_norm = dt
                    .iter()
                    .zip(&sc.d)
                    .map(|(x, d)| (x * d).powi(2))
                    .sum::<f64>()
                    .sqrt();
                let x_norm = free
                    .iter()
                    .zip(&sc.d)
                    .map(|(c, d)| (theta[c.index()] * d).powi(2))
                    .sum::<f64>()
                    .sqrt();
                if step_norm <= options.step_tolerance * (x_norm + options.step_tolerance) {
                    break 'outer if failed {
                        StopReason::Stalled
                    } else {
                        StopReason::Step
                    };
                }
                // predicted reduction of the linear model for the (clamped) step
                let jd: Vec<f64> = (0..points.len())
                    .map(|i| (0..p).map(|j| jac[(i, j)] * dt[j]).sum())
                    .collect();
                let pred = -(dot(&r, &jd) + 0.5 * dot(&jd, &jd));
                let mut accepted = None;
                if pred > 0.0 {
                    match pb.residuals(&trial) {
                        Ok((rt, ft)) => {
                            let ct = 0.5 * dot(&rt, &rt);
                            let rho = (cost - ct) / pred;
                            if rho > ACCEPT {
                                match pb.jacobian(&trial, &ft) {
                                    Ok(jt) => accepted = Some((rt, ft, jt, ct, rho)),
                                    Err(_) => failed = true,
                                }
                            }
                        }
                        Err(_) => failed = true,
                    }
                }
                match accepted {
                    Some((rt, ft, jt, ct, rho)) => {
                        let rel_actual = (cost - ct) / cost;
                        let rel_pred = pred / cost;
                        theta = trial;
                        r = rt;
                        f = ft;
                        jac = jt;
                        cost = ct;
                        iterations += 1;
                        *mu_now *= (1.0f64 / 3.0).max(1.0 - (2.0 * rho - 1.0).powi(3));
                        nu = 2.0;
                        if rel_actual <= options.cost_tolerance
                            && rel_pred <= options.cost_tolerance
                        {
                            break 'outer StopReason::Cost;
                        }
                        continue 'outer;
                    }
                    None => {
                        *mu_now *= nu;
                        nu *= 2.0;
                        if *mu_now > MU_MAX * s1sq {
                            break 'outer StopReason::Damping;
                        }
                    }
                }
            }
        };
        let evaluations = pb.evaluations;
        self.report(
            data,
            &points,
            &free,
            start,
            start_cost,
            theta,
            &r,
            &f,
            &jac,
            cost,
            iterations,
            evaluations,
            stop,
            options,
        )
    }

    #[allow(clippy::too_many_arguments)]
    fn report(
        &self,
        data: &FeData,
        points: &[Point],
        free: &[Constant],
        start: EffectiveRadiusFit,
        start_cost: f64,
        theta: [f64; 6],
        r: &[f64],
        forces: &[f64],
        jac: &Mat<f64>,
        cost: f64,
        iterations: usize,
        evaluations: usize,
        stop: StopReason,
        options: &FitOptions,
    ) -> Result<FitReport, CalibError> {
        let fit = from_array(&theta)?;
        let sc = Scaled::new(jac, options.rank_tolerance)?;
        let p = free.len();
        let n = points.len();
        let weights = sc.null_weights(p);
        let determined: Vec<bool> = weights.iter().map(|w| *w <= NULL_WEIGHT).collect();
        let not_determined: Vec<Constant> = free
            .iter()
            .zip(&determined)
            .filter(|(_, d)| !**d)
            .map(|(c, _)| *c)
            .collect();
        let smax = sc.s.first().copied().unwrap_or(0.0);
        let subset = sc.pivoted_subset(jac);
        let suggested_fit: Vec<Constant> = if not_determined.is_empty() {
            Vec::new()
        } else {
            subset.iter().map(|&j| free[j]).collect()
        };
        let directions = if not_determined.is_empty() {
            Vec::new()
        } else {
            sc.directions(jac, &subset, smax)?
        };
        let directions = directions
            .into_iter()
            .map(|(sv, v)| {
                let mut components: Vec<DirectionComponent> = v
                    .into_iter()
                    .filter(|(_, x)| x.abs() >= 1e-3)
                    .map(|(j, x)| DirectionComponent {
                        constant: free[j],
                        component: x,
                    })
                    .collect();
                components.sort_by(|a, b| b.component.abs().total_cmp(&a.component.abs()));
                Direction {
                    relative_singular_value: sv,
                    components,
                }
            })
            .collect();
        let mut singular_values: Vec<f64> =
            sc.s.iter()
                .map(|s| if smax > 0.0 { s / smax } else { 0.0 })
                .collect();
        singular_values.resize(p, 0.0);

        // covariance in scaled coordinates over the determined subspace:
        // C = s^2 sum_{i < rank} v_i v_i^T / s_i^2, s^2 = |r|^2/(n - rank)
        let dof = n.saturating_sub(sc.rank);
        let mut standard_errors = StandardErrors::default();
        let mut correlation = Correlation::default();
        if dof > 0 && sc.rank > 0 {
            let s2 = 2.0 * cost / dof as f64;
            let m = sc.nz.len();
            let cov = |a: usize, b: usize| -> f64 {
                (0..sc.rank)
                    .map(|i| sc.v[(a, i)] * sc.v[(b, i)] / (sc.s[i] * sc.s[i]))
                    .sum::<f64>()
                    * s2
            };
            let kept: Vec<usize> = (0..m).filter(|&k| determined[sc.nz[k]]).collect();
            for &k in &kept {
                let j = sc.nz[k];
                let se = cov(k, k).sqrt() / sc.d[j];
                if se.is_finite() {
                    standard_errors.insert(free[j], se);
                }
            }
            correlation.names = kept.iter().map(|&k| free[sc.nz[k]]).collect();
            correlation.matrix = kept
                .iter()
                .map(|&a| {
                    kept.iter()
                        .map(|&b| {
                            let c = cov(a, b) / (cov(a, a) * cov(b, b)).sqrt();
                            if c.is_finite() {
                                c.clamp(-1.0, 1.0)
                            } else {
                                0.0
                            }
                        })
                        .collect()
                })
                .collect();
        }

        // sums of squares scaled by the data's peak forces: no overflow or underflow of
        // the squares, whatever the unit of the forces
        let scale = data
            .curves()
            .iter()
            .fold(0.0f64, |m, c| m.max(c.peak_force()));
        let mut curves = Vec::new();
        let mut sum_sq = 0.0;
        for (k, c) in data.curves().iter().enumerate() {
            let peak = c.peak_force();
            let (mut ss, mut cnt) = (0.0, 0usize);
            for (pt, fm) in points.iter().zip(forces) {
                if pt.curve == k {
                    ss += ((fm - pt.force) / peak).powi(2);
                    sum_sq += ((fm - pt.force) / scale).powi(2);
                    cnt += 1;
                }
            }
            let rms = peak * (ss / cnt.max(1) as f64).sqrt();
            curves.push(CurveReport {
                delta_max_m: c.delta_max,
                omega: self.omega(c),
                branch: c.branch,
                points: c.points.len(),
                peak_force_n: peak,
                rms_n: rms,
                rms_relative: rms / peak,
            });
        }
        let _ = r;
        Ok(FitReport {
            c1: fit.c1,
            c2: fit.c2,
            start_c1: start.c1,
            start_c2: start.c2,
            fitted: free.to_vec(),
            standard_errors,
            correlation,
            residual_rms_n: scale * (sum_sq / n as f64).sqrt(),
            start_cost,
            cost,
            iterations,
            evaluations,
            converged: stop.converged(),
            stop,
            rank: sc.rank,
            rank_tolerance: options.rank_tolerance,
            singular_values,
            not_determined,
            suggested_fit,
            undetermined_directions: directions,
            at_bound: at_bound(&theta, free),
            degrees_of_freedom: dof,
            yield_modulus: self.plasticity().yield_modulus(),
            delta_cp_m: self.delta_cp(),
            curves,
            scene_fragment: scene_fragment(&fit),
        })
    }
}
