//! Tabulation of a law from a model ([`LawSource`]): adaptive grids in d and in d_min, and
//! the measurement of the interpolation error at points off every grid.
//!
//! The build, for a d_min range [lo, hi]:
//!
//! 1. each curve is sampled in x = d - d_min (in d for the virgin envelope) on a start grid
//!    that is geometric near x = 0 (from 1e-4 of the length scale, where a retract branch
//!    drops steeply) and uniform up to the curve's reach, plus the pull-out exactly; then an
//!    interval is bisected while the interpolant's value at its midpoint misses the source
//!    by more than `tol (|p| + |p_pull_out(d_min)|)`; the most tensile point of the approach
//!    branches and of the envelope is located by golden section and added as a node;
//! 2. the d_min grid (unless the user gives one) starts uniform with 5 nodes and an
//!    interval is bisected while the rule in d_min (linear at fixed x, with the continuity
//!    correction) applied to the two neighbouring branches misses the directly computed
//!    branch of the mid d_min by more than the tolerance, at the union of the neighbours'
//!    nodes (at most 64 per branch) and the mid pull-out; the neighbours are taken from the
//!    source there, so that the check sees the error of the rule in d_min alone;
//! 3. the law is assembled from its data exactly as a reader would, and its error is
//!    measured against the source at points off every grid ([`crate::MeasuredError`]).
//!
//! Sequential by design: the model's evaluations need not be `Sync`.

use crate::error::{fmt_num, LawError};
use crate::law::{correction, fade_length, BranchSet, ContactLaw, Curve, Meta, Path, Point};
use crate::meta::{ErrorStats, MeasuredError, PartialReloadError, TabulationInfo};
use crate::steffen::Steffen;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// A curve of the law as the source computes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Branch {
    /// The virgin envelope (d_min ignored).
    Virgin,
    /// Coming from far with history d_min.
    Approach,
    /// Retracting after reaching d_min.
    Retract,
}

impl From<Path> for Branch {
    fn from(p: Path) -> Self {
        match p {
            Path::Approach => Branch::Approach,
            Path::Retract => Branch::Retract,
        }
    }
}

/// The model side of the tabulator: a rough-surface law evaluated directly (slowly).
pub trait LawSource {
    /// The source's own error.
    type Error: std::error::Error + Send + Sync + 'static;

    /// Pressure (Pa, compressive positive) at separation `d` (m) on `branch` of the law
    /// whose deepest separation is `d_min` (m), d >= d_min. For [`Branch::Virgin`] d_min is
    /// ignored. Zero beyond the branch's reach.
    fn pressure(&self, d: f64, d_min: f64, branch: Branch) -> Result<f64, Self::Error>;

    /// Largest separation (m) at which the branch can be non-zero (its reach: where the
    /// first asperity jumps in on approach, the last jumps out on retraction), for this
    /// d_min. Must exceed d_min.
    fn reach(&self, d_min: f64, branch: Branch) -> Result<f64, Self::Error>;

    /// The most tensile point (d in m, p in Pa) of the retract branch from `d_min`: the
    /// pull-out.
    fn pull_out(&self, d_min: f64) -> Result<(f64, f64), Self::Error>;

    /// A length (m) over which the law changes appreciably (the roughness sigma_s).
    fn length_scale(&self) -> f64;
}

/// A source that can also retract after a partial reload, for
/// [`measure_partial_reload`].
pub trait ReloadSource: LawSource {
    /// Pressure (Pa) at `d` (m) while retracting after a reload that came from far and
    /// turned at `d_turn` (d_min < d_turn <= d), the deepest separation ever reached being
    /// `d_min`.
    fn retract_after_reload(&self, d: f64, d_min: f64, d_turn: f64) -> Result<f64, Self::Error>;
}

/// A uniform grid `FROM:TO:N` (m, m, count), e.g. `8e-9:2e-9:25`; either order.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GridSpec {
    /// One end (m).
    pub from: f64,
    /// The other end (m).
    pub to: f64,
    /// Number of nodes, at least 2.
    pub n: usize,
}

impl GridSpec {
    /// The nodes, increasing.
    pub fn nodes(&self) -> Vec<f64> {
        let (a, b) = if self.from <= self.to {
            (self.from, self.to)
        } else {
            (self.to, self.from)
        };
        let n = self.n.max(2);
        (0..n)
            .map(|i| {
                if i + 1 == n {
                    b
                } else {
                    a + (b - a) * (i as f64 / (n - 1) as f64)
                }
            })
            .collect()
    }

    fn check(&self) -> Result<(), LawError> {
        if !self.from.is_finite() || !self.to.is_finite() || self.from == self.to {
            return Err(LawError::Invalid {
                name: "d_min grid",
                value: self.to_string(),
                allowed: "finite and distinct FROM and TO (m)",
            });
        }
        if self.n < 2 || self.n > 100_000 {
            return Err(LawError::Invalid {
                name: "d_min grid",
                value: self.to_string(),
                allowed: "N between 2 and 100000",
            });
        }
        Ok(())
    }
}

impl fmt::Display for GridSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", fmt_num(self.from), fmt_num(self.to), self.n)
    }
}

impl FromStr for GridSpec {
    type Err = LawError;
    /// Parses `FROM:TO:N`.
    fn from_str(s: &str) -> Result<Self, LawError> {
        let bad = || LawError::Invalid {
            name: "grid",
            value: s.chars().take(80).collect(),
            allowed: "FROM:TO:N with FROM, TO in m and N an integer >= 2, e.g. 8e-9:2e-9:25",
        };
        let parts: Vec<&str> = s.trim().split(':').collect();
        if parts.len() != 3 {
            return Err(bad());
        }
        let from: f64 = parts[0].trim().parse().map_err(|_| bad())?;
        let to: f64 = parts[1].trim().parse().map_err(|_| bad())?;
        let n: usize = parts[2].trim().parse().map_err(|_| bad())?;
        let g = GridSpec { from, to, n };
        g.check()?;
        Ok(g)
    }
}

/// How the d_min grid is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum DminGrid {
    /// Refined where the law changes fastest, on [lo, hi] (m).
    Adaptive {
        /// Deepest history (m): the depth the scene's impacts reach.
        lo: f64,
        /// Shallowest history (m): the first touch; below the virgin reach.
        hi: f64,
    },
    /// The user's uniform grid.
    Uniform(GridSpec),
}

/// Options of [`tabulate`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Tabulation {
    /// The d_min grid.
    pub d_min: DminGrid,
    /// Uniform start nodes per curve (the geometric ones near x = 0 come on top).
    pub points_per_branch: usize,
    /// Refinement tolerance on |p_interp - p_direct| / (|p_direct| + |p_pull_out|).
    pub tolerance: f64,
    /// Pseudo-random check points per branch kind for the measured error.
    pub random_points: usize,
    /// Seed of the pseudo-random points.
    pub seed: u64,
    /// Cap on the number of branches (adaptive d_min grid).
    pub max_branches: usize,
    /// Cap on the nodes of one curve.
    pub max_nodes: usize,
}

impl Tabulation {
    /// Defaults with an adaptive d_min grid on [lo, hi] (m): 48 start points per branch,
    /// tolerance 2e-4, 256 random points per kind, seed 2026, at most 400 branches and
    /// 20000 nodes per curve.
    pub fn adaptive(lo: f64, hi: f64) -> Tabulation {
        Tabulation {
            d_min: DminGrid::Adaptive { lo, hi },
            points_per_branch: 48,
            tolerance: 2e-4,
            random_points: 256,
            seed: 2026,
            max_branches: 400,
            max_nodes: 20_000,
        }
    }

    /// The same defaults with the user's d_min grid.
    pub fn uniform(grid: GridSpec) -> Tabulation {
        Tabulation {
            d_min: DminGrid::Uniform(grid),
            ..Tabulation::adaptive(0.0, 0.0)
        }
    }

    fn check(&self) -> Result<(), LawError> {
        match self.d_min {
            DminGrid::Adaptive { lo, hi } => {
                if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                    return Err(LawError::Invalid {
                        name: "d_min range",
                        value: format!("[{}, {}] m", fmt_num(lo), fmt_num(hi)),
                        allowed: "finite with d_min_lo < d_min_hi",
                    });
                }
            }
            DminGrid::Uniform(g) => g.check()?,
        }
        if !(self.tolerance > 0.0 && self.tolerance <= 0.1) {
            return Err(LawError::invalid(
                "tolerance",
                self.tolerance,
                "in (0, 0.1]",
            ));
        }
        if !(4..=100_000).contains(&self.points_per_branch) {
            return Err(LawError::invalid(
                "points_per_branch",
                self.points_per_branch as f64,
                "between 4 and 100000",
            ));
        }
        if self.random_points > 1_000_000 {
            return Err(LawError::invalid(
                "random_points",
                self.random_points as f64,
                "at most 1e6",
            ));
        }
        if self.max_branches < 2 || self.max_nodes < 2 * self.points_per_branch {
            return Err(LawError::Invalid {
                name: "caps",
                value: format!(
                    "max_branches {}, max_nodes {}",
                    self.max_branches, self.max_nodes
                ),
                allowed: "max_branches >= 2 and max_nodes >= 2 points_per_branch",
            });
        }
        Ok(())
    }
}

// ------------------------------------------------------------------------------------

/// The source with error context, finiteness checks and an evaluation counter.
struct Src<'a, S: ?Sized> {
    s: &'a S,
    evals: usize,
}

impl<S: LawSource + ?Sized> Src<'_, S> {
    fn p(&mut self, d: f64, d_min: f64, branch: Branch) -> Result<f64, LawError> {
        self.evals += 1;
        let ctx = || {
            format!(
                "pressure(d = {} m, d_min = {} m, {})",
                fmt_num(d),
                fmt_num(d_min),
                branch_name(branch)
            )
        };
        let v = self
            .s
            .pressure(d, d_min, branch)
            .map_err(|e| LawError::Source {
                context: ctx(),
                source: Box::new(e),
            })?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(LawError::BadSource(format!(
                "{} returned {}",
                ctx(),
                fmt_num(v)
            )))
        }
    }

    fn reach(&mut self, d_min: f64, branch: Branch) -> Result<f64, LawError> {
        let ctx = || {
            format!(
                "reach(d_min = {} m, {})",
                fmt_num(d_min),
                branch_name(branch)
            )
        };
        let r = self.s.reach(d_min, branch).map_err(|e| LawError::Source {
            context: ctx(),
            source: Box::new(e),
        })?;
        if r.is_finite() && (branch == Branch::Virgin || r > d_min) {
            Ok(r)
        } else {
            Err(LawError::BadSource(format!(
                "{} returned {}: a reach must be finite and above d_min",
                ctx(),
                fmt_num(r)
            )))
        }
    }

    fn pull_out(&mut self, d_min: f64) -> Result<Point, LawError> {
        let ctx = || format!("pull_out(d_min = {} m)", fmt_num(d_min));
        let (d, p) = self.s.pull_out(d_min).map_err(|e| LawError::Source {
            context: ctx(),
            source: Box::new(e),
        })?;
        if d.is_finite() && p.is_finite() && d >= d_min {
            Ok(Point { d, pressure: p })
        } else {
            Err(LawError::BadSource(format!(
                "{} returned ({}, {}): must be finite with d >= d_min",
                ctx(),
                fmt_num(d),
                fmt_num(p)
            )))
        }
    }
}

fn branch_name(b: Branch) -> &'static str {
    match b {
        Branch::Virgin => "virgin",
        Branch::Approach => "approach",
        Branch::Retract => "retract",
    }
}

/// A curve being sampled: nodes in x, values, and the source's value at the midpoint of
/// each interval once computed.
#[derive(Debug, Clone)]
struct Sampled {
    x: Vec<f64>,
    p: Vec<f64>,
    mid: Vec<Option<f64>>,
}

/// Refinement controls shared by all curves.
#[derive(Clone, Copy)]
struct Refine {
    tol: f64,
    h_min: f64,
    max_nodes: usize,
}

impl Sampled {
    fn new(mut nodes: Vec<(f64, f64)>) -> Sampled {
        nodes.sort_by(|a, b| a.0.total_cmp(&b.0));
        nodes.dedup_by(|b, a| b.0 == a.0);
        let n = nodes.len();
        Sampled {
            x: nodes.iter().map(|v| v.0).collect(),
            p: nodes.iter().map(|v| v.1).collect(),
            mid: vec![None; n.saturating_sub(1)],
        }
    }

    fn interp(&self) -> Result<Steffen, LawError> {
        Steffen::new(&self.x, &self.p)
    }

    /// Inserts a node (replacing one at the same abscissa).
    fn insert(&mut self, x: f64, p: f64) {
        let i = self.x.partition_point(|&v| v < x);
        if i < self.x.len() && self.x[i] == x {
            self.p[i] = p;
            if i > 0 {
                self.mid[i - 1] = None;
            }
            if i < self.mid.len() {
                self.mid[i] = None;
            }
            return;
        }
        self.x.insert(i, x);
        self.p.insert(i, p);
        // the interval i-1 (if any) is split in two: both halves need new midpoints
        if i == 0 {
            self.mid.insert(0, None);
        } else {
            self.mid[i - 1] = None;
            self.mid.insert(i, None);
        }
    }

    /// Bisects intervals until every midpoint meets the tolerance; returns false if a cap
    /// stopped it first.
    #[allow(clippy::needless_range_loop)] // x, p, mid and split are indexed together
    fn refine(
        &mut self,
        f: &mut dyn FnMut(f64) -> Result<f64, LawError>,
        floor: &dyn Fn(f64) -> f64,
        r: Refine,
    ) -> Result<bool, LawError> {
        let mut converged = true;
        loop {
            let st = self.interp()?;
            let n = self.x.len();
            let mut split = vec![false; n - 1];
            let mut count = 0;
            for i in 0..n - 1 {
                let h = self.x[i + 1] - self.x[i];
                let m = self.x[i] + 0.5 * h;
                let pm = match self.mid[i] {
                    Some(v) => v,
                    None => {
                        let v = f(m)?;
                        self.mid[i] = Some(v);
                        v
                    }
                };
                let e = (st.value_and_slope(m).0 - pm).abs();
                if e > r.tol * (pm.abs() + floor(m)) {
                    if h > r.h_min {
                        split[i] = true;
                        count += 1;
                    } else {
                        converged = false;
                    }
                }
            }
            if count == 0 {
                return Ok(converged);
            }
            if n + count > r.max_nodes {
                return Ok(false);
            }
            let mut x = Vec::with_capacity(n + count);
            let mut p = Vec::with_capacity(n + count);
            let mut mid = Vec::with_capacity(n + count - 1);
            for i in 0..n {
                x.push(self.x[i]);
                p.push(self.p[i]);
                if i + 1 < n {
                    if split[i] {
                        x.push(self.x[i] + 0.5 * (self.x[i + 1] - self.x[i]));
                        p.push(self.mid[i].unwrap_or(0.0));
                        mid.push(None);
                        mid.push(None);
                    } else {
                        mid.push(self.mid[i]);
                    }
                }
            }
            self.x = x;
            self.p = p;
            self.mid = mid;
        }
    }

    /// Index of the most tensile node.
    fn argmin(&self) -> usize {
        let mut k = 0;
        for i in 1..self.p.len() {
            if self.p[i] < self.p[k] {
                k = i;
            }
        }
        k
    }

    /// Locates the most tensile point by golden section between the neighbours of the most
    /// tensile node, adds it as a node and refines again. Returns (x, p).
    fn settle_min(
        &mut self,
        f: &mut dyn FnMut(f64) -> Result<f64, LawError>,
        floor: &dyn Fn(f64) -> f64,
        r: Refine,
    ) -> Result<(Point, bool), LawError> {
        let k = self.argmin();
        let n = self.x.len();
        let (mut a, mut b) = (self.x[k.saturating_sub(1)], self.x[(k + 1).min(n - 1)]);
        let mut best = (self.x[k], self.p[k]);
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let mut c = b - g * (b - a);
        let mut d = a + g * (b - a);
        let mut fc = f(c)?;
        let mut fd = f(d)?;
        let tol = 1e-9 * (self.x[n - 1] - self.x[0]);
        for _ in 0..200 {
            if b - a <= tol {
                break;
            }
            if fc < fd {
                b = d;
                d = c;
                fd = fc;
                c = b - g * (b - a);
                fc = f(c)?;
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + g * (b - a);
                fd = f(d)?;
            }
        }
        for (x, p) in [(c, fc), (d, fd)] {
            if p < best.1 {
                best = (x, p);
            }
        }
        let mut converged = true;
        if best.0 != self.x[k] {
            self.insert(best.0, best.1);
            converged = self.refine(f, floor, r)?;
            // the refinement may have sampled a point more tensile still: the most
            // tensile point is always the most tensile node (what a reader checks)
            let k = self.argmin();
            if self.p[k] < best.1 {
                best = (self.x[k], self.p[k]);
            }
        }
        Ok((
            Point {
                d: best.0,
                pressure: best.1,
            },
            converged,
        ))
    }
}

/// Start grid in x on [0, len]: uniform with `n` intervals plus geometric from
/// 1e-4 min(scale, len) up to the uniform spacing (ratio 1.6).
fn start_grid(len: f64, scale: f64, n: usize) -> Vec<f64> {
    let mut v: Vec<f64> = (0..=n).map(|i| len * (i as f64 / n as f64)).collect();
    v[n] = len;
    let mut g = 1e-4 * scale.min(len);
    while g < len / n as f64 {
        v.push(g);
        g *= 1.6;
    }
    v.sort_by(f64::total_cmp);
    v.dedup_by(|b, a| (*b - *a).abs() <= 1e-9 * len);
    v
}

/// One tabulated d_min while building.
struct Built {
    d_min: f64,
    pull_out: Point,
    approach: Sampled,
    approach_min: Point,
    retract: Sampled,
}

impl Built {
    fn curve(&self, path: Path) -> &Sampled {
        match path {
            Path::Approach => &self.approach,
            Path::Retract => &self.retract,
        }
    }
}

/// Samples both branches of `d_min`; `p_start` is the virgin envelope at d_min, the
/// common start of both.
fn build_branch<S: LawSource + ?Sized>(
    src: &mut Src<'_, S>,
    d_min: f64,
    p_start: f64,
    scale: f64,
    o: &Tabulation,
    r: Refine,
    converged: &mut bool,
) -> Result<Built, LawError> {
    let mut pull_out = src.pull_out(d_min)?;
    let floor_v = pull_out.pressure.abs();
    let floor = move |_x: f64| floor_v;
    let mut curves = Vec::new();
    let mut approach_min = Point {
        d: d_min,
        pressure: p_start,
    };
    for path in [Path::Approach, Path::Retract] {
        let branch = Branch::from(path);
        let len = src.reach(d_min, branch)? - d_min;
        if path == Path::Retract && pull_out.d - d_min > len {
            return Err(LawError::BadSource(format!(
                "pull-out at d = {} m lies beyond the retract reach {} m (d_min = {} m)",
                fmt_num(pull_out.d),
                fmt_num(d_min + len),
                fmt_num(d_min)
            )));
        }
        let r = Refine {
            h_min: r.h_min.max(1e-12 * len),
            ..r
        };
        let mut nodes = Vec::new();
        for x in start_grid(len, scale, o.points_per_branch) {
            let p = if x == 0.0 {
                p_start
            } else {
                src.p(d_min + x, d_min, branch)?
            };
            nodes.push((x, p));
        }
        let mut s = Sampled::new(nodes);
        if path == Path::Retract {
            // the pull-out becomes a node; its d is then the node's d as the curve writes
            // it, d_min + x (the source's d can differ from it by rounding, and lie an ulp
            // beyond the written reach: a special point is checked against its curve in
            // the curve's own coordinates)
            let x = pull_out.d - d_min;
            s.insert(x, pull_out.pressure);
            pull_out.d = d_min + x;
        }
        let mut f = |x: f64| src.p(d_min + x, d_min, branch);
        *converged &= s.refine(&mut f, &floor, r)?;
        match path {
            Path::Approach => {
                let (m, c) = s.settle_min(&mut f, &floor, r)?;
                *converged &= c;
                approach_min = Point {
                    d: d_min + m.d,
                    pressure: m.pressure,
                };
            }
            Path::Retract => {
                // trust the source's pull-out unless a sample is more tensile
                if s.p[s.argmin()] < pull_out.pressure {
                    let (m, c) = s.settle_min(&mut f, &floor, r)?;
                    *converged &= c;
                    pull_out = Point {
                        d: d_min + m.d,
                        pressure: m.pressure,
                    };
                }
            }
        }
        curves.push(s);
    }
    let retract = curves.pop().unwrap_or_else(|| Sampled::new(vec![]));
    let approach = curves.pop().unwrap_or_else(|| Sampled::new(vec![]));
    Ok(Built {
        d_min,
        pull_out,
        approach,
        approach_min,
        retract,
    })
}

/// |p_pull_out| linear in d_min between the tabulated branches (constant outside).
fn floor_between(built: &[Built], d: f64) -> f64 {
    let n = built.len();
    if d <= built[0].d_min {
        return built[0].pull_out.pressure.abs();
    }
    if d >= built[n - 1].d_min {
        return built[n - 1].pull_out.pressure.abs();
    }
    let k = built.partition_point(|b| b.d_min <= d) - 1;
    let (a, b) = (&built[k], &built[k + 1]);
    let w = (d - a.d_min) / (b.d_min - a.d_min);
    (1.0 - w) * a.pull_out.pressure.abs() + w * b.pull_out.pressure.abs()
}

/// The union of two node sets, midpoints of its intervals if `mids`, thinned by a stride
/// to at most `cap` points.
fn union_points(a: &[f64], b: &[f64], mids: bool, cap: usize) -> Vec<f64> {
    let mut u: Vec<f64> = a.iter().chain(b).copied().collect();
    u.sort_by(f64::total_cmp);
    u.dedup();
    if mids {
        u = u.windows(2).map(|w| w[0] + 0.5 * (w[1] - w[0])).collect();
    }
    if u.len() > cap {
        let stride = u.len().div_ceil(cap);
        u = u.into_iter().step_by(stride).collect();
    }
    u
}

/// Error metric of the format.
fn rel(interp: f64, direct: f64, floor: f64) -> f64 {
    let e = (interp - direct).abs();
    if e == 0.0 {
        0.0
    } else {
        e / (direct.abs() + floor)
    }
}

/// Does the rule in d_min meet the tolerance at the mid d_min of `lo`, `up`? The
/// neighbours are taken from the source at the same x (not from their interpolants), so
/// that the check sees the error of the rule in d_min alone; the rule in d has its own
/// refinement. Check points: the union of the neighbours' nodes (at most 64 per branch)
/// and the pull-out at the mid d_min.
fn mid_check<S: LawSource + ?Sized>(
    src: &mut Src<'_, S>,
    lo: &Built,
    up: &Built,
    tol: f64,
) -> Result<bool, LawError> {
    let d_mid = lo.d_min + 0.5 * (up.d_min - lo.d_min);
    let po = src.pull_out(d_mid)?;
    let floor = po.pressure.abs();
    let pv = src.p(d_mid, f64::INFINITY, Branch::Virgin)?;
    for path in [Path::Approach, Path::Retract] {
        let (a, b) = (lo.curve(path), up.curve(path));
        let branch = Branch::from(path);
        let c = pv - 0.5 * (a.p[0] + b.p[0]);
        let fade = 0.5 * (fade_length(&a.x, &a.p) + fade_length(&b.x, &b.p));
        let mut xs = union_points(&a.x, &b.x, false, 64);
        if path == Path::Retract {
            xs.push(po.d - d_mid);
        }
        for x in xs {
            let direct = src.p(d_mid + x, d_mid, branch)?;
            let pa = if x <= a.x[a.x.len() - 1] {
                src.p(lo.d_min + x, lo.d_min, branch)?
            } else {
                0.0
            };
            let pb = if x <= b.x[b.x.len() - 1] {
                src.p(up.d_min + x, up.d_min, branch)?
            } else {
                0.0
            };
            let p = 0.5 * (pa + pb) + correction(c, fade, x).0;
            if rel(p, direct, floor) > tol {
                return Ok(false);
            }
        }
    }
    Ok(true)
}

/// A 64-bit linear congruential generator (Knuth's MMIX constants): fixed-seed points.
struct Lcg(u64);

impl Lcg {
    fn uniform(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Tabulates the law of `source` (see the module documentation for the method).
///
/// The returned law has an empty scene ([`ContactLaw::set_scene`] sets it) and records
/// the measured interpolation error and the number of source evaluations.
pub fn tabulate<S: LawSource + ?Sized>(source: &S, o: &Tabulation) -> Result<ContactLaw, LawError> {
    o.check()?;
    let scale = source.length_scale();
    if !(scale.is_finite() && scale > 0.0) {
        return Err(LawError::BadSource(format!(
            "length_scale = {}: must be finite and > 0 (m)",
            fmt_num(scale)
        )));
    }
    let mut src = Src {
        s: source,
        evals: 0,
    };
    let mut grid = match o.d_min {
        DminGrid::Adaptive { lo, hi } => (0..5)
            .map(|i| lo + (hi - lo) * (i as f64 / 4.0))
            .collect::<Vec<_>>(),
        DminGrid::Uniform(g) => g.nodes(),
    };
    if let DminGrid::Adaptive { hi, .. } = o.d_min {
        grid[4] = hi;
    }
    let (lo, hi) = (grid[0], grid[grid.len() - 1]);
    let top = src.reach(f64::INFINITY, Branch::Virgin)?;
    if top <= hi {
        return Err(LawError::BadSource(format!(
            "the virgin reach {} m is not above d_min_hi = {} m: tabulate histories below the first touch",
            fmt_num(top),
            fmt_num(hi)
        )));
    }
    let r = Refine {
        tol: o.tolerance,
        h_min: 1e-7 * scale,
        max_nodes: o.max_nodes,
    };
    let mut converged = true;

    // virgin envelope: start grid uniform on [lo, top] plus the d_min nodes
    let n = o.points_per_branch;
    let mut nodes = Vec::new();
    for i in 0..=n {
        let d = if i == n {
            top
        } else {
            lo + (top - lo) * (i as f64 / n as f64)
        };
        nodes.push((d, src.p(d, f64::INFINITY, Branch::Virgin)?));
    }
    for &d in &grid[1..] {
        nodes.push((d, src.p(d, f64::INFINITY, Branch::Virgin)?));
    }
    let mut virgin = Sampled::new(nodes);
    // error floor of the envelope: |pull-out| at the start d_min nodes, refined later
    let mut built: Vec<Built> = Vec::new();
    let p_at = |s: &Sampled, d: f64| -> f64 {
        let i = s.x.partition_point(|&v| v < d);
        s.p[i.min(s.x.len() - 1)]
    };
    for &d_min in &grid {
        let p_start = p_at(&virgin, d_min);
        built.push(build_branch(
            &mut src,
            d_min,
            p_start,
            scale,
            o,
            r,
            &mut converged,
        )?);
    }
    {
        let floor = |d: f64| floor_between(&built, d);
        let mut f = |d: f64| src.p(d, f64::INFINITY, Branch::Virgin);
        converged &= virgin.refine(&mut f, &floor, r)?;
    }

    // d_min refinement
    if let DminGrid::Adaptive { .. } = o.d_min {
        let h_min = 1e-6 * scale;
        let mut checked = vec![false; built.len() - 1];
        let mut k = 0;
        while k + 1 < built.len() {
            if checked[k] {
                k += 1;
                continue;
            }
            let ok = mid_check(&mut src, &built[k], &built[k + 1], o.tolerance)?;
            let width = built[k + 1].d_min - built[k].d_min;
            if ok {
                checked[k] = true;
                continue;
            }
            if width <= h_min || built.len() >= o.max_branches {
                converged = false;
                checked[k] = true;
                continue;
            }
            let d_mid = built[k].d_min + 0.5 * width;
            let p_start = src.p(d_mid, f64::INFINITY, Branch::Virgin)?;
            virgin.insert(d_mid, p_start);
            let b = build_branch(&mut src, d_mid, p_start, scale, o, r, &mut converged)?;
            built.insert(k + 1, b);
            checked.insert(k + 1, false);
        }
        // the envelope with every d_min node: refine again against the final floor
        let floor = |d: f64| floor_between(&built, d);
        let mut f = |d: f64| src.p(d, f64::INFINITY, Branch::Virgin);
        converged &= virgin.refine(&mut f, &floor, r)?;
    } else {
        // the user's grid is not refined, but the interpolation between its histories is
        // checked as the adaptive rule checks it: a miss is reported, not hidden
        for k in 0..built.len().saturating_sub(1) {
            if !mid_check(&mut src, &built[k], &built[k + 1], o.tolerance)? {
                converged = false;
                break;
            }
        }
    }
    let virgin_min = {
        let floor = |d: f64| floor_between(&built, d);
        let mut f = |d: f64| src.p(d, f64::INFINITY, Branch::Virgin);
        let (m, c) = virgin.settle_min(&mut f, &floor, r)?;
        converged &= c;
        m
    };

    // assemble exactly as a reader would
    let virgin_curve = Curve::new(
        virgin.x.clone(),
        virgin.p.clone(),
        virgin_min,
        0.0,
        "virgin",
        "virgin.most_tensile",
    )?;
    let mut sets = Vec::with_capacity(built.len());
    for (k, b) in built.iter().enumerate() {
        let to_d = |s: &Sampled| s.x.iter().map(|x| b.d_min + x).collect::<Vec<f64>>();
        let approach = Curve::new(
            to_d(&b.approach),
            b.approach.p.clone(),
            b.approach_min,
            b.d_min,
            &format!("branches[{k}].approach"),
            &format!("branches[{k}].approach.most_tensile"),
        )?;
        let retract = Curve::new(
            to_d(&b.retract),
            b.retract.p.clone(),
            b.pull_out,
            b.d_min,
            &format!("branches[{k}].retract"),
            &format!("branches[{k}].pull_out"),
        )?;
        sets.push(BranchSet {
            d_min: b.d_min,
            approach,
            retract,
        });
    }
    let mut law = ContactLaw::assemble(
        virgin_curve,
        sets,
        Meta {
            length_scale: Some(scale),
            ..Meta::default()
        },
    )?;

    let measured = measure(&mut src, &law, &built, &virgin, o, top)?;
    // an infinite (or undefined) measured error is not a converged table, whatever the
    // refinement said at its own check points
    converged &= measured.is_finite();
    law.meta.measured = Some(measured);
    law.meta.tabulation = Some(TabulationInfo {
        tolerance: o.tolerance,
        points_per_branch: o.points_per_branch,
        d_min_rule: match o.d_min {
            DminGrid::Adaptive { .. } => "adaptive".into(),
            DminGrid::Uniform(g) => format!("uniform {g}"),
        },
        source_evaluations: src.evals,
        converged,
    });
    Ok(law)
}

/// The interpolation error of `law` against the source, at points off every grid.
fn measure<S: LawSource + ?Sized>(
    src: &mut Src<'_, S>,
    law: &ContactLaw,
    built: &[Built],
    virgin: &Sampled,
    o: &Tabulation,
    top: f64,
) -> Result<MeasuredError, LawError> {
    let mut ev: Vec<(f64, f64, f64)> = Vec::new();
    let mut ea: Vec<(f64, f64, f64)> = Vec::new();
    let mut er: Vec<(f64, f64, f64)> = Vec::new();
    let (lo, hi) = law.d_min_range();
    let mut rng = Lcg(o.seed);

    // virgin: interval midpoints (cached source values) and random separations
    for i in 0..virgin.x.len() - 1 {
        let d = virgin.x[i] + 0.5 * (virgin.x[i + 1] - virgin.x[i]);
        let direct = match virgin.mid[i] {
            Some(v) => v,
            None => src.p(d, f64::INFINITY, Branch::Virgin)?,
        };
        let p = law.virgin_pressure(d)?.0;
        ev.push((rel(p, direct, floor_between(built, d)), d, d));
    }
    for _ in 0..o.random_points {
        let d = lo + (top - lo) * rng.uniform();
        let direct = src.p(d, f64::INFINITY, Branch::Virgin)?;
        let p = law.virgin_pressure(d)?.0;
        ev.push((rel(p, direct, floor_between(built, d)), d, d));
    }

    let sink = |path: Path, ea: &mut Vec<_>, er: &mut Vec<_>, v: (f64, f64, f64)| match path {
        Path::Approach => ea.push(v),
        Path::Retract => er.push(v),
    };
    // branch interval midpoints
    for b in built {
        let floor = b.pull_out.pressure.abs();
        for path in [Path::Approach, Path::Retract] {
            let s = b.curve(path);
            for i in 0..s.x.len() - 1 {
                let x = s.x[i] + 0.5 * (s.x[i + 1] - s.x[i]);
                let d = b.d_min + x;
                let direct = match s.mid[i] {
                    Some(v) => v,
                    None => src.p(d, b.d_min, Branch::from(path))?,
                };
                let p = law.branch_pressure(d, b.d_min, path)?.0;
                sink(path, &mut ea, &mut er, (rel(p, direct, floor), d, b.d_min));
            }
        }
    }
    // mid d_min of neighbouring branches
    for w in built.windows(2) {
        let d_min = w[0].d_min + 0.5 * (w[1].d_min - w[0].d_min);
        let floor = src.pull_out(d_min)?.pressure.abs();
        for path in [Path::Approach, Path::Retract] {
            for x in union_points(&w[0].curve(path).x, &w[1].curve(path).x, true, 64) {
                let d = d_min + x;
                let direct = src.p(d, d_min, Branch::from(path))?;
                let p = law.branch_pressure(d, d_min, path)?.0;
                sink(path, &mut ea, &mut er, (rel(p, direct, floor), d, d_min));
            }
        }
    }
    // pseudo-random (d_min, d), x concentrated near 0 where the branches are steepest
    let per = 8;
    for _ in 0..o.random_points.div_ceil(per) {
        let d_min = lo + (hi - lo) * rng.uniform();
        let floor = src.pull_out(d_min)?.pressure.abs();
        for path in [Path::Approach, Path::Retract] {
            let len = src.reach(d_min, Branch::from(path))? - d_min;
            for _ in 0..per {
                let u = rng.uniform();
                let d = d_min + len * u * u;
                let direct = src.p(d, d_min, Branch::from(path))?;
                let p = law.branch_pressure(d, d_min, path)?.0;
                sink(path, &mut ea, &mut er, (rel(p, direct, floor), d, d_min));
            }
        }
    }
    let stats = |v: &[(f64, f64, f64)], what: &str| {
        ErrorStats::from_samples(v)
            .ok_or_else(|| LawError::BadSource(format!("no {what} check points")))
    };
    Ok(MeasuredError {
        virgin: stats(&ev, "virgin")?,
        approach: stats(&ea, "approach")?,
        retract: stats(&er, "retract")?,
        seed: o.seed,
    })
}

/// Measures the error of the one-number history after a partial reload: for every
/// tabulated d_min and each fraction f in `turn_fractions` (each in (0, 1)), a reload
/// turning at d_turn = d_min + f (approach reach - d_min), then `points` separations from
/// d_turn to the retract reach (denser near d_turn); the law's retract branch of d_min
/// against [`ReloadSource::retract_after_reload`]. Record the result in the file with
/// [`ContactLaw::set_partial_reload`].
pub fn measure_partial_reload<S: ReloadSource + ?Sized>(
    law: &ContactLaw,
    source: &S,
    turn_fractions: &[f64],
    points: usize,
) -> Result<PartialReloadError, LawError> {
    if turn_fractions.is_empty() || turn_fractions.iter().any(|f| !(*f > 0.0 && *f < 1.0)) {
        return Err(LawError::Invalid {
            name: "turn_fractions",
            value: format!("{turn_fractions:?}"),
            allowed: "a non-empty list of numbers in (0, 1)",
        });
    }
    if !(2..=100_000).contains(&points) {
        return Err(LawError::invalid(
            "points",
            points as f64,
            "between 2 and 100000",
        ));
    }
    let mut samples = Vec::new();
    for b in law.branches() {
        let d_min = b.d_min();
        let floor = b.pull_out().pressure.abs();
        let reach_a = b.approach().reach();
        let reach_r = b.retract().reach();
        for &f in turn_fractions {
            let d_turn = d_min + f * (reach_a - d_min);
            let end = reach_r.max(d_turn);
            for j in 0..points {
                let u = j as f64 / (points - 1) as f64;
                let d = d_turn + (end - d_turn) * u * u;
                let truth = source.retract_after_reload(d, d_min, d_turn).map_err(|e| {
                    LawError::Source {
                        context: format!(
                            "retract_after_reload(d = {} m, d_min = {} m, d_turn = {} m)",
                            fmt_num(d),
                            fmt_num(d_min),
                            fmt_num(d_turn)
                        ),
                        source: Box::new(e),
                    }
                })?;
                if !truth.is_finite() {
                    return Err(LawError::BadSource(format!(
                        "retract_after_reload returned {} at d = {} m",
                        fmt_num(truth),
                        fmt_num(d)
                    )));
                }
                let p = law.branch_pressure(d, d_min, Path::Retract)?.0;
                samples.push((rel(p, truth, floor), d, d_min, d_turn));
            }
        }
    }
    let triples: Vec<(f64, f64, f64)> = samples.iter().map(|s| (s.0, s.1, s.2)).collect();
    let stats = ErrorStats::from_samples(&triples)
        .ok_or_else(|| LawError::BadSource("no partial-reload points".into()))?;
    let mut worst = 0;
    for (i, s) in samples.iter().enumerate() {
        if s.0 > samples[worst].0 {
            worst = i;
        }
    }
    let worst_d_turn = samples[worst].3;
    Ok(PartialReloadError {
        stats,
        worst_d_turn,
    })
}
