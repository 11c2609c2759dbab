//! The tabulated law, its one-number history state and its evaluation.

use crate::error::{fmt_num, LawError};
use crate::meta::{MeasuredError, PartialReloadError, TabulationInfo};
use crate::steffen::Steffen;
use serde::{Deserialize, Serialize};

/// The path of a surface above its deepest separation d_min.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Path {
    /// Coming from far, or reloading: the approach (reload) branch p_A(d; d_min).
    Approach,
    /// Moving away after a reversal: the retract branch p_R(d; d_min).
    Retract,
}

impl Path {
    /// `"approach"` or `"retract"`, as in `law.csv` and `law.json`.
    pub fn as_str(self) -> &'static str {
        match self {
            Path::Approach => "approach",
            Path::Retract => "retract",
        }
    }
}

/// Where an evaluation lies relative to what the tabulator measured.
///
/// * [`Region::Measured`]: inside the tabulated histories (`d_min` between the deepest and
///   the shallowest branch, or the virgin envelope between its first node and its reach)
///   and within the curve's reach: the interpolation error there is what the file's
///   `measured_error` states.
/// * [`Region::BeyondReach`]: beyond the reach of the curve evaluated (every asperity out
///   of contact): the pressure and the tangent are exactly 0, which is the model's own value
///   (its heights are truncated at 9 sigma_s), not an interpolation.
/// * [`Region::AboveTable`]: a history shallower than the shallowest tabulated branch (a
///   touch lighter than the table's first touch), within reach: the law blends the
///   shallowest branch towards zero at the virgin reach; not measured. Its pressures are
///   of the order of the file's `pressure_floor` or less.
/// * [`Region::BelowTable`]: a history (or a deepening separation) deeper than the deepest
///   tabulated branch: the law has no data there and evaluation is an error
///   ([`LawError::OutOfRange`]); this variant names the region of such errors.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Region {
    /// Inside the tabulated and measured region.
    Measured,
    /// Beyond the curve's reach: exactly 0.
    BeyondReach,
    /// Shallower than the shallowest tabulated history: a blend to zero, not measured.
    AboveTable,
    /// Deeper than the deepest tabulated history: an error, no value.
    BelowTable,
}

impl Region {
    /// `"measured"`, `"beyond_reach"`, `"above_table"` or `"below_table"` (the names of
    /// `stiction law eval --format json`, a public contract).
    pub fn as_str(self) -> &'static str {
        match self {
            Region::Measured => "measured",
            Region::BeyondReach => "beyond_reach",
            Region::AboveTable => "above_table",
            Region::BelowTable => "below_table",
        }
    }
}

/// A point of the law: separation `d` (m) and pressure (Pa).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// Separation (m).
    pub d: f64,
    /// Pressure (Pa), compressive positive.
    pub pressure: f64,
}

/// The history and path of one point of a surface, updated by [`ContactLaw::pressure`].
///
/// Plain data, so that an FE code can store it in its own state variables (see the C
/// struct `scl_state`). [`State::VIRGIN`] is a surface never loaded. Not serializable on
/// purpose: its infinite fields would become JSON `null`; store the fields yourself or use
/// the C struct, whose numbers are always finite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// Deepest separation reached (m); `+inf` while virgin.
    pub d_min: f64,
    /// Current path.
    pub path: Path,
    /// Separation of the previous call (m); `+inf` before the first.
    pub last_d: f64,
    /// Separation (m) of the last reversal, where the current path began; `+inf` while the
    /// approach comes from far or runs on the virgin envelope. A retraction with
    /// `d_turn > d_min` follows a partial reload (see [`ContactLaw::is_history_exact`]).
    pub d_turn: f64,
}

impl State {
    /// A surface never loaded: d_min = +inf, approach.
    pub const VIRGIN: State = State {
        d_min: f64::INFINITY,
        path: Path::Approach,
        last_d: f64::INFINITY,
        d_turn: f64::INFINITY,
    };

    /// True before any finite separation was reached.
    pub fn is_virgin(&self) -> bool {
        self.d_min == f64::INFINITY
    }

    fn check(&self) -> Result<(), LawError> {
        if self.d_min.is_nan() || self.d_min == f64::NEG_INFINITY {
            return Err(LawError::invalid(
                "state.d_min",
                self.d_min,
                "finite, or +inf for a virgin surface",
            ));
        }
        if self.last_d.is_nan() || self.last_d == f64::NEG_INFINITY {
            return Err(LawError::invalid(
                "state.last_d",
                self.last_d,
                "finite, or +inf before the first call",
            ));
        }
        if self.d_turn.is_nan() {
            return Err(LawError::invalid(
                "state.d_turn",
                self.d_turn,
                "a number or +inf",
            ));
        }
        Ok(())
    }
}

impl Default for State {
    fn default() -> Self {
        State::VIRGIN
    }
}

/// The result of [`ContactLaw::evaluate`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// Pressure (Pa), compressive positive, adhesive negative.
    pub pressure: f64,
    /// dp/dd (Pa/m) at fixed history: the derivative of the interpolant.
    pub tangent: f64,
    /// The history after the call (m): d if d was below the d_min given.
    pub d_min: f64,
    /// The path after the call (approach when the history deepened).
    pub path: Path,
    /// Where the point lies: measured, beyond the reach, above the table (see [`Region`]).
    pub region: Region,
}

/// One tabulated curve: nodes from its start to its reach (the last node; the pressure is
/// zero beyond) and its most tensile point.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    d: Vec<f64>,
    pressure: Vec<f64>,
    most_tensile: Point,
    /// Interpolant in x = d - origin (origin: d_min for a branch, 0 for the envelope).
    interp: Steffen,
    /// Length in x over which the continuity correction fades (see [`fade_length`]).
    fade: f64,
}

impl Curve {
    /// A validated curve; `path` names it in errors (e.g. `branches[3].retract`) and
    /// `most_tensile_path` its most tensile point.
    pub(crate) fn new(
        d: Vec<f64>,
        pressure: Vec<f64>,
        most_tensile: Point,
        origin: f64,
        path: &str,
        most_tensile_path: &str,
    ) -> Result<Curve, LawError> {
        if d.len() != pressure.len() {
            return Err(LawError::format(
                format!("{path}.pressure"),
                format!(
                    "{} values for {} separations: the lengths must match",
                    pressure.len(),
                    d.len()
                ),
            ));
        }
        if d.len() < 2 {
            return Err(LawError::format(
                format!("{path}.d"),
                format!("{} nodes: at least 2 are required", d.len()),
            ));
        }
        for i in 0..d.len() {
            if !d[i].is_finite() {
                return Err(LawError::format(
                    format!("{path}.d[{i}]"),
                    format!("{}: must be finite", fmt_num(d[i])),
                ));
            }
            if !pressure[i].is_finite() {
                return Err(LawError::format(
                    format!("{path}.pressure[{i}]"),
                    format!("{}: must be finite", fmt_num(pressure[i])),
                ));
            }
            if i > 0 && d[i] <= d[i - 1] {
                return Err(LawError::format(
                    format!("{path}.d[{i}]"),
                    format!(
                        "{} m: separations must increase strictly (previous {} m)",
                        fmt_num(d[i]),
                        fmt_num(d[i - 1])
                    ),
                ));
            }
        }
        let reach = d[d.len() - 1];
        if !(most_tensile.d >= d[0] && most_tensile.d <= reach) {
            return Err(LawError::format(
                format!("{most_tensile_path}.d"),
                format!(
                    "{} m: must lie on its curve, in [{}, {}] m",
                    fmt_num(most_tensile.d),
                    fmt_num(d[0]),
                    fmt_num(reach)
                ),
            ));
        }
        if !most_tensile.pressure.is_finite() {
            return Err(LawError::format(
                format!("{most_tensile_path}.pressure"),
                format!("{}: must be finite", fmt_num(most_tensile.pressure)),
            ));
        }
        let x: Vec<f64> = d.iter().map(|v| v - origin).collect();
        let interp = Steffen::new(&x, &pressure).map_err(|e| {
            LawError::format(
                format!("{path}.d"),
                format!(
                    "cannot build the interpolant in d - {}: {e}",
                    fmt_num(origin)
                ),
            )
        })?;
        check_most_tensile(
            &interp,
            &d,
            &pressure,
            most_tensile,
            origin,
            most_tensile_path,
        )?;
        let fade = fade_length(interp.nodes(), &pressure);
        Ok(Curve {
            d,
            pressure,
            most_tensile,
            interp,
            fade,
        })
    }

    /// Node separations (m), strictly increasing.
    pub fn d(&self) -> &[f64] {
        &self.d
    }

    /// Node pressures (Pa).
    pub fn pressure(&self) -> &[f64] {
        &self.pressure
    }

    /// The reach (m): the last node; the pressure is zero beyond.
    pub fn reach(&self) -> f64 {
        self.d[self.d.len() - 1]
    }

    /// The most tensile point (for a retract branch, its pull-out).
    pub fn most_tensile(&self) -> Point {
        self.most_tensile
    }

    /// The interpolant in x = d - origin.
    pub(crate) fn interp(&self) -> &Steffen {
        &self.interp
    }

    /// Value and slope at x = d - origin; zero beyond the reach.
    #[inline]
    fn at_x(&self, x: f64) -> (f64, f64) {
        at_x(&self.interp, x)
    }

    #[inline]
    fn x_end(&self) -> f64 {
        self.interp.end()
    }
}

/// A rise of a retract branch before its pull-out: as the surfaces separate the pressure
/// grows, so the tangent dp/dd is positive and an implicit FE code sees a negative
/// unloading stiffness there. The cause on elasto-plastic surfaces is the eq-12 reload
/// overshoot (`docs/theory.md` section 2.5), which the reload reading
/// `contact.reload = "bounded"` removes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PositiveTangent {
    /// Separation (m) of the largest tangent.
    pub d: f64,
    /// The largest tangent dp/dd (Pa/m, > 0) between d_min and the pull-out.
    pub tangent: f64,
    /// The largest rise of the pressure (Pa) as d increases between d_min and the pull-out
    /// (a node value above the lowest node value before it).
    pub rise: f64,
    /// That rise relative to the start pressure p_V(d_min) when it is compressive, else
    /// relative to the curve's largest |p|.
    pub relative_rise: f64,
}

/// A rise smaller than this fraction of the curve's largest |p| is rounding, not a rise.
const RISE_TOLERANCE: f64 = 1e-6;

/// The positive tangent of a retract branch between its start and its pull-out, if any.
fn positive_tangent(c: &Curve, origin: f64) -> Option<PositiveTangent> {
    let s = &c.interp;
    let x = s.nodes();
    let p = &c.pressure;
    let x_limit = c.most_tensile.d - origin;
    let scale = p.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut low = p[0];
    let mut rise: f64 = 0.0;
    for i in 1..p.len() {
        if x[i] > x_limit {
            break;
        }
        rise = rise.max(p[i] - low);
        low = low.min(p[i]);
    }
    if !(rise > RISE_TOLERANCE * scale) {
        return None;
    }
    let (mut best_t, mut best_x) = (f64::NEG_INFINITY, 0.0);
    for i in 0..x.len() - 1 {
        if x[i] >= x_limit {
            break;
        }
        let u_end = (x[i + 1] - x[i]).min(x_limit - x[i]);
        let [_, c1, c2, c3] = s.coefficients(i);
        let mut cand = vec![0.0, u_end];
        if c3 != 0.0 {
            let u = -c2 / (3.0 * c3);
            if u > 0.0 && u < u_end {
                cand.push(u);
            }
        }
        for u in cand {
            let t = c1 + u * (2.0 * c2 + 3.0 * u * c3);
            if t > best_t {
                best_t = t;
                best_x = x[i] + u;
            }
        }
    }
    if !(best_t > 0.0) {
        return None;
    }
    let relative_rise = if p[0] > 0.0 {
        rise / p[0]
    } else {
        rise / scale
    };
    Some(PositiveTangent {
        d: origin + best_x,
        tangent: best_t,
        rise,
        relative_rise,
    })
}

/// The two branches tabulated for one history d_min.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchSet {
    pub(crate) d_min: f64,
    pub(crate) approach: Curve,
    pub(crate) retract: Curve,
    /// ln of the branch's pressure scale S = |p_V(d_min)| + |p_pull_out| + pressure_floor.
    pub(crate) ln_scale: f64,
    /// 1 / S.
    pub(crate) inv_scale: f64,
    pub(crate) positive_tangent: Option<PositiveTangent>,
    pub(crate) measured: Option<BranchError>,
}

/// The interpolation error measured for one tabulated history: at the check points whose
/// d_min lies between this branch and the next shallower one (this branch's own included),
/// per path. Same metric as [`crate::ErrorStats`]; `+inf` where it is infinite.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BranchError {
    /// Largest error on the approach branches.
    pub approach: f64,
    /// Largest error on the retract branches.
    pub retract: f64,
}

impl BranchSet {
    /// A branch set: the two curves of history `d_min`.
    pub(crate) fn new(d_min: f64, approach: Curve, retract: Curve) -> BranchSet {
        let positive_tangent = positive_tangent(&retract, d_min);
        BranchSet {
            d_min,
            approach,
            retract,
            ln_scale: f64::NAN,
            inv_scale: f64::NAN,
            positive_tangent,
            measured: None,
        }
    }

    /// The history (m).
    pub fn d_min(&self) -> f64 {
        self.d_min
    }

    /// The approach (reload) branch, from d_min to its reach.
    pub fn approach(&self) -> &Curve {
        &self.approach
    }

    /// The retract branch, from d_min to its reach.
    pub fn retract(&self) -> &Curve {
        &self.retract
    }

    /// The pull-out: the most tensile point of the retract branch.
    pub fn pull_out(&self) -> Point {
        self.retract.most_tensile
    }

    /// The positive tangent of the retract branch before its pull-out, if it has one (see
    /// [`PositiveTangent`]).
    pub fn positive_retract_tangent(&self) -> Option<PositiveTangent> {
        self.positive_tangent
    }

    /// The interpolation error measured for this history and the interval of histories up
    /// to the next branch, if recorded.
    pub fn measured_error(&self) -> Option<BranchError> {
        self.measured
    }

    /// The pressure scale S = |p_V(d_min)| + |p_pull_out| + pressure_floor (Pa) by which
    /// the rule in d_min normalises this branch.
    pub fn pressure_scale(&self) -> f64 {
        1.0 / self.inv_scale
    }

    pub(crate) fn curve(&self, path: Path) -> &Curve {
        match path {
            Path::Approach => &self.approach,
            Path::Retract => &self.retract,
        }
    }
}

/// The branches of the law with a positive retract tangent (see [`PositiveTangent`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PositiveRetractTangent {
    /// Number of tabulated histories whose retract branch rises before its pull-out.
    pub branches: usize,
    /// Deepest and shallowest of them (m).
    pub d_min_range: [f64; 2],
    /// History (m) of the largest tangent.
    pub worst_d_min: f64,
    /// The largest tangent itself.
    pub worst: PositiveTangent,
    /// The largest relative rise over those branches.
    pub largest_relative_rise: f64,
}

/// Everything of a law file besides the curves.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Meta {
    pub length_scale: Option<f64>,
    pub measured: Option<MeasuredError>,
    pub tabulation: Option<TabulationInfo>,
    pub partial_reload: Option<PartialReloadError>,
    pub scene: serde_json::Value,
}

impl Default for Meta {
    fn default() -> Self {
        Meta {
            length_scale: None,
            measured: None,
            tabulation: None,
            partial_reload: None,
            scene: serde_json::Value::Object(serde_json::Map::new()),
        }
    }
}

/// A tabulated adhesive-contact law p(d; d_min, path) of a rough surface against a flat.
///
/// Read from `law.json` ([`ContactLaw::from_path`]) or built by
/// [`crate::tabulate::tabulate`]. Immutable; evaluation takes `&self`, so one law serves
/// every integration point and thread.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactLaw {
    pub(crate) virgin: Curve,
    pub(crate) grid: Vec<f64>,
    pub(crate) branches: Vec<BranchSet>,
    /// The pressure floor (Pa) of the error metric and of the branch scales.
    pub(crate) floor: f64,
    pub(crate) positive_retract: Option<PositiveRetractTangent>,
    pub(crate) meta: Meta,
}

/// Where a d_min sits among the tabulated branches.
enum Bracket {
    /// On a tabulated history (or the only one): that branch alone.
    Node(usize),
    /// Between histories: the Lagrange weights `c` of the `len` branches from `first`, the
    /// pressure scale S(d_min) = exp(sum c ln S_j), the bracketing pair (k, k + 1) and the
    /// fraction `w` of the way from k to k + 1.
    Between {
        first: usize,
        len: usize,
        c: [f64; 4],
        scale: f64,
        k: usize,
        w: f64,
    },
    /// Above the shallowest history, below the virgin reach: that branch scaled by (1 - w).
    Above { w: f64 },
    /// At or above the virgin reach above the table: the zero law.
    Zero,
}

/// Lagrange weights at `t` of the nodes `g` (2 to 4 of them).
#[inline]
fn lagrange(g: &[f64], t: f64) -> [f64; 4] {
    let mut c = [0.0; 4];
    for j in 0..g.len() {
        let mut v = 1.0;
        for m in 0..g.len() {
            if m != j {
                v *= (t - g[m]) / (g[j] - g[m]);
            }
        }
        c[j] = v;
    }
    c
}

impl ContactLaw {
    /// Assembles and validates a law; error paths name the JSON keys. `floor` is the
    /// pressure floor (Pa) of the branch scales.
    pub(crate) fn assemble(
        virgin: Curve,
        mut branches: Vec<BranchSet>,
        floor: f64,
        meta: Meta,
    ) -> Result<ContactLaw, LawError> {
        if branches.is_empty() {
            return Err(LawError::format(
                "branches",
                "at least one branch is required",
            ));
        }
        if !(floor.is_finite() && floor >= 0.0) {
            return Err(LawError::format(
                "interpolation.pressure_floor",
                format!("{} Pa: must be finite and >= 0", fmt_num(floor)),
            ));
        }
        let grid: Vec<f64> = branches.iter().map(|b| b.d_min).collect();
        for (k, b) in branches.iter_mut().enumerate() {
            let at = format!("branches[{k}]");
            if k > 0 && b.d_min <= grid[k - 1] {
                return Err(LawError::format(
                    format!("{at}.d_min"),
                    format!(
                        "{} m: branches must be sorted by strictly increasing d_min (previous {} m)",
                        fmt_num(b.d_min),
                        fmt_num(grid[k - 1])
                    ),
                ));
            }
            for (name, c) in [("approach", &b.approach), ("retract", &b.retract)] {
                if c.d[0] != b.d_min {
                    return Err(LawError::format(
                        format!("{at}.{name}.d[0]"),
                        format!(
                            "{} m: a branch starts at its d_min = {} m",
                            fmt_num(c.d[0]),
                            fmt_num(b.d_min)
                        ),
                    ));
                }
            }
            let scale = b.retract.pressure[0].abs() + b.pull_out().pressure.abs() + floor;
            if !(scale.is_normal() && (1.0 / scale).is_normal()) {
                return Err(LawError::format(
                    format!("{at}.retract.pressure[0]"),
                    format!(
                        "the branch's pressure scale |p(d_min)| + |pull_out| + pressure_floor = {} Pa must be a positive normal number: a branch without pressure needs a pressure_floor > 0",
                        fmt_num(scale)
                    ),
                ));
            }
            b.ln_scale = scale.ln();
            b.inv_scale = 1.0 / scale;
        }
        if grid[0] < virgin.d[0] {
            return Err(LawError::format(
                "virgin.d[0]",
                format!(
                    "{} m: the virgin envelope must start at or below the deepest d_min = {} m",
                    fmt_num(virgin.d[0]),
                    fmt_num(grid[0])
                ),
            ));
        }
        let mut positive: Option<PositiveRetractTangent> = None;
        for b in &branches {
            if let Some(t) = b.positive_tangent {
                match &mut positive {
                    None => {
                        positive = Some(PositiveRetractTangent {
                            branches: 1,
                            d_min_range: [b.d_min, b.d_min],
                            worst_d_min: b.d_min,
                            worst: t,
                            largest_relative_rise: t.relative_rise,
                        })
                    }
                    Some(s) => {
                        s.branches += 1;
                        s.d_min_range[1] = b.d_min;
                        s.largest_relative_rise = s.largest_relative_rise.max(t.relative_rise);
                        if t.tangent > s.worst.tangent {
                            s.worst = t;
                            s.worst_d_min = b.d_min;
                        }
                    }
                }
            }
        }
        Ok(ContactLaw {
            virgin,
            grid,
            branches,
            floor,
            positive_retract: positive,
            meta,
        })
    }

    /// The virgin envelope p_V(d).
    pub fn virgin(&self) -> &Curve {
        &self.virgin
    }

    /// The tabulated branches, by increasing d_min.
    pub fn branches(&self) -> &[BranchSet] {
        &self.branches
    }

    /// The tabulated d_min values (m), increasing.
    pub fn d_min_grid(&self) -> &[f64] {
        &self.grid
    }

    /// The deepest and shallowest tabulated d_min (m). Histories deeper than the first are
    /// out of range ([`Region::BelowTable`]); above the last the law blends to the zero law
    /// at the virgin reach ([`Region::AboveTable`], not measured).
    pub fn d_min_range(&self) -> (f64, f64) {
        (self.grid[0], self.grid[self.grid.len() - 1])
    }

    /// The pressure floor (Pa): added to the denominator of the error metric, so that
    /// pressures far below the law's own scale are judged against it rather than against
    /// themselves, and to every branch's pressure scale.
    pub fn pressure_floor(&self) -> f64 {
        self.floor
    }

    /// The branches whose retract branch rises before its pull-out (a positive tangent:
    /// a negative unloading stiffness for an FE code), if any.
    pub fn positive_retract_tangent(&self) -> Option<&PositiveRetractTangent> {
        self.positive_retract.as_ref()
    }

    /// The interpolation error the tabulator measured, if the file records it.
    pub fn measured_error(&self) -> Option<&MeasuredError> {
        self.meta.measured.as_ref()
    }

    /// How the law was tabulated, if recorded.
    pub fn tabulation(&self) -> Option<&TabulationInfo> {
        self.meta.tabulation.as_ref()
    }

    /// The measured error of the partial-reload approximation, if recorded.
    pub fn partial_reload(&self) -> Option<&PartialReloadError> {
        self.meta.partial_reload.as_ref()
    }

    /// Records the measured error of the partial-reload approximation (written to the file).
    pub fn set_partial_reload(&mut self, error: PartialReloadError) {
        self.meta.partial_reload = Some(error);
    }

    /// The length (m) over which the law changes appreciably (roughness), if recorded.
    pub fn length_scale(&self) -> Option<f64> {
        self.meta.length_scale
    }

    /// The scene the law was computed for: an arbitrary JSON object, stored and returned,
    /// never interpreted.
    pub fn scene(&self) -> &serde_json::Value {
        &self.meta.scene
    }

    /// Sets the scene object echoed in the file. Only a JSON object is accepted.
    pub fn set_scene(&mut self, scene: serde_json::Value) -> Result<(), LawError> {
        if !scene.is_object() {
            return Err(LawError::format("scene", "must be a JSON object"));
        }
        crate::json::check_no_null(&scene, "scene")?;
        self.meta.scene = scene;
        Ok(())
    }

    /// Pressure and tangent with a history `state`, updated by the call:
    ///
    /// * `d < state.d_min`: the approach deepens the history (d_min <- d), the path is
    ///   approach and the value is the virgin envelope's;
    /// * otherwise a reversal switches the path (approach and d > last d: retract; retract
    ///   and d < last d: approach) and the value is that branch's for the current d_min.
    ///
    /// Returns (p in Pa, dp/dd in Pa/m). On error the state is unchanged. In an implicit FE
    /// code call it on a copy of the state of the last converged increment during the
    /// Newton iterations and keep the updated state only when the increment converges.
    /// [`ContactLaw::step`] returns the same with the [`Region`] of the point.
    ///
    /// With a one-number history, a retraction after a partial reload (a re-approach that
    /// turned at d_turn > d_min) follows the retract branch of d_min, and a re-approach
    /// after a partial retraction follows the approach branch of d_min: see
    /// [`ContactLaw::is_history_exact`].
    pub fn pressure(&self, d: f64, state: &mut State) -> Result<(f64, f64), LawError> {
        self.step(d, state).map(|e| (e.pressure, e.tangent))
    }

    /// [`ContactLaw::pressure`] with the whole [`Evaluation`]: pressure, tangent, the
    /// history and path after the call (also in `state`) and the [`Region`] of the point.
    pub fn step(&self, d: f64, state: &mut State) -> Result<Evaluation, LawError> {
        check_separation(d)?;
        state.check()?;
        if d < state.d_min {
            let (p, t, region) = self.deepen(d)?;
            *state = State {
                d_min: d,
                path: Path::Approach,
                last_d: d,
                d_turn: f64::INFINITY,
            };
            return Ok(Evaluation {
                pressure: p,
                tangent: t,
                d_min: d,
                path: Path::Approach,
                region,
            });
        }
        let (path, d_turn) = match state.path {
            Path::Approach if d > state.last_d => (Path::Retract, state.last_d),
            Path::Retract if d < state.last_d => (Path::Approach, state.last_d),
            p => (p, state.d_turn),
        };
        let (p, t, region) = self.branch(d, state.d_min, path)?;
        state.path = path;
        state.last_d = d;
        state.d_turn = d_turn;
        Ok(Evaluation {
            pressure: p,
            tangent: t,
            d_min: state.d_min,
            path,
            region,
        })
    }

    /// Stateless evaluation at separation `d` (m) with history `d_min` (m, `+inf` for a
    /// virgin surface) on `path`: d < d_min deepens the history (the returned d_min is d and
    /// the path approach, the value the virgin envelope's); otherwise the branch `path` of
    /// `d_min`. The result says in which [`Region`] the point lies.
    pub fn evaluate(&self, d: f64, d_min: f64, path: Path) -> Result<Evaluation, LawError> {
        check_separation(d)?;
        if d_min.is_nan() || d_min == f64::NEG_INFINITY {
            return Err(LawError::invalid(
                "d_min",
                d_min,
                "finite, or +inf for a virgin surface",
            ));
        }
        if d < d_min {
            let (pressure, tangent, region) = self.deepen(d)?;
            return Ok(Evaluation {
                pressure,
                tangent,
                d_min: d,
                path: Path::Approach,
                region,
            });
        }
        let (pressure, tangent, region) = self.branch(d, d_min, path)?;
        Ok(Evaluation {
            pressure,
            tangent,
            d_min,
            path,
            region,
        })
    }

    /// The virgin envelope p_V(d) and its slope; zero beyond its reach. Errors below the
    /// start of the envelope.
    pub fn virgin_pressure(&self, d: f64) -> Result<(f64, f64), LawError> {
        check_separation(d)?;
        if d < self.virgin.d[0] {
            return Err(LawError::OutOfRange(format!(
                "separation d = {} m is below the virgin envelope, tabulated from {} m",
                fmt_num(d),
                fmt_num(self.virgin.d[0])
            )));
        }
        Ok(self.virgin.at_x(d))
    }

    /// The branch `path` of history `d_min` at d >= d_min, with its slope at fixed d_min.
    pub fn branch_pressure(&self, d: f64, d_min: f64, path: Path) -> Result<(f64, f64), LawError> {
        self.branch(d, d_min, path).map(|(p, t, _)| (p, t))
    }

    /// [`ContactLaw::branch_pressure`] with the region of the point.
    fn branch(&self, d: f64, d_min: f64, path: Path) -> Result<(f64, f64, Region), LawError> {
        check_separation(d)?;
        if d < d_min || d_min.is_nan() {
            return Err(LawError::Invalid {
                name: "d",
                value: format!("{} m with d_min = {} m", fmt_num(d), fmt_num(d_min)),
                allowed: "a branch is defined for d >= d_min",
            });
        }
        let br = self.bracket(d_min)?;
        Ok(self.blend(&br, d - d_min, d_min, path))
    }

    /// The reach (m) of the branch `path` of history `d_min`: the pressure is zero beyond.
    pub fn reach(&self, d_min: f64, path: Path) -> Result<f64, LawError> {
        if d_min.is_nan() {
            return Err(LawError::invalid("d_min", d_min, "a number"));
        }
        let end = match self.bracket(d_min)? {
            Bracket::Zero => 0.0,
            Bracket::Node(k) => self.branches[k].curve(path).x_end(),
            Bracket::Above { .. } => self.branches[self.grid.len() - 1].curve(path).x_end(),
            Bracket::Between { first, len, .. } => self.branches[first..first + len]
                .iter()
                .fold(0.0f64, |m, b| m.max(b.curve(path).x_end())),
        };
        Ok(d_min + end)
    }

    /// True when the one-number history is exact for `state`: a virgin surface, an
    /// approach from far or on the envelope, a retraction that began at d_min, or a
    /// re-approach after a retraction that went beyond the retract reach. False after a
    /// partial reload (retract with d_turn > d_min) or a partial retraction (approach with
    /// d_turn below the retract reach): there the law uses the branch of d_min while the
    /// real surface also remembers d_turn. (Whether the point lies in the measured region
    /// is a separate question: [`Evaluation::region`].)
    pub fn is_history_exact(&self, state: &State) -> bool {
        if state.is_virgin() || state.d_turn == f64::INFINITY {
            return true;
        }
        match state.path {
            Path::Retract => state.d_turn <= state.d_min,
            Path::Approach => match self.reach(state.d_min, Path::Retract) {
                Ok(r) => state.d_turn >= r,
                Err(_) => false,
            },
        }
    }

    /// Where a history `d_min` (m) lies relative to the table: [`Region::BelowTable`] deeper
    /// than the deepest branch (evaluation there is an error), [`Region::Measured`] within
    /// the tabulated range, [`Region::AboveTable`] between the shallowest branch and the
    /// virgin reach (the law blends to zero there, not measured), [`Region::BeyondReach`]
    /// at or beyond the virgin reach, including `+inf` (a surface never touched: the law
    /// is exactly zero there, as the model is). NaN is below the table (no value).
    pub fn history_region(&self, d_min: f64) -> Region {
        let (lo, hi) = self.d_min_range();
        if !(d_min >= lo) {
            Region::BelowTable
        } else if d_min <= hi {
            Region::Measured
        } else if d_min < self.virgin.reach() {
            Region::AboveTable
        } else {
            Region::BeyondReach
        }
    }

    /// The virgin value on a deepening approach; errors below the tabulated histories.
    fn deepen(&self, d: f64) -> Result<(f64, f64, Region), LawError> {
        if d < self.grid[0] {
            return Err(self.too_deep("separation d", d));
        }
        if d > self.virgin.reach() {
            return Ok((0.0, 0.0, Region::BeyondReach));
        }
        let (p, t) = self.virgin.at_x(d);
        Ok((p, t, Region::Measured))
    }

    fn too_deep(&self, what: &str, v: f64) -> LawError {
        LawError::OutOfRange(format!(
            "{what} = {} m is deeper than the law was tabulated for (region below_table): \
             d_min covers [{}, {}] m (tabulate again with a smaller d_min_lo)",
            fmt_num(v),
            fmt_num(self.grid[0]),
            fmt_num(self.grid[self.grid.len() - 1])
        ))
    }

    /// The branches that carry `d_min`.
    #[inline]
    fn bracket(&self, d_min: f64) -> Result<Bracket, LawError> {
        let n = self.grid.len();
        if d_min < self.grid[0] {
            return Err(self.too_deep("history d_min", d_min));
        }
        let last = self.grid[n - 1];
        if d_min >= last {
            if d_min == last {
                return Ok(Bracket::Node(n - 1));
            }
            let top = self.virgin.reach();
            if d_min >= top {
                return Ok(Bracket::Zero);
            }
            return Ok(Bracket::Above {
                w: (d_min - last) / (top - last),
            });
        }
        let k = self.grid.partition_point(|&g| g <= d_min) - 1;
        if self.grid[k] == d_min {
            return Ok(Bracket::Node(k));
        }
        let len = n.min(4);
        let first = (k.saturating_sub(1)).min(n - len);
        let g = &self.grid[first..first + len];
        let c = lagrange(g, d_min);
        let mut ln_s = 0.0;
        for (cj, b) in c.iter().zip(&self.branches[first..first + len]) {
            ln_s += cj * b.ln_scale;
        }
        let (g0, g1) = (self.grid[k], self.grid[k + 1]);
        Ok(Bracket::Between {
            first,
            len,
            c,
            scale: ln_s.exp(),
            k,
            w: (d_min - g0) / (g1 - g0),
        })
    }

    /// Pressure, tangent and region at x = d - d_min on `path` of the bracketed history.
    #[inline]
    fn blend(&self, br: &Bracket, x: f64, d_min: f64, path: Path) -> (f64, f64, Region) {
        match *br {
            Bracket::Zero => (0.0, 0.0, Region::BeyondReach),
            Bracket::Node(k) => {
                let c = self.branches[k].curve(path);
                if x > c.x_end() {
                    (0.0, 0.0, Region::BeyondReach)
                } else {
                    let (p, t) = c.at_x(x);
                    (p, t, Region::Measured)
                }
            }
            Bracket::Above { w } => {
                let lo = self.branches[self.grid.len() - 1].curve(path);
                if x > lo.x_end() {
                    return (0.0, 0.0, Region::BeyondReach);
                }
                let v = 1.0 - w;
                let (p0, t0) = lo.at_x(x);
                let pv = self.virgin.at_x(d_min).0;
                let (dp, dt) = correction(pv - v * lo.interp.first_value(), lo.fade, x);
                (v * p0 + dp, v * t0 + dt, Region::AboveTable)
            }
            Bracket::Between {
                first,
                len,
                c,
                scale,
                k,
                w,
            } => {
                let (mut p, mut t, mut start) = (0.0, 0.0, 0.0);
                let mut end: f64 = 0.0;
                for (cj, b) in c.iter().zip(&self.branches[first..first + len]) {
                    let cu = b.curve(path);
                    let a = cj * scale * b.inv_scale;
                    let (pj, tj) = cu.at_x(x);
                    p += a * pj;
                    t += a * tj;
                    start += a * cu.interp.first_value();
                    end = end.max(cu.x_end());
                }
                if x > end {
                    return (0.0, 0.0, Region::BeyondReach);
                }
                let fade = (1.0 - w) * self.branches[k].curve(path).fade
                    + w * self.branches[k + 1].curve(path).fade;
                let pv = self.virgin.at_x(d_min).0;
                let (dp, dt) = correction(pv - start, fade, x);
                (p + dp, t + dt, Region::Measured)
            }
        }
    }
}

/// Relative tolerance (of the curve's largest |p|) on a special point's pressure: the
/// rounding of a writer that computes it rather than copying a node.
pub const MOST_TENSILE_TOLERANCE: f64 = 1e-9;

/// The most tensile point of a curve lies on it, in d (checked by the caller) and in
/// pressure: its pressure is the interpolant's at its d, and no node is more tensile (the
/// interpolant has no overshoot, so that is its minimum), both within
/// [`MOST_TENSILE_TOLERANCE`] of the curve's largest |p|.
fn check_most_tensile(
    interp: &Steffen,
    d: &[f64],
    pressure: &[f64],
    mt: Point,
    origin: f64,
    path: &str,
) -> Result<(), LawError> {
    let scale = pressure.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let tol = MOST_TENSILE_TOLERANCE * scale;
    // x as a node's x is computed: a point on a node is exactly that node
    let on = interp.value_and_slope(mt.d - origin).0;
    if !((mt.pressure - on).abs() <= tol) {
        return Err(LawError::format(
            format!("{path}.pressure"),
            format!(
                "{} Pa: must lie on its curve, which is {} Pa at d = {} m",
                fmt_num(mt.pressure),
                fmt_num(on),
                fmt_num(mt.d)
            ),
        ));
    }
    let (k, lowest) = pressure
        .iter()
        .copied()
        .enumerate()
        .fold(
            (0, f64::INFINITY),
            |a, (i, p)| if p < a.1 { (i, p) } else { a },
        );
    if mt.pressure > lowest + tol {
        return Err(LawError::format(
            format!("{path}.pressure"),
            format!(
                "{} Pa: must be the most tensile point of its curve, but the node at d = {} m \
                 has {} Pa",
                fmt_num(mt.pressure),
                fmt_num(d[k]),
                fmt_num(lowest)
            ),
        ));
    }
    Ok(())
}

/// Value and slope of a curve's interpolant at x; zero beyond its last node.
#[inline]
fn at_x(s: &Steffen, x: f64) -> (f64, f64) {
    if x > s.end() {
        (0.0, 0.0)
    } else {
        s.value_and_slope(x)
    }
}

/// The length over which a branch makes the first half of its largest change from its
/// start value: the first node x where |p - p(0)| reaches half of max |p - p(0)| (the last
/// node for a constant branch). The continuity correction fades over it, so that it acts
/// where the branch is still of the size of its start value and not on the small tail.
pub(crate) fn fade_length(x: &[f64], p: &[f64]) -> f64 {
    let p0 = p[0];
    let big = p.iter().fold(0.0f64, |m, v| m.max((v - p0).abs()));
    let last = x[x.len() - 1];
    if big == 0.0 {
        return last;
    }
    x.iter()
        .zip(p)
        .find(|(_, v)| (**v - p0).abs() >= 0.5 * big)
        .map_or(last, |(xi, _)| *xi)
}

/// The continuity correction c (1 - x/L)^2 for x < L (zero beyond), with its slope:
/// c = p_V(d_min) minus the value the blended branches have at x = 0, L their blended
/// [`fade_length`]. It makes every interpolated branch start on the virgin envelope,
/// p(d_min; d_min) = p_V(d_min), and is C1 where it ends.
#[inline]
pub(crate) fn correction(c: f64, fade: f64, x: f64) -> (f64, f64) {
    if c == 0.0 || x >= fade {
        return (0.0, 0.0);
    }
    let s = 1.0 - x / fade;
    (c * s * s, -2.0 * c * s / fade)
}

fn check_separation(d: f64) -> Result<(), LawError> {
    if d.is_finite() {
        Ok(())
    } else {
        Err(LawError::invalid("separation d", d, "finite (m)"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fresh_state_is_virgin() {
        let s = State::default();
        assert!(s.is_virgin());
        assert_eq!(s.path, Path::Approach);
    }
}
