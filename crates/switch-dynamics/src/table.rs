//! The contact pressure on one path, tabulated where the motion asks for it.

use contact_core::numeric::Interpolant;
use contact_core::{Estimate, LawError, Path, SurfaceLaw};
use std::cell::RefCell;
use std::collections::HashMap;

/// Nodes of a panel's interpolating polynomial (Chebyshev-Lobatto: both ends included).
const NODES: usize = 9;
/// Bisections of a base panel before its pieces are evaluated exactly.
const MAX_DEPTH: u32 = 14;

/// One panel: a polynomial through Chebyshev-Lobatto nodes that met the surface at four
/// interior points, two halves, or the surface itself.
#[derive(Debug, Clone)]
enum Panel {
    /// The polynomial, the evaluations' own error estimates at its nodes (x, Pa; by x) and
    /// its largest miss at the check points (Pa).
    Leaf(Interpolant, Vec<(f64, f64)>, f64),
    Split(f64, Box<Panel>, Box<Panel>),
    /// Evaluated directly; the error estimates of the evaluations made to try a polynomial
    /// there (x, Pa; by x).
    Exact(Vec<(f64, f64)>),
}

impl Panel {
    /// The integral over [lo, hi] ∩ [a, b] of the panel's error (Pa m), the panel spanning
    /// [a, b]: the evaluations' estimates by the trapezoidal rule (at the nearest node
    /// beyond the outermost ones) plus the largest miss.
    fn error_integral(&self, a: f64, b: f64, lo: f64, hi: f64) -> f64 {
        let (from, to) = (lo.max(a), hi.min(b));
        if !(to > from) {
            return 0.0;
        }
        match self {
            Panel::Leaf(_, errors, miss) => trapezoid(errors, from, to) + miss * (to - from),
            Panel::Exact(errors) => trapezoid(errors, from, to),
            Panel::Split(mid, left, right) => {
                left.error_integral(a, *mid, lo, hi) + right.error_integral(*mid, b, lo, hi)
            }
        }
    }
}

/// The integral over [from, to] of the piecewise-linear function through `points` (sorted
/// by x), constant beyond its ends.
fn trapezoid(points: &[(f64, f64)], from: f64, to: f64) -> f64 {
    let at = |x: f64| -> f64 {
        match points.iter().position(|p| p.0 >= x) {
            None => points.last().map_or(0.0, |p| p.1),
            Some(0) => points[0].1,
            Some(i) => {
                let (p, q) = (points[i - 1], points[i]);
                p.1 + (q.1 - p.1) * (x - p.0) / (q.0 - p.0)
            }
        }
    };
    let mut xs: Vec<f64> = vec![from];
    xs.extend(points.iter().map(|p| p.0).filter(|&x| x > from && x < to));
    xs.push(to);
    xs.windows(2)
        .map(|w| 0.5 * (at(w[0]) + at(w[1])) * (w[1] - w[0]))
        .sum()
}

/// The surface's pressure on `path` with `history`, built lazily in panels of `width` where
/// an evaluation falls: each panel's degree-8 polynomial through Chebyshev-Lobatto nodes is
/// checked against the surface at the four Chebyshev-Gauss points of degree 4 (the 13
/// evaluations of a panel run in parallel; none at or above the path's reach, where the
/// pressure is zero) and bisected
/// until it meets them to `tol` of max(|p| there, `floor`); after 14 bisections (a
/// kink: the deepest separation, where reloading turns into virgin loading) the surface is
/// evaluated directly there. A contact phase asks for the pressure thousands of times within
/// a few roughness scales: the table holds the surface's evaluations to about 13 a panel.
pub(crate) struct PressureTable<'a, S: SurfaceLaw> {
    surface: &'a S,
    history: S::History,
    path: Path,
    origin: f64,
    reach: f64,
    width: f64,
    tol: f64,
    floor: f64,
    panels: RefCell<HashMap<i64, Panel>>,
}

impl<'a, S: SurfaceLaw> PressureTable<'a, S> {
    /// A table on `path` with `history`, its panels `width` wide from `origin` (a kink of
    /// the pressure: the deepest separation of the history on approach, the excursion's
    /// extreme on a retraction), so that no panel straddles it.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        surface: &'a S,
        history: S::History,
        path: Path,
        origin: f64,
        reach: f64,
        width: f64,
        tol: f64,
        floor: f64,
    ) -> Self {
        Self {
            surface,
            history,
            path,
            origin,
            reach,
            width,
            tol,
            floor,
            panels: RefCell::new(HashMap::new()),
        }
    }

    /// Whether this table is for `history` on `path`, in panels of `width` to `tol` of
    /// max(|p|, `floor`).
    pub fn is_for(
        &self,
        history: &S::History,
        path: Path,
        width: f64,
        tol: f64,
        floor: f64,
    ) -> bool {
        self.path == path
            && self.width == width
            && self.tol == tol
            && self.floor == floor
            && &self.history == history
    }

    /// The surface's pressure; zero at and above the path's reach, where the law says it
    /// is (`SurfaceLaw::reach`), without evaluating it.
    fn exact(&self, d: f64) -> Result<f64, LawError> {
        if d >= self.reach {
            return Ok(0.0);
        }
        self.surface.pressure(d, &self.history, self.path)
    }

    /// The pressure at `d` (Pa).
    pub fn pressure(&self, d: f64) -> Result<f64, LawError> {
        if d >= self.reach {
            return Ok(0.0);
        }
        let k = ((d - self.origin) / self.width).floor();
        if !k.is_finite() || k.abs() > 1e15 {
            return self.exact(d);
        }
        let key = k as i64;
        if !self.panels.borrow().contains_key(&key) {
            let lo = self.origin + k * self.width;
            let panel = self.build(lo, lo + self.width, 0)?;
            self.panels.borrow_mut().insert(key, panel);
        }
        let panels = self.panels.borrow();
        let mut panel = &panels[&key];
        loop {
            match panel {
                Panel::Leaf(p, ..) => return Ok(p.eval(d)),
                Panel::Exact(_) => {
                    drop(panels);
                    return self.exact(d);
                }
                Panel::Split(mid, left, right) => panel = if d < *mid { left } else { right },
            }
        }
    }

    /// The integral over [lo, hi] of the error bound of the panels built there (Pa m): the
    /// error of the work the table's pressure does over that range, as far as the panels
    /// the motion asked for cover it (the pressure is exactly zero at and above the reach).
    pub fn error_integral(&self, lo: f64, hi: f64) -> f64 {
        let hi = hi.min(self.reach);
        self.panels
            .borrow()
            .iter()
            .map(|(&k, panel)| {
                let a = self.origin + k as f64 * self.width;
                panel.error_integral(a, a + self.width, lo, hi)
            })
            .sum()
    }

    /// The integral of the pressure over [lo, hi] (Pa m): exact on the panels' polynomials,
    /// Gauss-Legendre (8 nodes) on the surface where a panel evaluates it directly; the
    /// panels over the range are built if the motion has not asked for them.
    pub fn work(&self, lo: f64, hi: f64) -> Result<f64, LawError> {
        let hi = hi.min(self.reach);
        if !(hi > lo) {
            return Ok(0.0);
        }
        let first = ((lo - self.origin) / self.width).floor() as i64;
        let last = ((hi - self.origin) / self.width).floor() as i64;
        let mut total = 0.0;
        for k in first..=last {
            let a = self.origin + k as f64 * self.width;
            // build the panel (a pressure inside it asks for it)
            self.pressure(a.max(lo).min(hi))?;
            let panels = self.panels.borrow();
            total += self.panel_work(&panels[&k], a, a + self.width, lo, hi)?;
        }
        Ok(total)
    }

    fn panel_work(&self, panel: &Panel, a: f64, b: f64, lo: f64, hi: f64) -> Result<f64, LawError> {
        let (from, to) = (lo.max(a), hi.min(b));
        if !(to > from) {
            return Ok(0.0);
        }
        Ok(match panel {
            Panel::Leaf(poly, ..) => poly.integral(from, to),
            Panel::Split(mid, left, right) => {
                self.panel_work(left, a, *mid, lo, hi)? + self.panel_work(right, *mid, b, lo, hi)?
            }
            Panel::Exact(_) => {
                let gl = contact_core::numeric::GaussLegendre::new(8);
                let mut w = 0.0;
                for (x, wt) in gl.mapped(from, to) {
                    w += wt * self.exact(x)?;
                }
                w
            }
        })
    }

    fn build(&self, lo: f64, hi: f64, depth: u32) -> Result<Panel, LawError> {
        let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        let pi = std::f64::consts::PI;
        // the nodes, then the four check points: evaluated together, in parallel
        let mut xs: Vec<f64> = (0..NODES)
            .map(|j| mid + half * (pi * j as f64 / (NODES - 1) as f64).cos())
            .collect();
        xs.extend((0..4).map(|i| mid + half * (pi * (2 * i + 1) as f64 / 8.0).cos()));
        let (surface, history, path, reach) = (self.surface, &self.history, self.path, self.reach);
        let estimates = contact_core::par::map(&xs, |&x| {
            if x >= reach {
                Ok(Estimate {
                    value: 0.0,
                    error: 0.0,
                })
            } else {
                surface.pressure_estimate(x, history, path)
            }
        })?;
        let values: Vec<f64> = estimates.iter().map(|e| e.value).collect();
        let mut own: Vec<(f64, f64)> = xs
            .iter()
            .zip(&estimates)
            .map(|(&x, e)| (x, e.error))
            .collect();
        own.sort_by(|p, q| p.0.total_cmp(&q.0));
        let points: Vec<(f64, f64)> = xs[..NODES]
            .iter()
            .copied()
            .zip(values[..NODES].iter().copied())
            .collect();
        let poly = Interpolant::new(&points);
        let misses: Vec<(f64, f64)> = xs[NODES..]
            .iter()
            .zip(&values[NODES..])
            .map(|(&x, &p)| ((poly.eval(x) - p).abs(), self.tol * p.abs().max(self.floor)))
            .collect();
        if misses.iter().all(|&(miss, allowed)| miss <= allowed) {
            let miss = misses.iter().map(|m| m.0).fold(0.0, f64::max);
            return Ok(Panel::Leaf(poly, own, miss));
        }
        if depth >= MAX_DEPTH {
            return Ok(Panel::Exact(own));
        }
        Ok(Panel::Split(
            mid,
            Box::new(self.build(lo, mid, depth + 1)?),
            Box::new(self.build(mid, hi, depth + 1)?),
        ))
    }
}
