//! Numeric adapters shared by the law crates. Every solver takes a *fallible* closure
//! (`FnMut(f64) -> Result<f64, E>`), stops at the first error and returns it, and reports
//! its own failures as [`CoreError`] (converted into the caller's error by `From`): a
//! solver never returns NaN or a silently wrong value.
//!
//! * [`brent`], [`brent_from`]: Brent-Dekker bracketed root with a [`Tolerance`] (relative
//!   and absolute parts, an iteration cap). The `roots` crate's `find_root_brent` was
//!   measured and not used: it re-evaluates the function at the kept end point on every
//!   iteration (two evaluations per step in the hot loops of the Maugis-Dugdale solver),
//!   returns the previous iterate rather than the best one on x-convergence, and its
//!   tolerance is absolute.
//! * [`local_min`]: Brent's minimiser (golden section with parabolic steps), and
//!   [`grid_min`], *the* minimum search of the workspace: a function sampled on a grid the
//!   caller chooses from the law's length scales, then its best local minima refined.
//! * [`integrate`]: globally adaptive, error-controlled quadrature on panels between
//!   break points, by nested Gauss-Legendre rules ([`AdaptiveRule`]).
//! * [`GaussLegendre`]: the n-point rule, nodes by Newton's iteration.
//! * [`linspace`], [`geomspace`]: the one sampling helper.

use crate::error::CoreError;

/// When an iterative solver stops: an interval narrower than `rel * |x| + abs`, or after
/// `max_iter` iterations (an error).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Relative part (of the magnitude of the solution).
    pub rel: f64,
    /// Absolute part, in the units of x.
    pub abs: f64,
    /// Iteration cap; reaching it is [`CoreError::NoConvergence`].
    pub max_iter: usize,
}

impl Tolerance {
    /// A root to the last digits of a double: 4 eps relative, 300 iterations.
    pub const ROOT: Self = Self {
        rel: 4.0 * f64::EPSILON,
        abs: 0.0,
        max_iter: 300,
    };

    /// `rel` relative, no absolute part, 300 iterations.
    pub const fn relative(rel: f64) -> Self {
        Self {
            rel,
            abs: 0.0,
            max_iter: 300,
        }
    }

    /// `abs` absolute, no relative part, 300 iterations.
    pub const fn absolute(abs: f64) -> Self {
        Self {
            rel: 0.0,
            abs,
            max_iter: 300,
        }
    }

    /// The same tolerance with another iteration cap.
    pub const fn with_max_iter(self, max_iter: usize) -> Self {
        Self { max_iter, ..self }
    }

    fn width(&self, x: f64) -> f64 {
        self.rel * x.abs() + self.abs
    }
}

/// A point where a function is known: f(x).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Abscissa.
    pub x: f64,
    /// f(x).
    pub f: f64,
}

fn finite<E: From<CoreError>>(what: &'static str, x: f64, y: f64) -> Result<f64, E> {
    if y.is_finite() {
        Ok(y)
    } else {
        Err(CoreError::NotFinite { what, x }.into())
    }
}

/// Finds x in [a, b] with f(x) = 0, given f(a) f(b) <= 0 (Brent 1973, "zeroin").
///
/// Converges when the bracket is narrower than `tol` (plus 2 eps |x|), or when f is exactly
/// zero. Errors if the end points do not bracket a root, if f is not finite, after
/// `tol.max_iter` iterations, or with the first error of `f`.
///
/// ```
/// use contact_core::numeric::{brent, Tolerance};
/// use contact_core::CoreError;
/// // a root of size 1e-9 (a nanometre) found to relative precision
/// let r = brent("cube", |x| Ok::<_, CoreError>(x * x * x - 8e-27), 0.0, 1e-8, Tolerance::ROOT)?;
/// assert!((r / 2e-9 - 1.0).abs() < 1e-14);
/// # Ok::<(), CoreError>(())
/// ```
pub fn brent<E: From<CoreError>>(
    what: &'static str,
    mut f: impl FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    tol: Tolerance,
) -> Result<f64, E> {
    let fa = f(a)?;
    let fb = f(b)?;
    brent_from(what, f, Sample { x: a, f: fa }, Sample { x: b, f: fb }, tol)
}

/// [`brent`] for a caller that already knows f at the end points.
pub fn brent_from<E: From<CoreError>>(
    what: &'static str,
    mut f: impl FnMut(f64) -> Result<f64, E>,
    lo: Sample,
    hi: Sample,
    tol: Tolerance,
) -> Result<f64, E> {
    let lo = Sample {
        x: lo.x,
        f: finite::<E>(what, lo.x, lo.f)?,
    };
    let hi = Sample {
        x: hi.x,
        f: finite::<E>(what, hi.x, hi.f)?,
    };
    for end in [lo, hi] {
        if end.f == 0.0 {
            return Ok(end.x);
        }
    }
    if (lo.f < 0.0) == (hi.f < 0.0) {
        return Err(CoreError::NotBracketed {
            what,
            lo: lo.x,
            hi: hi.x,
            f_lo: lo.f,
            f_hi: hi.f,
        }
        .into());
    }
    match zeroin(
        |x| finite::<E>(what, x, f(x)?),
        lo,
        hi,
        |x| tol.width(x),
        tol.max_iter,
    ) {
        Ok(bracket) => Ok(bracket.best.x),
        Err(ZeroinStop::Failed(e, _)) => Err(e),
        Err(ZeroinStop::NoConvergence(_)) => Err(CoreError::NoConvergence {
            what,
            iterations: tol.max_iter,
        }
        .into()),
    }
}

/// How [`expand_bracket`] steps away from its start.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Expansion {
    /// Steps of one length, the first step's (x_k = x_(k-1) + h).
    Linear,
    /// The distance from the start multiplied by this factor (> 1) at every step
    /// (x_k = start + h g^k).
    Geometric(f64),
}

/// Steps away from a known sample `start` through `first` (the first point tried), as
/// `expansion` says, the last step clamped to `limit`, until f changes side (f < 0 against
/// f >= 0, as [`zeroin`] reads sides). Returns the bracket (the last sample on `start`'s
/// side, the first on the other), or None when f keeps its side up to `limit` (also when
/// `limit` is `start` itself). The one bracket expansion of the workspace.
///
/// ```
/// use contact_core::numeric::{expand_bracket, Expansion, Sample};
/// use contact_core::CoreError;
/// let f = |x: f64| Ok::<_, CoreError>(x - 37.0);
/// let start = Sample { x: 0.0, f: -37.0 };
/// let (lo, hi) = expand_bracket("x - 37", f, start, 1.0, Expansion::Geometric(2.0), 1e3)?.unwrap();
/// assert_eq!((lo.x, hi.x), (32.0, 64.0));
/// let (lo, hi) = expand_bracket("x - 37", f, start, 10.0, Expansion::Linear, 1e3)?.unwrap();
/// assert_eq!((lo.x, hi.x), (30.0, 40.0));
/// assert!(expand_bracket("x - 37", f, start, 1.0, Expansion::Linear, 10.0)?.is_none());
/// # Ok::<(), CoreError>(())
/// ```
pub fn expand_bracket<E: From<CoreError>>(
    what: &'static str,
    mut f: impl FnMut(f64) -> Result<f64, E>,
    start: Sample,
    first: f64,
    expansion: Expansion,
    limit: f64,
) -> Result<Option<(Sample, Sample)>, E> {
    let side = start.f < 0.0;
    let span = limit - start.x;
    if span == 0.0 {
        return Ok(None);
    }
    let h = first - start.x;
    let grows = match expansion {
        Expansion::Linear => true,
        Expansion::Geometric(g) => g > 1.0 && g.is_finite(),
    };
    if !(grows && h != 0.0 && h.is_finite() && (h > 0.0) == (span > 0.0)) {
        return Err(CoreError::Invalid {
            field: "bracket expansion",
            value: h,
            allowed: "a first step towards the limit and a growth factor above 1",
        }
        .into());
    }
    let mut prev = start;
    let mut x = first;
    let mut distance = h;
    for _ in 0..100_000 {
        let at_limit = (x - start.x).abs() >= span.abs();
        if at_limit {
            x = limit;
        }
        let s = Sample {
            x,
            f: finite::<E>(what, x, f(x)?)?,
        };
        if (s.f < 0.0) != side {
            return Ok(Some((prev, s)));
        }
        if at_limit {
            return Ok(None);
        }
        prev = s;
        match expansion {
            Expansion::Linear => x += h,
            Expansion::Geometric(g) => {
                distance *= g;
                x = start.x + distance;
            }
        }
    }
    Err(CoreError::NoConvergence {
        what,
        iterations: 100_000,
    }
    .into())
}

/// Where [`zeroin`] ended: `best` the end with the smaller |f| (the root's estimate), `other`
/// the far end of the bracket, and the evaluations spent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bracket {
    /// The root's estimate.
    pub best: Sample,
    /// The other end of the bracket.
    pub other: Sample,
    /// Evaluations of f.
    pub evaluations: usize,
}

/// Why [`zeroin`] stopped without a bracket narrow enough.
#[derive(Debug, Clone, PartialEq)]
pub enum ZeroinStop<E> {
    /// `max_evaluations` spent; the bracket reached.
    NoConvergence(Bracket),
    /// f failed; its error and the last bracket before it.
    Failed(E, Bracket),
}

/// The Brent-Dekker "zeroin" iteration (Brent 1973, ch. 4: inverse quadratic interpolation
/// or secant, falling back to bisection) on a bracket whose ends lie on different sides
/// (f < 0 against f >= 0), returning the final bracket. Values may be infinite (a side known
/// by its sign only, like the log of a zero ratio): while any kept value is, the step is a
/// bisection. Stops when half the bracket is below `width(b)/2 + 2 eps |b|` or f(b) = 0.
/// [`brent_from`] is this with finite values and a [`Tolerance`]; the design sweeps call it
/// directly for the bracket and the infinite sides.
pub fn zeroin<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    lo: Sample,
    hi: Sample,
    width: impl Fn(f64) -> f64,
    max_evaluations: usize,
) -> Result<Bracket, ZeroinStop<E>> {
    let (mut a, mut fa, mut b, mut fb) = (lo.x, lo.f, hi.x, hi.f);
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    let mut evaluations = 0;
    loop {
        if (fb < 0.0) == (fc < 0.0) {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let t = 2.0 * f64::EPSILON * b.abs() + 0.5 * width(b);
        let m = 0.5 * (c - b);
        let here = Bracket {
            best: Sample { x: b, f: fb },
            other: Sample { x: c, f: fc },
            evaluations,
        };
        if m.abs() <= t || fb == 0.0 {
            return Ok(here);
        }
        if evaluations >= max_evaluations {
            return Err(ZeroinStop::NoConvergence(here));
        }
        let finite = fa.is_finite() && fb.is_finite() && fc.is_finite();
        if finite && e.abs() >= t && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (t * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > t { d } else { t.copysign(m) };
        evaluations += 1;
        fb = match f(b) {
            Ok(v) => v,
            Err(err) => {
                let last = Bracket {
                    best: Sample { x: a, f: fa },
                    other: Sample { x: c, f: fc },
                    evaluations,
                };
                return Err(ZeroinStop::Failed(err, last));
            }
        };
    }
}

/// A minimum found by [`local_min`] or [`grid_min`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Minimum {
    /// Where (x).
    pub x: f64,
    /// The value f(x).
    pub value: f64,
    /// Evaluations of f spent.
    pub evaluations: usize,
}

/// Minimum of f on [a, b] by Brent's method (Brent 1973, ch. 5: golden section with
/// parabolic interpolation), to an interval `tol` around x. Exact for a unimodal f,
/// otherwise a local minimum. The value at a smooth minimum is determined to rounding even
/// though its location is only determined to about sqrt(eps) of the scale.
pub fn local_min<E: From<CoreError>>(
    what: &'static str,
    mut f: impl FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    tol: Tolerance,
) -> Result<Minimum, E> {
    let (mut a, mut b) = (a.min(b), a.max(b));
    let golden = 0.5 * (3.0 - 5f64.sqrt());
    let mut x = a + golden * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = finite::<E>(what, x, f(x)?)?;
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e) = (0.0f64, 0.0f64);
    // one evaluation before the loop and one per completed iteration
    for evaluations in (1..).take(tol.max_iter) {
        let m = 0.5 * (a + b);
        let t = 2.0 * f64::EPSILON * x.abs() + 0.5 * tol.width(x) + f64::MIN_POSITIVE;
        let t2 = 2.0 * t;
        if (x - m).abs() <= t2 - 0.5 * (b - a) {
            return Ok(Minimum {
                x,
                value: fx,
                evaluations,
            });
        }
        let mut parabolic = false;
        if e.abs() > t {
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            let r = e;
            e = d;
            if p.abs() < (0.5 * q * r).abs() && p > q * (a - x) && p < q * (b - x) {
                d = p / q;
                let u = x + d;
                if u - a < t2 || b - u < t2 {
                    d = if x < m { t } else { -t };
                }
                parabolic = true;
            }
        }
        if !parabolic {
            e = if x < m { b - x } else { a - x };
            d = golden * e;
        }
        let u = x + if d.abs() >= t { d } else { t.copysign(d) };
        let fu = finite::<E>(what, u, f(u)?)?;
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            v = w;
            fv = fw;
            w = x;
            fw = fx;
            x = u;
            fx = fu;
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                v = w;
                fv = fw;
                w = u;
                fw = fu;
            } else if fu <= fv || v == x || v == w {
                v = u;
                fv = fu;
            }
        }
    }
    Err(CoreError::NoConvergence {
        what,
        iterations: tol.max_iter,
    }
    .into())
}

/// How many local minima of the samples [`grid_min`] refines, best first.
pub const GRID_MIN_CANDIDATES: usize = 3;

/// The minimum search of the workspace: f sampled on `grid` (sorted, chosen by the caller
/// from the law's length scales so that no well is narrower than the local spacing), then
/// each of the [`GRID_MIN_CANDIDATES`] best local minima of the samples refined by
/// [`local_min`] between its neighbours, each to `tol` *relative to its own bracket*
/// (`tol.rel` of the bracket width, plus `tol.abs`). Returns the lowest.
///
/// ```
/// use contact_core::numeric::{geomspace, grid_min, Tolerance};
/// use contact_core::CoreError;
/// // a narrow well at x = 1e-3 on [0, 1]: a geometric grid from the well's own scale finds it
/// let f = |x: f64| Ok::<_, CoreError>(-(-((x - 1e-3) / 2e-4).powi(2)).exp());
/// let grid: Vec<f64> = std::iter::once(0.0).chain(geomspace(1e-5, 1.0, 80)).collect();
/// let m = grid_min("well", f, &grid, Tolerance::relative(1e-8))?;
/// assert!((m.value + 1.0).abs() < 1e-12 && (m.x - 1e-3).abs() < 1e-6);
/// # Ok::<(), CoreError>(())
/// ```
pub fn grid_min<E: From<CoreError>>(
    what: &'static str,
    mut f: impl FnMut(f64) -> Result<f64, E>,
    grid: &[f64],
    tol: Tolerance,
) -> Result<Minimum, E> {
    let mut ys = Vec::with_capacity(grid.len());
    for &x in grid {
        ys.push(finite::<E>(what, x, f(x)?)?);
    }
    let mut m = refine_minima(what, f, grid, &ys, tol)?;
    m.evaluations += grid.len();
    Ok(m)
}

/// The refinement half of [`grid_min`], for a caller that sampled the grid itself (for
/// instance with a cheaper evaluation that only needs to rank the samples): the
/// [`GRID_MIN_CANDIDATES`] best local minima of `ys` are refined with `f` and the lowest
/// refined value is returned (its `evaluations` count the refinement only).
pub fn refine_minima<E: From<CoreError>>(
    what: &'static str,
    mut f: impl FnMut(f64) -> Result<f64, E>,
    grid: &[f64],
    ys: &[f64],
    tol: Tolerance,
) -> Result<Minimum, E> {
    let brackets = minimum_brackets::<E>(grid, ys)?;
    let found = brackets
        .iter()
        .map(|&bracket| refine_one(what, &mut f, bracket, tol))
        .collect::<Result<Vec<_>, E>>()?;
    Ok(lowest(found))
}

/// [`refine_minima`] with the candidates refined in parallel (see [`crate::par`]); the
/// same result.
pub fn refine_minima_par<E: From<CoreError> + Send>(
    what: &'static str,
    f: impl Fn(f64) -> Result<f64, E> + Sync,
    grid: &[f64],
    ys: &[f64],
    tol: Tolerance,
) -> Result<Minimum, E> {
    let brackets = minimum_brackets::<E>(grid, ys)?;
    let found = crate::par::map(&brackets, |&bracket| {
        refine_one(what, &mut &f, bracket, tol)
    })?;
    Ok(lowest(found))
}

/// The brackets (neighbouring grid points) of the [`GRID_MIN_CANDIDATES`] best local
/// minima of the samples, best first.
fn minimum_brackets<E: From<CoreError>>(grid: &[f64], ys: &[f64]) -> Result<Vec<(f64, f64)>, E> {
    if grid.is_empty() || grid.len() != ys.len() {
        return Err(CoreError::Invalid {
            field: "grid",
            value: grid.len() as f64,
            allowed: "at least one point, one value per point",
        }
        .into());
    }
    let n = grid.len();
    // local minima of the samples (ends included), best first; ties keep grid order
    let mut cand: Vec<usize> = (0..n)
        .filter(|&i| (i == 0 || ys[i] <= ys[i - 1]) && (i + 1 == n || ys[i] <= ys[i + 1]))
        .collect();
    cand.sort_by(|&i, &j| ys[i].total_cmp(&ys[j]).then(i.cmp(&j)));
    // where some sample is negative, a local minimum whose sample is not cannot be the
    // lowest (the grid resolves every well by construction): it is not refined
    let any_negative = ys.iter().any(|&y| y < 0.0);
    Ok(cand
        .iter()
        .filter(|&&i| !any_negative || ys[i] < 0.0)
        .take(GRID_MIN_CANDIDATES)
        .map(|&i| (grid[i.saturating_sub(1)], grid[(i + 1).min(n - 1)]))
        .collect())
}

/// The minimum in one bracket, to `tol` relative to the bracket's width.
fn refine_one<E: From<CoreError>>(
    what: &'static str,
    f: &mut impl FnMut(f64) -> Result<f64, E>,
    (a, b): (f64, f64),
    tol: Tolerance,
) -> Result<Minimum, E> {
    if a == b {
        return Ok(Minimum {
            x: a,
            value: finite::<E>(what, a, f(a)?)?,
            evaluations: 1,
        });
    }
    let t = Tolerance {
        rel: 0.0,
        abs: tol.rel * (b - a).abs() + tol.abs,
        max_iter: tol.max_iter,
    };
    local_min(what, f, a, b, t)
}

/// The lowest of the refined minima (the first of equals), counting every evaluation.
fn lowest(found: Vec<Minimum>) -> Minimum {
    let evaluations = found.iter().map(|m| m.evaluations).sum();
    let mut best = found
        .into_iter()
        .reduce(|best, m| if m.value < best.value { m } else { best })
        .expect("a grid has at least one local minimum");
    best.evaluations = evaluations;
    best
}

/// `n` evenly spaced points from `a` to `b` inclusive (`a` alone when n = 1).
pub fn linspace(
    a: f64,
    b: f64,
    n: usize,
) -> impl DoubleEndedIterator<Item = f64> + ExactSizeIterator + Clone {
    let step = if n > 1 { (b - a) / (n - 1) as f64 } else { 0.0 };
    (0..n).map(move |i| {
        if i + 1 == n && n > 1 {
            b
        } else {
            a + step * i as f64
        }
    })
}

/// `n` geometrically spaced points from `a` to `b` inclusive (both > 0).
pub fn geomspace(
    a: f64,
    b: f64,
    n: usize,
) -> impl DoubleEndedIterator<Item = f64> + ExactSizeIterator + Clone {
    let (la, lb) = (a.ln(), b.ln());
    linspace(la, lb, n).enumerate().map(move |(i, l)| {
        if i == 0 {
            a
        } else if i + 1 == n {
            b
        } else {
            l.exp()
        }
    })
}

/// Result of a quadrature.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Integral {
    /// The integral.
    pub value: f64,
    /// The error estimate (absolute).
    pub error: f64,
    /// Evaluations of the integrand.
    pub evaluations: usize,
}

/// The nested Gauss-Legendre rule of [`integrate`]. On every panel: the `nodes`-point rule
/// on the whole panel and on each half (the halves' sum is the panel's value), and the
/// integrand at the panel's two ends. Two error estimates are taken, the larger counts:
/// the difference between the whole-panel and the halves' values, and the mismatch between
/// the end values and the polynomial through the halves' 2 `nodes` values extrapolated to
/// the ends (times the panel width). The second catches what the first cannot: a kink or
/// step hidden between a panel's end and its first node, where every Gauss rule sees the
/// same smooth function. A refined panel's halves become panels whose whole-panel value is
/// already known, so each refinement costs 2 (2 `nodes` + 1) evaluations.
#[derive(Debug, Clone, PartialEq)]
pub struct AdaptiveRule {
    gl: GaussLegendre,
    /// Nodes of the two halves of [-1, 1] and their weights.
    halves: Vec<(f64, f64)>,
    /// Lagrange basis of the n nodes of a half at its lower and upper end.
    at_lo: Vec<f64>,
    at_hi: Vec<f64>,
    /// The same through the n - 1 nodes nearest that end.
    low_lo: Vec<f64>,
    low_hi: Vec<f64>,
    /// How much the extrapolation to an end amplifies noise (sum of |basis|).
    gain: f64,
    /// Distance from a half's end to its nearest node, as a fraction of the half.
    sliver: f64,
}

impl AdaptiveRule {
    /// The rule of `nodes` (2..=6) points per (half) panel. Rules of more nodes are cheaper
    /// on smooth integrands but were measured to miss hidden steps (the whole-panel and
    /// halves' values then agree by coincidence too often).
    pub fn new(nodes: usize) -> Result<Self, CoreError> {
        if !(2..=6).contains(&nodes) {
            return Err(CoreError::Invalid {
                field: "nodes",
                value: nodes as f64,
                allowed: "an integer in [2, 6]",
            });
        }
        let gl = GaussLegendre::new(nodes);
        let halves: Vec<(f64, f64)> = gl.mapped(-1.0, 0.0).chain(gl.mapped(0.0, 1.0)).collect();
        // the Lagrange basis of the n nodes on [-1, 1] at -1 and +1 (the ends of a half)
        let xs: Vec<f64> = gl.mapped(-1.0, 1.0).map(|p| p.0).collect();
        let basis = |t: f64| -> Vec<f64> {
            (0..xs.len())
                .map(|j| {
                    xs.iter()
                        .enumerate()
                        .filter(|&(k, _)| k != j)
                        .map(|(_, &xk)| (t - xk) / (xs[j] - xk))
                        .product()
                })
                .collect()
        };
        // the same through the n - 1 nodes nearest each end (the farthest dropped)
        let basis_without = |t: f64, drop: usize| -> Vec<f64> {
            (0..xs.len())
                .map(|j| {
                    if j == drop {
                        return 0.0;
                    }
                    xs.iter()
                        .enumerate()
                        .filter(|&(k, _)| k != j && k != drop)
                        .map(|(_, &xk)| (t - xk) / (xs[j] - xk))
                        .product()
                })
                .collect()
        };
        let sliver = 0.5 * (1.0 + xs[0]);
        let last = xs.len() - 1;
        let at_lo = basis(-1.0);
        let gain = at_lo.iter().map(|x| x.abs()).sum::<f64>();
        Ok(Self {
            at_hi: basis(1.0),
            at_lo,
            low_lo: basis_without(-1.0, last),
            low_hi: basis_without(1.0, 0),
            gain,
            sliver,
            gl,
            halves,
        })
    }

    /// Nodes per (half) panel.
    pub fn nodes(&self) -> usize {
        self.gl.len()
    }
}

/// Factor on |whole - halves|: that difference estimates the whole-panel rule's error,
/// which for a smooth integrand is orders of magnitude above the halves' error, but for a
/// step or kink inside the panel only a few times it.
const WHOLE_SAFETY: f64 = 4.0;

/// Share of the difference between the extrapolations through n and n - 1 nodes that is
/// taken as a smooth integrand's own extrapolation error and discounted from the end
/// mismatch. Measured on 4000 hidden kinks and steps (`hidden_kinks_and_steps...` test):
/// 0.25 keeps every error within its estimate for 4 and 6 nodes while halving the cost on
/// smooth integrands compared with no discount.
const DISCOUNT: f64 = 0.25;

/// Factor on the end-mismatch estimate (mismatch x sliver bounds a hidden feature's error).
const END_SAFETY: f64 = 2.0;

/// Relative noise assumed in integrand values (64 eps): the laws integrated here solve
/// their equations to rounding, but an interference h - d formed from two nearly equal
/// heights carries a few tens of eps.
pub const NOISE: f64 = 64.0 * f64::EPSILON;

/// What [`integrate`] aims for: an error estimate at most
/// `max(rel * |integral|, rel_of_abs * integral of |f|, abs)`, and never below the
/// integrand's noise (`noise` times the integral of |f|).
///
/// `rel` is relative to the result itself, which matters where positive and negative
/// parts cancel (an adhesive pressure near its pull-out); `rel_of_abs` bounds the work
/// spent where the result is near zero.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadTolerance {
    /// Relative to |integral|.
    pub rel: f64,
    /// Relative to the integral of |f| (the scale of the terms summed).
    pub rel_of_abs: f64,
    /// Absolute floor, in the units of the integral.
    pub abs: f64,
    /// Panels no wider than this at the start (in x; 0 for no limit); refinement then goes
    /// where the estimate is large.
    pub max_width: f64,
    /// Refinement cap. Reaching it, or panels too narrow to halve, with the estimate within
    /// [`STAGNATION_ALLOWANCE`] of the target returns the value with its honest (larger)
    /// estimate: the integrand's noise is then the limit. Beyond that it is
    /// [`CoreError::Quadrature`].
    pub max_panels: usize,
    /// Relative noise of the integrand's values: [`NOISE`] for a function computed to
    /// rounding, more where its argument comes from a cancellation (a rough surface's
    /// interference h - d over a range of heights much narrower than the heights). No
    /// estimate is trusted below it, and a target below it is raised to it.
    pub noise: f64,
}

/// How far above its target a quadrature stopped by its panel cap or by rounding may end
/// and still return its value (with the error estimate it reached).
pub const STAGNATION_ALLOWANCE: f64 = 1e3;

#[derive(Debug)]
struct Panel {
    /// Values at the halves' nodes (panel variable, Jacobian included).
    ys: Vec<f64>,
    /// Interval index (for the edge substitution).
    k: usize,
    a: f64,
    b: f64,
    fa: f64,
    fm: f64,
    fb: f64,
    left: f64,
    right: f64,
    abs: f64,
    error: f64,
}

/// Globally adaptive quadrature of `f` over the consecutive intervals of `breaks`
/// (sorted; f may jump or kink at each break, and is never evaluated exactly there). With
/// `edge_substitution`, the first interval is integrated in tau with x = x0 + L tau^2,
/// which makes an integrable square-root behaviour at its lower end,
/// f - f(x0) ~ sqrt(x - x0), and a Hertz edge, f ~ (x - x0)^(3/2), smooth.
///
/// The panel with the largest error estimate (see [`AdaptiveRule`]) is bisected until the
/// sum of the estimates meets `tol`. For an integrand the rule resolves the estimate
/// overstates the error of the value returned by orders of magnitude; an unresolved one
/// (a feature narrower than the panels that no node sees) is refined until it is seen.
///
/// ```
/// use contact_core::numeric::{integrate, AdaptiveRule, QuadTolerance, NOISE};
/// use contact_core::CoreError;
/// // |x - 0.3137| on [0, 1], with the kink nowhere declared
/// let rule = AdaptiveRule::new(6)?;
/// let tol = QuadTolerance { rel: 1e-12, rel_of_abs: 1e-12, abs: 0.0, max_width: 0.0, max_panels: 10_000, noise: NOISE };
/// let r = integrate("kink", |x: f64| Ok::<_, CoreError>((x - 0.3137).abs()), &[0.0, 1.0], false, &rule, tol)?;
/// let exact = 0.5 * (0.3137f64.powi(2) + 0.6863f64.powi(2));
/// assert!((r.value - exact).abs() < 1e-12);
/// # Ok::<(), CoreError>(())
/// ```
pub fn integrate<E: From<CoreError>>(
    what: &'static str,
    f: impl FnMut(f64) -> Result<f64, E>,
    breaks: &[f64],
    edge_substitution: bool,
    rule: &AdaptiveRule,
    tol: QuadTolerance,
) -> Result<Integral, E> {
    integrate_seq(what, f, breaks, edge_substitution, rule, tol, false).map(|(i, _)| i)
}

/// An accepted panel of [`integrate_panels`], in the integration variable: its ends with
/// the integrand there, and the integrand at the rule's nodes. Through these
/// 2 nodes + 2 points passes the polynomial [`PanelNodes::interpolant`], which resolves
/// the integrand to about the accuracy the quadrature reached on the panel.
#[derive(Debug, Clone, PartialEq)]
pub struct PanelNodes {
    /// Lower end.
    pub a: f64,
    /// Upper end.
    pub b: f64,
    /// (x, f(x)) at a, the nodes, and b, in increasing x.
    pub points: Vec<(f64, f64)>,
    /// The panel's integral.
    pub value: f64,
    /// Its error estimate.
    pub error: f64,
}

impl PanelNodes {
    /// The interpolating polynomial through [`PanelNodes::points`] (barycentric form).
    pub fn interpolant(&self) -> Interpolant {
        Interpolant::new(&self.points)
    }
}

/// A polynomial through given points, evaluated in barycentric form (Berrut & Trefethen
/// 2004), with its exact integral over any sub-interval.
#[derive(Debug, Clone, PartialEq)]
pub struct Interpolant {
    /// The nodes mapped to about [-1, 1]: (x - centre) / half_width.
    x: Vec<f64>,
    y: Vec<f64>,
    w: Vec<f64>,
    centre: f64,
    half_width: f64,
    gl: GaussLegendre,
}

impl Interpolant {
    /// Through `points` (distinct x).
    ///
    /// Points whose x repeats an earlier one are left out (a panel refined to a few ulps,
    /// where its nodes round onto each other, would otherwise give infinite weights), and
    /// the barycentric weights are formed on the nodes mapped to [-1, 1], where
    /// 1/prod(x_j - x_k) cannot underflow as it does on a panel a few ulps wide.
    pub fn new(points: &[(f64, f64)]) -> Self {
        let mut unique: Vec<(f64, f64)> = Vec::with_capacity(points.len());
        for &p in points {
            if !unique.iter().any(|q| q.0 == p.0) {
                unique.push(p);
            }
        }
        let points = &unique[..];
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.0), hi.max(p.0))
            });
        let centre = if lo.is_finite() && hi.is_finite() {
            0.5 * (lo + hi)
        } else {
            0.0
        };
        let half_width = if hi > lo { 0.5 * (hi - lo) } else { 1.0 };
        let x: Vec<f64> = points.iter().map(|p| (p.0 - centre) / half_width).collect();
        let y: Vec<f64> = points.iter().map(|p| p.1).collect();
        let w = (0..x.len())
            .map(|j| {
                1.0 / (0..x.len())
                    .filter(|&k| k != j)
                    .map(|k| x[j] - x[k])
                    .product::<f64>()
            })
            .collect();
        // degree n - 1: a Gauss rule of ceil(n/2) nodes integrates it exactly
        let gl = GaussLegendre::new(x.len().div_ceil(2).max(1));
        Self {
            x,
            y,
            w,
            centre,
            half_width,
            gl,
        }
    }

    /// The polynomial at `t`.
    pub fn eval(&self, t: f64) -> f64 {
        let t = (t - self.centre) / self.half_width;
        let (mut num, mut den) = (0.0, 0.0);
        for ((&xj, &yj), &wj) in self.x.iter().zip(&self.y).zip(&self.w) {
            if t == xj {
                return yj;
            }
            let c = wj / (t - xj);
            num += c * yj;
            den += c;
        }
        num / den
    }

    /// Its integral from `a` to `b`.
    pub fn integral(&self, a: f64, b: f64) -> f64 {
        self.gl.integrate(|t| self.eval(t), a, b)
    }
}

/// [`integrate`], also returning the accepted panels in increasing order (in the
/// integration variable: tau on an edge-substituted first interval).
pub fn integrate_panels<E: From<CoreError>>(
    what: &'static str,
    f: impl FnMut(f64) -> Result<f64, E>,
    breaks: &[f64],
    edge_substitution: bool,
    rule: &AdaptiveRule,
    tol: QuadTolerance,
) -> Result<(Integral, Vec<PanelNodes>), E> {
    integrate_seq(what, f, breaks, edge_substitution, rule, tol, true)
}

/// The sequential quadrature, with the accepted panels only when `nodes` (a caller that
/// wants the integral alone, such as every pressure of a rough surface, does not pay for
/// copying each panel's points).
fn integrate_seq<E: From<CoreError>>(
    what: &'static str,
    mut f: impl FnMut(f64) -> Result<f64, E>,
    breaks: &[f64],
    edge_substitution: bool,
    rule: &AdaptiveRule,
    tol: QuadTolerance,
    nodes: bool,
) -> Result<(Integral, Vec<PanelNodes>), E> {
    let map = Substitution {
        breaks,
        edge_substitution,
    };
    integrate_core(
        what,
        &mut |pts: &[(usize, f64)]| {
            crate::par::collect_exact(
                pts.iter().map(|&(k, t)| map.eval(what, &mut f, k, t)),
                pts.len(),
            )
        },
        map,
        rule,
        tol,
        nodes,
    )
}

/// [`integrate_panels`] with the integrand evaluated in parallel (rayon, with the
/// `parallel` feature; sequentially without it): each batch of a panel's nodes, and of
/// both children of a refined panel, is evaluated at once. Worth it where one evaluation
/// costs tens of microseconds (a rough surface's pressure); the result is the same as
/// [`integrate_panels`]' to the last bit, since the nodes and the order of the sums do not
/// change.
pub fn integrate_panels_par<E: From<CoreError> + Send>(
    what: &'static str,
    f: impl Fn(f64) -> Result<f64, E> + Sync,
    breaks: &[f64],
    edge_substitution: bool,
    rule: &AdaptiveRule,
    tol: QuadTolerance,
) -> Result<(Integral, Vec<PanelNodes>), E> {
    let map = Substitution {
        breaks,
        edge_substitution,
    };
    integrate_core(
        what,
        &mut |pts: &[(usize, f64)]| crate::par::map(pts, |&(k, t)| map.eval(what, &mut &f, k, t)),
        map,
        rule,
        tol,
        true,
    )
}

/// The integration variable of each interval of `breaks`: x itself, or on an
/// edge-substituted first interval tau with x = x0 + L tau^2.
#[derive(Clone, Copy)]
struct Substitution<'a> {
    breaks: &'a [f64],
    edge_substitution: bool,
}

impl Substitution<'_> {
    fn substituted(&self, k: usize) -> bool {
        k == 0 && self.edge_substitution
    }

    /// The integrand at t of interval k, Jacobian included, checked finite.
    fn eval<E: From<CoreError>>(
        &self,
        what: &'static str,
        f: &mut impl FnMut(f64) -> Result<f64, E>,
        k: usize,
        t: f64,
    ) -> Result<f64, E> {
        let (x, jac) = if self.substituted(k) {
            let l = self.breaks[1] - self.breaks[0];
            (self.breaks[0] + l * t * t, 2.0 * l * t)
        } else {
            (t, 1.0)
        };
        Ok(finite::<E>(what, x, f(x)?)? * jac)
    }
}

/// The points at which [`panel`] needs the integrand on [a, b]: the halves' nodes, then
/// the midpoint.
fn split_nodes(rule: &AdaptiveRule, (a, b): (f64, f64)) -> impl Iterator<Item = f64> + '_ {
    let (c, m) = (0.5 * (b - a), 0.5 * (a + b));
    rule.halves
        .iter()
        .map(move |&(x, _)| m + c * x)
        .chain(std::iter::once(m))
}

/// A panel of interval k on [a, b] from the integrand at its ends, the whole-panel rule's
/// value, and the integrand at [`split_nodes`] (`ys`: 2n halves' values, then the midpoint).
fn panel(
    rule: &AdaptiveRule,
    k: usize,
    (a, b): (f64, f64),
    (fa, fb): (f64, f64),
    whole: f64,
    ys: &[f64],
    noise: f64,
) -> Panel {
    let (c, n) = (0.5 * (b - a), rule.gl.len());
    let (ys, fm) = (&ys[..2 * n], ys[2 * n]);
    let (mut left, mut right, mut abs) = (0.0, 0.0, 0.0);
    for (i, (&(_, w), &y)) in rule.halves.iter().zip(ys).enumerate() {
        if i < n {
            left += c * w * y;
        } else {
            right += c * w * y;
        }
        abs += c * w * y.abs();
    }
    // each half's polynomial through its nodes, extrapolated to the half's ends, against
    // the integrand there: a feature hidden between an end and the nearest node, where
    // every Gauss rule sees the same smooth function, shows as a mismatch, and costs at
    // most mismatch x sliver
    // (a smooth integrand's own extrapolation error is discounted: the extrapolations
    // through n and through n - 1 nodes differ by about that much, while a hidden
    // feature, seen by no node, moves neither)
    let size = ys
        .iter()
        .fold(fa.abs().max(fb.abs()), |s, y| s.max(y.abs()));
    let noise = 2.0 * rule.gain * noise * size;
    let dot = |basis: &[f64], y: &[f64]| basis.iter().zip(y).map(|(p, y)| p * y).sum::<f64>();
    let signal = |full: &[f64], low: &[f64], y: &[f64], f_end: f64| {
        let p = dot(full, y);
        ((p - f_end).abs() - DISCOUNT * (p - dot(low, y)).abs() - noise).max(0.0)
    };
    let mismatch = signal(&rule.at_lo, &rule.low_lo, &ys[..n], fa)
        .max(signal(&rule.at_hi, &rule.low_hi, &ys[..n], fm))
        .max(signal(&rule.at_lo, &rule.low_lo, &ys[n..], fm))
        .max(signal(&rule.at_hi, &rule.low_hi, &ys[n..], fb));
    let ends = END_SAFETY * mismatch * rule.sliver * (b - a);
    Panel {
        ys: ys.to_vec(),
        k,
        a,
        b,
        fa,
        fm,
        fb,
        left,
        right,
        abs,
        error: (WHOLE_SAFETY * (whole - (left + right)).abs()).max(ends),
    }
}

/// Evaluates the integrand at a batch of (interval, t) points.
type Batch<'a, E> = dyn FnMut(&[(usize, f64)]) -> Result<Vec<f64>, E> + 'a;

fn integrate_core<E: From<CoreError>>(
    what: &'static str,
    eval: &mut Batch<'_, E>,
    map: Substitution<'_>,
    rule: &AdaptiveRule,
    tol: QuadTolerance,
    want_nodes: bool,
) -> Result<(Integral, Vec<PanelNodes>), E> {
    let breaks = map.breaks;
    let noise = tol.noise.max(NOISE);
    let mut evaluations = 0usize;
    let mut eval = |pts: &[(usize, f64)]| {
        evaluations += pts.len();
        eval(pts)
    };
    // the starting panels of every interval: (k, a, b) and the points where the integrand
    // is needed at their ends
    // one piece per interval unless a maximum width cuts them
    let n = breaks.len().saturating_sub(1);
    let mut pieces: Vec<(usize, f64, f64)> = Vec::with_capacity(n);
    let mut end_points: Vec<(usize, f64)> = Vec::with_capacity(2 * n);
    let mut end_index: Vec<usize> = Vec::with_capacity(n); // first end of each piece in end_points
    for k in 0..breaks.len().saturating_sub(1) {
        let (lo, hi) = if map.substituted(k) {
            (0.0, 1.0)
        } else {
            (breaks[k], breaks[k + 1])
        };
        // an empty or NaN interval has nothing to integrate
        if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
            continue;
        }
        let span = breaks[k + 1] - breaks[k];
        let count = if tol.max_width > 0.0 {
            ((span / tol.max_width).ceil() as usize).clamp(1, 10_000)
        } else {
            1
        };
        let cuts: Vec<f64> = linspace(lo, hi, count + 1).collect();
        // end values: one-sided just inside a break, exact at the cuts in between
        let inside = 1e-12 * (hi - lo);
        let first = end_points.len();
        for (i, &t) in cuts.iter().enumerate() {
            let t = if i == 0 {
                t + inside
            } else if i + 1 == cuts.len() {
                t - inside
            } else {
                t
            };
            end_points.push((k, t));
        }
        for (i, w) in cuts.windows(2).enumerate() {
            pieces.push((k, w[0], w[1]));
            end_index.push(first + i);
        }
    }
    let end_values = eval(&end_points)?;
    // the whole-panel rule and the split nodes of every starting panel, in one batch
    let per_piece = rule.gl.len() + rule.halves.len() + 1;
    let mut inner: Vec<(usize, f64)> = Vec::with_capacity(pieces.len() * per_piece);
    inner.extend(pieces.iter().flat_map(|&(k, a, b)| {
        rule.gl
            .mapped(a, b)
            .map(|(t, _)| t)
            .chain(split_nodes(rule, (a, b)))
            .map(move |t| (k, t))
    }));
    let inner_values = eval(&inner)?;
    let mut panels: Vec<Panel> = pieces
        .iter()
        .zip(&end_index)
        .zip(inner_values.chunks(per_piece))
        .map(|((&(k, a, b), &e), ys)| {
            let n = rule.gl.len();
            let whole: f64 = rule
                .gl
                .mapped(a, b)
                .zip(&ys[..n])
                .map(|((_, w), y)| w * y)
                .sum();
            panel(
                rule,
                k,
                (a, b),
                (end_values[e], end_values[e + 1]),
                whole,
                &ys[n..],
                noise,
            )
        })
        .collect();
    // Noise floor: no estimate is trusted below the integrand's noise; a target below the
    // floor is raised to it.
    let floor_rel = 8.0 * noise;
    let error_of = |p: &Panel| p.error.max(floor_rel * p.abs);
    let mut heap: std::collections::BinaryHeap<(Key, usize)> = panels
        .iter()
        .enumerate()
        .map(|(i, p)| (Key(error_of(p)), i))
        .collect();
    let mut alive = vec![true; panels.len()];
    let (mut abs, mut error, mut value_now) = panels.iter().fold((0.0, 0.0, 0.0), |s, p| {
        (s.0 + p.abs, s.1 + error_of(p), s.2 + p.left + p.right)
    });
    loop {
        let target = (tol.rel * value_now.abs())
            .max(tol.rel_of_abs * abs)
            .max(tol.abs)
            .max(2.0 * floor_rel * abs);
        let stagnated = heap.len() >= tol.max_panels
            || heap.peek().is_some_and(|&(_, i)| {
                let m = 0.5 * (panels[i].a + panels[i].b);
                !(m > panels[i].a && m < panels[i].b)
            });
        if stagnated && error > STAGNATION_ALLOWANCE * target {
            return Err(CoreError::Quadrature {
                what,
                achieved: error,
                tolerance: target,
            }
            .into());
        }
        if error <= target || stagnated {
            // sums afresh, free of the drift of the running totals
            let mut live: Vec<&Panel> = panels
                .iter()
                .zip(&alive)
                .filter(|(_, &a)| a)
                .map(|(p, _)| p)
                .collect();
            live.sort_by(|p, q| p.k.cmp(&q.k).then(p.a.total_cmp(&q.a)));
            let (value, error) = live.iter().fold((0.0, 0.0), |s, p| {
                (s.0 + p.left + p.right, s.1 + error_of(p))
            });
            if !want_nodes {
                return Ok((
                    Integral {
                        value,
                        error,
                        evaluations,
                    },
                    Vec::new(),
                ));
            }
            let nodes = live
                .iter()
                .map(|p| {
                    let (c, m) = (0.5 * (p.b - p.a), 0.5 * (p.a + p.b));
                    let mut points = Vec::with_capacity(p.ys.len() + 2);
                    points.push((p.a, p.fa));
                    points.extend(
                        rule.halves
                            .iter()
                            .zip(&p.ys)
                            .map(|(&(x, _), &y)| (m + c * x, y)),
                    );
                    points.push((p.b, p.fb));
                    PanelNodes {
                        a: p.a,
                        b: p.b,
                        points,
                        value: p.left + p.right,
                        error: error_of(p),
                    }
                })
                .collect();
            return Ok((
                Integral {
                    value,
                    error,
                    evaluations,
                },
                nodes,
            ));
        }
        let Some((_, worst)) = heap.pop() else {
            unreachable!("a positive error has a panel")
        };
        let (a, b, k) = (panels[worst].a, panels[worst].b, panels[worst].k);
        let m = 0.5 * (a + b);
        alive[worst] = false;
        let (fa, fm, fb, pl, pr) = {
            let p = &panels[worst];
            (p.fa, p.fm, p.fb, p.left, p.right)
        };
        // both children's nodes in one batch; the parent's halves are their whole-panel values
        let pts: Vec<(usize, f64)> = split_nodes(rule, (a, m))
            .chain(split_nodes(rule, (m, b)))
            .map(|t| (k, t))
            .collect();
        let ys = eval(&pts)?;
        let (yl, yr) = ys.split_at(rule.halves.len() + 1);
        let left = panel(rule, k, (a, m), (fa, fm), pl, yl, noise);
        let right = panel(rule, k, (m, b), (fm, fb), pr, yr, noise);
        abs += left.abs + right.abs - panels[worst].abs;
        value_now += left.left + left.right + right.left + right.right
            - panels[worst].left
            - panels[worst].right;
        error += error_of(&left) + error_of(&right) - error_of(&panels[worst]);
        for child in [left, right] {
            heap.push((Key(error_of(&child)), panels.len()));
            panels.push(child);
            alive.push(true);
        }
    }
}

/// A total order on error estimates for the refinement heap.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Key(f64);
impl Eq for Key {}
impl PartialOrd for Key {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Key {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// n-point Gauss-Legendre rule on [-1, 1], nodes from Newton's iteration on P_n.
#[derive(Debug, Clone, PartialEq)]
pub struct GaussLegendre {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl GaussLegendre {
    /// The n-point rule (n >= 1), exact for polynomials of degree 2n - 1.
    pub fn new(n: usize) -> Self {
        let n = n.max(1);
        let mut nodes = vec![0.0; n];
        let mut weights = vec![0.0; n];
        for i in 0..n.div_ceil(2) {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (p, d) = legendre(n, x);
                dp = d;
                let dx = p / d;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            let (_, d) = legendre(n, x);
            dp = if d != 0.0 { d } else { dp };
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            nodes[i] = -x;
            nodes[n - 1 - i] = x;
            weights[i] = w;
            weights[n - 1 - i] = w;
        }
        Self { nodes, weights }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Always false: a rule has at least one node.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Nodes mapped to [a, b] with their weights (sum of weights = b - a).
    pub fn mapped(&self, a: f64, b: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
        let c = 0.5 * (b - a);
        let m = 0.5 * (a + b);
        self.nodes
            .iter()
            .zip(&self.weights)
            .map(move |(x, w)| (m + c * x, c * w))
    }

    /// Integral of f on [a, b].
    pub fn integrate<F: FnMut(f64) -> f64>(&self, mut f: F, a: f64, b: f64) -> f64 {
        self.mapped(a, b).map(|(x, w)| w * f(x)).sum()
    }
}

/// P_n(x) and P_n'(x) by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=n {
        let k = k as f64;
        let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    if n == 0 {
        return (1.0, 0.0);
    }
    (p1, n as f64 * (x * p1 - p0) / (x * x - 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    type R<T> = Result<T, CoreError>;

    /// 14 nodes (eq 17's panels with 6-node halves) on a panel 8 ulps wide at x = -2.35e-8
    /// (a panel refined to rounding): the nodes round onto 9 values, several twice. The
    /// interpolant keeps one point per x, stays finite, and reproduces a linear function
    /// of x there to rounding; the weights of the raw nodes were infinite.
    #[test]
    fn an_interpolant_on_a_panel_a_few_ulps_wide_stays_finite() {
        let a = -2.35e-8_f64;
        let ulp = a.abs() * f64::EPSILON;
        let w = 8.0 * ulp;
        let f = |x: f64| 3.0 + (x - a) / w;
        let pts: Vec<(f64, f64)> = (0..14)
            .map(|i| {
                let x = a + w * (1.0 - (std::f64::consts::PI * i as f64 / 13.0).cos()) / 2.0;
                (x, f(x))
            })
            .collect();
        let distinct = {
            let mut xs: Vec<f64> = pts.iter().map(|p| p.0).collect();
            xs.dedup();
            xs.len()
        };
        assert!(distinct < 14, "the test needs repeated nodes");
        let p = Interpolant::new(&pts);
        for &(x, y) in &pts {
            let got = p.eval(x);
            assert!(got.is_finite() && (got - y).abs() <= 1e-12, "{got} vs {y}");
        }
        let mid = p.eval(a + 0.5 * w);
        assert!(mid.is_finite() && (mid - 3.5).abs() <= 0.2, "{mid}");
        assert!(p.integral(a, a + w).is_finite());
    }

    #[test]
    fn brent_reports_missing_bracket_and_closure_errors() {
        let e = brent("sq", |x| R::Ok(x * x + 1.0), -1.0, 1.0, Tolerance::ROOT).unwrap_err();
        assert!(matches!(e, CoreError::NotBracketed { .. }));
        let e = brent(
            "fails",
            |x| {
                if x > 0.5 {
                    Err(CoreError::NotFinite { what: "inner", x })
                } else {
                    Ok(x - 0.7)
                }
            },
            0.0,
            1.0,
            Tolerance::ROOT,
        )
        .unwrap_err();
        assert!(matches!(e, CoreError::NotFinite { what: "inner", .. }));
        let e = brent(
            "nan",
            |x| R::Ok(if x > 0.1 { f64::NAN } else { -1.0 }),
            0.0,
            1.0,
            Tolerance::ROOT,
        )
        .unwrap_err();
        assert!(matches!(e, CoreError::NotFinite { what: "nan", .. }));
    }

    #[test]
    fn brent_meets_an_absolute_tolerance_and_its_iteration_cap() {
        let r = brent(
            "lin",
            |x| R::Ok(x - 0.3),
            -1.0,
            1.0,
            Tolerance::absolute(1e-3),
        )
        .unwrap();
        assert!((r - 0.3).abs() <= 1e-3);
        let e = brent(
            "cap",
            |x| R::Ok(x.powi(3) - 0.1),
            0.0,
            1.0,
            Tolerance::ROOT.with_max_iter(2),
        )
        .unwrap_err();
        assert!(matches!(e, CoreError::NoConvergence { iterations: 2, .. }));
    }

    #[test]
    fn local_min_finds_a_parabola_vertex_to_rounding_in_value() {
        let m = local_min(
            "parabola",
            |x| R::Ok((x - 0.3) * (x - 0.3) + 2.0),
            -1.0,
            1.0,
            Tolerance::absolute(1e-12),
        )
        .unwrap();
        // the value is exact to rounding; the location only to sqrt(eps) ~ 1.5e-8, since
        // f(0.3 + e) = 2 + e^2 rounds to 2 for |e| < 1e-8
        assert!((m.value - 2.0).abs() <= 4.0 * f64::EPSILON, "{m:?}");
        assert!((m.x - 0.3).abs() < 3e-8, "{m:?}");
        assert!(m.evaluations < 60, "parabolic steps converge fast: {m:?}");
    }

    #[test]
    fn grid_min_refines_the_deepest_of_several_wells() {
        // two wells; the deeper is the narrower and falls between samples' best guess
        let f = |x: f64| {
            R::Ok(-(-((x - 0.2) / 0.05).powi(2)).exp() - 1.5 * (-((x - 0.71) / 0.02).powi(2)).exp())
        };
        let grid: Vec<f64> = linspace(0.0, 1.0, 41).collect();
        let m = grid_min("two wells", f, &grid, Tolerance::relative(1e-9)).unwrap();
        assert!((m.x - 0.71).abs() < 1e-4, "{m:?}");
        assert!(m.value < -1.5 + 1e-9 && m.value > -1.6);
    }

    #[test]
    fn sampling_helpers_hit_their_end_points_exactly() {
        let v: Vec<f64> = linspace(1e-9, 3e-9, 7).collect();
        assert_eq!((v[0], v[6]), (1e-9, 3e-9));
        assert!(v.windows(2).all(|w| w[1] > w[0]));
        let g: Vec<f64> = geomspace(1e-12, 1e-6, 25).collect();
        assert_eq!((g[0], g[24]), (1e-12, 1e-6));
        assert!((g[4] / g[0] - 10.0).abs() < 1e-12, "{}", g[4] / g[0]);
        assert_eq!(linspace(2.0, 5.0, 1).collect::<Vec<_>>(), vec![2.0]);
    }

    #[test]
    fn gauss_legendre_is_exact_to_degree_2n_minus_1() {
        for n in [1usize, 2, 5, 8, 20] {
            let g = GaussLegendre::new(n);
            let deg = 2 * n - 1;
            let v = g.integrate(|x| x.powi(deg as i32) + x.powi(deg as i32 - 1), 0.0, 2.0);
            let exact =
                2f64.powi(deg as i32 + 1) / (deg as f64 + 1.0) + 2f64.powi(deg as i32) / deg as f64;
            assert!((v / exact - 1.0).abs() < 1e-13, "n={n}: {v} vs {exact}");
        }
    }

    fn tol(rel: f64) -> QuadTolerance {
        QuadTolerance {
            rel,
            rel_of_abs: rel,
            abs: 0.0,
            max_width: 0.0,
            max_panels: 10_000,
            noise: NOISE,
        }
    }

    #[test]
    fn adaptive_rule_meets_its_tolerance_on_a_gaussian_and_its_estimate_is_honest() {
        let rule = AdaptiveRule::new(6).unwrap();
        let exact = (2.0 * std::f64::consts::PI).sqrt() * 0.5 * (1.0 + erf_ref(3.0 / 2f64.sqrt()));
        for rel in [1e-4, 1e-8, 1e-12] {
            let r = integrate(
                "gauss",
                |x| R::Ok((-0.5 * x * x).exp()),
                &[-12.0, 3.0],
                false,
                &rule,
                tol(rel),
            )
            .unwrap();
            let err = (r.value - exact).abs();
            assert!(
                err <= r.error.max(1e-15 * exact),
                "rel {rel}: err {err:e} > estimate {:e}",
                r.error
            );
            assert!(err <= rel * exact, "rel {rel}: err {err:e}");
        }
    }

    #[test]
    fn edge_substitution_resolves_square_root_and_hertz_edges() {
        let rule = AdaptiveRule::new(6).unwrap();
        for (p, exact) in [(0.5, 2.0 / 3.0), (1.5, 0.4)] {
            let plain = integrate(
                "edge",
                |x: f64| R::Ok(x.powf(p)),
                &[0.0, 1.0],
                false,
                &rule,
                tol(1e-12),
            )
            .unwrap();
            let sub = integrate(
                "edge",
                |x: f64| R::Ok(x.powf(p)),
                &[0.0, 1.0],
                true,
                &rule,
                tol(1e-12),
            )
            .unwrap();
            assert!((sub.value - exact).abs() < 1e-14, "p {p}: {}", sub.value);
            assert!(
                (plain.value - exact).abs() < 1e-11,
                "p {p}: {}",
                plain.value
            );
            assert!(
                sub.evaluations < plain.evaluations,
                "p {p}: {} vs {}",
                sub.evaluations,
                plain.evaluations
            );
        }
    }

    #[test]
    fn an_unannounced_kink_is_refined_around_not_a_source_of_error() {
        // |x - 0.3137| on [0, 1], no break point at the kink
        let rule = AdaptiveRule::new(6).unwrap();
        let k = 0.3137;
        let exact = 0.5 * (k * k + (1.0 - k) * (1.0 - k));
        let r = integrate(
            "kink",
            |x: f64| R::Ok((x - k).abs()),
            &[0.0, 1.0],
            false,
            &rule,
            tol(1e-12),
        )
        .unwrap();
        assert!((r.value - exact).abs() < 1e-12, "{} vs {exact}", r.value);
    }

    #[test]
    fn hidden_kinks_and_steps_anywhere_in_the_range_meet_the_tolerance() {
        // 500 positions spread by the golden ratio, including the slivers between a
        // panel's end and its first node, where every Gauss rule sees a smooth function
        for n in [4usize, 6] {
            let rule = AdaptiveRule::new(n).unwrap();
            for rel in [1e-6, 1e-10] {
                for j in 0..500 {
                    let k = 0.0005 + 0.999 * (j as f64 * 0.618_033_988_749_894_9).fract();
                    let kink = 0.5 * (k * k + (1.0 - k) * (1.0 - k));
                    let r = integrate(
                        "kink",
                        |x: f64| R::Ok((x - k).abs()),
                        &[0.0, 1.0],
                        false,
                        &rule,
                        tol(rel),
                    )
                    .unwrap();
                    assert!(
                        (r.value - kink).abs() <= rel * kink,
                        "n {n} rel {rel} kink at {k}: {}",
                        r.value
                    );
                    let step = 1.0 - 0.5 * k;
                    let r = integrate(
                        "step",
                        |x: f64| R::Ok(if x > k { 1.0 } else { 0.5 }),
                        &[0.0, 1.0],
                        false,
                        &rule,
                        tol(rel),
                    )
                    .unwrap();
                    assert!(
                        (r.value - step).abs() <= rel * step,
                        "n {n} rel {rel} step at {k}: {}",
                        r.value
                    );
                }
            }
        }
    }

    #[test]
    fn a_tolerance_below_rounding_is_raised_to_the_rounding_floor() {
        let rule = AdaptiveRule::new(6).unwrap();
        let exact = (2.0 * std::f64::consts::PI).sqrt();
        let r = integrate(
            "gauss",
            |x: f64| R::Ok((-0.5 * x * x).exp()),
            &[-12.0, 12.0],
            false,
            &rule,
            tol(1e-30),
        )
        .unwrap();
        assert!((r.value - exact).abs() < 1e-14 * exact);
        // the estimate stops at the rounding floor of the end extrapolation
        assert!(r.error < 1e-10 * exact && r.evaluations < 2000, "{r:?}");
    }

    #[test]
    fn quadrature_reports_failure_instead_of_a_wrong_value() {
        let rule = AdaptiveRule::new(4).unwrap();
        let mut t = tol(1e-14);
        t.max_panels = 4;
        let e = integrate(
            "wild",
            |x: f64| R::Ok((50.0 * x).sin().abs()),
            &[0.0, 10.0],
            false,
            &rule,
            t,
        )
        .unwrap_err();
        assert!(matches!(e, CoreError::Quadrature { .. }));
        let e = integrate(
            "nan",
            |x: f64| R::Ok(if x > 0.5 { f64::NAN } else { x }),
            &[0.0, 1.0],
            false,
            &rule,
            tol(1e-6),
        )
        .unwrap_err();
        assert!(matches!(e, CoreError::NotFinite { what: "nan", .. }));
    }

    /// erf by its Taylor series (|x| < 3), an independent reference for the test above.
    fn erf_ref(x: f64) -> f64 {
        let mut term = x;
        let mut sum = x;
        for n in 1..200 {
            term *= -x * x / n as f64;
            sum += term / (2 * n + 1) as f64;
        }
        2.0 / std::f64::consts::PI.sqrt() * sum
    }
}
