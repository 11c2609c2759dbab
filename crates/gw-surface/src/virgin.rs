//! The virgin loading of one asperity, tabulated once per surface: its force F_v(x) and
//! its work V(x) = integral from the virgin jump-in to x of F_v (what eq 17 needs below
//! the deepest separation a flat reached, where every asperity in contact loads on its
//! virgin curve; docs/theory.md section 6.2).

use crate::blocks::{Blocks, Span, MAX_BLOCK_PIECES};
use crate::error::GwError;
use crate::reload::{Piece, MAX_DEPTH, NODES};
use contact_core::{par, AsperityHistory, AsperityModel, Path};

/// One piece: F_v at the Lobatto points of [a, b], the Chebyshev coefficients of its
/// antiderivative in t in [-1, 1] (times (b - a)/2, zero at a), V(a), and the error
/// estimate of F_v's interpolant on the piece.
#[derive(Debug, Clone)]
pub(crate) struct VirginPiece {
    a: f64,
    b: f64,
    forces: [f64; NODES],
    work: [f64; NODES + 1],
    work_at_a: f64,
    error: f64,
    /// The error estimate of V at a: the pieces' before, each times its width.
    error_at_a: f64,
}

/// The Chebyshev coefficients a_k of the interpolant through `values` at the Lobatto
/// points (f(t) = sum a_k T_k(t), t_j = cos(j pi / n)).
fn coefficients(values: &[f64; NODES]) -> [f64; NODES] {
    let n = NODES - 1;
    let mut a = [0.0; NODES];
    for (k, ak) in a.iter_mut().enumerate() {
        let mut c = 0.0;
        for (j, v) in values.iter().enumerate() {
            let w = if j == 0 || j == n { 0.5 } else { 1.0 };
            c += w * v * (std::f64::consts::PI * (k * j) as f64 / n as f64).cos();
        }
        *ak = 2.0 * c / n as f64;
    }
    a[0] *= 0.5;
    a[n] *= 0.5;
    a
}

/// sum c_k T_k(t) by Clenshaw's recurrence.
fn clenshaw(c: &[f64], t: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    for &ck in c.iter().skip(1).rev() {
        let b0 = 2.0 * t * b1 - b2 + ck;
        b2 = b1;
        b1 = b0;
    }
    t * b1 - b2 + c[0]
}

impl VirginPiece {
    fn new(
        a: f64,
        b: f64,
        forces: [f64; NODES],
        error: f64,
        (work_at_a, error_at_a): (f64, f64),
    ) -> Self {
        // integral of sum a_k T_k: T_0 -> T_1, T_1 -> T_2/4, T_k -> T_k+1/(2(k+1)) -
        // T_k-1/(2(k-1)); then the constant that makes it zero at t = -1
        let c = coefficients(&forces);
        let n = NODES - 1;
        let mut w = [0.0; NODES + 1];
        for k in 1..=n + 1 {
            let prev = c[k - 1] * if k == 1 { 2.0 } else { 1.0 };
            let next = if k < n { c[k + 1] } else { 0.0 };
            w[k] = (prev - next) / (2.0 * k as f64);
        }
        w[0] = -(1..=n + 1)
            .map(|k| if k % 2 == 0 { w[k] } else { -w[k] })
            .sum::<f64>();
        let half = 0.5 * (b - a);
        for wk in &mut w {
            *wk *= half;
        }
        Self {
            a,
            b,
            forces,
            work: w,
            work_at_a,
            error,
            error_at_a,
        }
    }

    fn t(&self, x: f64) -> f64 {
        ((2.0 * x - self.a - self.b) / (self.b - self.a)).clamp(-1.0, 1.0)
    }

    /// The work on [a, x].
    fn work_to(&self, x: f64) -> f64 {
        clenshaw(&self.work, self.t(x))
    }
}

/// F_v(x) (N), the force of a never-pressed asperity loaded to interference x (m), and
/// V(x) (J) its work from the jump-in, tabulated in pieces of degree 16 on the same fixed
/// blocks as the reload table (`ReloadTable`), each block halved until the three highest
/// Chebyshev coefficients of F_v sum to at most `eps` times its largest |F_v| on the
/// block. V integrates the interpolants exactly; its error estimate is the integral of the
/// pieces' estimates.
pub(crate) type VirginTable = Blocks<VirginPiece>;

impl Span for VirginPiece {
    fn end(&self) -> f64 {
        self.b
    }
}

impl VirginTable {
    /// F_v(x) (N); 0 at and below the jump-in.
    pub(crate) fn force(&self, x: f64) -> f64 {
        self.piece(x)
            .map_or(0.0, |p| Piece::interpolate(p.a, p.b, &p.forces, x))
    }

    /// V(x) (J) and its error estimate; 0 at and below the jump-in.
    pub(crate) fn work(&self, x: f64) -> (f64, f64) {
        self.piece(x).map_or((0.0, 0.0), |p| {
            let error = p.error_at_a + p.error * (x.min(p.b) - p.a);
            (p.work_at_a + p.work_to(x), error)
        })
    }

    /// A bound on the integral of e_V(h - base) over a measure of heights, given its
    /// cumulative distribution `cdf(h)` (which must put no mass beyond base + x_max): e_V
    /// only grows with x, so each piece counts at its upper end (J). Pieces beyond the
    /// heights weigh nothing, so the sum does not depend on how far the table reaches.
    pub(crate) fn error_mass(&self, base: f64, cdf: impl Fn(f64) -> f64) -> f64 {
        self.pieces
            .iter()
            .map(|p| {
                (p.error_at_a + p.error * (p.b - p.a))
                    * (cdf(base + p.b) - cdf(base + p.a)).max(0.0)
            })
            .sum()
    }

    /// The pieces of the block [a, b] (from index `first` on), false past
    /// [`MAX_BLOCK_PIECES`].
    pub(crate) fn block<M: AsperityModel + Sync>(
        &mut self,
        asperity: &M,
        a: f64,
        b: f64,
        first: usize,
    ) -> Result<bool, GwError> {
        let values = forces(asperity, a, b)?;
        let tol = self.eps * values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        self.refine(asperity, a, b, values, tol, 0, first)
    }

    #[allow(clippy::too_many_arguments)]
    fn refine<M: AsperityModel + Sync>(
        &mut self,
        asperity: &M,
        a: f64,
        b: f64,
        values: [f64; NODES],
        tol: f64,
        depth: u32,
        first: usize,
    ) -> Result<bool, GwError> {
        if self.pieces.len() - first >= MAX_BLOCK_PIECES {
            return Ok(false);
        }
        let error = Piece::tail(&values);
        if error <= tol || depth >= MAX_DEPTH {
            let at_a = self.pieces.last().map_or((0.0, 0.0), |p| {
                (
                    p.work_at_a + p.work_to(p.b),
                    p.error_at_a + p.error * (p.b - p.a),
                )
            });
            self.pieces
                .push(VirginPiece::new(a, b, values, error, at_a));
            return Ok(true);
        }
        let m = if a > 0.0 && b > 4.0 * a {
            (a * b).sqrt()
        } else {
            0.5 * (a + b)
        };
        let (left, right) = par::join(|| forces(asperity, a, m), || forces(asperity, m, b));
        Ok(self.refine(asperity, a, m, left?, tol, depth + 1, first)?
            && self.refine(asperity, m, b, right?, tol, depth + 1, first)?)
    }
}

/// F_v at the Lobatto points of [a, b].
fn forces<M: AsperityModel>(asperity: &M, a: f64, b: f64) -> Result<[f64; NODES], GwError> {
    let mut out = [0.0; NODES];
    for (j, o) in out.iter_mut().enumerate() {
        let x = Piece::node(a, b, j);
        let f = asperity
            .force(x, AsperityHistory::VIRGIN, Path::Approach)
            .map_err(|source| GwError::Asperity {
                height: x,
                d: 0.0,
                source,
            })?;
        if !f.is_finite() {
            return Err(GwError::LawNotFinite {
                height: x,
                d: 0.0,
                value: f,
            });
        }
        *o = f;
    }
    Ok(out)
}
