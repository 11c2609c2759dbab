use crate::error::GwError;
use crate::history::GwHistory;
use crate::reload::ReloadTables;
use contact_core::numeric::{
    brent_from, integrate, AdaptiveRule, Integral, QuadTolerance, Sample, Tolerance, NOISE,
};
use contact_core::{
    positive, AboveDeepest, AsperityHistory, AsperityModel, CoreError, Estimate, LawError,
    LengthScales, Path, SurfaceLaw, VirginWork,
};
use statrs::distribution::{Continuous, ContinuousCDF, Normal};
use std::sync::Arc;

/// Heights are integrated over |h| <= TAIL_SIGMAS sigma_s. The Gaussian mass left out,
/// 2 Q(9) = 2.3e-19, times the force of the highest asperity, bounds the truncation
/// error; for separations d < 7 sigma_s that is below 1e-12 of the pressure.
pub const TAIL_SIGMAS: f64 = 9.0;

/// Heights (in sigma_s) of the widest panel the height quadrature starts from.
const START_PANEL_SIGMAS: f64 = 20.0;

/// The roughness of the equivalent surface against a smooth flat (eq 14): the argument of
/// [`GreenwoodWilliamson::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Roughness {
    /// Standard deviation of asperity heights sigma_s (m).
    pub sigma_s: f64,
    /// Asperities per unit area N (1/m^2).
    pub asperity_density: f64,
}

/// How the height integral is evaluated: globally adaptive nested Gauss-Legendre
/// ([`contact_core::numeric::integrate`]) with error control in every setting. The pressure's
/// error estimate meets `max(rel_tol |p|, 1e-3 rel_tol N integral of |F| phi, abs_tol)`:
/// relative to the pressure itself, also where compressive and adhesive asperities nearly
/// cancel (at a pull-out), down to a thousandth of the target relative to the forces summed.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Quadrature {
    /// Relative to the integral of |F| phi (the scale of the asperity forces summed).
    pub rel_tol: f64,
    /// Absolute floor (Pa): below it a pressure's error does not matter to the caller.
    pub abs_tol: f64,
    /// Gauss-Legendre nodes per half panel.
    pub nodes: usize,
}

impl Default for Quadrature {
    /// 1e-10 relative, no absolute floor, 6 nodes.
    fn default() -> Self {
        Quadrature {
            rel_tol: 1e-10,
            abs_tol: 0.0,
            nodes: 6,
        }
    }
}

/// The contact spots of a surface at one separation
/// ([`GreenwoodWilliamson::contact_spots`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct ContactSpots {
    /// Real contact area over nominal area A_r/A_n (-).
    pub real_contact_fraction: f64,
    /// Contact spots per unit nominal area (1/m^2).
    pub spot_density: f64,
    /// Mean radius of the spots (m; 0 without contact).
    pub mean_spot_radius: f64,
    /// Conductance of the spots in parallel per unit nominal area (S/m^2), when a spot
    /// conductance was given.
    pub conductance_per_area: Option<f64>,
    /// The largest relative error estimate of the integrals.
    pub relative_error: f64,
}

/// Greenwood-Williamson surface of asperities `M` with Gaussian heights (eq 14).
///
/// p(d) = N integral F(h - d; delta_max(h), path) phi(h) dh (eq 16 in SI), with the
/// height axis split at the contact edge, yield onset and the asperity law's kinks.
///
/// ```
/// use asperity_plastic::{ElastoPlasticAsperity, EtsionKadin, YieldModulus};
/// use contact_core::{paper, Material, Pair, Path, SurfaceLaw};
/// use gw_surface::{GreenwoodWilliamson, Quadrature, Roughness};
/// use maugis_kim::{DugdaleParams, MaugisKim};
/// let ru = Material::new(paper::RU)?;
/// let pair = Pair::new(ru, Some(ru), paper::RADIUS)?;
/// let asperity = ElastoPlasticAsperity::new(
///     EtsionKadin::new(&pair, YieldModulus::AsPrinted)?,
///     MaugisKim::new(DugdaleParams::for_pair(&pair, paper::WORK_OF_ADHESION, paper::Z0))?,
/// );
/// let roughness = Roughness { sigma_s: paper::SIGMA_S, asperity_density: paper::ASPERITY_DENSITY };
/// let gw = GreenwoodWilliamson::new(asperity, roughness, Quadrature::default())?;
/// // pressed to one sigma_s, then pulled back to two: the surface pulls (pressure < 0)
/// let history = gw.load(&gw.virgin(), paper::SIGMA_S);
/// let p = gw.pressure(2.0 * paper::SIGMA_S, &history, Path::Retract { from: paper::SIGMA_S })?;
/// assert!(p < 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct GreenwoodWilliamson<M> {
    asperity: M,
    roughness: Roughness,
    quadrature: Quadrature,
    rule: AdaptiveRule,
    scan_rule: AdaptiveRule,
    normal: Normal,
    /// The reload work of one asperity, tabulated on first use by eq 17's search.
    reload: Arc<ReloadTables>,
}

/// The finest tolerance the asperity tables are built to: asked for less (the reference
/// mode), a surface goes without them, and eq 17 integrates evaluated pressures (so the
/// reference the modes are measured against does not share the tables' numerics).
const FINEST_TABLE: f64 = 1e-13;

/// The tolerance of an integral over the heights of tabulated asperity works (the approach
/// work above or below the deepest point) asked to `abs` (J/m^2) or `rel_of_abs`: half of
/// it, the tables' interpolation error taking the other half, per unit asperity density
/// `n` (the integral runs over the height distribution).
fn table_integral_tolerance(abs: f64, rel_of_abs: f64, n: f64) -> QuadTolerance {
    QuadTolerance {
        rel: 0.0,
        rel_of_abs: 0.5 * rel_of_abs,
        abs: 0.5 * abs / n,
        max_width: START_PANEL_SIGMAS,
        max_panels: 20_000,
        noise: NOISE,
    }
}

/// Relative tolerance of [`SurfaceLaw::pressure_scan`].
const SCAN_TOLERANCE: f64 = 1e-3;
/// The relative tolerance of the rough pressure ([`SurfaceLaw::pressure_rough`]).
const ROUGH_TOLERANCE: f64 = 1e-1;

impl<M: AsperityModel> GreenwoodWilliamson<M> {
    /// A surface of `asperity` with the given `roughness` (sigma_s > 0 m, density > 0 1/m^2),
    /// integrated with `quadrature` (rel_tol in [1e-14, 1), abs_tol >= 0, nodes 2..=6).
    pub fn new(asperity: M, roughness: Roughness, quadrature: Quadrature) -> Result<Self, GwError> {
        positive("sigma_s", roughness.sigma_s)?;
        positive("asperity_density", roughness.asperity_density)?;
        let q = quadrature;
        if !(q.rel_tol.is_finite() && q.rel_tol >= 1e-14 && q.rel_tol < 1.0) {
            return Err(CoreError::Invalid {
                field: "rel_tol",
                value: q.rel_tol,
                allowed: "in [1e-14, 1)",
            }
            .into());
        }
        if !(q.abs_tol.is_finite() && q.abs_tol >= 0.0) {
            return Err(CoreError::Invalid {
                field: "abs_tol",
                value: q.abs_tol,
                allowed: "finite and >= 0",
            }
            .into());
        }
        Ok(Self {
            asperity,
            roughness,
            quadrature,
            rule: AdaptiveRule::new(q.nodes)?,
            scan_rule: AdaptiveRule::new(4)?,
            normal: Normal::new(0.0, 1.0).expect("standard normal"),
            reload: Arc::default(),
        })
    }

    /// The asperity model.
    pub fn asperity(&self) -> &M {
        &self.asperity
    }
    /// Standard deviation of asperity heights (m).
    pub fn sigma_s(&self) -> f64 {
        self.roughness.sigma_s
    }
    /// Asperities per unit area (1/m^2).
    pub fn density(&self) -> f64 {
        self.roughness.asperity_density
    }
    /// The roughness.
    pub fn roughness(&self) -> Roughness {
        self.roughness
    }
    /// The same surface drawing on `tables` for the reload work and virgin loading of its
    /// asperities (eq 17): a surface of the same asperity model with another roughness or
    /// quadrature may have built them already (the tables use their own fixed rule). Share
    /// them only between surfaces of equal asperity models.
    pub fn with_reload_tables(mut self, tables: Arc<ReloadTables>) -> Self {
        self.reload = tables;
        self
    }
    /// The reload-work tables this surface draws on (see [`Self::with_reload_tables`]).
    pub fn reload_tables(&self) -> Arc<ReloadTables> {
        self.reload.clone()
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
        Self::new(self.asperity.clone(), self.roughness, quadrature)
    }

    /// Gaussian mass beyond the truncation, both tails: 2 Q(TAIL_SIGMAS).
    pub fn tail_mass(&self) -> f64 {
        2.0 * self.normal.sf(TAIL_SIGMAS)
    }

    /// Fraction of the asperities (by count) whose delta_max exceeds `ratio` delta_CP in
    /// `history`. Zero if nothing yields.
    pub fn fraction_beyond(&self, history: &GwHistory, ratio: f64) -> f64 {
        match self.height_beyond(history, ratio) {
            Some(h) => self.normal.sf(h / self.sigma_s()),
            None => 0.0,
        }
    }

    /// The lowest height whose delta_max exceeds `ratio` delta_CP, if any asperity does.
    fn height_beyond(&self, history: &GwHistory, ratio: f64) -> Option<f64> {
        let dcp = self.asperity.delta_cp();
        if !dcp.is_finite() {
            return None;
        }
        let top = TAIL_SIGMAS * self.sigma_s();
        let at = self.asperity.fit_interference(ratio);
        match history.deepest() {
            Some(deep) if deep.is_finite() => Some(deep + at),
            Some(_) => None,
            None => {
                // delta_max(h) increases with h for histories made by flats
                let n = 4000;
                (0..=n)
                    .map(|i| -top + 2.0 * top * i as f64 / n as f64)
                    .find(|&h| history.delta_max(h) > at)
            }
        }
    }

    /// The share of the pressure at `d` on `path` carried by asperities whose delta_max
    /// exceeds `ratio` delta_CP (for ratio = 110: the load the Etsion-Kadin fits
    /// extrapolate), as |part| / |total|; zero where nothing is loaded that far.
    pub fn load_share_beyond(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
        ratio: f64,
    ) -> Result<f64, GwError> {
        // the history during the excursion includes the excursion's extreme
        let during = match path {
            Path::Approach => history.loaded(d),
            Path::Retract { from } => history.loaded(from),
        };
        let Some(h) = self.height_beyond(&during, ratio) else {
            return Ok(0.0);
        };
        let total = self.integral(d, history, path, None)?.value;
        if total == 0.0 {
            return Ok(0.0);
        }
        let part = self.integral(d, history, path, Some(h))?.value;
        Ok((part / total).abs().min(1.0))
    }

    /// The separation where the approach's contact edge reaches the height that yielded
    /// to `b` on a surface last pressed to `deepest` ([`SurfaceLaw::kinks`]), None where
    /// the edge there is not a simple crossing: the edge function h - d - jump_in(h)
    /// rises just above that height with slope 1 - d(jump_in)/d(delta_max), measured
    /// over a step of 1e-3 b and required to exceed 1e-6.
    fn yield_crossing(&self, deepest: f64, b: f64) -> Option<f64> {
        let j = |delta_max: f64| self.asperity.jump_in(AsperityHistory { delta_max }).ok();
        let step = 1e-3 * b;
        let (j0, j1) = (j(b)?, j(b + step)?);
        let slope = 1.0 - (j1 - j0) / step;
        let x = deepest + b - j0;
        (slope > 1e-6 && x.is_finite() && x > deepest).then_some(x)
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

    fn law<T>(&self, h: f64, d: f64, r: Result<T, LawError>) -> Result<T, GwError> {
        r.map_err(|source| GwError::Asperity {
            height: h,
            d,
            source,
        })
    }

    fn force_at(&self, h: f64, d: f64, history: &GwHistory, path: Path) -> Result<f64, GwError> {
        let f = self.law(
            h,
            d,
            self.asperity.force(
                h - d,
                self.history_at(history, h),
                Self::asperity_path(h, path),
            ),
        )?;
        if f.is_finite() {
            Ok(f)
        } else {
            Err(GwError::LawNotFinite {
                height: h,
                d,
                value: f,
            })
        }
    }

    /// Lowest height where `g` (increasing in h) turns non-negative within [lo, hi];
    /// None if g < 0 everywhere there.
    fn edge(
        &self,
        what: &'static str,
        mut g: impl FnMut(f64) -> Result<f64, GwError>,
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
        brent_from(
            what,
            g,
            Sample { x: lo, f: g_lo },
            Sample { x: hi, f: g_hi },
            Tolerance::absolute(1e-15 * self.sigma_s()).with_max_iter(200),
        )
        .map(Some)
    }

    /// The contact edge at separation `d` (m): the lowest height in contact, None when no
    /// asperity is.
    fn contact_edge(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
    ) -> Result<Option<f64>, GwError> {
        let top = TAIL_SIGMAS * self.sigma_s();
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
        let mut edge = match self.edge("contact edge (jump-in)", jumped_in, bottom, top)? {
            Some(e) => e,
            None => return Ok(None),
        };
        if let Path::Retract { from } = path {
            let still_in = |h: f64| -> Result<f64, GwError> {
                let hist = a.load(self.history_at(history, h), h - from);
                let j = self.law(h, d, a.jumps(hist))?;
                Ok(h - d - j.jump_out)
            };
            match self.edge("contact edge (jump-out)", still_in, bottom, top)? {
                Some(e) => edge = edge.max(e),
                None => return Ok(None),
            }
        }
        Ok(Some(edge))
    }

    /// Break points of the height integral at separation d: the contact edge first, then
    /// the kinks at yield onset and the asperity law's declared kinks, then the top of
    /// the range. None when no asperity is in contact. The kinks only save work: the
    /// quadrature's error control does not rely on them.
    pub fn breakpoints(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
    ) -> Result<Option<Vec<f64>>, GwError> {
        let top = TAIL_SIGMAS * self.sigma_s();
        let a = &self.asperity;
        let Some(edge) = self.contact_edge(d, history, path)? else {
            return Ok(None);
        };
        // the deepest separation this excursion or any before it reached
        let excursion = match path {
            Path::Approach => d,
            Path::Retract { from } => from,
        };
        let mut points = vec![edge];
        // History each asperity carries during this excursion.
        let hist_eff = |h: f64| a.load(self.history_at(history, h), h - excursion);
        // Yield onset and the plasticity law's declared breaks: delta_max(h) = b
        // (increasing in h for a surface loaded by flats).
        for b in a.plastic_breaks() {
            let y = |h: f64| -> Result<f64, GwError> { Ok(hist_eff(h).delta_max - b) };
            if let Some(h_y) = self.edge("yield onset height", y, edge, top)? {
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
                let k = self.law(h, d, a.kink(i, hist_eff(h)))?;
                // an asperity without this kink (None or absent: delta_res before yield,
                // the junction above lambda_c) counts as below it; above the yield
                // height h - d - delta_res increases with h
                Ok(k.map_or(-self.sigma_s(), |x| h - d - x))
            };
            if let Some(h_k) = self.edge("kink height", g, edge, top)? {
                points.push(h_k);
            }
        }
        points.retain(|&h| h >= edge && h < top);
        points.sort_by(f64::total_cmp);
        points.dedup_by(|a, b| (*a - *b).abs() <= 1e-14 * self.sigma_s());
        points.push(top);
        Ok(Some(points))
    }

    /// The pressure integral (Pa) with its error estimate and the number of asperity-law
    /// evaluations; heights below `from_height` (m) are left out when given.
    fn integral(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
        from_height: Option<f64>,
    ) -> Result<Integral, GwError> {
        self.integral_with(
            d,
            history,
            path,
            from_height,
            &self.rule,
            self.quadrature.rel_tol,
        )
    }

    fn integral_with(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
        from_height: Option<f64>,
        rule: &AdaptiveRule,
        rel_tol: f64,
    ) -> Result<Integral, GwError> {
        contact_core::finite("separation", d)?;
        let Some(mut points) = self.breakpoints(d, history, path)? else {
            return Ok(Integral::default());
        };
        let mut edge_panel = true;
        if let Some(h0) = from_height {
            if h0 > points[0] {
                edge_panel = false;
                points.retain(|&h| h > h0);
                points.insert(0, h0);
                if points.len() < 2 {
                    return Ok(Integral::default());
                }
            }
        }
        self.integral_over(d, history, path, &points, edge_panel, rule, rel_tol)
    }

    /// The pressure integral over the heights between `points` (m, increasing; the first
    /// the contact edge when `edge_panel`), as [`Self::integral_with`].
    #[allow(clippy::too_many_arguments)]
    fn integral_over(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
        points: &[f64],
        edge_panel: bool,
        rule: &AdaptiveRule,
        rel_tol: f64,
    ) -> Result<Integral, GwError> {
        let sigma = self.sigma_s();
        let us: Vec<f64> = points.iter().map(|h| h / sigma).collect();
        let q = self.quadrature;
        let n = self.density();
        // the interference h - d carries the rounding of the heights: over a range of
        // heights much narrower than the heights themselves (a flat just inside the
        // highest asperity's reach) that is a large part of it
        let (h_lo, h_hi) = (points[0], points[points.len() - 1]);
        let magnitude = h_lo.abs().max(h_hi.abs()).max(d.abs());
        let noise = NOISE * (magnitude / (h_hi - h_lo)).max(1.0);
        let tol = QuadTolerance {
            rel: rel_tol,
            // where the pressure nearly cancels, stop at a thousandth of the target relative
            // to the forces summed
            rel_of_abs: 1e-3 * rel_tol,
            abs: q.abs_tol / n,
            max_width: START_PANEL_SIGMAS,
            max_panels: 20_000,
            noise,
        };
        // integrand in u = h/sigma_s: F(sigma u - d) phi(u)
        let r = integrate(
            "height integral",
            |u: f64| {
                Ok::<_, GwError>(self.force_at(sigma * u, d, history, path)? * self.normal.pdf(u))
            },
            &us,
            edge_panel,
            rule,
            tol,
        )?;
        Ok(Integral {
            value: n * r.value,
            error: n * r.error,
            evaluations: r.evaluations,
        })
    }

    /// The rough pressure (Pa) of [`SurfaceLaw::pressure_rough`] with its error estimate
    /// and the number of asperity-law evaluations: a quadrature to 1e-1 relative (4 nodes)
    /// from the contact edge to the top of the heights, without the kinks' break points.
    pub fn rough_integral(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
    ) -> Result<Integral, GwError> {
        contact_core::finite("separation", d)?;
        let Some(edge) = self.contact_edge(d, history, path)? else {
            return Ok(Integral::default());
        };
        let top = TAIL_SIGMAS * self.sigma_s();
        if !(edge < top) {
            return Ok(Integral::default());
        }
        self.integral_over(
            d,
            history,
            path,
            &[edge, top],
            true,
            &self.scan_rule,
            ROUGH_TOLERANCE,
        )
    }

    /// The scan pressure (Pa) of [`SurfaceLaw::pressure_scan`] with its error estimate and
    /// the number of asperity-law evaluations (1e-3 relative, 4 nodes).
    pub fn scan_integral(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
    ) -> Result<Integral, GwError> {
        self.integral_with(d, history, path, None, &self.scan_rule, SCAN_TOLERANCE)
    }

    /// Pressure (Pa) with the quadrature's error estimate (Pa) and the number of
    /// asperity-law evaluations.
    pub fn pressure_integral(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
    ) -> Result<Integral, GwError> {
        self.integral(d, history, path, None)
    }

    /// The contact spots at separation `d` (m) with `history` on `path`: the real contact
    /// area over the nominal one, the spots per unit area, their mean radius, and (given
    /// the conductance of one spot of radius a, S) the conductance per unit nominal area of
    /// the spots in parallel (S/m^2):
    ///
    ///   A_r/A_n = N integral pi a(h)^2 phi(h) dh,   n = N integral [a(h) > 0] phi(h) dh,
    ///   mean a = N integral a(h) phi(h) dh / n,     G/A_n = N integral g(a(h)) phi(h) dh,
    ///
    /// with a(h) the contact radius of the asperity of height h from its law
    /// ([`AsperityModel::contact_radius`]; an adhesive asperity held by its cohesive zone
    /// without touching is not a spot), over the same break points and with the same error
    /// control as the pressure (each integral to the quadrature's relative tolerance of its
    /// own magnitude).
    pub fn contact_spots(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
        spot_conductance: Option<&(dyn Fn(f64) -> f64 + Sync)>,
    ) -> Result<ContactSpots, GwError> {
        contact_core::finite("separation", d)?;
        let Some(points) = self.breakpoints(d, history, path)? else {
            return Ok(ContactSpots::default());
        };
        let sigma = self.sigma_s();
        let us: Vec<f64> = points.iter().map(|h| h / sigma).collect();
        let (h_lo, h_hi) = (points[0], points[points.len() - 1]);
        let magnitude = h_lo.abs().max(h_hi.abs()).max(d.abs());
        let tol = QuadTolerance {
            rel: self.quadrature.rel_tol,
            rel_of_abs: 1e-3 * self.quadrature.rel_tol,
            abs: 0.0,
            max_width: START_PANEL_SIGMAS,
            max_panels: 20_000,
            noise: NOISE * (magnitude / (h_hi - h_lo)).max(1.0),
        };
        let n = self.density();
        let radius = |u: f64| -> Result<f64, GwError> {
            let h = sigma * u;
            let a = self.law(
                h,
                d,
                self.asperity.contact_radius(
                    h - d,
                    self.history_at(history, h),
                    Self::asperity_path(h, path),
                ),
            )?;
            if a.is_finite() && a >= 0.0 {
                Ok(a)
            } else {
                Err(GwError::LawNotFinite {
                    height: h,
                    d,
                    value: a,
                })
            }
        };
        // the four integrals start on the same panels: each radius is solved once (by the
        // bits of u), the same value for each, so the same sums to the bit
        let radii = std::cell::RefCell::new(std::collections::HashMap::<u64, f64>::new());
        let known_radius = |u: f64| -> Result<f64, GwError> {
            if let Some(&a) = radii.borrow().get(&u.to_bits()) {
                return Ok(a);
            }
            let a = radius(u)?;
            radii.borrow_mut().insert(u.to_bits(), a);
            Ok(a)
        };
        let integral = |what: &'static str, g: &dyn Fn(f64) -> f64| {
            integrate(
                what,
                |u: f64| Ok::<_, GwError>(g(known_radius(u)?) * self.normal.pdf(u)),
                &us,
                true,
                &self.rule,
                tol,
            )
        };
        let area = integral("real contact area", &|a| std::f64::consts::PI * a * a)?;
        let count = integral("contact spots", &|a| if a > 0.0 { 1.0 } else { 0.0 })?;
        let sum_a = integral("spot radii", &|a| a)?;
        let conductance = match spot_conductance {
            Some(g) => Some(integral("spot conductance", &|a| {
                if a > 0.0 {
                    g(a)
                } else {
                    0.0
                }
            })?),
            None => None,
        };
        let spots = n * count.value;
        Ok(ContactSpots {
            real_contact_fraction: n * area.value,
            spot_density: spots,
            mean_spot_radius: if count.value > 0.0 {
                sum_a.value / count.value
            } else {
                0.0
            },
            conductance_per_area: conductance.map(|c| n * c.value),
            relative_error: [
                (area.error, area.value),
                (count.error, count.value),
                (sum_a.error, sum_a.value),
            ]
            .into_iter()
            .map(|(e, v)| if v > 0.0 { e / v } else { 0.0 })
            .fold(0.0, f64::max),
        })
    }

    fn jumps_of(&self, history: AsperityHistory) -> Result<contact_core::Jumps, GwError> {
        self.law(f64::NAN, f64::NAN, self.asperity.jumps(history))
    }
}

impl<M: AsperityModel + Sync> GreenwoodWilliamson<M> {
    /// The approach work from `lo` to `hi` where every asperity in contact loads on its
    /// virgin curve (J/m^2): N integral phi(h) (V(h - lo) - V(h - hi)) dh, V(x) the work of
    /// a never-pressed asperity loaded to x, tabulated once per surface and tolerance
    /// decade (`VirginTable`, to a tenth of `rel_of_abs`), with the quadrature's estimate
    /// and the table's (N integral phi (e_V(h - lo) + e_V(h - hi)) dh); and the tabulated
    /// pressure at `lo`, N integral phi(h) F_v(h - lo) dh.
    fn virgin_loading(
        &self,
        lo: f64,
        hi: f64,
        abs: f64,
        rel_of_abs: f64,
    ) -> Result<VirginWork, GwError> {
        let sigma = self.sigma_s();
        let n = self.density();
        let top = TAIL_SIGMAS * sigma;
        let table = self
            .reload
            .virgin(&self.asperity, 0.1 * rel_of_abs, top - lo)?;
        let j0 = table.x_min();
        let u_lo = (lo + j0) / sigma;
        let u_top = TAIL_SIGMAS;
        if !(u_lo < u_top) {
            return Ok(VirginWork {
                work: Estimate::default(),
                pressure: 0.0,
            });
        }
        let mut us = vec![u_lo, u_top];
        for &e in table.hard_breaks() {
            for base in [lo, hi] {
                let u = (base + e) / sigma;
                if u > u_lo && u < u_top {
                    us.push(u);
                }
            }
        }
        us.sort_by(f64::total_cmp);
        us.dedup();
        let tol = table_integral_tolerance(abs, rel_of_abs, n);
        let w = integrate(
            "virgin approach work",
            |u: f64| {
                let h = sigma * u;
                Ok::<_, GwError>((table.work(h - lo).0 - table.work(h - hi).0) * self.normal.pdf(u))
            },
            &us,
            true,
            &self.rule,
            tol,
        )?;
        // the table's error, over the mass of heights in contact
        let cdf = |h: f64| self.normal.cdf((h / sigma).clamp(u_lo, u_top));
        let table_error = table.error_mass(lo, cdf) + table.error_mass(hi, cdf);
        let p = integrate(
            "tabulated virgin pressure",
            |u: f64| Ok::<_, GwError>(table.force(sigma * u - lo) * self.normal.pdf(u)),
            &us,
            true,
            &self.scan_rule,
            // for bracketing and the film term's slope: the evaluated pressure decides
            QuadTolerance {
                rel: 1e-3,
                rel_of_abs: 1e-4,
                abs: 0.0,
                ..tol
            },
        )?;
        Ok(VirginWork {
            work: Estimate {
                value: n * w.value,
                error: n * (w.error + table_error),
            },
            pressure: n * p.value,
        })
    }

    /// The approach work down to `deep`, the deepest separation D of a flat-loaded
    /// `history` (J/m^2), the other way round (Fubini): W(D) = N integral R(h - D) phi(h) dh
    /// over the heights in contact at D, with R(x) the work of one asperity reloading up to
    /// its own largest interference x (above D no asperity is loaded beyond its delta_max,
    /// so each one's history is fixed along the way). R depends on x alone, so it is
    /// tabulated once per surface and tolerance decade (`ReloadTable`, to a tenth of
    /// `rel_of_abs`) and serves every cycle. The outer quadrature aims at half of
    /// max(`abs`, `rel_of_abs` N integral |R| phi); the estimate adds N integral e(h - D)
    /// phi(h) dh, e the table's error estimate piece by piece. The pressure bound above D
    /// is N integral P(h - D) phi(h) dh, P the table's bound on each asperity's largest
    /// force on its reload (each reload curve is crossed from its jump-in up to its
    /// delta_max on the way to D), plus the quadrature's estimate.
    fn reload_work(
        &self,
        deep: f64,
        history: &GwHistory,
        abs: f64,
        rel_of_abs: f64,
    ) -> Result<AboveDeepest, GwError> {
        let Some(points) = self.breakpoints(deep, history, Path::Approach)? else {
            return Ok(AboveDeepest {
                deepest: deep,
                work: Estimate::default(),
                pressure_bound: 0.0,
            });
        };
        let sigma = self.sigma_s();
        let n = self.density();
        let top = TAIL_SIGMAS * sigma;
        let table = self
            .reload
            .table(&self.asperity, 0.1 * rel_of_abs, top - deep)?;
        let mut us: Vec<f64> = points.iter().map(|h| h / sigma).collect();
        let (lo, hi) = (us[0], us[us.len() - 1]);
        us.extend(
            table
                .hard_breaks()
                .iter()
                .map(|x| (deep + x) / sigma)
                .filter(|&u| u > lo && u < hi),
        );
        us.sort_by(f64::total_cmp);
        us.dedup();
        let outer = table_integral_tolerance(abs, rel_of_abs, n);
        let w = integrate(
            "approach work to the deepest separation",
            |u: f64| Ok::<_, GwError>(table.eval(sigma * u - deep) * self.normal.pdf(u)),
            &us,
            true,
            &self.rule,
            outer,
        )?;
        // the table's error, piece by piece, over the mass of heights it serves
        let cdf = |x: f64| self.normal.cdf(((deep + x) / sigma).clamp(lo, hi));
        let table_error: f64 = table
            .pieces_errors()
            .map(|(a, b, e)| e * (cdf(b) - cdf(a)))
            .sum();
        let peak = integrate(
            "pressure bound above the deepest separation",
            |u: f64| {
                Ok::<_, GwError>(table.peak_bound(sigma * u - deep).max(0.0) * self.normal.pdf(u))
            },
            &us,
            true,
            &self.rule,
            QuadTolerance {
                rel: 0.1 * rel_of_abs,
                abs: 0.0,
                ..outer
            },
        )?;
        Ok(AboveDeepest {
            deepest: deep,
            work: Estimate {
                value: n * w.value,
                error: n * (w.error + table_error),
            },
            pressure_bound: n * (peak.value + peak.error),
        })
    }
}

impl<M: AsperityModel + Sync> SurfaceLaw for GreenwoodWilliamson<M> {
    type History = GwHistory;

    fn virgin(&self) -> GwHistory {
        GwHistory::VIRGIN
    }

    /// p(d) = N integral F(h - d; delta_max(h), path) phi(h) dh (eq 16, in SI), with the
    /// quadrature's error estimate.
    fn pressure_estimate(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
    ) -> Result<Estimate, LawError> {
        let r = self.integral(d, history, path, None)?;
        Ok(Estimate {
            value: r.value,
            error: r.error,
        })
    }

    /// The pressure with a coarse quadrature (1e-3 relative, 4 nodes), about a third of
    /// the cost of a 1e-10 evaluation.
    fn pressure_scan(&self, d: f64, history: &GwHistory, path: Path) -> Result<f64, LawError> {
        Ok(self.scan_integral(d, history, path)?.value)
    }

    /// The pressure with a rough quadrature (1e-1 relative, 4 nodes) from the contact edge
    /// to the top of the heights, without the kinks' break points (not worth their search
    /// at this tolerance), with its error estimate: about a third of the cost of a scan
    /// pressure ([`Self::rough_integral`]).
    fn pressure_rough(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
    ) -> Result<Option<Estimate>, LawError> {
        let r = self.rough_integral(d, history, path)?;
        Ok(Some(Estimate {
            value: r.value,
            error: r.error,
        }))
    }

    fn load(&self, history: &GwHistory, d: f64) -> GwHistory {
        history.loaded(d)
    }

    /// On approach the first asperity to touch decides: the highest one, deformed as the
    /// history makes it, or (for a surface loaded by a flat) the highest one the flat never
    /// reached, which is still virgin. On retraction also their jump-outs after the
    /// excursion.
    fn reach(&self, history: &GwHistory, path: Path) -> Result<f64, LawError> {
        let top = TAIL_SIGMAS * self.sigma_s();
        let virgin = self.jumps_of(AsperityHistory::VIRGIN)?;
        let deformed = self.jumps_of(AsperityHistory {
            delta_max: history.delta_max(top),
        })?;
        let highest_virgin = match history.deepest() {
            // every asperity above `deepest` has been pressed; h - jump_in grows with h on
            // both sides (delta_res grows more slowly than delta_max)
            Some(deep) => deep.min(top),
            None => top,
        };
        let mut reach = (top - deformed.jump_in).max(highest_virgin - virgin.jump_in);
        if history.deepest().is_none() {
            reach = reach.max(top - virgin.jump_in);
        }
        if let Path::Retract { from } = path {
            let excursion = self.jumps_of(AsperityHistory {
                delta_max: history.delta_max(top).max(top - from),
            })?;
            let lowest = virgin
                .jump_out
                .min(deformed.jump_out)
                .min(excursion.jump_out)
                .min(excursion.jump_in)
                .min(virgin.jump_in);
            reach = reach.max(top - lowest);
        }
        Ok(reach)
    }

    /// finest: the smallest non-zero jump distance of a virgin asperity and of the most
    /// deformed one (at least 1e-6 sigma_s, at most sigma_s); roughness: sigma_s;
    /// deepest: the lowest asperity (at -TAIL_SIGMAS sigma_s) pressed by its own radius.
    fn length_scales(&self, history: &GwHistory) -> Result<LengthScales, LawError> {
        let sigma = self.sigma_s();
        let top = TAIL_SIGMAS * sigma;
        let mut finest = sigma;
        for h in [
            AsperityHistory::VIRGIN,
            AsperityHistory {
                delta_max: history.delta_max(top).max(0.0),
            },
        ] {
            let j = self.jumps_of(h)?;
            let st = self.asperity.plastic_state(h);
            for x in [j.jump_in - st.delta_res, j.jump_out - st.delta_res] {
                if x != 0.0 && x.is_finite() {
                    finest = finest.min(x.abs());
                }
            }
        }
        Ok(LengthScales {
            finest: finest.max(1e-6 * sigma),
            roughness: sigma,
            deepest: -top - self.asperity.radius(),
        })
    }

    /// The deepest separation reached (reloading turns into virgin loading there; none for
    /// asperities that never yield: their loading does not depend on the history), and
    /// above it, for each plastic break b (yield onset delta_CP first), the separation
    /// where the approach's contact edge crosses the height that yielded to b:
    /// d = deepest + b - jump_in(delta_max = b). There the asperities that jump in change
    /// from elastic to plastic ones, and p_L(d) has a kink the energy integral of eq 17
    /// would otherwise resolve by bisection (about a sixth of its panels in accurate
    /// mode on the paper's switch; docs/performance.md).
    ///
    /// Not declared where the yielded asperities' tops lie level (jump_in grows one for
    /// one with delta_max just past b, as for a law that flattens every yielded tip to
    /// the same height): there all of them jump in at once, p_L jumps rather than kinks,
    /// and at that very separation the contact edge is undetermined (the edge function
    /// is zero, up to rounding, over the whole plateau). The quadrature then finds the
    /// jump between its nodes, as it would without the declaration.
    fn kinks(&self, history: &GwHistory) -> Vec<f64> {
        match history.deepest() {
            Some(d) if d.is_finite() && self.asperity.delta_cp().is_finite() => {
                let mut k = vec![d];
                for b in self.asperity.plastic_breaks() {
                    if let Some(x) = self.yield_crossing(d, b) {
                        k.push(x);
                    }
                }
                k
            }
            _ => Vec::new(),
        }
    }

    /// For a history loaded by flats, at or below its deepest separation: N integral
    /// phi(h) (V(h - lo) - V(h - hi)) dh, V(x) the work of a never-pressed asperity loaded
    /// to x, from the surface's tabulated virgin loading ([`ReloadTables`]); the pressure
    /// from the same table. A table or an integral that fails leaves the surface without
    /// it (eq 17 then integrates evaluated pressures).
    fn virgin_work(
        &self,
        history: &GwHistory,
        lo: f64,
        hi: f64,
        abs: f64,
        rel_of_abs: f64,
    ) -> Result<Option<VirginWork>, LawError> {
        let Some(deep) = history.deepest() else {
            return Ok(None);
        };
        if !(lo < hi && hi <= deep && 0.1 * rel_of_abs >= FINEST_TABLE) {
            return Ok(None);
        }
        Ok(self.virgin_loading(lo, hi, abs, rel_of_abs).ok())
    }

    /// For a history loaded by a flat to a finite depth: the reload work over the asperities
    /// and the bound on their largest forces from the surface's tables ([`ReloadTables`],
    /// docs/theory.md section 6.2). A table
    /// or an integral that fails leaves the surface without it (it only saves work: eq 17
    /// then searches from the first touch, and meets any failure of the law there).
    fn above_deepest(
        &self,
        history: &GwHistory,
        abs: f64,
        rel_of_abs: f64,
    ) -> Result<Option<AboveDeepest>, LawError> {
        let Some(deep) = history.deepest().filter(|d| d.is_finite()) else {
            return Ok(None);
        };
        if 0.1 * rel_of_abs < FINEST_TABLE {
            return Ok(None);
        }
        Ok(self.reload_work(deep, history, abs, rel_of_abs).ok())
    }

    /// On retraction: B(d) = N integral over the heights still in contact at d of
    /// T(h) phi(h) dh, T(h) the asperity's own tension bound for its history after the
    /// excursion ([`AsperityModel::max_tension`]), with the quadrature's error estimate
    /// and a relative headroom of 1e-3 added. Further out the contact only loses
    /// asperities (the contact edge rises with d), so B(d) bounds the tension there too.
    /// None on approach, or when the asperity law has no bound.
    fn tension_bound(
        &self,
        d: f64,
        history: &GwHistory,
        path: Path,
    ) -> Result<Option<f64>, LawError> {
        let Path::Retract { from } = path else {
            return Ok(None);
        };
        let a = &self.asperity;
        let sigma = self.sigma_s();
        let bound = |h: f64| a.max_tension(a.load(self.history_at(history, h), h - from));
        if bound(TAIL_SIGMAS * sigma).is_none() {
            return Ok(None);
        }
        let Some(points) = self.breakpoints(d, history, path)? else {
            return Ok(Some(0.0));
        };
        let us: Vec<f64> = points.iter().map(|h| h / sigma).collect();
        let tol = QuadTolerance {
            rel: 1e-6,
            rel_of_abs: 1e-6,
            abs: 0.0,
            max_width: START_PANEL_SIGMAS,
            max_panels: 20_000,
            noise: NOISE,
        };
        // a height whose asperity has no finite bound, or a bound the quadrature cannot
        // integrate, leaves the surface without one (the bound only saves work, so neither
        // is an error: the scan then runs to its end)
        let unknown = std::cell::Cell::new(false);
        let r = integrate(
            "tension bound",
            |u: f64| {
                Ok::<_, GwError>(match bound(sigma * u) {
                    Some(t) if t.is_finite() && t >= 0.0 => t * self.normal.pdf(u),
                    _ => {
                        unknown.set(true);
                        0.0
                    }
                })
            },
            &us,
            false,
            &self.scan_rule,
            tol,
        );
        let r = match r {
            Ok(r) if !unknown.get() && r.value.is_finite() && r.error.is_finite() => r,
            _ => return Ok(None),
        };
        let n = self.density();
        Ok(Some(n * (r.value * (1.0 + 1e-3) + r.error)))
    }
}
