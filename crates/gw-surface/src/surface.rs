use crate::error::GwError;
use crate::history::GwHistory;
use contact_core::numeric::{integrate, GaussLegendre};
use contact_core::{AsperityHistory, AsperityModel, LawError, Path, SurfaceLaw};
use serde::{Deserialize, Serialize};
use statrs::distribution::{Continuous, ContinuousCDF, Normal};
use std::cell::RefCell;

/// Heights are integrated over |h| <= TAIL_SIGMAS sigma_s. The Gaussian mass left out,
/// 2 Q(9) = 2.3e-19, times the force of the highest asperity, bounds the truncation
/// error; for separations d < 7 sigma_s that is below 1e-12 of the pressure.
pub const TAIL_SIGMAS: f64 = 9.0;

/// How the height integral is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Quadrature {
    /// Adaptive tanh-sinh on every panel, to `rel_tol` of the integral of |F| phi.
    Adaptive { rel_tol: f64 },
    /// `nodes`-point Gauss-Legendre on sub-panels no wider than `panel_sigmas` sigma_s;
    /// fixed cost, error measured against `Adaptive` in `docs/performance.md`.
    GaussLegendre { nodes: usize, panel_sigmas: f64 },
}

impl Default for Quadrature {
    fn default() -> Self {
        Quadrature::Adaptive { rel_tol: 1e-10 }
    }
}

/// Greenwood-Williamson surface of asperities `M` with Gaussian heights (eq 14):
/// standard deviation `sigma_s` (m) and `density` N (asperities per m^2).
#[derive(Debug, Clone)]
pub struct GreenwoodWilliamson<M> {
    asperity: M,
    sigma_s: f64,
    density: f64,
    quadrature: Quadrature,
    gl: GaussLegendre,
    normal: Normal,
}

impl<M: AsperityModel> GreenwoodWilliamson<M> {
    /// A surface of `asperity` with height standard deviation `sigma_s` (m, > 0) and
    /// `density` (1/m^2, > 0).
    pub fn new(
        asperity: M,
        sigma_s: f64,
        density: f64,
        quadrature: Quadrature,
    ) -> Result<Self, GwError> {
        let check = |field, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(v)
            } else {
                Err(GwError::Invalid {
                    field,
                    value: v,
                    allowed: "finite and > 0",
                })
            }
        };
        check("sigma_s", sigma_s)?;
        check("asperity_density", density)?;
        let nodes = match quadrature {
            Quadrature::Adaptive { rel_tol } => {
                if !(rel_tol.is_finite() && rel_tol >= 1e-14 && rel_tol < 1.0) {
                    return Err(GwError::Invalid {
                        field: "rel_tol",
                        value: rel_tol,
                        allowed: "in [1e-14, 1)",
                    });
                }
                8
            }
            Quadrature::GaussLegendre {
                nodes,
                panel_sigmas,
            } => {
                if !(1..=200).contains(&nodes) {
                    return Err(GwError::Invalid {
                        field: "nodes",
                        value: nodes as f64,
                        allowed: "an integer in [1, 200]",
                    });
                }
                check("panel_sigmas", panel_sigmas)?;
                nodes
            }
        };
        Ok(Self {
            asperity,
            sigma_s,
            density,
            quadrature,
            gl: GaussLegendre::new(nodes),
            normal: Normal::new(0.0, 1.0).expect("standard normal"),
        })
    }

    /// The asperity model.
    pub fn asperity(&self) -> &M {
        &self.asperity
    }
    /// Standard deviation of asperity heights (m).
    pub fn sigma_s(&self) -> f64 {
        self.sigma_s
    }
    /// Asperities per unit area (1/m^2).
    pub fn density(&self) -> f64 {
        self.density
    }
    /// The quadrature in use.
    pub fn quadrature(&self) -> Quadrature {
        self.quadrature
    }
    /// The same surface with another quadrature.
    pub fn with_quadrature(&self, quadrature: Quadrature) -> Result<Self, GwError>
    where
        M: Clone,
    {
        Self::new(
            self.asperity.clone(),
            self.sigma_s,
            self.density,
            quadrature,
        )
    }

    /// Gaussian mass beyond the truncation, both tails: 2 Q(TAIL_SIGMAS).
    pub fn tail_mass(&self) -> f64 {
        2.0 * self.normal.sf(TAIL_SIGMAS)
    }

    /// Fraction of the asperities whose delta_max exceeds `ratio` delta_CP in `history`
    /// (for ratio = 110: those the Etsion-Kadin fits extrapolate). Zero if nothing yields.
    pub fn fraction_beyond(&self, history: &GwHistory, ratio: f64) -> f64 {
        let dcp = self.asperity.yield_interference();
        if !dcp.is_finite() {
            return 0.0;
        }
        match history.deepest() {
            // delta_max(h) = h - deepest > ratio delta_CP above one height
            Some(deep) if deep.is_finite() => self.normal.sf((deep + ratio * dcp) / self.sigma_s),
            Some(_) => 0.0,
            None => {
                let n = 4000;
                let du = 2.0 * TAIL_SIGMAS / n as f64;
                (0..n)
                    .map(|i| -TAIL_SIGMAS + du * (i as f64 + 0.5))
                    .filter(|&u| history.delta_max(u * self.sigma_s) > ratio * dcp)
                    .map(|u| self.normal.pdf(u) * du)
                    .sum()
            }
        }
    }

    fn history_at(&self, history: &GwHistory, h: f64) -> AsperityHistory {
        AsperityHistory {
            delta_max: history.delta_max(h),
        }
    }

    fn asperity_path(h: f64, path: Path) -> Path {
        match path {
            Path::Approach => Path::Approach,
            Path::Retract { from } => Path::Retract { from: h - from },
        }
    }

    fn force_at(&self, h: f64, d: f64, history: &GwHistory, path: Path) -> Result<f64, GwError> {
        self.asperity
            .force(
                h - d,
                self.history_at(history, h),
                Self::asperity_path(h, path),
            )
            .map_err(|source| GwError::Asperity {
                height: h,
                d,
                source,
            })
    }

    fn law<T>(&self, h: f64, d: f64, r: Result<T, LawError>) -> Result<T, GwError> {
        r.map_err(|source| GwError::Asperity {
            height: h,
            d,
            source,
        })
    }

    /// Lowest height where `g` (increasing in h) turns non-negative within [lo, hi];
    /// None if g < 0 everywhere there.
    fn edge(
        &self,
        what: &'static str,
        g: &dyn Fn(f64) -> Result<f64, GwError>,
        lo: f64,
        hi: f64,
    ) -> Result<Option<f64>, GwError> {
        let g_hi = g(hi)?;
        if g_hi < 0.0 {
            return Ok(None);
        }
        let g_lo = g(lo)?;
        if g_lo >= 0.0 {
            return Ok(Some(lo));
        }
        let err = RefCell::new(None);
        let f = |h: f64| match g(h) {
            Ok(v) => v,
            Err(e) => {
                err.borrow_mut().get_or_insert(e);
                f64::NAN
            }
        };
        let r = contact_core::numeric::brent_with_values(
            what,
            f,
            (lo, g_lo),
            (hi, g_hi),
            0.0,
            1e-15 * self.sigma_s,
            200,
        );
        if let Some(e) = err.into_inner() {
            return Err(e);
        }
        Ok(Some(r?))
    }

    /// Break points of the height integral at separation d: the contact edge first, then
    /// the kinks at yield onset and at delta = delta_res, then the top of the range.
    /// None when no asperity is in contact.
    pub fn breakpoints(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
    ) -> Result<Option<Vec<f64>>, GwError> {
        let top = TAIL_SIGMAS * self.sigma_s;
        let bottom = -top;
        let a = &self.asperity;
        // the deepest separation this excursion or any before it reached
        let excursion = match path {
            Path::Approach => d,
            Path::Retract { from } => from,
        };
        // Approach: in contact above (h - d) = jump_in(history(h)).
        // Retract: jumped in during the excursion, (h - from) >= jump_in, and not yet
        // out, (h - d) >= jump_out of the state after the excursion.
        let jumped_in = |h: f64| -> Result<f64, GwError> {
            let j = self.law(h, d, a.jump_in(self.history_at(history, h)))?;
            Ok(h - excursion - j)
        };
        let mut edge = match self.edge("contact edge (jump-in)", &jumped_in, bottom, top)? {
            Some(e) => e,
            None => return Ok(None),
        };
        if let Path::Retract { from } = path {
            let still_in = |h: f64| -> Result<f64, GwError> {
                let hist = a.load(self.history_at(history, h), h - from);
                let j = self.law(h, d, a.jumps(hist))?;
                Ok(h - d - j.jump_out)
            };
            match self.edge("contact edge (jump-out)", &still_in, bottom, top)? {
                Some(e) => edge = edge.max(e),
                None => return Ok(None),
            }
        }
        let mut points = vec![edge];
        // History each asperity carries during this excursion.
        let hist_eff = |h: f64| a.load(self.history_at(history, h), h - excursion);
        // Yield onset: delta_max(h) = delta_CP (increasing in h for a surface loaded by flats).
        let dcp = a.yield_interference();
        if dcp.is_finite() {
            let y = |h: f64| -> Result<f64, GwError> { Ok(hist_eff(h).delta_max - dcp) };
            if let Some(h_y) = self.edge("yield onset height", &y, edge, top)? {
                points.push(h_y);
            }
        }
        // Kinks of each asperity's law: heights where h - d = kink_i(history(h)).
        let n_kinks = self
            .law(top, d, a.kinks(hist_eff(top)))?
            .len()
            .max(self.law(edge, d, a.kinks(hist_eff(edge)))?.len());
        for i in 0..n_kinks {
            let g = |h: f64| -> Result<f64, GwError> {
                let k = self.law(h, d, a.kinks(hist_eff(h)))?;
                // an asperity without this kink (NaN or absent: delta_res before yield, the
                // junction above lambda_c) counts as below it;
                // above the yield height h - d - delta_res increases with h
                Ok(k.get(i)
                    .filter(|x| !x.is_nan())
                    .map_or(-self.sigma_s, |&x| h - d - x))
            };
            if let Some(h_k) = self.edge("kink height", &g, edge, top)? {
                points.push(h_k);
            }
        }
        points.retain(|&h| h >= edge && h < top);
        points.sort_by(f64::total_cmp);
        points.dedup_by(|a, b| (*a - *b).abs() <= 1e-14 * self.sigma_s);
        points.push(top);
        Ok(Some(points))
    }

    /// Pressure (Pa) with the quadrature's error estimate (Pa) and the number of
    /// asperity-law evaluations.
    pub fn pressure_detailed(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
    ) -> Result<(f64, f64, u32), GwError> {
        if !d.is_finite() {
            return Err(GwError::Invalid {
                field: "separation",
                value: d,
                allowed: "finite",
            });
        }
        let Some(points) = self.breakpoints(d, history, path)? else {
            return Ok((0.0, 0.0, 0));
        };
        let sigma = self.sigma_s;
        let err = RefCell::new(None);
        let evals = std::cell::Cell::new(0u32);
        // integrand in u = h/sigma_s: F(sigma u - d) phi(u)
        let f = |u: f64| -> f64 {
            evals.set(evals.get() + 1);
            match self.force_at(sigma * u, d, history, path) {
                Ok(v) => v * self.normal.pdf(u),
                Err(e) => {
                    err.borrow_mut().get_or_insert(e);
                    f64::NAN
                }
            }
        };
        let us: Vec<f64> = points.iter().map(|h| h / sigma).collect();
        let (value, error) = match self.quadrature {
            Quadrature::GaussLegendre { panel_sigmas, .. } => {
                (self.gauss_legendre(&f, &us, panel_sigmas), f64::NAN)
            }
            Quadrature::Adaptive { rel_tol } => {
                // scale of the integral of |F| phi from a cheap pass, for a relative tolerance
                let scale: f64 = self.gauss_legendre(&|u: f64| f(u).abs(), &us, 1.0);
                if let Some(e) = err.borrow_mut().take() {
                    return Err(e);
                }
                let tol = (rel_tol * scale / (us.len() - 1) as f64).max(f64::MIN_POSITIVE);
                let mut total = 0.0;
                let mut error = 0.0;
                for w in us.windows(2) {
                    let r = integrate("height integral", &f, w[0], w[1], tol, 14);
                    if let Some(e) = err.borrow_mut().take() {
                        return Err(e);
                    }
                    let r = r?;
                    total += r.value;
                    error += r.error;
                }
                (total, error)
            }
        };
        if let Some(e) = err.into_inner() {
            return Err(e);
        }
        if !value.is_finite() {
            return Err(GwError::Invalid {
                field: "pressure",
                value,
                allowed: "finite",
            });
        }
        Ok((self.density * value, self.density * error, evals.get()))
    }

    /// Composite Gauss-Legendre over the panels; the first sub-panel (at the contact
    /// edge, where F - F_edge ~ sqrt(h - h_edge)) through u = u0 + w tau^2.
    fn gauss_legendre(&self, f: &dyn Fn(f64) -> f64, us: &[f64], panel: f64) -> f64 {
        let mut total = 0.0;
        for (k, w) in us.windows(2).enumerate() {
            let (a, b) = (w[0], w[1]);
            let n = ((b - a) / panel).ceil().max(1.0) as usize;
            let step = (b - a) / n as f64;
            for i in 0..n {
                let lo = a + step * i as f64;
                if k == 0 && i == 0 {
                    total += self
                        .gl
                        .integrate(|t| f(lo + step * t * t) * 2.0 * step * t, 0.0, 1.0);
                } else {
                    total += self.gl.integrate(f, lo, lo + step);
                }
            }
        }
        total
    }
}

impl<M: AsperityModel> SurfaceLaw for GreenwoodWilliamson<M> {
    type History = GwHistory;

    fn virgin(&self) -> GwHistory {
        GwHistory::VIRGIN
    }

    /// p(d) = N integral F(h - d; delta_max(h), path) phi(h) dh (eq 16, in SI).
    fn pressure(&self, d: f64, history: &GwHistory, path: Path) -> Result<f64, LawError> {
        Ok(self.pressure_detailed(d, history, path)?.0)
    }

    fn load(&self, history: &GwHistory, d: f64) -> GwHistory {
        history.loaded(d)
    }

    fn reach(&self, history: &GwHistory) -> Result<f64, LawError> {
        let top = TAIL_SIGMAS * self.sigma_s;
        let virgin = self.asperity.jumps(AsperityHistory::VIRGIN)?;
        let deformed = self.asperity.jumps(AsperityHistory {
            delta_max: history.delta_max(top),
        })?;
        let lowest = virgin
            .jump_in
            .min(virgin.jump_out)
            .min(deformed.jump_out)
            .min(deformed.jump_in);
        Ok(top - lowest)
    }

    fn length_scale(&self) -> f64 {
        self.sigma_s
    }

    fn kinks(&self, history: &GwHistory) -> Vec<f64> {
        match history.deepest() {
            Some(d) if d.is_finite() => vec![d],
            _ => Vec::new(),
        }
    }
}
