//! Tabulation of a law from a model ([`LawSource`]): adaptive grids in d and in d_min, and
//! the measurement of the interpolation error at points off every grid.
//!
//! The error metric is e = |p_table - p_direct| / (|p_direct| + |p_pull_out(d_min)| + floor),
//! the floor a fraction ([`DEFAULT_FLOOR_FRACTION`]) of the pressure scale of the deepest
//! history unless the options give it. The build, for a d_min range [lo, hi]:
//!
//! 1. each curve is sampled in x = d - d_min (in d for the virgin envelope) on a start grid
//!    that is geometric near x = 0 (from 1e-4 of the length scale, where a retract branch
//!    drops steeply) and uniform up to the curve's reach, plus the pull-out exactly; then an
//!    interval is bisected while the interpolant's value at its midpoint misses the source
//!    by more than a quarter of the tolerance (in e); the most tensile point of the approach
//!    branches and of the envelope is located by golden section and added as a node;
//! 2. the d_min grid (unless the user gives one) starts uniform with
//!    [`START_BRANCHES`] histories; the law is assembled as a reader would, and at the mid
//!    d_min of every pair of neighbouring branches it is compared with the source at the
//!    union of the pair's nodes and its midpoints (at most 96 per path) and at the mid
//!    pull-out; an interval is bisected while the law misses by more than half the
//!    tolerance there, and the source's values at the mid d_min become the start nodes
//!    of the new branch, so that no evaluation is wasted; after every insertion the
//!    intervals whose rule changed are judged again on their cached points;
//! 3. the error is measured on the final law: the curves' interval midpoints, the d_min
//!    checks, and held-out pseudo-random points; where a held-out point misses the
//!    tolerance its interval of histories is bisected (or the envelope refined) and a new
//!    batch is drawn, at most [`REPAIR_ROUNDS`] times. The file states the last batch's
//!    errors with the others, per kind and per branch; `converged` is true only when every
//!    recorded error is within the tolerance.
//!
//! Branches and checks run in parallel on `threads` threads (the source is `Sync`); the
//! result is the same to the bit on any number of threads.

use crate::error::{fmt_num, LawError};
use crate::law::{BranchError, BranchSet, ContactLaw, Curve, Meta, Path, Point};
use crate::meta::{ErrorStats, MeasuredError, PartialReloadError, TabulationInfo};
use crate::steffen::Steffen;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// The pressure floor of the error metric, unless the options give one: this fraction of
/// the pressure scale of the deepest history (the larger of |p_V(d_min_lo)| and its
/// |p_pull_out|). An error of the tolerance times the floor is 2e-9 of the largest pressure
/// the law carries at the default tolerance: far below anything an FE model resolves, but
/// a floor, so that pressures that are numerically zero (a law without adhesion beyond its
/// reach, the Gaussian tail of a shallow history) are not chased relative to themselves.
pub const DEFAULT_FLOOR_FRACTION: f64 = 1e-5;

/// Histories of the adaptive grid before refinement (uniform on [lo, hi]).
pub const START_BRANCHES: usize = 9;

/// Rounds of repair after a held-out batch found a point above the tolerance.
pub const REPAIR_ROUNDS: usize = 3;

/// Check points per path at a mid d_min (thinned from the union of the pair's nodes).
const CHECK_POINTS: usize = 96;

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
    /// Tolerance on e = |p_interp - p_direct| / (|p_direct| + |p_pull_out| + floor): the
    /// largest error the table may have at any point the tabulator measures.
    pub tolerance: f64,
    /// The pressure floor (Pa) of the error metric; `None`: [`DEFAULT_FLOOR_FRACTION`] of
    /// the pressure scale of the deepest history.
    pub pressure_floor: Option<f64>,
    /// Pseudo-random check points per branch kind for the measured error.
    pub random_points: usize,
    /// Seed of the pseudo-random points.
    pub seed: u64,
    /// Cap on the number of branches (adaptive d_min grid).
    pub max_branches: usize,
    /// Cap on the nodes of one curve.
    pub max_nodes: usize,
    /// Threads for the branches and checks; 0: the machine's available parallelism.
    pub threads: usize,
}

impl Tabulation {
    /// Defaults with an adaptive d_min grid on [lo, hi] (m): 48 start points per branch,
    /// tolerance 2e-4, the default pressure floor, 256 random points per kind, seed 2026,
    /// at most 400 branches and 20000 nodes per curve, all available threads.
    pub fn adaptive(lo: f64, hi: f64) -> Tabulation {
        Tabulation {
            d_min: DminGrid::Adaptive { lo, hi },
            points_per_branch: 48,
            tolerance: 2e-4,
            pressure_floor: None,
            random_points: 256,
            seed: 2026,
            max_branches: 400,
            max_nodes: 20_000,
            threads: 0,
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
        if let Some(f) = self.pressure_floor {
            if !(f.is_finite() && f > 0.0) {
                return Err(LawError::invalid(
                    "pressure_floor",
                    f,
                    "finite and > 0 (Pa)",
                ));
            }
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

/// The source with error context, finiteness checks and an evaluation counter (shared by
/// the threads).
struct Src<'a, S: ?Sized> {
    s: &'a S,
    evals: AtomicUsize,
}

impl<S: LawSource + ?Sized> Src<'_, S> {
    fn p(&self, d: f64, d_min: f64, branch: Branch) -> Result<f64, LawError> {
        self.evals.fetch_add(1, Ordering::Relaxed);
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

    fn reach(&self, d_min: f64, branch: Branch) -> Result<f64, LawError> {
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

    fn pull_out(&self, d_min: f64) -> Result<Point, LawError> {
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

/// The number of threads of `o`.
fn threads_of(o: &Tabulation) -> usize {
    if o.threads > 0 {
        o.threads
    } else {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    }
}

/// `f` over `items` on up to `threads` scoped threads, results in the order of the items
/// (so that the result does not depend on the number of threads).
fn par_map<T: Sync, R: Send>(items: &[T], threads: usize, f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let n = items.len();
    let threads = threads.min(n);
    if threads <= 1 {
        return items.iter().map(f).collect();
    }
    let next = AtomicUsize::new(0);
    let slots: Vec<Mutex<Option<R>>> = (0..n).map(|_| Mutex::new(None)).collect();
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= n {
                    break;
                }
                let r = f(&items[i]);
                if let Ok(mut slot) = slots[i].lock() {
                    *slot = Some(r);
                }
            });
        }
    });
    slots
        .into_iter()
        .map(|m| {
            m.into_inner()
                .ok()
                .flatten()
                .unwrap_or_else(|| unreachable!("every item is computed by a scoped thread"))
        })
        .collect()
}

/// A curve being sampled: nodes in x, values, and the source's value at the midpoint of
/// each interval once computed.
#[derive(Debug, Clone)]
struct Sampled {
    /// d = origin + x (d_min for a branch, 0 for the envelope).
    origin: f64,
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
    /// Nodes in x = d - origin; two nodes whose d = origin + x round to the same number
    /// are one (the first kept).
    fn new(origin: f64, mut nodes: Vec<(f64, f64)>) -> Sampled {
        nodes.sort_by(|a, b| a.0.total_cmp(&b.0));
        nodes.dedup_by(|b, a| origin + b.0 == origin + a.0);
        let n = nodes.len();
        Sampled {
            origin,
            x: nodes.iter().map(|v| v.0).collect(),
            p: nodes.iter().map(|v| v.1).collect(),
            mid: vec![None; n.saturating_sub(1)],
        }
    }

    fn interp(&self) -> Result<Steffen, LawError> {
        Steffen::new(&self.x, &self.p)
    }

    /// Inserts a node (replacing one at the same d = origin + x, which keeps its x).
    fn insert(&mut self, x: f64, p: f64) {
        let mut i = self.x.partition_point(|&v| v < x);
        let d = self.origin + x;
        if i > 0 && self.origin + self.x[i - 1] == d {
            i -= 1;
        }
        if i < self.x.len() && self.origin + self.x[i] == d {
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
    /// Both curves met the tolerance before a cap.
    converged: bool,
}

impl Built {
    fn curve(&self, path: Path) -> &Sampled {
        match path {
            Path::Approach => &self.approach,
            Path::Retract => &self.retract,
        }
    }

    fn curve_mut(&mut self, path: Path) -> &mut Sampled {
        match path {
            Path::Approach => &mut self.approach,
            Path::Retract => &mut self.retract,
        }
    }
}

/// What a failing check at a mid d_min already knows about the branch there.
struct Seed<'a> {
    pull_out: Point,
    samples: &'a [Vec<(f64, f64)>; 2],
}

/// Refinement controls of everything: the metric's floor and the curves' tolerance.
#[derive(Clone, Copy)]
struct Setup {
    /// Pressure floor of the metric (Pa).
    floor: f64,
    /// Length scale (m).
    scale: f64,
    /// Refinement of the curves in x.
    r: Refine,
}

/// Samples both branches of `d_min`; `p_start` is the virgin envelope at d_min, the
/// common start of both. With a `seed`, its samples are start nodes (beside the geometric
/// ones near x = 0) and its pull-out is the branch's.
fn build_branch<S: LawSource + ?Sized>(
    src: &Src<'_, S>,
    d_min: f64,
    p_start: f64,
    seed: Option<Seed<'_>>,
    o: &Tabulation,
    st: Setup,
) -> Result<Built, LawError> {
    let mut pull_out = match &seed {
        Some(s) => s.pull_out,
        None => src.pull_out(d_min)?,
    };
    let floor_v = pull_out.pressure.abs() + st.floor;
    let floor = move |_x: f64| floor_v;
    let mut curves = Vec::new();
    let mut converged = true;
    let mut approach_min = Point {
        d: d_min,
        pressure: p_start,
    };
    for (ip, path) in [Path::Approach, Path::Retract].into_iter().enumerate() {
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
            h_min: st.r.h_min.max(1e-12 * len),
            ..st.r
        };
        let mut nodes = vec![(0.0, p_start)];
        match &seed {
            None => {
                for x in start_grid(len, st.scale, o.points_per_branch) {
                    if x > 0.0 {
                        nodes.push((x, src.p(d_min + x, d_min, branch)?));
                    }
                }
            }
            Some(s) => {
                let known = &s.samples[ip];
                let first = known
                    .iter()
                    .map(|v| v.0)
                    .find(|&x| x > 0.0 && x < len)
                    .unwrap_or(len);
                let mut g = 1e-4 * st.scale.min(len);
                while g < 0.6 * first {
                    nodes.push((g, src.p(d_min + g, d_min, branch)?));
                    g *= 1.6;
                }
                nodes.extend(known.iter().copied().filter(|v| v.0 > 0.0 && v.0 < len));
                nodes.push((len, src.p(d_min + len, d_min, branch)?));
                // nodes closer than the start grid's own resolution are dropped (d_min + x
                // of two of them could round to the same d)
                nodes.sort_by(|a, b| a.0.total_cmp(&b.0));
                let gap = 1e-9 * len;
                let mut kept: Vec<(f64, f64)> = Vec::with_capacity(nodes.len());
                for v in nodes.drain(..) {
                    match kept.last() {
                        Some(last) if v.0 - last.0 <= gap && v.0 != len => {}
                        Some(last) if v.0 - last.0 <= gap => {
                            kept.pop();
                            kept.push(v);
                        }
                        _ => kept.push(v),
                    }
                }
                nodes = kept;
            }
        }
        let mut s = Sampled::new(d_min, nodes);
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
        converged &= s.refine(&mut f, &floor, r)?;
        match path {
            Path::Approach => {
                let (m, c) = s.settle_min(&mut f, &floor, r)?;
                converged &= c;
                approach_min = Point {
                    d: d_min + m.d,
                    pressure: m.pressure,
                };
            }
            Path::Retract => {
                // trust the source's pull-out unless a sample is more tensile
                if s.p[s.argmin()] < pull_out.pressure {
                    let (m, c) = s.settle_min(&mut f, &floor, r)?;
                    converged &= c;
                    pull_out = Point {
                        d: d_min + m.d,
                        pressure: m.pressure,
                    };
                }
            }
        }
        curves.push(s);
    }
    let retract = curves.pop().unwrap_or_else(|| Sampled::new(d_min, vec![]));
    let approach = curves.pop().unwrap_or_else(|| Sampled::new(d_min, vec![]));
    Ok(Built {
        d_min,
        pull_out,
        approach,
        approach_min,
        retract,
        converged,
    })
}

/// |p_pull_out| linear in d_min between the tabulated branches (constant outside), plus
/// the pressure floor: the denominator's floor of the envelope's error at d.
fn floor_between(built: &[Built], floor: f64, d: f64) -> f64 {
    let n = built.len();
    let po = if d <= built[0].d_min {
        built[0].pull_out.pressure.abs()
    } else if d >= built[n - 1].d_min {
        built[n - 1].pull_out.pressure.abs()
    } else {
        let k = built.partition_point(|b| b.d_min <= d) - 1;
        let (a, b) = (&built[k], &built[k + 1]);
        let w = (d - a.d_min) / (b.d_min - a.d_min);
        (1.0 - w) * a.pull_out.pressure.abs() + w * b.pull_out.pressure.abs()
    };
    po + floor
}

/// The union of two node sets and the midpoints of its intervals, inside (0, end], thinned
/// by a stride to at most `cap` points.
fn check_points(a: &[f64], b: &[f64], end: f64, cap: usize) -> Vec<f64> {
    let mut u: Vec<f64> = a.iter().chain(b).copied().collect();
    u.sort_by(f64::total_cmp);
    u.dedup();
    let mids: Vec<f64> = u.windows(2).map(|w| w[0] + 0.5 * (w[1] - w[0])).collect();
    u.extend(mids);
    u.sort_by(f64::total_cmp);
    u.retain(|&x| x > 0.0 && x <= end);
    if u.len() > cap {
        let stride = u.len().div_ceil(cap);
        u = u.into_iter().step_by(stride).collect();
    }
    u
}

/// Error metric of the format; `floor` is |p_pull_out(d_min)| plus the pressure floor.
fn rel(interp: f64, direct: f64, floor: f64) -> f64 {
    let e = (interp - direct).abs();
    if e == 0.0 {
        0.0
    } else {
        e / (direct.abs() + floor)
    }
}

/// The source at the mid d_min of two neighbouring branches: its pull-out and the
/// pressures at the check points of both paths. Judged against the law of the moment by
/// [`Check::error`]; the start nodes of the branch there if the interval is bisected.
struct Check {
    d_min: f64,
    pull_out: Point,
    /// |p_pull_out(d_min)| plus the pressure floor.
    floor: f64,
    /// (x, p) of the approach and of the retract branch.
    samples: [Vec<(f64, f64)>; 2],
}

impl Check {
    fn new<S: LawSource + ?Sized>(
        src: &Src<'_, S>,
        lo: &Built,
        up: &Built,
        floor: f64,
    ) -> Result<Check, LawError> {
        let d_mid = lo.d_min + 0.5 * (up.d_min - lo.d_min);
        let pull_out = src.pull_out(d_mid)?;
        let mut samples = [Vec::new(), Vec::new()];
        for (ip, path) in [Path::Approach, Path::Retract].into_iter().enumerate() {
            let (a, b) = (lo.curve(path), up.curve(path));
            let end = a.x[a.x.len() - 1].max(b.x[b.x.len() - 1]);
            let mut xs = check_points(&a.x, &b.x, end, CHECK_POINTS);
            if path == Path::Retract {
                let x = pull_out.d - d_mid;
                if x > 0.0 && !xs.contains(&x) {
                    xs.push(x);
                }
            }
            for x in xs {
                samples[ip].push((x, src.p(d_mid + x, d_mid, Branch::from(path))?));
            }
            samples[ip].sort_by(|a, b| a.0.total_cmp(&b.0));
        }
        Ok(Check {
            d_min: d_mid,
            pull_out,
            floor: pull_out.pressure.abs() + floor,
            samples,
        })
    }

    /// Every (e, d, path) of the check against `law`.
    fn errors(&self, law: &ContactLaw) -> Result<Vec<(f64, f64, Path)>, LawError> {
        let mut out = Vec::new();
        for (ip, path) in [Path::Approach, Path::Retract].into_iter().enumerate() {
            for &(x, direct) in &self.samples[ip] {
                let d = self.d_min + x;
                let p = law.branch_pressure(d, self.d_min, path)?.0;
                out.push((rel(p, direct, self.floor), d, path));
            }
        }
        Ok(out)
    }

    fn max_error(&self, law: &ContactLaw) -> Result<f64, LawError> {
        Ok(self.errors(law)?.into_iter().fold(0.0, |m: f64, e| {
            if e.0.is_nan() {
                f64::NAN
            } else {
                m.max(e.0)
            }
        }))
    }
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

/// One measured point: error, separation, history, kind (None: the virgin envelope).
#[derive(Clone, Copy)]
struct Sample {
    e: f64,
    d: f64,
    d_min: f64,
    path: Option<Path>,
}

/// The table while it is built.
struct Table {
    built: Vec<Built>,
    virgin: Sampled,
    /// Per interval of histories, the check at its mid d_min (None: not yet made).
    checks: Vec<Option<Check>>,
    /// Intervals that miss the tolerance and cannot be bisected (cap, minimum width).
    stuck: Vec<bool>,
    top: f64,
    st: Setup,
    meta_scale: f64,
}

impl Table {
    /// The law of the table as a reader would assemble it (the envelope's most tensile
    /// point: `virgin_min`, or its most tensile node).
    fn law(&self, virgin_min: Option<Point>) -> Result<ContactLaw, LawError> {
        let v = &self.virgin;
        let vm = virgin_min.unwrap_or_else(|| {
            let k = v.argmin();
            Point {
                d: v.x[k],
                pressure: v.p[k],
            }
        });
        let virgin_curve = Curve::new(
            v.x.clone(),
            v.p.clone(),
            vm,
            0.0,
            "virgin",
            "virgin.most_tensile",
        )?;
        let mut sets = Vec::with_capacity(self.built.len());
        for (k, b) in self.built.iter().enumerate() {
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
            sets.push(BranchSet::new(b.d_min, approach, retract));
        }
        ContactLaw::assemble(
            virgin_curve,
            sets,
            self.st.floor,
            Meta {
                length_scale: Some(self.meta_scale),
                ..Meta::default()
            },
        )
    }

    fn refine_virgin<S: LawSource + ?Sized>(&mut self, src: &Src<'_, S>) -> Result<bool, LawError> {
        let built = &self.built;
        let fl = self.st.floor;
        let floor = |d: f64| floor_between(built, fl, d);
        let mut f = |d: f64| src.p(d, f64::INFINITY, Branch::Virgin);
        self.virgin.refine(&mut f, &floor, self.st.r)
    }

    /// Makes the missing checks, judges every interval against the current law, bisects
    /// those above `tol` (adaptive grids only), until none is left to bisect. Returns
    /// whether the envelope met its tolerance.
    fn refine_histories<S: LawSource + Sync + ?Sized>(
        &mut self,
        src: &Src<'_, S>,
        o: &Tabulation,
        tol: f64,
        mut force: Vec<usize>,
        progress: &(dyn Fn(f64) + Sync),
        span: (f64, f64),
    ) -> Result<bool, LawError> {
        let threads = threads_of(o);
        let adaptive = matches!(o.d_min, DminGrid::Adaptive { .. });
        let h_min = 1e-6 * self.st.scale;
        let mut virgin_ok = true;
        let mut round = 0;
        loop {
            round += 1;
            progress(span.0 + (span.1 - span.0) * (1.0 - 1.0 / (round as f64 + 1.0)));
            let todo: Vec<usize> = (0..self.checks.len())
                .filter(|&k| self.checks[k].is_none())
                .collect();
            let made = {
                let built = &self.built;
                let floor = self.st.floor;
                par_map(&todo, threads, |&k| {
                    Check::new(src, &built[k], &built[k + 1], floor)
                })
            };
            for (k, c) in todo.into_iter().zip(made) {
                self.checks[k] = Some(c?);
            }
            let law = self.law(None)?;
            let mut split: Vec<usize> = Vec::new();
            for k in 0..self.checks.len() {
                let Some(c) = &self.checks[k] else { continue };
                let forced = force.contains(&k);
                let e = c.max_error(&law)?;
                if !(e <= tol) || forced {
                    let width = self.built[k + 1].d_min - self.built[k].d_min;
                    if adaptive && width > h_min && self.built.len() + split.len() < o.max_branches
                    {
                        split.push(k);
                    } else if !(e <= tol) {
                        self.stuck[k] = true;
                    }
                } else {
                    self.stuck[k] = false;
                }
            }
            force.clear();
            if split.is_empty() {
                return Ok(virgin_ok);
            }
            // the new branches, from what their checks know
            let made = {
                let built = &self.built;
                let checks = &self.checks;
                let st = self.st;
                par_map(&split, threads, |&k| -> Result<(f64, Built), LawError> {
                    let c = checks[k]
                        .as_ref()
                        .unwrap_or_else(|| unreachable!("a bisected interval was checked"));
                    let _ = built;
                    let p_start = src.p(c.d_min, f64::INFINITY, Branch::Virgin)?;
                    let b = build_branch(
                        src,
                        c.d_min,
                        p_start,
                        Some(Seed {
                            pull_out: c.pull_out,
                            samples: &c.samples,
                        }),
                        o,
                        st,
                    )?;
                    Ok((p_start, b))
                })
            };
            let mut made: Vec<(f64, Built)> = made.into_iter().collect::<Result<_, _>>()?;
            // insert from the deepest index down so that earlier indices stay valid
            for (&k, (p_start, b)) in split.iter().zip(made.drain(..)).rev() {
                self.virgin.insert(b.d_min, p_start);
                self.built.insert(k + 1, b);
                self.checks[k] = None;
                self.checks.insert(k + 1, None);
                self.stuck[k] = false;
                self.stuck.insert(k + 1, false);
            }
            virgin_ok &= self.refine_virgin(src)?;
        }
    }
}

/// Tabulates the law of `source` (see the module documentation for the method).
///
/// The returned law has an empty scene ([`ContactLaw::set_scene`] sets it) and records
/// the measured interpolation error and the number of source evaluations.
pub fn tabulate<S: LawSource + Sync + ?Sized>(
    source: &S,
    o: &Tabulation,
) -> Result<ContactLaw, LawError> {
    tabulate_with_progress(source, o, &|_| {})
}

/// [`tabulate`], reporting the fraction of the work done (0 to 1, rough) to `progress`.
pub fn tabulate_with_progress<S: LawSource + Sync + ?Sized>(
    source: &S,
    o: &Tabulation,
    progress: &(dyn Fn(f64) + Sync),
) -> Result<ContactLaw, LawError> {
    o.check()?;
    let scale = source.length_scale();
    if !(scale.is_finite() && scale > 0.0) {
        return Err(LawError::BadSource(format!(
            "length_scale = {}: must be finite and > 0 (m)",
            fmt_num(scale)
        )));
    }
    let threads = threads_of(o);
    let src = Src {
        s: source,
        evals: AtomicUsize::new(0),
    };
    let grid = match o.d_min {
        DminGrid::Adaptive { lo, hi } => {
            let n = START_BRANCHES;
            let mut g: Vec<f64> = (0..n)
                .map(|i| lo + (hi - lo) * (i as f64 / (n - 1) as f64))
                .collect();
            g[n - 1] = hi;
            g
        }
        DminGrid::Uniform(g) => g.nodes(),
    };
    let (lo, hi) = (grid[0], grid[grid.len() - 1]);
    let top = src.reach(f64::INFINITY, Branch::Virgin)?;
    if top <= hi {
        return Err(LawError::BadSource(format!(
            "the virgin reach {} m is not above d_min_hi = {} m: tabulate histories below the first touch",
            fmt_num(top),
            fmt_num(hi)
        )));
    }
    progress(0.0);
    // the virgin envelope at the histories, and the deepest history's pull-out
    let starts: Vec<f64> = par_map(&grid, threads, |&d| src.p(d, f64::INFINITY, Branch::Virgin))
        .into_iter()
        .collect::<Result<_, _>>()?;
    let deepest_pull_out = src.pull_out(lo)?;
    let floor = match o.pressure_floor {
        Some(f) => f,
        None => {
            let reference = starts[0].abs().max(deepest_pull_out.pressure.abs());
            let f = DEFAULT_FLOOR_FRACTION * reference;
            if !(f > 0.0 && f.is_finite()) {
                return Err(LawError::BadSource(format!(
                    "the deepest history d_min = {} m carries no pressure (virgin {} Pa, pull-out {} Pa): \
                     nothing to tabulate; give a pressure floor or deeper histories",
                    fmt_num(lo),
                    fmt_num(starts[0]),
                    fmt_num(deepest_pull_out.pressure)
                )));
            }
            f
        }
    };
    let tol = o.tolerance;
    let st = Setup {
        floor,
        scale,
        r: Refine {
            tol: 0.25 * tol,
            h_min: 1e-7 * scale,
            max_nodes: o.max_nodes,
        },
    };
    let indices: Vec<usize> = (0..grid.len()).collect();
    let built: Vec<Built> = par_map(&indices, threads, |&k| {
        build_branch(&src, grid[k], starts[k], None, o, st)
    })
    .into_iter()
    .collect::<Result<_, _>>()?;
    progress(0.25);

    // virgin envelope: start grid uniform on [lo, top] plus the d_min nodes
    let n = o.points_per_branch;
    let ds: Vec<f64> = (0..=n)
        .map(|i| {
            if i == n {
                top
            } else {
                lo + (top - lo) * (i as f64 / n as f64)
            }
        })
        .collect();
    let values: Vec<f64> = par_map(&ds, threads, |&d| src.p(d, f64::INFINITY, Branch::Virgin))
        .into_iter()
        .collect::<Result<_, _>>()?;
    let mut nodes: Vec<(f64, f64)> = ds.into_iter().zip(values).collect();
    nodes.retain(|v| !grid.contains(&v.0));
    nodes.extend(grid.iter().copied().zip(starts.iter().copied()));
    let n_int = built.len() - 1;
    let mut t = Table {
        built,
        virgin: Sampled::new(0.0, nodes),
        checks: (0..n_int).map(|_| None).collect(),
        stuck: vec![false; n_int],
        top,
        st,
        meta_scale: scale,
    };
    let mut converged = t.refine_virgin(&src)?;
    // histories: the rule in d_min to half the tolerance at the checks
    converged &= t.refine_histories(&src, o, 0.5 * tol, Vec::new(), progress, (0.25, 0.7))?;

    // measure on the final law; repair where a held-out batch misses the tolerance
    let mut round = 0;
    let (law, samples) = loop {
        converged &= t.refine_virgin(&src)?;
        let virgin_min = {
            let built = &t.built;
            let floor = |d: f64| floor_between(built, st.floor, d);
            let mut f = |d: f64| src.p(d, f64::INFINITY, Branch::Virgin);
            let (m, c) = t.virgin.settle_min(&mut f, &floor, st.r)?;
            converged &= c;
            m
        };
        let law = t.law(Some(virgin_min))?;
        let seed = o.seed.wrapping_add(round as u64);
        let held_out = random_batch(&src, &law, &t, o, seed, threads)?;
        let failing: Vec<Sample> = held_out.iter().copied().filter(|s| !(s.e <= tol)).collect();
        let adaptive = matches!(o.d_min, DminGrid::Adaptive { .. });
        if failing.is_empty() || !adaptive || round == REPAIR_ROUNDS {
            let mut all = own_samples(&law, &t)?;
            all.extend(held_out);
            break (law, all);
        }
        round += 1;
        // repair: the envelope takes its failing points as nodes; a failing branch point
        // bisects its interval of histories, and both neighbours take its x as a node
        let mut force: Vec<usize> = Vec::new();
        for s in &failing {
            match s.path {
                None => {
                    let p = src.p(s.d, f64::INFINITY, Branch::Virgin)?;
                    t.virgin.insert(s.d, p);
                }
                Some(path) => {
                    let k = t
                        .built
                        .partition_point(|b| b.d_min <= s.d_min)
                        .saturating_sub(1)
                        .min(t.built.len() - 2);
                    if !force.contains(&k) {
                        force.push(k);
                    }
                    for j in [k, k + 1] {
                        let b = &mut t.built[j];
                        let x = s.d - s.d_min;
                        let c = b.curve(path);
                        if x > 0.0 && x < c.x[c.x.len() - 1] {
                            let d_min = b.d_min;
                            let p = src.p(d_min + x, d_min, Branch::from(path))?;
                            let fl = b.pull_out.pressure.abs() + st.floor;
                            let c = b.curve_mut(path);
                            c.insert(x, p);
                            let mut f = |x: f64| src.p(d_min + x, d_min, Branch::from(path));
                            b.converged &= b.curve_mut(path).refine(&mut f, &|_| fl, st.r)?;
                            // the node set changed: this branch's checks are made again
                        }
                    }
                    for j in [k.saturating_sub(1), k, k + 1] {
                        if j < t.checks.len() {
                            t.checks[j] = None;
                        }
                    }
                }
            }
        }
        force.sort_unstable();
        converged &= t.refine_histories(&src, o, 0.5 * tol, force, progress, (0.7, 0.85))?;
    };
    progress(0.95);
    converged &= t.built.iter().all(|b| b.converged) && !t.stuck.iter().any(|&s| s);
    let mut law = law;
    let measured = statistics(&mut law, &samples, o.seed)?;
    converged &= measured.is_finite() && measured.max() <= tol;
    law.meta.measured = Some(measured);
    law.meta.tabulation = Some(TabulationInfo {
        tolerance: o.tolerance,
        points_per_branch: o.points_per_branch,
        d_min_rule: match o.d_min {
            DminGrid::Adaptive { .. } => "adaptive".into(),
            DminGrid::Uniform(g) => format!("uniform {g}"),
        },
        source_evaluations: src.evals.load(Ordering::Relaxed),
        converged,
    });
    progress(1.0);
    Ok(law)
}

/// The errors of the final law at the tabulator's own points: the midpoints of every
/// curve's intervals (cached source values) and the checks at every mid d_min.
fn own_samples(law: &ContactLaw, t: &Table) -> Result<Vec<Sample>, LawError> {
    let mut out = Vec::new();
    let v = &t.virgin;
    for i in 0..v.x.len() - 1 {
        if let Some(direct) = v.mid[i] {
            let d = v.x[i] + 0.5 * (v.x[i + 1] - v.x[i]);
            let p = law.virgin_pressure(d)?.0;
            out.push(Sample {
                e: rel(p, direct, floor_between(&t.built, t.st.floor, d)),
                d,
                d_min: d,
                path: None,
            });
        }
    }
    for b in &t.built {
        let floor = b.pull_out.pressure.abs() + t.st.floor;
        for path in [Path::Approach, Path::Retract] {
            let s = b.curve(path);
            for i in 0..s.x.len() - 1 {
                if let Some(direct) = s.mid[i] {
                    let x = s.x[i] + 0.5 * (s.x[i + 1] - s.x[i]);
                    let d = b.d_min + x;
                    let p = law.branch_pressure(d, b.d_min, path)?.0;
                    out.push(Sample {
                        e: rel(p, direct, floor),
                        d,
                        d_min: b.d_min,
                        path: Some(path),
                    });
                }
            }
        }
    }
    for c in t.checks.iter().flatten() {
        for (e, d, path) in c.errors(law)? {
            out.push(Sample {
                e,
                d,
                d_min: c.d_min,
                path: Some(path),
            });
        }
    }
    Ok(out)
}

/// Held-out pseudo-random points: d uniform on the envelope, and (d_min, x = reach u^2)
/// with d_min uniform on the tabulated range, 8 per history and path, plus the pull-out of
/// each history.
fn random_batch<S: LawSource + Sync + ?Sized>(
    src: &Src<'_, S>,
    law: &ContactLaw,
    t: &Table,
    o: &Tabulation,
    seed: u64,
    threads: usize,
) -> Result<Vec<Sample>, LawError> {
    let (lo, hi) = law.d_min_range();
    let mut rng = Lcg(seed);
    let ds: Vec<f64> = (0..o.random_points)
        .map(|_| lo + (t.top - lo) * rng.uniform())
        .collect();
    let per = 8;
    let histories: Vec<(f64, [f64; 2 * 8])> = (0..o.random_points.div_ceil(per))
        .map(|_| {
            let d_min = lo + (hi - lo) * rng.uniform();
            let mut u = [0.0; 16];
            for v in u.iter_mut() {
                *v = rng.uniform();
            }
            (d_min, u)
        })
        .collect();
    let mut out = Vec::new();
    let virgin: Vec<Result<Sample, LawError>> = par_map(&ds, threads, |&d| {
        let direct = src.p(d, f64::INFINITY, Branch::Virgin)?;
        let p = law.virgin_pressure(d)?.0;
        Ok(Sample {
            e: rel(p, direct, floor_between(&t.built, t.st.floor, d)),
            d,
            d_min: d,
            path: None,
        })
    });
    for s in virgin {
        out.push(s?);
    }
    let branches: Vec<Result<Vec<Sample>, LawError>> =
        par_map(&histories, threads, |&(d_min, u)| {
            let po = src.pull_out(d_min)?;
            let floor = po.pressure.abs() + t.st.floor;
            let mut v = Vec::new();
            for (ip, path) in [Path::Approach, Path::Retract].into_iter().enumerate() {
                let len = src.reach(d_min, Branch::from(path))? - d_min;
                let mut xs: Vec<f64> = u[8 * ip..8 * ip + 8].iter().map(|u| len * u * u).collect();
                if path == Path::Retract {
                    xs.push(po.d - d_min);
                }
                for x in xs {
                    let d = d_min + x;
                    let direct = src.p(d, d_min, Branch::from(path))?;
                    let p = law.branch_pressure(d, d_min, path)?.0;
                    v.push(Sample {
                        e: rel(p, direct, floor),
                        d,
                        d_min,
                        path: Some(path),
                    });
                }
            }
            Ok(v)
        });
    for s in branches {
        out.extend(s?);
    }
    Ok(out)
}

/// The statistics per kind, and per branch (each point belongs to the branch at or below
/// its d_min), recorded in `law`.
fn statistics(
    law: &mut ContactLaw,
    samples: &[Sample],
    seed: u64,
) -> Result<MeasuredError, LawError> {
    let mut kinds: [Vec<(f64, f64, f64)>; 3] = [Vec::new(), Vec::new(), Vec::new()];
    let n = law.branches.len();
    let mut per = vec![
        BranchError {
            approach: 0.0,
            retract: 0.0
        };
        n
    ];
    let grid = law.grid.clone();
    for s in samples {
        let i = match s.path {
            None => 0,
            Some(Path::Approach) => 1,
            Some(Path::Retract) => 2,
        };
        kinds[i].push((s.e, s.d, s.d_min));
        if let Some(path) = s.path {
            let k = grid
                .partition_point(|&g| g <= s.d_min)
                .saturating_sub(1)
                .min(n - 1);
            let slot = match path {
                Path::Approach => &mut per[k].approach,
                Path::Retract => &mut per[k].retract,
            };
            if s.e.is_nan() || s.e > *slot {
                *slot = s.e;
            }
        }
    }
    for (b, e) in law.branches.iter_mut().zip(per) {
        b.measured = Some(e);
    }
    let stats = |v: &[(f64, f64, f64)], what: &str| {
        ErrorStats::from_samples(v)
            .ok_or_else(|| LawError::BadSource(format!("no {what} check points")))
    };
    Ok(MeasuredError {
        virgin: stats(&kinds[0], "virgin")?,
        approach: stats(&kinds[1], "approach")?,
        retract: stats(&kinds[2], "retract")?,
        seed,
    })
}

/// Measures the error of the one-number history after a partial reload: for every
/// tabulated d_min and each fraction f in `turn_fractions` (each in (0, 1)), a reload
/// turning at d_turn = d_min + f (approach reach - d_min), then `points` separations from
/// d_turn to the retract reach (denser near d_turn); the law's retract branch of d_min
/// against [`ReloadSource::retract_after_reload`]. Record the result in the file with
/// [`ContactLaw::set_partial_reload`].
pub fn measure_partial_reload<S: ReloadSource + Sync + ?Sized>(
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
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let per_branch = par_map(law.branches(), threads, |b| {
        let mut samples = Vec::new();
        let d_min = b.d_min();
        let floor = b.pull_out().pressure.abs() + law.pressure_floor();
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
        Ok(samples)
    });
    let mut samples = Vec::new();
    for s in per_branch {
        samples.extend(s?);
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
