use crate::error::{positive, SwitchError};
use contact_core::numeric::{brent_with_values, refine_sampled_min, GaussLegendre};
use contact_core::{LawError, Path, SurfaceLaw};
use serde::Serialize;
use std::cell::RefCell;

/// One point of a pressure curve: separation d (m), pressure (Pa, compressive > 0).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PressurePoint {
    pub d: f64,
    pub pressure: f64,
}

/// The film that stores elastic energy at the end of impact (eq 17): thickness t_s (m)
/// and Young's modulus E (Pa).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactFilm {
    pub thickness: f64,
    pub youngs_modulus: f64,
}

impl ImpactFilm {
    /// Elastic energy per unit area of the film under pressure p: p^2 t_s / (2E).
    pub fn energy(&self, p: f64) -> f64 {
        p * p * self.thickness / (2.0 * self.youngs_modulus)
    }
}

/// The rule for the d-integral of eq 17: `nodes`-point Gauss-Legendre on panels of
/// `panel` times the surface's length scale. The loading pressure is smooth in d between
/// kinks (a Gaussian convolution), so the default, 12 nodes on half-sigma panels,
/// integrates it to about 1e-12 (the energy-balance test checks 1e-9 against adaptive
/// quadrature); [`EnergyRule::COARSE`], 8 nodes per sigma, needs 3x fewer pressures for
/// an error measured in `docs/performance.md`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyRule {
    pub nodes: usize,
    pub panel: f64,
}

impl EnergyRule {
    /// 12 nodes on half-sigma panels.
    pub const DEFAULT: Self = Self {
        nodes: 12,
        panel: 0.5,
    };
    /// 8 nodes on one-sigma panels.
    pub const COARSE: Self = Self {
        nodes: 8,
        panel: 1.0,
    };
}

impl Default for EnergyRule {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The interpolating polynomial through a panel's Gauss-Legendre nodes and its two end
/// points (barycentric form): inside the panel where eq 17 closes, the root search reads
/// the pressure off it instead of solving the surface again. Passing through the exact
/// end values keeps the energy at a panel end identical on both sides, so the bracket
/// found panel by panel is a true bracket even where the film term p^2 t_s/(2E) is a
/// large part of E_I.
struct PanelPolynomial {
    x: Vec<f64>,
    y: Vec<f64>,
    w: Vec<f64>,
}

impl PanelPolynomial {
    fn new(x: Vec<f64>, y: Vec<f64>) -> Self {
        let w = (0..x.len())
            .map(|j| {
                1.0 / (0..x.len())
                    .filter(|&k| k != j)
                    .map(|k| x[j] - x[k])
                    .product::<f64>()
            })
            .collect();
        Self { x, y, w }
    }

    fn eval(&self, t: f64) -> f64 {
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
}

fn law_call<T>(err: &RefCell<Option<LawError>>, r: Result<T, LawError>, nan: T) -> T {
    match r {
        Ok(v) => v,
        Err(e) => {
            err.borrow_mut().get_or_insert(e);
            nan
        }
    }
}

/// Separation d_e (m) at the end of impact (eq 17):
/// E_I = integral from d_e to infinity of p_L(d) dd + p_L(d_e)^2 t_s/(2E),
/// with p_L the loading (approach) pressure of a surface with `history`.
pub fn end_of_impact<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    impact_energy: f64,
    film: ImpactFilm,
) -> Result<f64, SwitchError> {
    end_of_impact_with(surface, history, impact_energy, film, EnergyRule::DEFAULT)
}

/// [`end_of_impact`] with a chosen rule for the d-integral.
pub fn end_of_impact_with<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    impact_energy: f64,
    film: ImpactFilm,
    rule: EnergyRule,
) -> Result<f64, SwitchError> {
    if !(2..=64).contains(&rule.nodes) || !(rule.panel.is_finite() && rule.panel > 0.0) {
        return Err(SwitchError::Invalid {
            field: "energy_rule",
            value: rule.panel,
            allowed: format!("2..=64 nodes ({} given) on panels > 0", rule.nodes),
        });
    }
    positive("impact_energy", impact_energy)?;
    positive("film_thickness", film.thickness)?;
    positive("film_youngs_modulus", film.youngs_modulus)?;
    let top = surface.reach(history)?;
    let scale = surface.length_scale();
    let step = rule.panel * scale;
    let mut kinks: Vec<f64> = surface
        .kinks(history)
        .into_iter()
        .filter(|&k| k < top)
        .collect();
    kinks.sort_by(|a, b| b.total_cmp(a));
    let gl = GaussLegendre::new(rule.nodes);
    let err = RefCell::new(None);
    let p = |x: f64| law_call(&err, surface.pressure(x, history, Path::Approach), f64::NAN);
    let check = || match err.borrow_mut().take() {
        Some(e) => Err(SwitchError::Surface(e)),
        None => Ok(()),
    };
    let mut hi = top;
    let mut p_hi = p(hi);
    let mut work = 0.0; // integral of p_L from hi to top
    let floor = top - 400.0 * scale;
    while hi > floor {
        let mut lo = hi - step;
        if let Some(&k) = kinks.iter().find(|&&k| k < hi && k > lo) {
            lo = k;
        }
        let (mut xs, ws): (Vec<f64>, Vec<f64>) = gl.mapped(lo, hi).unzip();
        let mut ys: Vec<f64> = xs.iter().map(|&x| p(x)).collect();
        let p_lo = p(lo);
        check()?;
        let w_panel: f64 = ws.iter().zip(&ys).map(|(w, y)| w * y).sum();
        let e_lo = work + w_panel + film.energy(p_lo);
        if e_lo >= impact_energy {
            xs.extend([lo, hi]);
            ys.extend([p_lo, p_hi]);
            let poly = PanelPolynomial::new(xs, ys);
            // degree nodes + 1 <= 2 nodes - 1: the same rule integrates it exactly
            let g = |x: f64| {
                work + gl.integrate(|t| poly.eval(t), x, hi) + film.energy(poly.eval(x))
                    - impact_energy
            };
            let ends = (
                (lo, e_lo - impact_energy),
                (hi, work + film.energy(p_hi) - impact_energy),
            );
            return Ok(brent_with_values(
                "end of impact, eq 17",
                g,
                ends.0,
                ends.1,
                0.0,
                1e-12 * scale,
                200,
            )?);
        }
        work += w_panel;
        hi = lo;
        p_hi = p_lo;
    }
    Err(SwitchError::EnergyNotAbsorbed {
        energy: impact_energy,
        d: hi,
        absorbed: work,
    })
}

/// The unloading branch of one cycle.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Unloading {
    /// Magnitude of the most tensile unloading pressure (Pa, >= 0).
    pub pull_out_pressure: f64,
    /// Separation where it occurs (m).
    pub pull_out_separation: f64,
    /// The curve from d_e to the surface's reach (empty when not asked for).
    pub curve: Vec<PressurePoint>,
}

/// Unloading from `d_e` for a surface whose `history` already includes the loading to
/// `d_e`: the curve at `points` separations (uniform from d_e to the reach; none if 0)
/// and the pull-out pressure, located on a scan and refined by golden section to
/// 1e-6 of the length scale (the pressure there to about 1e-12).
pub fn unload<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    d_e: f64,
    points: usize,
) -> Result<Unloading, SwitchError> {
    let top = surface.reach(history)?;
    let path = Path::Retract { from: d_e };
    let sample = |n: usize| -> Result<Vec<PressurePoint>, SwitchError> {
        (0..n)
            .map(|i| {
                let d = d_e + (top - d_e) * i as f64 / (n - 1) as f64;
                Ok(PressurePoint {
                    d,
                    pressure: surface.pressure(d, history, path)?,
                })
            })
            .collect()
    };
    // The search for the minimum never scans coarser than SCAN samples (spacing about a
    // quarter sigma across an adhesive well about a sigma wide), whatever curve was asked
    // for; a curve of at least SCAN points serves as the scan itself.
    const SCAN: usize = 32;
    let curve = if points == 0 {
        Vec::new()
    } else {
        sample(points.max(2))?
    };
    let scan = if curve.len() >= SCAN {
        curve.clone()
    } else {
        sample(SCAN)?
    };
    let samples: Vec<(f64, f64)> = scan.iter().map(|q| (q.d, q.pressure)).collect();
    let (d_min, p_best) = refine_sampled_min(
        &samples,
        |x| surface.pressure(x, history, path),
        // the minimum's value is quadratic in the location error: 1e-6 sigma -> ~1e-12
        1e-6 * surface.length_scale(),
    )?;
    Ok(Unloading {
        pull_out_pressure: (-p_best).max(0.0),
        pull_out_separation: d_min,
        curve,
    })
}

/// What the cycle runner computes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleOptions {
    /// Number of cycles (or the cap when `until_accommodated`).
    pub cycles: usize,
    /// Stop at the first cycle after which accommodation is detected.
    pub until_accommodated: bool,
    /// Accommodation: the next cycle changes the pull-out pressure by less than this
    /// fraction and d_e by less than this fraction of the surface's length scale.
    pub accommodation_tolerance: f64,
    /// Points on each unloading curve (0: pull-out pressures only).
    pub unloading_points: usize,
    /// Points on the first loading curve (0: none).
    pub loading_points: usize,
    /// Rule of the d-integral of eq 17.
    pub energy_rule: EnergyRule,
}

impl Default for CycleOptions {
    fn default() -> Self {
        Self {
            cycles: 10,
            until_accommodated: false,
            accommodation_tolerance: 1e-3,
            unloading_points: 200,
            loading_points: 200,
            energy_rule: EnergyRule::DEFAULT,
        }
    }
}

/// One loading/unloading cycle.
#[derive(Debug, Clone, Serialize)]
pub struct Cycle<H> {
    /// 1-based cycle number.
    pub cycle: usize,
    /// End-of-impact separation (m).
    pub d_e: f64,
    /// The history after this cycle's loading.
    #[serde(skip)]
    pub history: H,
    pub unloading: Unloading,
}

/// The cycles and what was learned from them.
#[derive(Debug, Clone, Serialize)]
pub struct CycleRun<H> {
    /// The first (virgin) loading curve, from d_e of cycle 1 to the reach.
    pub loading: Vec<PressurePoint>,
    pub cycles: Vec<Cycle<H>>,
    /// The cycle after which nothing changes any more (within the tolerance).
    pub accommodated_after: Option<usize>,
}

/// Runs impact cycles on `surface` from `history`: each cycle finds d_e from eq 17 with
/// the history so far, loads the history to d_e, and unloads.
pub fn run_cycles<S: SurfaceLaw>(
    surface: &S,
    history: S::History,
    impact_energy: f64,
    film: ImpactFilm,
    options: CycleOptions,
) -> Result<CycleRun<S::History>, SwitchError> {
    if options.cycles == 0 {
        return Err(SwitchError::Invalid {
            field: "cycles",
            value: 0.0,
            allowed: "at least 1".into(),
        });
    }
    let tol = options.accommodation_tolerance;
    if !(tol.is_finite() && tol > 0.0) {
        return Err(SwitchError::Invalid {
            field: "accommodation_tolerance",
            value: tol,
            allowed: "finite and > 0".into(),
        });
    }
    let scale = surface.length_scale();
    let mut hist = history;
    let mut cycles: Vec<Cycle<S::History>> = Vec::new();
    let mut accommodated_after = None;
    let mut loading = Vec::new();
    for k in 1..=options.cycles {
        let d_e = end_of_impact_with(surface, &hist, impact_energy, film, options.energy_rule)?;
        let first_history = hist.clone();
        let new_hist = surface.load(&hist, d_e);
        let unloading = unload(surface, &new_hist, d_e, options.unloading_points)?;
        if k == 1 && options.loading_points > 0 {
            let top = surface.reach(&first_history)?;
            let n = options.loading_points.max(2);
            for i in 0..n {
                let d = d_e + (top - d_e) * i as f64 / (n - 1) as f64;
                loading.push(PressurePoint {
                    d,
                    pressure: surface.pressure(d, &first_history, Path::Approach)?,
                });
            }
        }
        if let Some(prev) = cycles.last() {
            let dp = (unloading.pull_out_pressure - prev.unloading.pull_out_pressure).abs();
            let dd = (d_e - prev.d_e).abs();
            if accommodated_after.is_none()
                && dp <= tol * unloading.pull_out_pressure.abs().max(f64::MIN_POSITIVE)
                && dd <= tol * scale
            {
                accommodated_after = Some(prev.cycle);
            }
        }
        hist = new_hist.clone();
        cycles.push(Cycle {
            cycle: k,
            d_e,
            history: new_hist,
            unloading,
        });
        if options.until_accommodated && accommodated_after.is_some() {
            break;
        }
    }
    Ok(CycleRun {
        loading,
        cycles,
        accommodated_after,
    })
}
