use crate::error::SwitchError;
use contact_core::numeric::{
    brent_from, geomspace, integrate_panels_par, linspace, refine_minima_par, AdaptiveRule,
    GaussLegendre, Interpolant, PanelNodes, QuadTolerance, Sample, Tolerance, NOISE,
};
use contact_core::{par, positive, CoreError, Estimate, LengthScales, Path, SurfaceLaw};
use std::collections::HashMap;
use std::sync::Mutex;

/// One point of a pressure curve: separation d (m), pressure (Pa, compressive > 0).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct PressurePoint {
    /// Separation (m).
    pub d: f64,
    /// Pressure (Pa).
    pub pressure: f64,
}

/// The film that stores elastic energy at the end of impact (eq 17): thickness t_s (m)
/// and Young's modulus E (Pa).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct ImpactFilm {
    /// t_s (m).
    pub thickness: f64,
    /// E (Pa) of the film.
    pub youngs_modulus: f64,
}

impl ImpactFilm {
    /// Elastic energy per unit area of the film under pressure p: p^2 t_s / (2E).
    pub fn energy(&self, p: f64) -> f64 {
        p * p * self.thickness / (2.0 * self.youngs_modulus)
    }
}

/// The accuracy the switch computations aim for. The surface's own pressure error (its
/// quadrature) adds to these and is reported with them; configure both together (the
/// root package's accuracy modes do).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Precision {
    /// d_e to this fraction of the surface's roughness length scale.
    pub d_e: f64,
    /// The pull-out pressure to this fraction of itself (an absolute floor, a pressure
    /// error that does not matter to the caller, belongs to the surface's quadrature).
    pub pull_out: f64,
}

impl Default for Precision {
    /// d_e to 1e-10 sigma, pull-out to 1e-9.
    fn default() -> Self {
        Self {
            d_e: 1e-10,
            pull_out: 1e-9,
        }
    }
}

/// The end of impact (eq 17) with its error estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct EndOfImpact {
    /// Separation d_e (m).
    pub d_e: f64,
    /// Its estimated error (m).
    pub error: f64,
    /// The approach pressure there, p_L(d_e) (Pa, > 0: compressive).
    pub pressure: f64,
}

/// Nodes per half panel of the d-integral of eq 17 (6: degree 11 on each half; 4 took
/// 17 % more instructions in accurate mode and 4 % more in fast, docs/performance.md).
const ENERGY_NODES: usize = 6;
/// Share of the d_e target given to the energy integral (relative to the work of |p_L|).
const ENERGY_SHARE: f64 = 0.5;
/// The search for d_e gives up this many roughness scales below the first touch.
const DEPTH_LIMIT: f64 = 1e4;

/// The approach pressure, remembering every evaluation's error estimate so that the
/// energy error they cause can be integrated afterwards.
struct Approach<'a, S: SurfaceLaw> {
    surface: &'a S,
    history: &'a S::History,
    /// (d, error estimate) of every evaluation, in any order (they run in parallel).
    errors: Mutex<Vec<(f64, f64)>>,
    /// Every pressure evaluated for this end of impact, by the bits of d: a re-solve with
    /// a tighter energy integral starts on the same panels, whose nodes it need not
    /// evaluate again (the same values, so the same result to the bit).
    memo: &'a Memo,
}

/// Approach pressures by the bits of the separation.
type Memo = Mutex<HashMap<u64, Estimate>>;

impl<S: SurfaceLaw> Approach<'_, S> {
    fn p(&self, d: f64) -> Result<f64, SwitchError> {
        // a poisoned lock only follows a panic elsewhere; the map and list are still whole
        let known = self
            .memo
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .get(&d.to_bits())
            .copied();
        let e = match known {
            Some(e) => e,
            None => {
                let e = self
                    .surface
                    .pressure_estimate(d, self.history, Path::Approach)?;
                self.memo
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .insert(d.to_bits(), e);
                e
            }
        };
        self.errors
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push((d, e.error));
        Ok(e.value)
    }

    /// Integral of the pressure error estimates over [lo, hi] (J/m^2), trapezoidal on the
    /// evaluations made (a dense set: the quadrature nodes).
    fn error_integral(&mut self, lo: f64, hi: f64) -> f64 {
        let errors = self.errors.get_mut().unwrap_or_else(|e| e.into_inner());
        errors.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        let inside: Vec<&(f64, f64)> = errors.iter().filter(|e| e.0 >= lo && e.0 <= hi).collect();
        let trapezoid: f64 = inside
            .windows(2)
            .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
            .sum();
        // the ends of the range, at the nearest evaluation's error
        let ends = inside.first().map_or(0.0, |e| e.1 * (e.0 - lo))
            + inside.last().map_or(0.0, |e| e.1 * (hi - e.0));
        trapezoid + ends
    }
}

/// Separation d_e (m) at the end of impact (eq 17):
/// E_I = integral from d_e to infinity of p_L(d) dd + p_L(d_e)^2 t_s/(2E),
/// with p_L the loading (approach) pressure of a surface with `history`, `impact_energy`
/// per unit *contact* area.
///
/// **d_e is the first closure of the energy balance on the way in at which the approach
/// pressure is compressive** (`docs/theory.md` section 6.2): a closure in the tensile
/// well, where adhesion still pulls the electrode in, is not an end of impact. The search
/// starts where the first asperities touch (the approach reach) and integrates p_L
/// downward in steps with error-controlled quadrature; the root is found on the
/// interpolant of the accepted panels and verified with exact evaluations (Newton).
pub fn end_of_impact<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    impact_energy: f64,
    film: ImpactFilm,
    precision: Precision,
) -> Result<EndOfImpact, SwitchError> {
    end_of_impact_near(surface, history, impact_energy, film, precision, None)
}

/// [`end_of_impact`] with a guess of d_e (the previous cycle's): the first step of the
/// search then reaches just past it. Only the cost depends on the guess: the first closure
/// is found wherever it lies.
fn end_of_impact_near<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    impact_energy: f64,
    film: ImpactFilm,
    precision: Precision,
    guess: Option<f64>,
) -> Result<EndOfImpact, SwitchError> {
    positive("impact_energy", impact_energy)?;
    positive("film_thickness", film.thickness)?;
    positive("film_youngs_modulus", film.youngs_modulus)?;
    positive("precision.d_e", precision.d_e)?;
    let scales = surface.length_scales(history)?;
    let target = precision.d_e * scales.roughness;
    let mut tighten = 1.0;
    let balance = Balance {
        energy: impact_energy,
        film,
        precision,
        scales,
        guess,
    };
    let memo = Memo::default();
    let solve = |tighten| solve_eq17(surface, history, &balance, tighten, &memo);
    let (mut end, mut from_pressures) = solve(tighten)?;
    // The energy tolerance assumed a typical depth below the first touch: tighten it by
    // what the error estimate says, twice at most. Only the part of the estimate that the
    // energy quadrature controls can be tightened: the part the approach pressures' own
    // errors cause is the same however finely they are integrated. The quadrature's part is
    // aimed at a third of the target, and once it is there the solve is not repeated for
    // the rest (tightening by the whole estimate, where the pressures' part alone exceeded
    // the target, refined on the pressures' noise: a plausible MEMS scene spent 60 s in
    // accurate mode doing so, against 0.9 s in reference mode, docs/performance.md
    // section 9).
    for _ in 0..2 {
        let controlled = end.error - from_pressures;
        let aim = 0.3 * target;
        if end.error <= target || controlled <= aim {
            break;
        }
        tighten *= (aim / controlled).clamp(1e-6, 0.5);
        (end, from_pressures) = solve(tighten)?;
    }
    Ok(end)
}

/// The energy balance of eq 17 to solve, and what the search knows beforehand.
struct Balance {
    energy: f64,
    film: ImpactFilm,
    precision: Precision,
    scales: LengthScales,
    guess: Option<f64>,
}

/// One solve of eq 17 with the energy tolerance scaled by `tighten`: the end of impact, and
/// the part of its error estimate (m) that the approach pressures' own error estimates
/// cause (integrated over the approach, over the balance's slope).
fn solve_eq17<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    balance: &Balance,
    tighten: f64,
    memo: &Memo,
) -> Result<(EndOfImpact, f64), SwitchError> {
    let Balance {
        energy,
        film,
        precision,
        scales,
        guess,
    } = *balance;
    let sigma = scales.roughness;
    let top = surface.reach(history, Path::Approach)?;
    let tol_d = precision.d_e * sigma;
    let rule = AdaptiveRule::new(ENERGY_NODES)?;
    let polish_rule = GaussLegendre::new(POLISH_NODES);
    // energy error -> d_e error: delta d_e ~ delta W / p(d_e) <= delta W (top - d_e)/E_I,
    // with top - d_e about 20 sigma; checked a posteriori by the error estimate
    let quad = QuadTolerance {
        rel: 0.0,
        rel_of_abs: ENERGY_SHARE * precision.d_e * tighten,
        abs: ENERGY_SHARE * precision.d_e * tighten * energy,
        max_width: 0.0,
        max_panels: 4000,
        noise: NOISE,
    };
    let mut kinks = surface.kinks(history);
    kinks.sort_by(|a, b| b.total_cmp(a));
    let mut ap = Approach {
        surface,
        history,
        errors: Mutex::new(Vec::new()),
        memo,
    };
    let integral = |ap: &Approach<S>, lo: f64, hi: f64| {
        let mut breaks = vec![lo];
        breaks.extend(kinks.iter().rev().filter(|&&k| k > lo && k < hi));
        breaks.push(hi);
        integrate_panels_par(
            "eq 17 energy integral",
            |x| ap.p(x),
            &breaks,
            false,
            &rule,
            quad,
        )
    };
    let mut hi = top;
    let mut work = 0.0; // integral of p_L from hi to top
    let mut work_error = 0.0;
    // below the deepest separation reached before, when the surface gives the work above
    // it and the balance is shown not to close there: the search starts at D
    let start = below_deepest(surface, history, balance, quad, top)?;
    // twice the depth the energy left at D would reach at D's pressure (the pressure only
    // grows below D, so the balance closes before), at least a thousandth of sigma and at
    // most a quarter
    let below = |s: &Start| (START_DEPTHS * s.depth).clamp(1e-3 * sigma, 0.25 * sigma);
    let mut step = match (&start, guess) {
        // from where the balance is shown open down to D first
        (Some(s), _) if s.safe > s.d => s.safe - s.d,
        (Some(s), _) => below(s),
        // a quarter of sigma past the guess: between cycles d_e moves by less
        (None, Some(g)) if g < hi => hi - g + 0.25 * sigma,
        _ => 0.25 * sigma,
    };
    let mut next_step = None;
    let mut first_lo = None;
    if let Some(s) = &start {
        if s.safe > s.d {
            // the work above `safe`: W(D) less the integral from D to `safe`, on the panels
            // the first step then finds again (the memo holds their pressures)
            let (int, _) = integral(&ap, s.d, s.safe)?;
            (hi, work, work_error) = (s.safe, s.work.value - int.value, s.work.error + int.error);
            next_step = Some(below(s));
            // exactly D, so the step's panels are those just integrated
            first_lo = Some(s.d);
        } else {
            (hi, work, work_error) = (s.d, s.work.value, s.work.error);
        }
    }
    let floor = scales.deepest.max(top - DEPTH_LIMIT * sigma);
    // the approach pressures evaluated lie below where the search started (the work above
    // it carries its own error)
    let hi_start = hi;
    while hi > floor {
        // where the approach below is the virgin loading and the surface tabulates it,
        // the search needs no pressures but the last few
        if next_step.is_none() {
            let above = Above {
                hi,
                work: Estimate {
                    value: work,
                    error: work_error,
                },
                // the evaluated pressures' share of the work above hi
                pressures_error: ap.error_integral(hi, top.min(hi_start)),
                step,
                floor,
            };
            if let Some(found) = tabulated(surface, history, balance, quad, above)? {
                return Ok(found);
            }
        }
        // never below the deepest separation the surface covers: an end of impact beyond
        // it is no end of impact, as on the tables
        let lo = first_lo.take().unwrap_or(hi - step).max(floor);
        let (int, mut panels) = integral(&ap, lo, hi)?;
        panels.sort_by(|a, b| b.a.total_cmp(&a.a));
        if let Some(closure) = first_closure(&panels, work, film, energy, tol_d)? {
            work_error += int.error;
            // verify with exact evaluations: Newton on G(x) = W(x) + film(p(x)) - E_I
            let Closure {
                mut x,
                panel_top,
                work_above,
            } = closure;
            let mut correction = f64::INFINITY;
            let mut p_x = 0.0;
            let mut slope = 0.0;
            // the panel the closure lies in, accepted by the quadrature
            let width = panels
                .iter()
                .find(|p| p.b == panel_top)
                .map_or(0.0, |p| p.b - p.a);
            for _ in 0..6 {
                let (p_now, w) = if x < panel_top && panel_top - x <= width {
                    polish_work(&ap, x, panel_top, &polish_rule)?
                } else {
                    (ap.p(x)?, integral(&ap, x, panel_top)?.0.value)
                };
                p_x = p_now;
                let g = work_above + w + film.energy(p_x) - energy;
                // dG/dx = -p - (p t_s/E) |dp/dx|; dp/dx from the interpolant
                let dp = panel_slope(&panels, x);
                slope = -p_x + film.thickness / film.youngs_modulus * p_x * dp;
                if !(slope < 0.0) {
                    slope = -p_x.abs().max(f64::MIN_POSITIVE);
                }
                correction = -g / slope;
                x += correction;
                if correction.abs() <= 0.1 * tol_d {
                    break;
                }
            }
            let pressures_error = ap.error_integral(x, top.min(hi_start));
            let error = correction.abs() + (work_error + pressures_error) / slope.abs();
            let from_pressures = pressures_error / slope.abs();
            return Ok((
                EndOfImpact {
                    d_e: x,
                    error,
                    pressure: p_x,
                },
                from_pressures,
            ));
        }
        let p_lo = panels.last().map_or(0.0, |p| p.points[0].1);
        work += int.value;
        work_error += int.error;
        hi = lo;
        // grow the step geometrically towards the depth the remaining energy needs
        let remaining = if p_lo > 0.0 {
            (energy - work) / p_lo
        } else {
            f64::INFINITY
        };
        step = next_step.take().unwrap_or_else(|| {
            (2.0 * step)
                .min(remaining.max(0.25 * sigma))
                .min(64.0 * sigma)
        });
    }
    Err(SwitchError::EnergyNotAbsorbed {
        energy,
        d: hi,
        absorbed: work,
    })
}

/// Where eq 17's search starts when it need not cross the approach above the deepest
/// separation reached before.
struct Start {
    /// The deepest separation D (m).
    d: f64,
    /// From here (m, >= D) up the balance is shown open (the bounds of [`below_deepest`]).
    safe: f64,
    /// The approach work above it (J/m^2).
    work: Estimate,
    /// The depth below D at which the balance would close were the pressure to stay at
    /// p(D): (E_I - W(D) - film(p(D))) / p(D) (m).
    depth: f64,
}

/// The first step of eq 17's search below D, in depths the energy left at D would reach
/// at D's pressure.
const START_DEPTHS: f64 = 2.0;
/// Relative headroom on a scan pressure (its tolerance is 1e-3).
const SCAN_MARGIN: f64 = 1e-2;
/// A rough pressure's estimate times this bounds its error.
const ROUGH_ERROR_SAFETY: f64 = 2.0;
/// The largest spacing of the scan pressures that check the approach above D, in
/// sigma_s.
const ABOVE_DEEPEST_SPACING: f64 = 0.5;
/// The first of them, in sigma_s above D; the next ones twice as far, up to the largest
/// spacing.
const ABOVE_DEEPEST_NEAR: f64 = 1e-4;
/// Within this many sigma_s above D the film term is bounded interval by interval, by the
/// larger of its ends' evaluated pressures with their estimates (and [`NEAR_FILM_MARGIN`]):
/// after a nearly accommodated impact E_I - W(D) - film(p(D)) is a few 1e-5 J/m^2 on the
/// paper's switch, less than what the pressure bound P (the reload's rise above D) adds
/// to the film term, and the compressive work pays for that only about 4e-4 sigma_s up.
const NEAR_FILM_SPAN: f64 = 1e-3;
/// Headroom on the larger end's pressure within [`NEAR_FILM_SPAN`]: p is smooth there
/// (the nearest kinks of p_L lie a few hundredths of sigma_s above D) and its rise over an
/// interval of at most 1e-3 sigma_s beyond its ends is of the order of its relative change
/// squared, about 1e-7.
const NEAR_FILM_MARGIN: f64 = 1e-6;

/// The start of eq 17's search at or above the deepest separation D of the history, when
/// the surface knows the approach above D ([`SurfaceLaw::above_deepest`]: the work W(D),
/// integrated over its asperities, and a bound P on the pressure above D), with p(D) > 0:
/// the lowest of D and the samples above it from which the balance
/// G(x) = W(x) + film(p(x)) - E_I stays open all the way up, as far as these bounds show
/// on each interval between samples (at offsets from D growing geometrically from
/// ABOVE_DEEPEST_NEAR sigma_s up to steps of ABOVE_DEEPEST_SPACING sigma_s, each sample
/// read as bounds on the pressure):
/// - the work is at most W(D) + its estimate - C + T: C the compressive work from D to
///   the interval's start and T the tensile work to its end, each interval counted at its
///   smaller lower bound (the approach pressure is compressive from D up to where the
///   contact edge's adhesion takes over, and W(top) = 0 < W(D));
/// - the film term is at most film(max(P, p(D) + its estimate)), or, within
///   NEAR_FILM_SPAN sigma_s of D, film of the larger of the interval's ends (evaluated
///   pressures with their estimates, and NEAR_FILM_MARGIN).
///
/// None where no interval up to the first touch is open: the search starts at the first
/// touch as before. Below D the approach pressure is the virgin one (every asperity in
/// contact is loaded beyond its delta_max), so nothing else changes (docs/theory.md
/// section 6.2).
fn below_deepest<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    balance: &Balance,
    quad: QuadTolerance,
    top: f64,
) -> Result<Option<Start>, SwitchError> {
    let Some(above) = surface.above_deepest(history, quad.abs, quad.rel_of_abs)? else {
        return Ok(None);
    };
    let (d, work) = (above.deepest, above.work);
    let sigma = balance.scales.roughness;
    if !(d < top && d > balance.scales.deepest && work.value.is_finite()) {
        return Ok(None);
    }
    // the balance at D from below (not recorded with the approach's evaluations: a search
    // that starts at the top after all is then the same to the bit as one that never
    // looked here)
    let (energy, film) = (balance.energy, balance.film);
    let at_d = surface.pressure_estimate(d, history, Path::Approach)?;
    if !(at_d.value > 0.0 && above.pressure_bound.is_finite()) {
        return Ok(None);
    }
    // above D, on samples at offsets from D growing geometrically, then evenly up to the
    // first touch: on the interval from x_k to x_k+1 the work is at most
    // W(D) + its estimate - C_k + T_k+1, the compressive work from D counted at each
    // interval's smaller lower bound and the tensile work likewise, and the film term at
    // most film(P), P the surface's bound on the pressure (within NEAR_FILM_SPAN of D,
    // where the compressive work has not yet paid for that bound's slack, the samples are
    // evaluated pressures and the film term is bounded on each interval by its larger end,
    // with their estimates)
    let film_high = film.energy(above.pressure_bound.max(at_d.value + at_d.error));
    let mut xs = Vec::new();
    let mut offset = ABOVE_DEEPEST_NEAR * sigma;
    while d + offset < top {
        xs.push(d + offset);
        offset += offset.min(ABOVE_DEEPEST_SPACING * sigma);
    }
    xs.push(top);
    let near = |x: f64| x - d <= NEAR_FILM_SPAN * sigma;
    // each sample as bounds (lower, upper) on the pressure: evaluated within the near
    // span, else rough where the surface has a rough pressure (its estimate doubled), else
    // its scan pressure (to SCAN_MARGIN)
    let bounds = |e: Estimate, k: f64| (e.value - k * e.error, e.value + k * e.error);
    let ps = par::map(&xs, |&x| {
        if near(x) {
            return Ok::<_, SwitchError>(bounds(
                surface.pressure_estimate(x, history, Path::Approach)?,
                1.0,
            ));
        }
        if let Some(e) = surface.pressure_rough(x, history, Path::Approach)? {
            return Ok(bounds(e, ROUGH_ERROR_SAFETY));
        }
        let p = surface.pressure_scan(x, history, Path::Approach)?;
        Ok((p - SCAN_MARGIN * p.abs(), p + SCAN_MARGIN * p.abs()))
    })?;
    let base = work.value + work.error - energy;
    // interval k runs from starts[k] (D, then the samples); open[k]: its bound is below E_I
    let (mut pushed, mut pulled) = (0.0, 0.0);
    let mut prev = (d, bounds(at_d, 1.0));
    let mut open = Vec::with_capacity(xs.len());
    let mut starts = Vec::with_capacity(xs.len());
    for (&x, &(lower, upper)) in xs.iter().zip(&ps) {
        let (dx, (prev_lower, prev_upper)) = (x - prev.0, prev.1);
        let credit = pushed;
        let least = lower.min(prev_lower);
        pushed += dx * least.max(0.0);
        pulled += dx * (-least).max(0.0);
        let film_k = if near(x) {
            let larger = upper.max(prev_upper) * (1.0 + NEAR_FILM_MARGIN);
            film.energy(larger.min(above.pressure_bound).max(0.0))
        } else {
            film_high
        };
        starts.push(prev.0);
        open.push(base + film_k - credit + pulled < 0.0);
        prev = (x, (lower, upper));
    }
    // the lowest start from which every interval up is open
    let Some(k) = (0..open.len()).rev().take_while(|&k| open[k]).last() else {
        return Ok(None);
    };
    let safe = starts[k];
    let p_d = at_d.value;
    Ok(Some(Start {
        d,
        safe,
        work,
        depth: (energy - work.value - film.energy(p_d)) / p_d,
    }))
}

/// Where eq 17's search stands: at `hi` (m), with the approach work above it (J/m^2) and
/// the part of its estimate the evaluated pressures' own estimates make (J/m^2), the next
/// step (m) and the depth it may not go below (m).
struct Above {
    hi: f64,
    work: Estimate,
    pressures_error: f64,
    step: f64,
    floor: f64,
}

/// eq 17 below `above.hi` on the surface's tabulated virgin loading
/// ([`SurfaceLaw::virgin_work`]), when it offers it there (None otherwise, and where the
/// balance is already closed at the first sample, in the tensile well):
/// - the balance G(x) = W(x) + film(p(x)) - E_I, with W and p from the tables, is sampled
///   in steps growing as the search from the top grows them, to the first sample with
///   p > 0 and G >= 0;
/// - the root of the tabulated G in that step (Brent; where the first step's sample closes,
///   between it and hi, open as the evaluated pressure shows), then Newton on G with the
///   evaluated pressure p(x) and the tabulated work to the root within a tenth of the d_e
///   target, kept inside the bracket the evaluated balance shows, its slope refreshed from
///   the evaluated pressures (None where it does not converge in [`NEWTON_STEPS`]);
/// - the error estimate: the last correction, plus the work's estimate (above and the
///   tables') and the film term's share of the pressure's estimate, over |dG/dx|. The
///   second value returned is the evaluated pressures' share (those above hi and the last
///   one's), which a tighter energy tolerance cannot reduce.
fn tabulated<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    balance: &Balance,
    quad: QuadTolerance,
    above: Above,
) -> Result<Option<(EndOfImpact, f64)>, SwitchError> {
    let Above {
        hi,
        work,
        pressures_error,
        mut step,
        floor,
    } = above;
    let (energy, film) = (balance.energy, balance.film);
    let sigma = balance.scales.roughness;
    let tol_d = balance.precision.d_e * sigma;
    // the balance at x from the tables: (G, p, the work from x to hi)
    let at = |x: f64| -> Result<Option<(f64, f64, Estimate)>, SwitchError> {
        let Some(v) = surface.virgin_work(history, x, hi, quad.abs, quad.rel_of_abs)? else {
            return Ok(None);
        };
        let w = work.value + v.work.value;
        Ok(Some((
            w + film.energy(v.pressure) - energy,
            v.pressure,
            v.work,
        )))
    };
    // the tabulated balance closes at `lo` and is open at `hi` (where the first sample
    // closes, open as the evaluated pressure shows: just below a deepest point the last
    // impact nearly closed at, the tabulated pressure, to 1e-3, cannot tell)
    let mut upper = (hi, f64::NEG_INFINITY);
    let (lo, top) = loop {
        let lo = (upper.0 - step).max(floor);
        let Some((g, p, v)) = at(lo)? else {
            return Ok(None);
        };
        if g >= 0.0 && !(p > 0.0) {
            // closed in the tensile well: the search with panels decides
            return Ok(None);
        }
        if p > 0.0 && g >= 0.0 {
            if upper.0 == hi {
                let e = surface.pressure_estimate(hi, history, Path::Approach)?;
                let g_hi = work.value + film.energy(e.value) - energy;
                if !(e.value > 0.0) || g_hi >= 0.0 {
                    return Ok(None);
                }
                upper.1 = g_hi;
            }
            break (
                Sample { x: lo, f: g },
                Sample {
                    x: upper.0,
                    f: upper.1,
                },
            );
        }
        if lo <= floor {
            return Err(SwitchError::EnergyNotAbsorbed {
                energy,
                d: lo,
                absorbed: work.value + v.value,
            });
        }
        let remaining = if p > 0.0 {
            (energy - work.value - v.value) / p
        } else {
            f64::INFINITY
        };
        step = (2.0 * step)
            .min(remaining.max(0.25 * sigma))
            .min(64.0 * sigma);
        upper = (lo, g);
    };
    let g_of = |x: f64| -> Result<f64, SwitchError> { Ok(at(x)?.map_or(f64::NAN, |(g, _, _)| g)) };
    let root = brent_from(
        "eq 17 on the tabulated virgin loading",
        g_of,
        lo,
        top,
        // to a thousandth of sigma: Newton with the evaluated pressure goes on from there
        Tolerance {
            rel: 0.0,
            abs: (1e-3 * sigma).max(0.01 * tol_d),
            max_iter: 200,
        },
    );
    // a table the surface could not give inside the bracket: the search with panels
    // decides
    let Ok(mut x) = root else {
        return Ok(None);
    };
    let width = top.x - lo.x;
    // the tables answer below hi only
    let below_hi = hi.next_down();
    x = x.min(below_hi);
    // dp/dx of the tabulated pressure, for the film term's share of dG/dx (one-sided where
    // x lies within h of hi)
    let h = (1e-3 * width).max(16.0 * f64::EPSILON * x.abs());
    let (xa, xb) = if x + h < hi {
        (x - h, x + h)
    } else {
        (x - 2.0 * h, x)
    };
    let (p1, p2) = match (at(xa)?, at(xb)?) {
        (Some(a), Some(b)) => (a.1, b.1),
        _ => return Ok(None),
    };
    let mut dp = (p2 - p1) / (xb - xa);
    // Newton on G with the evaluated pressure, kept inside the bracket the evaluated
    // balance shows (closed at `closed`, open at `open`; halved where a step leaves it),
    // dp/dx refreshed from the evaluated pressures once the steps are long enough for
    // their difference to be above their noise: the film term makes G convex, and a slope
    // frozen at a far start converged too slowly (a soft film's d_e 4e-3 sigma_s off after
    // six steps, issue 41). A Newton that does not converge leaves it to the panels.
    let (mut closed, mut open) = (lo.x, top.x.min(below_hi));
    let mut correction = f64::INFINITY;
    let (mut p_x, mut slope, mut errors) = (0.0, -1.0, (0.0, 0.0));
    let mut last: Option<(f64, f64)> = None;
    let mut converged = false;
    for _ in 0..NEWTON_STEPS {
        let e = surface.pressure_estimate(x, history, Path::Approach)?;
        let Some((_, _, v)) = at(x)? else {
            return Ok(None);
        };
        p_x = e.value;
        if let Some((x0, p0)) = last {
            if (x - x0).abs() > 1e-3 * sigma {
                dp = (p_x - p0) / (x - x0);
            }
        }
        last = Some((x, p_x));
        let g = work.value + v.value + film.energy(p_x) - energy;
        if g >= 0.0 {
            closed = closed.max(x);
        } else {
            open = open.min(x);
        }
        slope = -p_x + film.thickness / film.youngs_modulus * p_x * dp;
        if !(slope < 0.0) {
            slope = -p_x.abs().max(f64::MIN_POSITIVE);
        }
        errors = (
            work.error + v.error,
            pressures_error + film.thickness / film.youngs_modulus * p_x.abs() * e.error,
        );
        correction = -g / slope;
        if correction.abs() <= 0.1 * tol_d {
            x = (x + correction).min(below_hi);
            converged = true;
            break;
        }
        let next = x + correction;
        x = if next > closed && next < open {
            next
        } else {
            0.5 * (closed + open)
        };
    }
    if !converged {
        return Ok(None);
    }
    if !(p_x > 0.0) {
        // a closure in the tensile well: the search with panels decides
        return Ok(None);
    }
    let error = correction.abs() + (errors.0 + errors.1) / slope.abs();
    Ok(Some((
        EndOfImpact {
            d_e: x,
            error,
            pressure: p_x,
        },
        errors.1 / slope.abs(),
    )))
}

/// Newton steps on the tabulated virgin loading before the search with panels is left to
/// decide (a step halves the bracket where Newton would leave it).
const NEWTON_STEPS: usize = 40;

/// Gauss-Legendre nodes of the work from a Newton iterate to its panel's top.
const POLISH_NODES: usize = 8;

/// The approach pressure at x and its work from x to `top` (J/m^2), all in one parallel
/// batch: the work by the `rule` (POLISH_NODES points, exact to degree 15) on [x, top]. Only
/// used where [x, top] lies inside a panel the adaptive quadrature accepted with its
/// 2 x ENERGY_NODES-point halves (degree 11 on each half, within the energy tolerance): a
/// rule of higher degree on a part of that panel errs less than the accepted halves did,
/// at 9 pressures instead of the 21 of a fresh adaptive integral.
fn polish_work<S: SurfaceLaw>(
    ap: &Approach<S>,
    x: f64,
    top: f64,
    rule: &GaussLegendre,
) -> Result<(f64, f64), SwitchError> {
    let mut points: Vec<(f64, f64)> = vec![(x, 0.0)];
    points.extend(rule.mapped(x, top));
    let ps = par::map(&points, |&(d, _)| ap.p(d))?;
    let work = points[1..]
        .iter()
        .zip(&ps[1..])
        .map(|(&(_, w), p)| w * p)
        .sum();
    Ok((ps[0], work))
}

/// Where the energy balance first closes with a compressive pressure, on the
/// interpolants of a step's panels.
struct Closure {
    /// The separation (to be polished).
    x: f64,
    /// The top of its panel ...
    panel_top: f64,
    /// ... and the work of p_L from there to the first touch.
    work_above: f64,
}

/// Walks the panels of a step from the top down (`work`: the work above the step), sampling
/// each panel's interpolant at its points, and returns the first closure of
/// G(x) = W(x) + film(p(x)) - E_I at which p(x) > 0: between the last sample where the
/// balance is open or the pressure tensile and the first where it is closed and
/// compressive. Samples at the rule's nodes resolve every sign change the quadrature
/// resolves, whatever the step's length.
fn first_closure(
    panels: &[PanelNodes],
    mut work: f64,
    film: ImpactFilm,
    energy: f64,
    tol_d: f64,
) -> Result<Option<Closure>, SwitchError> {
    for p in panels {
        let poly = p.interpolant();
        let g = |x: f64| w_plus(&poly, work, x, p.b) + film.energy(poly.eval(x)) - energy;
        // samples from the top of the panel down
        let mut prev: Option<(f64, f64, f64)> = None; // (x, p, G)
        for &(x, px) in p.points.iter().rev() {
            let gx = g(x);
            if px > 0.0 && gx >= 0.0 {
                let Some((xp, pp, gp)) = prev else {
                    // closed at the panel's top: the previous panel's bottom sample was not,
                    // so the closure is at this boundary
                    return Ok(Some(Closure {
                        x,
                        panel_top: p.b,
                        work_above: work,
                    }));
                };
                // bracket [x, xp]: if the pressure was tensile at xp, start where it turns
                let (top_x, top_g) = if pp > 0.0 {
                    (xp, gp)
                } else {
                    let z = brent_from(
                        "where the approach pressure turns compressive",
                        |t| Ok::<_, CoreError>(poly.eval(t)),
                        Sample { x, f: px },
                        Sample { x: xp, f: pp },
                        Tolerance::absolute(1e-3 * tol_d).with_max_iter(200),
                    )?;
                    (z, g(z))
                };
                let root = if top_g >= 0.0 {
                    top_x
                } else {
                    brent_from(
                        "end of impact, eq 17",
                        |t| Ok::<_, CoreError>(g(t)),
                        Sample { x, f: gx },
                        Sample { x: top_x, f: top_g },
                        Tolerance::absolute(1e-3 * tol_d).with_max_iter(200),
                    )?
                };
                return Ok(Some(Closure {
                    x: root,
                    panel_top: p.b,
                    work_above: work,
                }));
            }
            prev = Some((x, px, gx));
        }
        work += p.value;
    }
    Ok(None)
}

/// Work above the panel plus the interpolant's integral from x to the panel's top.
fn w_plus(poly: &Interpolant, work: f64, x: f64, b: f64) -> f64 {
    work + poly.integral(x, b)
}

/// dp/dx of the interpolant of the panel holding x (x in the step).
fn panel_slope(panels: &[PanelNodes], x: f64) -> f64 {
    let Some(p) = panels.iter().find(|p| x >= p.a && x <= p.b) else {
        return 0.0;
    };
    let poly: Interpolant = p.interpolant();
    let h = 1e-4 * (p.b - p.a);
    (poly.eval((x + h).min(p.b)) - poly.eval((x - h).max(p.a))) / (2.0 * h).max(f64::MIN_POSITIVE)
}

/// The unloading branch of one cycle.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Unloading {
    /// Magnitude of the most tensile unloading pressure (Pa, >= 0).
    pub pull_out_pressure: f64,
    /// Its estimated error (Pa).
    pub pull_out_error: f64,
    /// Separation where it occurs (m).
    pub pull_out_separation: f64,
    /// The curve from d_e to the surface's reach (empty when not asked for).
    pub curve: Vec<PressurePoint>,
    /// The adhesive well sampled on its own: half as many points as the curve, evenly
    /// from d_e to 2.5 times the pull-out's distance from d_e (empty when no curve is asked
    /// for or nothing pulls), for a plot that shows the well and its minimum.
    pub well: Vec<PressurePoint>,
}

/// Samples per decade of the geometric part of the pull-out search grid.
const SCAN_PER_DECADE: usize = 12;

/// The separations the pull-out search samples after unloading from `d_e`: geometric in
/// d - d_e from a quarter of the law's finest length scale (so a narrow well just after
/// d_e cannot fall between samples), united with even steps of a quarter of the
/// roughness up to the reach. Independent of any curve the caller asks for.
pub fn pull_out_grid(d_e: f64, reach: f64, scales: LengthScales) -> Vec<f64> {
    let span = reach - d_e;
    if !(span > 0.0) {
        return vec![d_e];
    }
    let start = (0.25 * scales.finest).min(0.5 * span);
    let decades = (span / start).log10().max(1.0);
    let n_geo = (decades * SCAN_PER_DECADE as f64).ceil() as usize + 1;
    let n_lin = ((span / (0.25 * scales.roughness)).ceil() as usize).clamp(8, 4000) + 1;
    let mut grid: Vec<f64> = std::iter::once(d_e)
        .chain(geomspace(start, span, n_geo).map(|x| d_e + x))
        .chain(linspace(d_e, reach, n_lin))
        .collect();
    grid.sort_by(f64::total_cmp);
    grid.dedup();
    grid
}

/// Unloading from `d_e` for a surface whose `history` already includes the loading to
/// `d_e`: the pull-out pressure (the most tensile unloading pressure), found on
/// [`pull_out_grid`] with the surface's scan pressure and refined with its accurate
/// pressure (best local minima, each to a tenth of the precision's pull-out target relative
/// to its bracket: a minimum may sit on a kink of the pressure, where the surface's contact
/// edge turns from jump-in to jump-out, and the value error is then linear in the location
/// error; Brent's parabolic steps make a smooth minimum cheap all the same); and the curve at `points` separations evenly from d_e to the
/// reach (none if 0), which never affects the pull-out.
pub fn unload<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    d_e: f64,
    points: usize,
    precision: Precision,
) -> Result<Unloading, SwitchError> {
    let path = Path::Retract { from: d_e };
    let reach = surface.reach(history, path)?;
    let scales = surface.length_scales(history)?;
    let grid = pull_out_grid(d_e, reach, scales);
    let (mut ys, cut) = scan(surface, history, path, &grid)?;
    // the refinement's estimates by the bits of x: the minimum's error estimate is then
    // the one evaluated with its value, not a second evaluation
    let mut refined: Memo = Memo::default();
    let refine = |ys: &[f64]| {
        refine_minima_par(
            "pull-out pressure",
            |x| {
                let e = surface.pressure_estimate(x, history, path)?;
                refined
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .insert(x.to_bits(), e);
                Ok::<_, SwitchError>(e.value)
            },
            &grid[..ys.len()],
            ys,
            Tolerance::relative((0.1 * precision.pull_out).clamp(1e-12, 1e-3)),
        )
    };
    let mut m = refine(&ys)?;
    // the scan stopped on its coarse samples; the refined pull-out must beat the bound too
    // (it does unless the scan pressure erred by half the tension, where the forces
    // summed nearly cancel): otherwise the rest of the grid is sampled after all
    if cut.is_some_and(|b| !(m.value < 0.0 && b < -m.value)) {
        ys.extend(par::map(&grid[ys.len()..], |&d| {
            surface.pressure_scan(d, history, path)
        })?);
        m = refine(&ys)?;
    }
    let (pull, at, error) = if m.value < 0.0 {
        let known = refined
            .get_mut()
            .unwrap_or_else(|e| e.into_inner())
            .get(&m.x.to_bits())
            .copied();
        let e = match known {
            Some(e) => e,
            None => surface.pressure_estimate(m.x, history, path)?,
        };
        (-m.value, m.x, e.error)
    } else {
        (0.0, reach, 0.0)
    };
    let sample = |ds: &[f64]| {
        par::map(ds, |&d| {
            Ok::<_, SwitchError>(PressurePoint {
                d,
                pressure: surface.pressure(d, history, path)?,
            })
        })
    };
    let ds: Vec<f64> = linspace(d_e, reach, if points == 0 { 0 } else { points.max(2) }).collect();
    let curve = sample(&ds)?;
    let well = if points > 0 && pull > 0.0 {
        let end = (d_e + 2.5 * (at - d_e)).min(reach);
        let mut ds: Vec<f64> = linspace(d_e, end, (points / 2).max(2)).collect();
        ds.push(at);
        ds.sort_by(f64::total_cmp);
        ds.dedup();
        sample(&ds)?
    } else {
        Vec::new()
    };
    Ok(Unloading {
        pull_out_pressure: pull,
        pull_out_error: error,
        pull_out_separation: at,
        curve,
        well,
    })
}

/// Samples of the pull-out scan evaluated before the first check of the tension bound:
/// the geometric start of the grid, where the contact is still compressive.
const SCAN_FIRST_BATCH: usize = 24;
/// Samples per batch after it (each batch in parallel).
const SCAN_BATCH: usize = 4;
/// The scan stops once the surface's tension bound beyond the next sample is below this
/// fraction of the most tensile sample: the scan's pressures err by about 1e-3 of the
/// forces summed, far less than the headroom.
const SCAN_STOP: f64 = 0.5;

/// A rough pressure counts as surely compressive when it exceeds this many times its
/// error estimate.
const ROUGH_SAFETY: f64 = 4.0;

/// The scan pressures of the pull-out search on `grid`, outward from d_e in batches,
/// ended early when the surface bounds the tension further out
/// ([`SurfaceLaw::tension_bound`]) below [`SCAN_STOP`] of the most tensile sample so far
/// and the last sample is not a local minimum (so the truncated grid offers the
/// refinement the same candidates as the whole grid, save those the bound rules out),
/// with the bound where it stopped. Without a bound, every sample.
///
/// The compressive start of the retraction is evaluated roughly
/// ([`SurfaceLaw::pressure_rough`]) as long as each rough pressure is surely compressive
/// (above [`ROUGH_SAFETY`] times its estimate); from the first that is not, every sample
/// is a scan pressure. Where a sample is tensile the refinement looks only at tensile
/// local minima, whose neighbours and brackets are the same as with scan pressures
/// throughout, so the pull-out is the same to the bit; where none is, the rough samples
/// are evaluated again as scan pressures before the refinement ranks them.
fn scan<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    path: Path,
    grid: &[f64],
) -> Result<(Vec<f64>, Option<f64>), SwitchError> {
    let pressures = |ds: &[f64]| par::map(ds, |&d| surface.pressure_scan(d, history, path));
    // the rough start: the samples before the first that is not surely compressive
    let mut rough = 0;
    let mut rough_open = true;
    let mut sample = |ds: &[f64], rough_open: &mut bool| -> Result<Vec<f64>, SwitchError> {
        if !*rough_open {
            return Ok(pressures(ds)?);
        }
        let estimates = par::map(ds, |&d| surface.pressure_rough(d, history, path))?;
        let sure = estimates
            .iter()
            .take_while(|e| e.is_some_and(|e| e.value > ROUGH_SAFETY * e.error && e.value > 0.0))
            .count();
        rough += sure;
        let mut ys: Vec<f64> = estimates[..sure]
            .iter()
            .map(|e| e.map_or(f64::NAN, |e| e.value))
            .collect();
        if sure < ds.len() {
            *rough_open = false;
            ys.extend(pressures(&ds[sure..])?);
        }
        Ok(ys)
    };
    let (mut ys, cut) = 'scan: {
        // a law without a bound (asked at the far end, where it is cheapest) gets one batch
        let Some(&last) = grid.last() else {
            return Ok((Vec::new(), None));
        };
        if surface.tension_bound(last, history, path)?.is_none() {
            break 'scan (sample(grid, &mut rough_open)?, None);
        }
        let mut ys: Vec<f64> = Vec::with_capacity(grid.len());
        while ys.len() < grid.len() {
            let start = ys.len();
            let batch = if start == 0 {
                SCAN_FIRST_BATCH
            } else {
                SCAN_BATCH
            };
            let end = (start + batch).min(grid.len());
            ys.extend(sample(&grid[start..end], &mut rough_open)?);
            let n = ys.len();
            let least = ys.iter().copied().fold(f64::INFINITY, f64::min);
            if n < grid.len() && least < 0.0 && ys[n - 1] >= ys[n - 2] {
                if let Some(b) = surface.tension_bound(grid[n], history, path)? {
                    if b < SCAN_STOP * -least {
                        break 'scan (ys, Some(b));
                    }
                }
            }
        }
        (ys, None)
    };
    // nothing tensile: the refinement ranks compressive local minima, which need the
    // scan pressures of the rough start too
    if rough > 0 && !ys.iter().any(|&y| y < 0.0) {
        let exact = pressures(&grid[..rough])?;
        ys[..rough].copy_from_slice(&exact);
    }
    Ok((ys, cut))
}

/// Where the closed switch rests after an impact under a hold pressure.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[non_exhaustive]
pub enum Rest {
    /// At this separation (m), on the unloading branch from d_e, where the contact
    /// pressure balances the hold pressure.
    At(f64),
    /// At this separation (m) below d_e: the hold pressure exceeds the contact pressure at
    /// the end of impact, so the hold loads the surface further, on the approach branch of
    /// the impact's history, until the contact pushes back as hard.
    Deeper(f64),
    /// The hold pressure pulls harder than the contact's pull-out can hold: no rest, the
    /// switch opens.
    Opens,
}

impl Rest {
    /// The rest separation (m), if the switch rests.
    pub fn separation(self) -> Option<f64> {
        match self {
            Rest::At(d) | Rest::Deeper(d) => Some(d),
            Rest::Opens => None,
        }
    }

    /// `rests`, `deeper_than_impact` or `opens`.
    pub fn as_str(self) -> &'static str {
        match self {
            Rest::At(_) => "rests",
            Rest::Deeper(_) => "deeper_than_impact",
            Rest::Opens => "opens",
        }
    }
}

/// The rest of a closed switch after an impact to `d_e` (`history` loaded to it) under the
/// hold pressure `hold` (Pa per contact area, compressive > 0; negative when the spring
/// outweighs the electrostatic hold and only adhesion keeps the switch shut).
///
/// When p(d_e) >= hold the rest is the smallest separation d >= d_e on the unloading
/// branch where the contact pressure equals `hold`: the unloading pressure falls from
/// p(d_e) to the pull-out minimum at `pull_out_separation`, so the root lies on that
/// falling part (stable: opening lowers the contact's push); when the pull-out minimum
/// still exceeds `hold` the switch opens. When p(d_e) < hold the hold presses further: the
/// rest lies below d_e on the approach branch with the impact's history. Found to 1e-12
/// of the roughness scale (`precision` is kept for callers and future use).
pub fn rest<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    d_e: f64,
    pull_out_separation: f64,
    hold: f64,
    precision: Precision,
) -> Result<Rest, SwitchError> {
    let scale = surface.length_scales(history)?.roughness;
    // Brent converges superlinearly: a rest far tighter than the mode's d_e tolerance costs
    // a few pressures more and keeps p(rest) = hold to the pressure's own precision even
    // where the unloading curve is steep (a small hold on a stiff contact)
    let _ = precision;
    let tolerance = Tolerance::absolute(1e-12 * scale).with_max_iter(200);
    let retract = Path::Retract { from: d_e };
    let g =
        |d: f64| -> Result<f64, SwitchError> { Ok(surface.pressure(d, history, retract)? - hold) };
    let top = Sample { x: d_e, f: g(d_e)? };
    if top.f == 0.0 {
        return Ok(Rest::At(d_e));
    }
    if top.f < 0.0 {
        let approach = |d: f64| -> Result<f64, SwitchError> {
            Ok(surface.pressure(d, history, Path::Approach)? - hold)
        };
        let deepest = surface.length_scales(history)?.deepest.min(d_e);
        let Some((a, b)) = contact_core::numeric::expand_bracket(
            "rest of the closed switch below the end of impact",
            approach,
            Sample { x: d_e, f: top.f },
            d_e - 0.05 * scale,
            contact_core::numeric::Expansion::Geometric(2.0),
            deepest,
        )?
        else {
            return Err(SwitchError::HoldNotBorne { hold, deepest });
        };
        let d = brent_from(
            "rest of the closed switch below the end of impact",
            approach,
            a,
            b,
            tolerance,
        )?;
        return Ok(Rest::Deeper(d));
    }
    let end = pull_out_separation.max(d_e);
    let bottom = Sample { x: end, f: g(end)? };
    if bottom.f > 0.0 {
        return Ok(Rest::Opens);
    }
    let d = brent_from("rest of the closed switch", g, top, bottom, tolerance)?;
    Ok(Rest::At(d))
}

/// What an impact brings to the contact, and what the spring opposes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Impact {
    /// Impact energy per unit electrode area E_I (J/m^2).
    pub energy: f64,
    /// The film that stores elastic energy (eq 17).
    pub film: ImpactFilm,
    /// Fraction phi in (0, 1] of the electrode area that meets the substrate (1: the
    /// paper's whole electrode). The contacting part absorbs the impact, E_I/phi per unit
    /// contact area; the adhesion acts on phi of the electrode area.
    pub contact_area_fraction: f64,
    /// The spring's restoring pressure at contact K_s d0 (Pa, per unit electrode area).
    pub restoring_pressure: f64,
}

impl Impact {
    fn validated(self) -> Result<Self, SwitchError> {
        positive("impact_energy", self.energy)?;
        positive("restoring_pressure", self.restoring_pressure)?;
        let phi = self.contact_area_fraction;
        if !(phi.is_finite() && phi > 0.0 && phi <= 1.0) {
            return Err(CoreError::Invalid {
                field: "contact_area_fraction",
                value: phi,
                allowed: "in (0, 1]",
            }
            .into());
        }
        Ok(self)
    }

    /// Pull-out pressure (per contact area) over restoring pressure (per electrode area),
    /// counting the adhesion on the contacting fraction only: phi p / (K_s d0).
    pub fn pull_out_ratio(&self, pull_out_pressure: f64) -> f64 {
        self.contact_area_fraction * pull_out_pressure / self.restoring_pressure
    }
}

/// What the cycle runner computes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleOptions {
    /// Number of cycles (or the cap when `until_accommodated`).
    pub cycles: usize,
    /// Stop at the first cycle after which accommodation is detected.
    pub until_accommodated: bool,
    /// Accommodation: the next cycle changes the pull-out pressure by less than this
    /// fraction and d_e by less than this fraction of the surface's roughness scale.
    pub accommodation_tolerance: f64,
    /// Points on each unloading curve (0: pull-out pressures only).
    pub unloading_points: usize,
    /// Points on the first loading curve (0: none).
    pub loading_points: usize,
    /// Accuracy of d_e and of the pull-out.
    pub precision: Precision,
}

impl Default for CycleOptions {
    fn default() -> Self {
        Self {
            cycles: 10,
            until_accommodated: false,
            accommodation_tolerance: 1e-3,
            unloading_points: 200,
            loading_points: 200,
            precision: Precision::default(),
        }
    }
}

/// One loading/unloading cycle.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Cycle<H> {
    /// 1-based cycle number.
    pub cycle: usize,
    /// End of impact.
    pub end: EndOfImpact,
    /// The history after this cycle's loading.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub history: H,
    /// Unloading and pull-out.
    pub unloading: Unloading,
    /// phi pull-out / (K_s d0).
    pub pull_out_ratio: f64,
    /// The spring cannot open the switch after this cycle: ratio > 1.
    pub sticks: bool,
    /// This impact went deeper than every earlier one (d_e below the deepest separation
    /// reached before; always true for the first cycle). An impact that does not deepen
    /// leaves the history unchanged, so every later cycle repeats it.
    pub deepened: bool,
    /// How far d_e stops above the deepest separation of the earlier cycles (m, >= 0; 0
    /// when it deepened).
    pub shallower_by: f64,
}

/// Why a run counts as accommodated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[non_exhaustive]
pub enum AccommodationCause {
    /// The impacts still deepen, by less than the tolerance: the history saturates.
    Saturated,
    /// The impact did not go deeper than an earlier one, so the history stopped changing
    /// and every later cycle repeats: accommodation by a non-deepening impact (with eq 12
    /// as printed, the reload overshoot can cause it; theory 6.3).
    NonDeepening,
}

impl AccommodationCause {
    /// The name outputs use: `saturated` or `non_deepening`.
    pub fn as_str(self) -> &'static str {
        match self {
            AccommodationCause::Saturated => "saturated",
            AccommodationCause::NonDeepening => "non_deepening",
        }
    }
}

impl<H> Cycle<H> {
    /// End-of-impact separation d_e (m).
    pub fn d_e(&self) -> f64 {
        self.end.d_e
    }
}

/// The cycles and what was learned from them.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct CycleRun<H> {
    /// The first (virgin) loading curve, from d_e of cycle 1 to the reach.
    pub loading: Vec<PressurePoint>,
    /// Every cycle run.
    pub cycles: Vec<Cycle<H>>,
    /// The cycle after which nothing changes any more (within the tolerance).
    pub accommodated_after: Option<usize>,
    /// Why: the history saturating, or an impact that did not deepen.
    pub accommodation_cause: Option<AccommodationCause>,
    /// When the run stopped at accommodation (`until_accommodated`): an estimate of how
    /// much the largest pull-out could still grow in the cycles not run (Pa): the last
    /// change accepted by the tolerance, extended as a geometric series of the last two
    /// changes (ratio capped at 0.9); 0 when the history stopped changing (every later
    /// cycle repeats) or when the run was not stopped early.
    pub stopping_error: f64,
    /// The largest pull-out pressure of all cycles (Pa, per contact area).
    pub largest_pull_out: f64,
    /// The largest phi pull-out / (K_s d0).
    pub pull_out_ratio: f64,
    /// The first cycle that sticks.
    pub first_sticking_cycle: Option<usize>,
    /// Some cycle sticks.
    pub stiction: bool,
}

/// Runs impact cycles on `surface` from `history`: each cycle finds d_e from eq 17 with
/// the history so far (energy E_I/phi per contact area), loads the history to d_e, unloads,
/// and judges the pull-out against the spring. `on_cycle` sees each cycle as it ends
/// (progress reporting).
pub fn run_cycles<S: SurfaceLaw>(
    surface: &S,
    history: S::History,
    impact: Impact,
    options: CycleOptions,
    on_cycle: &mut dyn FnMut(&Cycle<S::History>),
) -> Result<CycleRun<S::History>, SwitchError> {
    let impact = impact.validated()?;
    if options.cycles == 0 {
        return Err(CoreError::Invalid {
            field: "cycles",
            value: 0.0,
            allowed: "at least 1",
        }
        .into());
    }
    let tol = positive("accommodation_tolerance", options.accommodation_tolerance)?;
    let energy = impact.energy / impact.contact_area_fraction;
    let start = history.clone();
    let mut hist = history;
    let mut cycles: Vec<Cycle<S::History>> = Vec::new();
    let mut accommodated_after = None;
    let mut accommodation_cause = None;
    let mut loading = Vec::new();
    // the history the last cycle started from: a cycle starting from the same one repeats it
    let mut last_start: Option<S::History> = None;
    // the end of impact of the next cycle, found beside this cycle's unloading (it needs
    // only the history after this impact, which unloading does not change): computed as
    // it would be in its own cycle, so the same to the bit
    let mut next_end: Option<(S::History, Result<EndOfImpact, SwitchError>)> = None;
    // a fixed number of cycles needs every unloading: found ahead, a window at a time
    let mut ahead: std::collections::VecDeque<Result<Ahead<S::History>, SwitchError>> =
        Default::default();
    for k in 1..=options.cycles {
        let scale = surface.length_scales(&hist)?.roughness;
        if !options.until_accommodated && ahead.is_empty() {
            let prev = cycles
                .last()
                .zip(last_start.as_ref())
                .map(|(c, start)| (start, c.end));
            let count = AHEAD_WINDOW.min(options.cycles - k + 1);
            ahead = impacts_ahead(surface, &hist, prev, count, energy, impact.film, options).into();
        }
        let (end, new_hist, unloading) = match cycles.last() {
            _ if !options.until_accommodated => {
                let a = ahead
                    .pop_front()
                    .expect("a window holds the cycles asked for")?;
                let unloading = match a.unloading {
                    Some(u) => u?,
                    None => cycles
                        .last()
                        .expect("a repeated cycle follows another")
                        .unloading
                        .clone(),
                };
                (a.end, a.history, unloading)
            }
            Some(prev) if last_start.as_ref() == Some(&hist) => {
                (prev.end, prev.history.clone(), prev.unloading.clone())
            }
            prev => {
                let guess = prev.map(|c| c.end.d_e);
                let end = match next_end.take() {
                    Some((from, end)) if from == hist => end?,
                    _ => end_of_impact_near(
                        surface,
                        &hist,
                        energy,
                        impact.film,
                        options.precision,
                        guess,
                    )?,
                };
                let new_hist = surface.load(&hist, end.d_e);
                // a next cycle that starts from a changed history needs its own eq 17 (one
                // that starts from the same history repeats this cycle); found ahead only
                // when the run is sure to get there: a run that stops at accommodation may
                // stop after this cycle unless d_e alone already rules accommodation out
                let sure = !options.until_accommodated
                    || prev.is_none_or(|p| (end.d_e - p.end.d_e).abs() > tol * scale);
                let ahead = k < options.cycles && new_hist != hist && sure;
                let (unloading, ahead_end) = contact_core::par::join(
                    || {
                        unload(
                            surface,
                            &new_hist,
                            end.d_e,
                            options.unloading_points,
                            options.precision,
                        )
                    },
                    || {
                        ahead.then(|| {
                            end_of_impact_near(
                                surface,
                                &new_hist,
                                energy,
                                impact.film,
                                options.precision,
                                Some(end.d_e),
                            )
                        })
                    },
                );
                // an error of the next cycle's eq 17 belongs to that cycle: reported only
                // if the run gets there
                next_end = ahead_end.map(|e| (new_hist.clone(), e));
                (end, new_hist, unloading?)
            }
        };
        last_start = Some(hist.clone());
        if k == 1 && options.loading_points > 0 {
            let top = surface.reach(&hist, Path::Approach)?;
            let ds: Vec<f64> = linspace(end.d_e, top, options.loading_points.max(2)).collect();
            loading = par::map(&ds, |&d| {
                Ok::<_, SwitchError>(PressurePoint {
                    d,
                    pressure: surface.pressure(d, &hist, Path::Approach)?,
                })
            })?;
        }
        let (deepened, shallower_by, repeats) =
            against_before(&cycles, end.d_e, unloading.pull_out_pressure, tol, scale);
        if let (None, Some((after, cause))) = (accommodated_after, repeats) {
            accommodated_after = Some(after);
            accommodation_cause = Some(cause);
        }
        let ratio = impact.pull_out_ratio(unloading.pull_out_pressure);
        hist = new_hist.clone();
        let cycle = Cycle {
            cycle: k,
            end,
            history: new_hist,
            unloading,
            pull_out_ratio: ratio,
            sticks: ratio > 1.0,
            deepened,
            shallower_by,
        };
        on_cycle(&cycle);
        cycles.push(cycle);
        if options.until_accommodated && accommodated_after.is_some() {
            break;
        }
    }
    carry_history_errors(surface, &start, &mut cycles)?;
    let largest_pull_out = cycles
        .iter()
        .map(|c| c.unloading.pull_out_pressure)
        .fold(0.0, f64::max);
    let first_sticking_cycle = cycles.iter().find(|c| c.sticks).map(|c| c.cycle);
    let stopped_early =
        options.until_accommodated && accommodated_after.is_some() && cycles.len() < options.cycles;
    let stopping_error =
        if stopped_early && accommodation_cause == Some(AccommodationCause::Saturated) {
            stopping_error(&cycles)
        } else {
            0.0
        };
    Ok(CycleRun {
        loading,
        accommodation_cause,
        stopping_error,
        pull_out_ratio: impact.pull_out_ratio(largest_pull_out),
        largest_pull_out,
        stiction: first_sticking_cycle.is_some(),
        first_sticking_cycle,
        accommodated_after,
        cycles,
    })
}

/// A new cycle (deepest separation `d_e`, pull-out pressure `pull_out`) against the cycles
/// before it: whether it deepened the history (its d_e below every earlier one), how far
/// above the deepest earlier d_e it stopped (0 if it deepened), and, where it repeats the
/// last cycle (pull-out within `tol` relative, d_e within `tol` x `scale`), the
/// accommodation it shows: after the last cycle, `Saturated` if this one still deepened,
/// else `NonDeepening`. The quasi-static and the dynamic runners judge cycles by it.
#[must_use]
pub fn against_before<H>(
    cycles: &[Cycle<H>],
    d_e: f64,
    pull_out: f64,
    tol: f64,
    scale: f64,
) -> (bool, f64, Option<(usize, AccommodationCause)>) {
    let deepest_before = cycles.iter().map(|c| c.end.d_e).reduce(f64::min);
    let deepened = deepest_before.is_none_or(|d| d_e < d);
    let shallower_by = deepest_before.map_or(0.0, |d| (d_e - d).max(0.0));
    let repeats = cycles.last().and_then(|prev| {
        let dp = (pull_out - prev.unloading.pull_out_pressure).abs();
        let dd = (d_e - prev.end.d_e).abs();
        (dp <= tol * pull_out.abs().max(f64::MIN_POSITIVE) && dd <= tol * scale).then(|| {
            let cause = if deepened {
                AccommodationCause::Saturated
            } else {
                AccommodationCause::NonDeepening
            };
            (prev.cycle, cause)
        })
    });
    (deepened, shallower_by, repeats)
}

/// The step of the differences that carry a history's error into a pull-out, in the
/// roughness scale: far above the noise of the pressures (their errors over the step are
/// added to the slope), well within the scale on which the pull-out changes with the
/// history.
const HISTORY_STEP: f64 = 1e-3;

/// Adds to each cycle's error estimates the error its history carries (docs/theory.md
/// section 6.6). A cycle's d_e and pull-out are computed to the mode's precision *on the
/// history the cycles before left*, whose deepest separation D is itself known only to its
/// own estimate; a run compared with a tighter one differs by both:
/// - d_e: its own estimate plus that of D (the end of impact moves by at most as much as
///   the deepest separation before it: the reload after a deeper delta_max is the same
///   curve shifted by at most the same depth, and the virgin loading below D pushes back
///   harder than the reload above it);
/// - the pull-out: its own estimate plus |dp/dd_e| times the estimate of d_e and, where
///   the impact did not deepen, |dp/dD| times that of D: each slope a difference of the
///   retraction pressure at the pull-out's separation (which moves the minimum only to
///   second order) with the history loaded 1e-3 sigma_s deeper (`HISTORY_STEP`), plus the
///   pressures' estimates over the step.
///
/// A cycle that repeats the one before (the same history to start from) repeats its
/// estimates. `start` is the history the first cycle started from. Public for runners
/// that find each cycle's d_e otherwise (the switch in time) and carry the errors alike.
pub fn carry_history_errors<S: SurfaceLaw>(
    surface: &S,
    start: &S::History,
    cycles: &mut [Cycle<S::History>],
) -> Result<(), SwitchError> {
    // the history cycle k started from
    let before = |cycles: &[Cycle<S::History>], k: usize| -> S::History {
        if k == 0 {
            start.clone()
        } else {
            cycles[k - 1].history.clone()
        }
    };
    // a cycle repeats the one before when both started from the same history; a cycle
    // changed the history when its impact went deeper than the history reached
    let repeats = |cycles: &[Cycle<S::History>], k: usize| {
        k >= 1 && before(cycles, k) == before(cycles, k - 1)
    };
    let changed = |cycles: &[Cycle<S::History>], k: usize| cycles[k].history != before(cycles, k);
    // the d_e of the last cycle before k that changed the history (its deepest separation)
    let last_change = |cycles: &[Cycle<S::History>], k: usize| {
        (0..k)
            .rev()
            .find(|&i| changed(cycles, i))
            .map(|i| cycles[i].end.d_e)
    };
    let ks: Vec<usize> = (0..cycles.len()).collect();
    let view: &[Cycle<S::History>] = cycles;
    // (dp/dd_e, dp/dD) of each cycle's pull-out (Pa/m)
    let slopes = par::map(&ks, |&k| -> Result<(f64, f64), SwitchError> {
        let c = &view[k];
        let pull = c.unloading.pull_out_pressure;
        if repeats(view, k) || !(pull > 0.0) {
            return Ok((0.0, 0.0));
        }
        let start_k = before(view, k);
        let h = HISTORY_STEP * surface.length_scales(&start_k)?.roughness;
        let at = c.unloading.pull_out_separation;
        let own = c.unloading.pull_out_error;
        let slope = |hist: &S::History, from: f64| -> Result<f64, SwitchError> {
            let e = surface.pressure_estimate(at, hist, Path::Retract { from })?;
            Ok(((e.value + pull).abs() + e.error + own) / h)
        };
        let d_e = c.end.d_e;
        if changed(view, k) {
            return Ok((slope(&surface.load(&start_k, d_e - h), d_e - h)?, 0.0));
        }
        let of_d_e = || slope(&surface.load(&c.history, d_e - h), d_e - h);
        match last_change(view, k) {
            Some(deep) => {
                let (of_d_e, of_deep) =
                    par::join(of_d_e, || slope(&surface.load(&c.history, deep - h), d_e));
                Ok((of_d_e?, of_deep?))
            }
            None => Ok((of_d_e()?, 0.0)),
        }
    })?;
    // the estimate of the deepest separation the history holds (0: the history given)
    let mut deep_error = 0.0;
    for k in 0..cycles.len() {
        if repeats(cycles, k) {
            let (end, pull) = (
                cycles[k - 1].end.error,
                cycles[k - 1].unloading.pull_out_error,
            );
            cycles[k].end.error = end;
            cycles[k].unloading.pull_out_error = pull;
            continue;
        }
        let changed_k = changed(cycles, k);
        let c = &mut cycles[k];
        c.end.error += deep_error;
        let (s_d_e, s_deep) = slopes[k];
        c.unloading.pull_out_error += s_d_e * c.end.error + s_deep * deep_error;
        if changed_k {
            deep_error = c.end.error;
        }
    }
    Ok(())
}

/// Cycles whose impacts and unloadings are found ahead at once ([`impacts_ahead`]) when
/// the number of cycles is fixed: enough that the window's end seldom stalls the pipeline
/// (eq 17 in turn, the unloadings beside it; the paper's 10 cycles in fast mode took 8 %
/// longer with windows of 8), few enough that progress is reported as it goes.
const AHEAD_WINDOW: usize = 32;

/// One cycle found ahead: its end of impact, the history after it, and its unloading
/// (None: the cycle repeats the one before, whose unloading it shares).
struct Ahead<H> {
    end: EndOfImpact,
    history: H,
    unloading: Option<Result<Unloading, SwitchError>>,
}

/// The next `count` cycles from `hist` when every one of them will be run: eq 17 in turn
/// (each impact needs the history the one before left), each unloading started as soon as
/// its impact is known, beside the next impacts and the other unloadings (unloading never
/// changes the history), the same computations as one cycle after the other, so the same
/// results to the bit. `prev`: the history the cycle before started from and its end of
/// impact (a cycle that starts from the same history repeats it; its d_e guides eq 17).
/// Ends after the first error of eq 17, which it returns last.
fn impacts_ahead<S: SurfaceLaw>(
    surface: &S,
    hist: &S::History,
    prev: Option<(&S::History, EndOfImpact)>,
    count: usize,
    energy: f64,
    film: ImpactFilm,
    options: CycleOptions,
) -> Vec<Result<Ahead<S::History>, SwitchError>> {
    if count == 0 {
        return Vec::new();
    }
    let found = match prev {
        Some((start, end)) if start == hist => Ok((end, surface.load(hist, end.d_e), true)),
        _ => end_of_impact_near(
            surface,
            hist,
            energy,
            film,
            options.precision,
            prev.map(|p| p.1.d_e),
        )
        .map(|end| (end, surface.load(hist, end.d_e), false)),
    };
    let (end, new_hist, repeat) = match found {
        Ok(f) => f,
        Err(e) => return vec![Err(e)],
    };
    // the impacts first: they are the chain every later cycle waits for, and the
    // unloadings beside them are taken up by whichever thread is free
    let (mut rest, unloading) = contact_core::par::join(
        || {
            impacts_ahead(
                surface,
                &new_hist,
                Some((hist, end)),
                count - 1,
                energy,
                film,
                options,
            )
        },
        || {
            (!repeat).then(|| {
                unload(
                    surface,
                    &new_hist,
                    end.d_e,
                    options.unloading_points,
                    options.precision,
                )
            })
        },
    );
    rest.insert(
        0,
        Ok(Ahead {
            end,
            history: new_hist,
            unloading,
        }),
    );
    rest
}

/// How much the pull-out could still grow after the last cycle run: the last change
/// d_n = p_n - p_(n-1), and the cycles after it as a geometric series of ratio
/// r = |d_n / d_(n-1)| (capped at 0.9; 0.5 when only one change is known):
/// |d_n| r/(1 - r).
fn stopping_error<H>(cycles: &[Cycle<H>]) -> f64 {
    let p: Vec<f64> = cycles
        .iter()
        .map(|c| c.unloading.pull_out_pressure)
        .collect();
    let n = p.len();
    if n < 2 {
        return 0.0;
    }
    let last = (p[n - 1] - p[n - 2]).abs();
    let r = if n >= 3 {
        let before = (p[n - 2] - p[n - 3]).abs();
        if before > 0.0 {
            (last / before).min(0.9)
        } else {
            0.9
        }
    } else {
        0.5
    };
    last * r / (1.0 - r)
}

/// The residual of eq 17 at `d`, G(d) = integral_d^inf p_L + p_L(d)^2 t_s/(2E) - E_I
/// (J/m^2), computed independently of [`end_of_impact`] (one adaptive integral at 1e-13 of
/// the integral of |p_L|, from `d` to the first touch): a check of the energy balance for
/// tests and tools.
pub fn eq17_residual<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    d: f64,
    impact_energy: f64,
    film: ImpactFilm,
) -> Result<f64, SwitchError> {
    let top = surface.reach(history, Path::Approach)?;
    let rule = AdaptiveRule::new(6)?;
    let quad = QuadTolerance {
        rel: 0.0,
        rel_of_abs: 1e-13,
        abs: 0.0,
        max_width: 0.0,
        max_panels: 100_000,
        noise: NOISE,
    };
    let mut breaks = vec![d];
    let mut kinks = surface.kinks(history);
    kinks.sort_by(f64::total_cmp);
    breaks.extend(kinks.into_iter().filter(|&k| k > d && k < top));
    breaks.push(top);
    let (w, _) = integrate_panels_par(
        "eq 17 residual",
        |x| Ok::<_, SwitchError>(surface.pressure(x, history, Path::Approach)?),
        &breaks,
        false,
        &rule,
        quad,
    )?;
    let p = surface.pressure(d, history, Path::Approach)?;
    Ok(w.value + film.energy(p) - impact_energy)
}
