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

/// The two branches tabulated for one history d_min.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchSet {
    pub(crate) d_min: f64,
    pub(crate) approach: Curve,
    pub(crate) retract: Curve,
}

impl BranchSet {
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

    fn curve(&self, path: Path) -> &Curve {
        match path {
            Path::Approach => &self.approach,
            Path::Retract => &self.retract,
        }
    }
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
    pub(crate) meta: Meta,
}

/// Where a d_min sits among the tabulated branches: p = (1-w) lower + w upper, the upper
/// being the zero law when `upper` is `None`.
struct Bracket<'a> {
    lower: &'a BranchSet,
    upper: Option<&'a BranchSet>,
    w: f64,
}

impl ContactLaw {
    /// Assembles and validates a law; error paths name the JSON keys.
    pub(crate) fn assemble(
        virgin: Curve,
        branches: Vec<BranchSet>,
        meta: Meta,
    ) -> Result<ContactLaw, LawError> {
        if branches.is_empty() {
            return Err(LawError::format(
                "branches",
                "at least one branch is required",
            ));
        }
        let grid: Vec<f64> = branches.iter().map(|b| b.d_min).collect();
        for (k, b) in branches.iter().enumerate() {
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
        Ok(ContactLaw {
            virgin,
            grid,
            branches,
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
    /// out of range; above the last the law blends to the zero law at the virgin reach.
    pub fn d_min_range(&self) -> (f64, f64) {
        (self.grid[0], self.grid[self.grid.len() - 1])
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
        crate::format::check_no_null(&scene, "scene")?;
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
    ///
    /// With a one-number history, a retraction after a partial reload (a re-approach that
    /// turned at d_turn > d_min) follows the retract branch of d_min, and a re-approach
    /// after a partial retraction follows the approach branch of d_min: see
    /// [`ContactLaw::is_history_exact`].
    pub fn pressure(&self, d: f64, state: &mut State) -> Result<(f64, f64), LawError> {
        check_separation(d)?;
        state.check()?;
        if d < state.d_min {
            let (p, t) = self.deepen(d)?;
            *state = State {
                d_min: d,
                path: Path::Approach,
                last_d: d,
                d_turn: f64::INFINITY,
            };
            return Ok((p, t));
        }
        let (path, d_turn) = match state.path {
            Path::Approach if d > state.last_d => (Path::Retract, state.last_d),
            Path::Retract if d < state.last_d => (Path::Approach, state.last_d),
            p => (p, state.d_turn),
        };
        let (p, t) = self.branch_pressure(d, state.d_min, path)?;
        state.path = path;
        state.last_d = d;
        state.d_turn = d_turn;
        Ok((p, t))
    }

    /// Stateless evaluation at separation `d` (m) with history `d_min` (m, `+inf` for a
    /// virgin surface) on `path`: d < d_min deepens the history (the returned d_min is d and
    /// the path approach, the value the virgin envelope's); otherwise the branch `path` of
    /// `d_min`.
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
            let (pressure, tangent) = self.deepen(d)?;
            return Ok(Evaluation {
                pressure,
                tangent,
                d_min: d,
                path: Path::Approach,
            });
        }
        let (pressure, tangent) = self.branch_pressure(d, d_min, path)?;
        Ok(Evaluation {
            pressure,
            tangent,
            d_min,
            path,
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
        check_separation(d)?;
        if d < d_min || d_min.is_nan() {
            return Err(LawError::Invalid {
                name: "d",
                value: format!("{} m with d_min = {} m", fmt_num(d), fmt_num(d_min)),
                allowed: "a branch is defined for d >= d_min",
            });
        }
        let Some(br) = self.bracket(d_min)? else {
            return Ok((0.0, 0.0));
        };
        Ok(self.blend(&br, d - d_min, d_min, path))
    }

    /// The reach (m) of the branch `path` of history `d_min`: the pressure is zero beyond.
    pub fn reach(&self, d_min: f64, path: Path) -> Result<f64, LawError> {
        if d_min.is_nan() {
            return Err(LawError::invalid("d_min", d_min, "a number"));
        }
        let Some(br) = self.bracket(d_min)? else {
            return Ok(d_min);
        };
        let mut end = br.lower.curve(path).x_end();
        if let (Some(u), true) = (br.upper, br.w > 0.0) {
            end = end.max(u.curve(path).x_end());
        }
        Ok(d_min + end)
    }

    /// True when the one-number history is exact for `state`: a virgin surface, an
    /// approach from far or on the envelope, a retraction that began at d_min, or a
    /// re-approach after a retraction that went beyond the retract reach. False after a
    /// partial reload (retract with d_turn > d_min) or a partial retraction (approach with
    /// d_turn below the retract reach): there the law uses the branch of d_min while the
    /// real surface also remembers d_turn.
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

    /// The virgin value on a deepening approach; errors below the tabulated histories.
    fn deepen(&self, d: f64) -> Result<(f64, f64), LawError> {
        if d < self.grid[0] {
            return Err(self.too_deep("separation d", d));
        }
        Ok(self.virgin.at_x(d))
    }

    fn too_deep(&self, what: &str, v: f64) -> LawError {
        LawError::OutOfRange(format!(
            "{what} = {} m is deeper than the law was tabulated for: d_min covers [{}, {}] m \
             (tabulate again with a smaller d_min_lo)",
            fmt_num(v),
            fmt_num(self.grid[0]),
            fmt_num(self.grid[self.grid.len() - 1])
        ))
    }

    /// The neighbouring branches of `d_min`; `None` where the law is zero (d_min at or
    /// above the virgin reach and above every tabulated branch).
    #[inline]
    fn bracket(&self, d_min: f64) -> Result<Option<Bracket<'_>>, LawError> {
        let n = self.grid.len();
        if d_min < self.grid[0] {
            return Err(self.too_deep("history d_min", d_min));
        }
        let last = self.grid[n - 1];
        if d_min > last {
            let top = self.virgin.reach();
            if d_min >= top {
                return Ok(None);
            }
            return Ok(Some(Bracket {
                lower: &self.branches[n - 1],
                upper: None,
                w: (d_min - last) / (top - last),
            }));
        }
        let k = self.grid.partition_point(|&g| g <= d_min) - 1;
        if k + 1 == n {
            return Ok(Some(Bracket {
                lower: &self.branches[k],
                upper: None,
                w: 0.0,
            }));
        }
        let (g0, g1) = (self.grid[k], self.grid[k + 1]);
        Ok(Some(Bracket {
            lower: &self.branches[k],
            upper: Some(&self.branches[k + 1]),
            w: (d_min - g0) / (g1 - g0),
        }))
    }

    #[inline]
    fn blend(&self, br: &Bracket<'_>, x: f64, d_min: f64, path: Path) -> (f64, f64) {
        let lo = br.lower.curve(path);
        let pv = self.virgin.at_x(d_min).0;
        let v = 1.0 - br.w;
        let (p0, t0) = lo.at_x(x);
        let (mut p, mut t) = (v * p0, v * t0);
        let mut start = v * lo.interp.first_value();
        let mut fade = lo.fade;
        if let (Some(up), true) = (br.upper, br.w > 0.0) {
            let up = up.curve(path);
            let (p1, t1) = up.at_x(x);
            p += br.w * p1;
            t += br.w * t1;
            start += br.w * up.interp.first_value();
            fade = v * lo.fade + br.w * up.fade;
        }
        let (dp, dt) = correction(pv - start, fade, x);
        (p + dp, t + dt)
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
