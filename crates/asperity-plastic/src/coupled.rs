//! Plasticity driven by the adhesive contact itself: the `adhesion_coupled` law
//! (`docs/theory.md` section 2.8).

use contact_core::numeric::{brent, brent_from, expand_bracket, Expansion, Sample, Tolerance};
use contact_core::{AdhesionLaw, LawError, Path, PlasticState, PlasticityLaw, YieldingBody};

use crate::PlasticError;

/// An uncoupled plasticity law `P` (Etsion-Kadin or Kogut-Etsion) driven by the adhesive
/// contact of the adhesion law `A` instead of the geometric interference alone.
///
/// The pressure under an adhesive elastic sphere of contact radius a is the Hertz pressure
/// of that contact, p_H(r) = (2 E* a / (pi R)) sqrt(1 - r^2/a^2), plus the adhesive
/// (tensile) part of the law: the flat-punch term of JKR, concentrated at the contact's
/// edge, or the Dugdale ring of Maugis-Dugdale (Johnson 1985, sec 5.5; Maugis 1992).
/// The compressive core, whose subsurface shear yields the asperity first, is the Hertz
/// pressure of a non-adhesive contact pressed to the Hertz interference
///
/// ```text
///   delta_H = a^2 / R = delta + delta_a,      delta_a = a^2/R - delta >= 0,
/// ```
///
/// delta_a being the elastic displacement the adhesive stresses add (JKR:
/// delta_a = sqrt(2 pi w a / E*)). Maugis & Pollock (1984) base the onset of
/// adhesion-induced plastic flow on exactly this core: yield begins when p_H's peak,
/// 2 E* a / (pi R), reaches C_v S_Y, i.e. when delta_H reaches delta_CP. This law takes
/// that reading through the whole elastic-plastic range: the state after loading to
/// delta_max is the base law's state (eqs 4-5) at the Hertz interference delta_P of the
/// adhesive contact *on the asperity that state leaves*, the root of
///
/// ```text
///   g(delta_P) = a'^2 / R_eff - (delta_P - delta_res(delta_P)) = 0,
/// ```
///
/// a' the adhesion law's contact radius (contact branch) on the deformed sphere, R_eff its
/// eq 12 at x = 1, at the geometric interference delta_max - delta_res(delta_P): the
/// compressive core the adhesion law computes on the deformed asperity is then the base
/// law's loading at delta_P, and the adhesion law adds its own adhesive stresses once, so
/// the force while loading is the base law's core force less the adhesive tension, as
/// JKR's is Hertz's less the flat punch. Out of contact (delta_max at or below the virgin
/// sphere's jump-in) delta_P = delta_max; above it an asperity that jumped in at a negative
/// interference already has a Hertz core. The state carries delta_a = delta_P - delta_max
/// ([`PlasticState::adhesive_displacement`]); eq 12 is read at delta + delta_a, so the core
/// unloads along the base law's curve with the adhesive displacement riding on it.
/// Unloading and pull-off are the adhesion law on the residual profile (Mesarovic &
/// Johnson 2000: elastic unloading of the plastically formed junction).
///
/// delta_P(delta_max) is tabulated at construction (a few thousand solves, about 3 ms) to
/// 1e-9 of the law's length scale and read by cubic interpolation; [`Self::hertz_interference_solved`]
/// is the direct solve.
///
/// Limits (tests in `tests/coupled.rs`): without adhesion (Hertz) the law is its base law
/// to the bit; with weak adhesion it tends to it; a film that does not yield is the elastic
/// adhesive law; the onset meets Maugis & Pollock's criterion.
#[derive(Debug, Clone)]
pub struct AdhesionCoupled<P, A> {
    base: P,
    adhesion: A,
    jump_in: f64,
    onset: f64,
    tables: Vec<ShiftTable>,
}

impl<P: PlasticityLaw, A: AdhesionLaw> AdhesionCoupled<P, A> {
    /// The base law `base` driven by the adhesive contact of `adhesion` (the law the
    /// asperity uses, on the base law's radius).
    pub fn new(base: P, adhesion: A) -> Result<Self, LawError> {
        let r = base.radius();
        let jump_in = adhesion.jump_in(r)?;
        if !jump_in.is_finite() {
            return Err(PlasticError::Core(contact_core::CoreError::Invalid {
                field: "jump-in interference",
                value: jump_in,
                allowed: "finite (the adhesion law's jump-in on the virgin sphere)",
            })
            .into());
        }
        let mut law = Self {
            base,
            adhesion,
            jump_in,
            onset: f64::INFINITY,
            tables: Vec::new(),
        };
        law.onset = law.geometric_onset()?;
        // one table from the jump-in, another from the yield onset where the state bends
        let scale = law.scale();
        let mut starts = vec![law.jump_in];
        if law.onset.is_finite() && law.onset > law.jump_in {
            starts.push(law.onset);
        }
        let mut tables = Vec::with_capacity(starts.len());
        for (i, &x0) in starts.iter().enumerate() {
            let end = starts.get(i + 1).copied().unwrap_or(f64::INFINITY);
            tables.push(ShiftTable::build(x0, end, 0.03 * scale, |d, g| {
                law.solve_shift(d, g)
            })?);
        }
        law.tables = tables;
        Ok(law)
    }

    /// The tables of delta_P - delta_max: (start x0 (m), nodes, the largest deviation of
    /// the spline from the direct solve at the midpoints, relative to the law's scale plus
    /// delta_max - x0).
    pub fn table_sizes(&self) -> Vec<(f64, usize, f64)> {
        self.tables
            .iter()
            .map(|t| (t.x0, t.values.len(), t.deviation))
            .collect()
    }

    /// The base law.
    pub fn base(&self) -> &P {
        &self.base
    }

    /// The adhesion law the coupling reads.
    pub fn adhesion(&self) -> &A {
        &self.adhesion
    }

    /// The virgin sphere's jump-in interference (m): above it the asperity is in adhesive
    /// contact.
    pub fn jump_in(&self) -> f64 {
        self.jump_in
    }

    /// The adhesive displacement delta_a = a^2/R - delta (m, >= 0) of the virgin sphere at
    /// interference `delta` on the contact branch; 0 out of contact.
    pub fn adhesive_displacement(&self, delta: f64) -> Result<f64, LawError> {
        if !(delta > self.jump_in) {
            return Ok(0.0);
        }
        let r = self.base.radius();
        let a = self.adhesion.contact_radius(r, delta, Path::Approach)?;
        Ok((a * a / r - delta).max(0.0))
    }

    /// delta_P (m): the Hertz interference of the adhesive contact at `delta_max`, the
    /// interference the base law's state is taken at: the root of
    ///
    /// ```text
    ///   g(delta_P) = a'^2 / R_eff - (delta_P - delta_res(delta_P)) = 0,
    /// ```
    ///
    /// a' the adhesion law's contact radius (contact branch) on the sphere the state at
    /// delta_P leaves, R_eff = eq 12 at x = 1, at the interference delta_max - delta_res:
    /// the compressive core of the adhesive contact on the deformed asperity is the base
    /// law's at delta_P. g(delta_max) = delta_a' >= 0; delta_P is found by bracket
    /// expansion and Brent to 1e-13 of the contact's scale. Out of contact, delta_max.
    pub fn hertz_interference(&self, delta_max: f64) -> Result<f64, LawError> {
        let table = self
            .tables
            .iter()
            .rev()
            .find(|t| delta_max > t.x0)
            .and_then(|t| t.shift(delta_max));
        match table {
            Some(shift) => Ok(delta_max + shift),
            None => Ok(delta_max + self.solve_shift(delta_max, None)?),
        }
    }

    /// The length scale of the law (m): the larger of delta_CP, |jump-in| and the virgin
    /// adhesive displacement at zero interference.
    fn scale(&self) -> f64 {
        let d0 = self.adhesive_displacement(0.0).unwrap_or(0.0);
        let dcp = self.base.delta_cp();
        [
            d0,
            self.jump_in.abs(),
            if dcp.is_finite() { dcp } else { 0.0 },
        ]
        .into_iter()
        .fold(f64::MIN_POSITIVE, f64::max)
    }

    /// delta_P - delta_max solved at `delta_max` (the tables' reference), from a guess of
    /// it if one is known (a neighbouring node's).
    fn solve_shift(&self, delta_max: f64, guess: Option<f64>) -> Result<f64, LawError> {
        let g = |dp: f64| self.core_gap(delta_max, dp);
        if let Some(guess) = guess.filter(|&s| s > 0.0) {
            // a bracket of 1e-3 of the guess around it, if it holds the root
            let (lo, hi) = (delta_max + 0.999 * guess, delta_max + 1.001 * guess);
            let (flo, fhi) = (g(lo)?, g(hi)?);
            if flo > 0.0 && fhi <= 0.0 && self.adhesive_displacement(delta_max)? > 0.0 {
                let scale = guess.max(delta_max.abs());
                let dp = brent_from::<LawError>(
                    "adhesion-coupled Hertz interference",
                    g,
                    Sample { x: lo, f: flo },
                    Sample { x: hi, f: fhi },
                    Tolerance::absolute(1e-13 * scale),
                )?;
                return Ok(dp - delta_max);
            }
        }
        Ok(self.solve_hertz_interference(delta_max)? - delta_max)
    }

    /// [`Self::hertz_interference`] solved directly, without the table (its reference).
    pub fn hertz_interference_solved(&self, delta_max: f64) -> Result<f64, LawError> {
        self.solve_hertz_interference(delta_max)
    }

    fn solve_hertz_interference(&self, delta_max: f64) -> Result<f64, LawError> {
        let virgin = self.adhesive_displacement(delta_max)?;
        if !(virgin > 0.0) {
            return Ok(delta_max);
        }
        let g = |dp: f64| self.core_gap(delta_max, dp);
        let start = Sample {
            x: delta_max,
            f: g(delta_max)?,
        };
        if !(start.f > 0.0) {
            return Ok(delta_max);
        }
        let scale = virgin.max(delta_max.abs());
        let Some((lo, hi)) = expand_bracket::<LawError>(
            "adhesion-coupled Hertz interference",
            g,
            start,
            delta_max + virgin,
            Expansion::Geometric(2.0),
            delta_max + 1e6 * scale,
        )?
        else {
            return Err(PlasticError::Core(contact_core::CoreError::Invalid {
                field: "adhesion-coupled Hertz interference",
                value: delta_max,
                allowed: "an interference whose adhesive contact the base law's flattening can balance within 1e6 of its scale",
            })
            .into());
        };
        brent_from::<LawError>(
            "adhesion-coupled Hertz interference",
            g,
            lo,
            hi,
            Tolerance::absolute(1e-13 * scale),
        )
    }

    /// g(delta_P) of [`Self::hertz_interference`] (m).
    fn core_gap(&self, delta_max: f64, dp: f64) -> Result<f64, LawError> {
        let b = self.base.state(dp);
        let r_eff = self.base.effective_radius(&b, dp);
        let d_eff = delta_max - b.delta_res;
        let reach = contact_reach(self.adhesion.jump_in(r_eff)?);
        let a = self.adhesion.contact_radius(
            r_eff,
            d_eff,
            Path::Retract {
                from: d_eff.max(reach),
            },
        )?;
        Ok(a * a / r_eff - (dp - b.delta_res))
    }

    /// The geometric interference (m) where yield begins: delta_P = delta_CP, at or above
    /// the jump-in (where the state jumps if adhesion alone yields the asperity).
    pub fn yield_onset(&self) -> f64 {
        self.onset
    }

    fn geometric_onset(&self) -> Result<f64, LawError> {
        let hertz = |d: f64| self.solve_hertz_interference(d);
        let dcp = self.base.delta_cp();
        if !dcp.is_finite() {
            return Ok(f64::INFINITY);
        }
        // just above the jump-in the contact and its Hertz core appear at once
        let lo = if self.jump_in < dcp {
            let above = self.jump_in + 1e-9 * dcp.max(self.jump_in.abs());
            if hertz(above)? >= dcp {
                return Ok(self.jump_in);
            }
            above
        } else {
            return Ok(self.jump_in.max(dcp));
        };
        if hertz(dcp)? <= dcp && self.adhesive_displacement(dcp)? == 0.0 {
            return Ok(dcp);
        }
        brent::<LawError>(
            "adhesion-coupled yield onset",
            |d| Ok(hertz(d)? - dcp),
            lo,
            dcp,
            Tolerance::relative(1e-13),
        )
    }
}

impl<P: PlasticityLaw, A: AdhesionLaw> PlasticityLaw for AdhesionCoupled<P, A> {
    fn radius(&self) -> f64 {
        self.base.radius()
    }

    /// The base law's delta_CP (eq 1): the material's yield onset in Hertz interference.
    fn delta_cp(&self) -> f64 {
        self.base.delta_cp()
    }

    /// The base law's state at delta_P(delta_max), with `delta_max` the geometric
    /// interference and `adhesive_displacement` delta_a = delta_P - delta_max. An adhesion
    /// law that fails on the virgin sphere (it cannot for the built-in laws: a finite
    /// interference on a validated radius) leaves the state uncoupled and marked
    /// `extrapolated`, which the guards report.
    fn state(&self, delta_max: f64) -> PlasticState {
        let (dp, extrapolated) = match self.hertz_interference(delta_max) {
            Ok(dp) => (dp, false),
            Err(_) => (delta_max, true),
        };
        let b = self.base.state(dp);
        let shift = dp - delta_max;
        PlasticState {
            delta_max: if shift > 0.0 { delta_max } else { b.delta_max },
            adhesive_displacement: if shift > 0.0 { shift } else { 0.0 },
            extrapolated: b.extrapolated || extrapolated,
            ..b
        }
    }

    /// The base law's eq 12 at the Hertz interference delta + delta_a: the compressive
    /// core of the adhesive contact unloads along the base law's curve, the adhesive
    /// displacement riding on it (x = 1 at delta_max, R_res from delta_res - delta_a down).
    fn effective_radius(&self, state: &PlasticState, delta: f64) -> f64 {
        self.base
            .effective_radius(&base_state(state), delta + state.adhesive_displacement)
    }

    fn radius_bound(&self, state: &PlasticState) -> Option<f64> {
        self.base.radius_bound(&base_state(state))
    }

    /// The jump-in (the state jumps there when adhesion alone yields the asperity) and the
    /// geometric yield onset; the base law's own breaks (in delta_P) are left to the
    /// quadrature's error control.
    fn breaks(&self) -> Vec<f64> {
        let mut b = vec![self.jump_in];
        if self.onset.is_finite() && self.onset > self.jump_in {
            b.push(self.onset);
        }
        b
    }

    fn kinks(&self, state: &PlasticState) -> Vec<Option<f64>> {
        let shift = state.adhesive_displacement;
        self.base
            .kinks(&base_state(state))
            .into_iter()
            .map(|k| k.map(|k| k - shift))
            .collect()
    }

    /// The base law's range, in delta_P / delta_CP.
    fn fit_range(&self) -> Option<(f64, f64)> {
        self.base.fit_range()
    }

    fn yielding_body(&self) -> Option<YieldingBody> {
        self.base.yielding_body()
    }

    fn couples_adhesion(&self) -> bool {
        true
    }

    /// The delta_max whose Hertz interference is omega delta_CP (delta_P grows with
    /// delta_max: bisection by Brent from the jump-in), omega delta_CP if the adhesive
    /// contact cannot be solved there.
    fn fit_interference(&self, omega: f64) -> f64 {
        let target = omega * self.base.delta_cp();
        if !target.is_finite() || !(target > self.jump_in) {
            return target;
        }
        let lo = self.jump_in + 1e-12 * self.jump_in.abs().max(target.abs());
        match self.hertz_interference(lo) {
            Ok(h) if h >= target => return lo,
            Ok(_) => {}
            Err(_) => return target,
        }
        brent::<LawError>(
            "adhesion-coupled fit interference",
            |d| Ok(self.hertz_interference(d)? - target),
            lo,
            target,
            Tolerance::relative(1e-12),
        )
        .unwrap_or(target)
    }
}

/// The base law's own state: its delta_max is the Hertz interference.
fn base_state(state: &PlasticState) -> PlasticState {
    PlasticState {
        delta_max: state.delta_max + state.adhesive_displacement,
        adhesive_displacement: 0.0,
        ..*state
    }
}

/// An excursion's extreme (m) that certainly reached a sphere's `jump_in` (m): at least 0
/// (the built-in laws jump in at or below 0), nudged above a positive jump-in so that no
/// rounding of the adhesion law's own scaling reads it as short of contact.
pub(crate) fn contact_reach(jump_in: f64) -> f64 {
    let reach = jump_in.max(0.0);
    reach + 8.0 * f64::EPSILON * reach
}

/// delta_P - delta_max tabulated from a start `x0` (the jump-in or the yield onset, where
/// the state jumps or bends) against u = ln(1 + (delta_max - x0)/L), L a length scale of the
/// law, uniform in u up to 3e7 L, read by a cubic spline (C2, clamped with end slopes from
/// the four end nodes) so that the force stays smooth for the quadrature over asperity
/// heights at any tolerance. Built by doubling the nodes until the spline meets the direct
/// solve at every midpoint to [`TABLE_TOLERANCE`] of L plus delta_max - x0, at most 4097
/// nodes; the largest deviation found is kept ([`AdhesionCoupled::table_sizes`]). The
/// spline is the law's definition; anything beyond its end is solved directly.
#[derive(Debug, Clone)]
struct ShiftTable {
    x0: f64,
    scale: f64,
    du: f64,
    values: Vec<f64>,
    /// The spline's second derivatives at the nodes.
    curvature: Vec<f64>,
    /// The largest midpoint deviation from the direct solve, relative to L + delta_max - x0.
    deviation: f64,
}

/// Relative tolerance of the shift tables, on the law's length scale plus delta_max - x0.
const TABLE_TOLERANCE: f64 = 1e-9;

impl ShiftTable {
    fn build(
        x0: f64,
        end: f64,
        scale: f64,
        solve: impl Fn(f64, Option<f64>) -> Result<f64, LawError>,
    ) -> Result<Self, LawError> {
        let u_end = (3e7f64).ln_1p().min(if end.is_finite() {
            ((end - x0) / scale).ln_1p()
        } else {
            f64::INFINITY
        });
        let mut n = 65usize;
        let mut du = u_end / (n - 1) as f64;
        // the state jumps at x0: node 0 is its limit from above
        let at = |u: f64| (x0 + scale * u.exp_m1()).max(x0 + 1e-12 * scale);
        let mut values: Vec<f64> = Vec::with_capacity(n);
        for k in 0..n {
            let guess = values.last().copied();
            values.push(solve(at(du * k as f64), guess)?);
        }
        loop {
            let t = ShiftTable::spline(x0, scale, du, values.clone());
            let mids = (0..n - 1)
                .map(|k| {
                    let guess = 0.5 * (values[k] + values[k + 1]);
                    solve(at(du * (k as f64 + 0.5)), Some(guess))
                })
                .collect::<Result<Vec<_>, _>>()?;
            let deviation = (0..n - 1)
                .map(|k| {
                    let u = du * (k as f64 + 0.5);
                    (t.eval(u) - mids[k]).abs() / (scale * (1.0 + u.exp_m1()))
                })
                .fold(0.0f64, f64::max);
            if deviation <= TABLE_TOLERANCE || n >= 4097 {
                return Ok(ShiftTable { deviation, ..t });
            }
            let mut refined = Vec::with_capacity(2 * n - 1);
            for k in 0..n - 1 {
                refined.push(values[k]);
                refined.push(mids[k]);
            }
            refined.push(values[n - 1]);
            values = refined;
            n = 2 * n - 1;
            du *= 0.5;
        }
    }

    /// The clamped cubic spline through `values` on the nodes k du (Thomas' algorithm on
    /// M_(k-1) + 4 M_k + M_(k+1) = 6 (y_(k+1) - 2 y_k + y_(k-1))/du^2, the end slopes from
    /// the cubic through the four end nodes).
    fn spline(x0: f64, scale: f64, du: f64, values: Vec<f64>) -> Self {
        let n = values.len();
        let y = &values;
        let h = du;
        let d0 = (-11.0 * y[0] + 18.0 * y[1] - 9.0 * y[2] + 2.0 * y[3]) / (6.0 * h);
        let dn = (11.0 * y[n - 1] - 18.0 * y[n - 2] + 9.0 * y[n - 3] - 2.0 * y[n - 4]) / (6.0 * h);
        // tridiagonal a_k M_(k-1) + b_k M_k + c_k M_(k+1) = r_k
        let mut b = vec![4.0; n];
        let mut r = vec![0.0; n];
        b[0] = 2.0;
        b[n - 1] = 2.0;
        r[0] = 6.0 * ((y[1] - y[0]) / h - d0) / h;
        r[n - 1] = 6.0 * (dn - (y[n - 1] - y[n - 2]) / h) / h;
        for k in 1..n - 1 {
            r[k] = 6.0 * (y[k + 1] - 2.0 * y[k] + y[k - 1]) / (h * h);
        }
        // forward sweep (a_k = c_k = 1)
        for k in 1..n {
            let m = 1.0 / b[k - 1];
            b[k] -= m;
            r[k] -= m * r[k - 1];
        }
        let mut curvature = vec![0.0; n];
        curvature[n - 1] = r[n - 1] / b[n - 1];
        for k in (0..n - 1).rev() {
            curvature[k] = (r[k] - curvature[k + 1]) / b[k];
        }
        ShiftTable {
            x0,
            scale,
            du,
            values,
            curvature,
            deviation: 0.0,
        }
    }

    /// The spline at `u` (clamped to the table's span).
    fn eval(&self, u: f64) -> f64 {
        let n = self.values.len();
        let t = (u / self.du).clamp(0.0, (n - 1) as f64);
        let k = (t.floor() as usize).min(n - 2);
        let x = t - k as f64;
        let (y0, y1) = (self.values[k], self.values[k + 1]);
        let (m0, m1) = (self.curvature[k], self.curvature[k + 1]);
        let w = 1.0 - x;
        w * y0 + x * y1 + self.du * self.du / 6.0 * ((w * w * w - w) * m0 + (x * x * x - x) * m1)
    }

    /// The tabulated shift at `delta_max` (> x0), None beyond the table.
    fn shift(&self, delta_max: f64) -> Option<f64> {
        let u = ((delta_max - self.x0) / self.scale).ln_1p();
        let t = u / self.du;
        if !(t >= 0.0 && t <= (self.values.len() - 1) as f64) {
            return None;
        }
        Some(self.eval(u))
    }
}
