//! The contact pressure on one path, tabulated where the motion asks for it.

use contact_core::numeric::Interpolant;
use contact_core::{LawError, Path, SurfaceLaw};
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
    Leaf(Interpolant),
    Split(f64, Box<Panel>, Box<Panel>),
    Exact,
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

    /// Whether this table is for `history` on `path`.
    pub fn is_for(&self, history: &S::History, path: Path) -> bool {
        self.path == path && &self.history == history
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
                Panel::Leaf(p) => return Ok(p.eval(d)),
                Panel::Exact => {
                    drop(panels);
                    return self.exact(d);
                }
                Panel::Split(mid, left, right) => panel = if d < *mid { left } else { right },
            }
        }
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
        let values = contact_core::par::map(&xs, |&x| {
            if x >= reach {
                Ok(0.0)
            } else {
                surface.pressure(x, history, path)
            }
        })?;
        let points: Vec<(f64, f64)> = xs[..NODES]
            .iter()
            .copied()
            .zip(values[..NODES].iter().copied())
            .collect();
        let poly = Interpolant::new(&points);
        let fits = xs[NODES..]
            .iter()
            .zip(&values[NODES..])
            .all(|(&x, &p)| (poly.eval(x) - p).abs() <= self.tol * p.abs().max(self.floor));
        if fits {
            return Ok(Panel::Leaf(poly));
        }
        if depth >= MAX_DEPTH {
            return Ok(Panel::Exact);
        }
        Ok(Panel::Split(
            mid,
            Box::new(self.build(lo, mid, depth + 1)?),
            Box::new(self.build(mid, hi, depth + 1)?),
        ))
    }
}
