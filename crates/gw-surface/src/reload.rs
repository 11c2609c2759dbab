//! The reload work of one asperity, tabulated once per surface: what eq 17 needs of the
//! approach above the deepest separation a flat reached (docs/theory.md section 6.2).

use crate::blocks::{Blocks, Cache, Span, MAX_BLOCK_PIECES};
use crate::error::GwError;
use crate::virgin::{VirginPiece, VirginTable};
use contact_core::numeric::{integrate, AdaptiveRule, QuadTolerance, NOISE};
use contact_core::{par, AsperityHistory, AsperityModel, Path};
use std::sync::Arc;

/// Chebyshev-Lobatto points per piece (a polynomial of degree 16).
pub(crate) const NODES: usize = 17;
/// Halvings of a block before a piece is accepted with the error it has.
pub(crate) const MAX_DEPTH: u32 = 24;

/// The Chebyshev-Lobatto points cos(j pi / 16), j = 0..=16.
fn lobatto() -> &'static [f64; NODES] {
    static POINTS: std::sync::OnceLock<[f64; NODES]> = std::sync::OnceLock::new();
    POINTS.get_or_init(|| {
        std::array::from_fn(|j| (std::f64::consts::PI * j as f64 / (NODES - 1) as f64).cos())
    })
}

/// One piece of the table: R (J) and the peak force P (N) at the Chebyshev-Lobatto points
/// of [a, b], and the estimates of their interpolation errors anywhere on it.
#[derive(Debug, Clone)]
pub(crate) struct Piece {
    a: f64,
    b: f64,
    values: [f64; NODES],
    error: f64,
    peaks: [f64; NODES],
    peak_error: f64,
}

impl Piece {
    /// The point of node `j` (x_0 = b, x_16 = a).
    pub(crate) fn node(a: f64, b: f64, j: usize) -> f64 {
        0.5 * (a + b) + 0.5 * (b - a) * lobatto()[j]
    }

    /// The interpolant of `values` at `x` (barycentric formula of the second kind on the
    /// Lobatto points of [a, b]: weights (-1)^j, halved at both ends).
    pub(crate) fn interpolate(a: f64, b: f64, values: &[f64; NODES], x: f64) -> f64 {
        let t = (2.0 * x - a - b) / (b - a);
        let (mut num, mut den) = (0.0, 0.0);
        for (j, (&tj, &v)) in lobatto().iter().zip(values).enumerate() {
            let diff = t - tj;
            if diff == 0.0 {
                return v;
            }
            let mut w = if j % 2 == 0 { 1.0 } else { -1.0 };
            if j == 0 || j == NODES - 1 {
                w *= 0.5;
            }
            let c = w / diff;
            num += c * v;
            den += c;
        }
        num / den
    }

    /// The interpolation error estimate: the sum of the three highest Chebyshev
    /// coefficients' magnitudes (where the series has converged they bound its tail).
    pub(crate) fn tail(values: &[f64; NODES]) -> f64 {
        let n = NODES - 1;
        (n - 2..=n)
            .map(|k| {
                let mut c = 0.0;
                for (j, v) in values.iter().enumerate() {
                    let w = if j == 0 || j == n { 0.5 } else { 1.0 };
                    c += w * v * (std::f64::consts::PI * (k * j) as f64 / n as f64).cos();
                }
                let c = 2.0 * c / n as f64;
                if k == n {
                    0.5 * c.abs()
                } else {
                    c.abs()
                }
            })
            .sum()
    }
}

/// R(x) = integral from j(x) to x of F(w; delta_max = x, approach) dw (J), the work of one
/// asperity reloading to its own largest interference x (m), with j(x) its jump-in; zero
/// where x <= j(x). On a flat's history the asperity of height h has x = h - D, so the
/// approach work above D is N integral R(h - D) phi(h) dh. Beside it P(x), the largest
/// force on that reload: F(x) where no quadrature node exceeds it (then exactly the end
/// value), else the peak found by a golden-section search around the best node, raised by
/// PEAK_MARGIN.
///
/// Tabulated in pieces of degree 16 in x, on fixed blocks: their ends are the virgin
/// jump-in, zero, the asperity's plastic breaks and the doubling points 2^k R/1000 (R the
/// asperity's radius). Each block is halved until the three
/// highest Chebyshev coefficients of each piece sum to at most `eps` times the largest |R|
/// on the block (likewise P). The blocks do not depend on what was asked first, so neither
/// does a result.
pub(crate) type ReloadTable = Blocks<Piece>;

impl Span for Piece {
    fn end(&self) -> f64 {
        self.b
    }
}

impl ReloadTable {
    /// R(x) (J), x within [x_min, x_max]; 0 below x_min.
    pub(crate) fn eval(&self, x: f64) -> f64 {
        self.piece(x)
            .map_or(0.0, |p| Piece::interpolate(p.a, p.b, &p.values, x))
    }

    /// An upper bound on the largest force (N) of the asperity on its reload up to x:
    /// the interpolated peak plus the piece's error estimate; 0 below x_min.
    pub(crate) fn peak_bound(&self, x: f64) -> f64 {
        self.piece(x).map_or(0.0, |p| {
            Piece::interpolate(p.a, p.b, &p.peaks, x) + p.peak_error
        })
    }

    /// Each piece's range and the error estimate of R on it (m, m, J).
    pub(crate) fn pieces_errors(&self) -> impl Iterator<Item = (f64, f64, f64)> + '_ {
        self.pieces.iter().map(|p| (p.a, p.b, p.error))
    }
}

/// One R(x) by an adaptive integral to `rel` of the integral of |F|, split at the
/// asperity's kinks; the force rises like a square root from the jump-in at worst (the
/// stable branch's end), hence the edge substitution there.
fn reload_work<M: AsperityModel>(
    asperity: &M,
    x: f64,
    rule: &AdaptiveRule,
    rel: f64,
) -> Result<(f64, f64), GwError> {
    let hist = AsperityHistory { delta_max: x };
    let fail = |source| GwError::Asperity {
        height: x,
        d: 0.0,
        source,
    };
    let j = asperity.jump_in(hist).map_err(fail)?;
    if !(x > j) {
        return Ok((0.0, 0.0));
    }
    let finite = |f: f64| {
        if f.is_finite() {
            Ok(f)
        } else {
            Err(GwError::LawNotFinite {
                height: x,
                d: 0.0,
                value: f,
            })
        }
    };
    let end = finite(asperity.force(x, hist, Path::Approach).map_err(fail)?)?;
    let mut inner = (f64::NEG_INFINITY, x);
    let mut breaks = vec![j];
    let mut kinks: Vec<f64> = asperity
        .kinks(hist)
        .map_err(fail)?
        .into_iter()
        .flatten()
        .filter(|&k| k > j && k < x)
        .collect();
    kinks.sort_by(f64::total_cmp);
    breaks.extend(kinks);
    breaks.push(x);
    let tol = QuadTolerance {
        rel: 0.0,
        rel_of_abs: rel,
        abs: 0.0,
        max_width: 0.0,
        max_panels: 20_000,
        noise: NOISE,
    };
    let r = integrate(
        "reload work of one asperity",
        |w: f64| {
            let f = finite(asperity.force(w, hist, Path::Approach).map_err(fail)?)?;
            if f > inner.0 {
                inner = (f, w);
            }
            Ok::<_, GwError>(f)
        },
        &breaks,
        true,
        rule,
        tol,
    )?;
    if !(inner.0 > end) {
        return Ok((r.value, end));
    }
    // a peak inside: golden-section search around the best node, within PEAK_BRACKET of
    // the reload's range either side, to PEAK_WIDTH of that range
    let force = |w: f64| -> Result<f64, GwError> {
        finite(asperity.force(w, hist, Path::Approach).map_err(fail)?)
    };
    let half = PEAK_BRACKET * (x - j);
    let (mut a, mut b) = ((inner.1 - half).max(j), (inner.1 + half).min(x));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (force(c)?, force(d)?);
    let mut best = inner.0.max(fc).max(fd);
    while b - a > PEAK_WIDTH * (x - j) {
        if fc > fd {
            (b, d, fd) = (d, c, fc);
            c = b - g * (b - a);
            fc = force(c)?;
            best = best.max(fc);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + g * (b - a);
            fd = force(d)?;
            best = best.max(fd);
        }
    }
    Ok((r.value, best + PEAK_MARGIN * best.abs()))
}

/// Gauss-Legendre nodes per half panel of each R's integral (the surfaces' default).
const RULE_NODES: usize = 6;
/// Half the bracket of the search for a force peak inside a reload, in the reload's range.
const PEAK_BRACKET: f64 = 0.02;
/// The golden-section search for a peak stops at this fraction of the reload's range
/// (where the force is flat to about its square, far below PEAK_TOLERANCE).
const PEAK_WIDTH: f64 = 1e-5;
/// Headroom on a force peak found inside a reload.
const PEAK_MARGIN: f64 = 1e-6;
/// The peak force is tabulated to this fraction of its largest value on a block.
const PEAK_TOLERANCE: f64 = 1e-4;

impl ReloadTable {
    /// The pieces of the block [a, b], false past [`MAX_BLOCK_PIECES`].
    fn block<M: AsperityModel + Sync>(
        &mut self,
        asperity: &M,
        a: f64,
        b: f64,
        first: usize,
        rule: &AdaptiveRule,
    ) -> Result<bool, GwError> {
        let rel = self.eps / 16.0;
        let xs: Vec<f64> = (0..NODES).map(|j| Piece::node(a, b, j)).collect();
        let both = split(par::map(&xs, |&x| reload_work(asperity, x, rule, rel))?);
        let scale = |v: &[f64; NODES]| v.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let tol = (self.eps * scale(&both.0), PEAK_TOLERANCE * scale(&both.1));
        self.refine(asperity, a, b, both, tol, 0, first, rule)
    }

    /// Accepts [a, b] as one piece when the tails of R and P are within `tol` (J, N),
    /// else halves it (at the geometric mean where it spans more than a factor 4 above
    /// zero). False when the block begun at piece `first` would take more than
    /// [`MAX_BLOCK_PIECES`].
    #[allow(clippy::too_many_arguments)]
    fn refine<M: AsperityModel + Sync>(
        &mut self,
        asperity: &M,
        a: f64,
        b: f64,
        (values, peaks): ([f64; NODES], [f64; NODES]),
        tol: (f64, f64),
        depth: u32,
        first: usize,
        rule: &AdaptiveRule,
    ) -> Result<bool, GwError> {
        if self.pieces.len() - first >= MAX_BLOCK_PIECES {
            return Ok(false);
        }
        let error = Piece::tail(&values);
        let peak_error = Piece::tail(&peaks);
        if (error <= tol.0 && peak_error <= tol.1) || depth >= MAX_DEPTH {
            self.pieces.push(Piece {
                a,
                b,
                values,
                error,
                peaks,
                peak_error,
            });
            return Ok(true);
        }
        let m = if a > 0.0 && b > 4.0 * a {
            (a * b).sqrt()
        } else {
            0.5 * (a + b)
        };
        let rel = self.eps / 16.0;
        let xs: Vec<f64> = (0..NODES)
            .map(|j| Piece::node(a, m, j))
            .chain((0..NODES).map(|j| Piece::node(m, b, j)))
            .collect();
        let mut v = par::map(&xs, |&x| reload_work(asperity, x, rule, rel))?;
        let right = split(v.split_off(NODES));
        let left = split(v);
        Ok(
            self.refine(asperity, a, m, left, tol, depth + 1, first, rule)?
                && self.refine(asperity, m, b, right, tol, depth + 1, first, rule)?,
        )
    }
}

/// NODES pairs (R, P) as two arrays.
fn split(v: Vec<(f64, f64)>) -> ([f64; NODES], [f64; NODES]) {
    let mut out = ([0.0; NODES], [0.0; NODES]);
    for (j, (r, p)) in v.into_iter().take(NODES).enumerate() {
        out.0[j] = r;
        out.1[j] = p;
    }
    out
}

/// The reload work of one asperity, tabulated ([`crate::GreenwoodWilliamson`] builds it
/// on first use by eq 17's search, one table per tolerance decade). It depends on the
/// asperity model alone, not on the roughness: surfaces of the same asperity may share it
/// ([`crate::GreenwoodWilliamson::with_reload_tables`]), as the points of a design map do.
#[derive(Debug, Default)]
pub struct ReloadTables {
    reload: Cache<Piece>,
    virgin: Cache<VirginPiece>,
}

impl ReloadTables {
    /// The table of `asperity` to within `eps` (rounded down to a power of ten) covering
    /// x up to `x_need` (m); only the table of that very decade serves ([`Cache::table`]).
    pub(crate) fn table<M: AsperityModel + Sync>(
        &self,
        asperity: &M,
        eps: f64,
        x_need: f64,
    ) -> Result<Arc<ReloadTable>, GwError> {
        // its own rule, so a table does not depend on the surface that built it
        let rule = &AdaptiveRule::new(RULE_NODES)?;
        self.reload.table(
            asperity,
            eps,
            x_need,
            "reload-work table",
            |t, a, b, first| t.block(asperity, a, b, first, rule),
        )
    }

    /// The virgin-loading table of `asperity` to within `eps` covering x up to `x_need`
    /// (m), likewise.
    pub(crate) fn virgin<M: AsperityModel + Sync>(
        &self,
        asperity: &M,
        eps: f64,
        x_need: f64,
    ) -> Result<Arc<VirginTable>, GwError> {
        self.virgin.table(
            asperity,
            eps,
            x_need,
            "virgin-loading table",
            |t, a, b, first| t.block(asperity, a, b, first),
        )
    }
}
