//! The adhesive-contact law p(d; d_min, path) of a scene's rough surface, tabulated for a
//! finite-element code.
//!
//! The surface is the scene's contact and surface sections at the run's accuracy. Its
//! whole history is one number, d_min, the deepest separation reached
//! (`GwHistory::Flat { deepest: d_min }`), so the law is a family of curves in d (m,
//! separation from the mean plane of asperity heights to the flat): the virgin envelope,
//! and for each tabulated d_min the approach (reload) branch and the retract branch. The
//! tabulator of `contact-law` samples them from the surface directly and measures its
//! interpolation error; this module supplies the surface ([`SceneSurface`]), the default
//! range of histories and the measured error of the one-number history after a partial
//! reload. A switch scene's default histories reach down past its impacts; a surface
//! scene's down to its `unload_from`.

use crate::accuracy::{Accuracy, Targets};
use crate::error::ModelError;
use crate::guards::{self, Validity, Warning};
use crate::keys::num;
use crate::spec::{ContactSpec, RoughSurface, RoughnessSpec, Spec, SurfaceSpec, SwitchSpec};
use crate::switch::{rough_surface, Laws, SwitchModel};
use crate::{Progress, Silent};
use contact_core::numeric::{brent_from, expand_bracket, Expansion, Sample, Tolerance};
use contact_core::{Path as SurfacePath, SurfaceLaw};
use contact_law::tabulate::{
    self, Branch, GridSpec, LawSource, ReloadSource, Tabulation, DEFAULT_FLOOR_FRACTION,
};
use contact_law::{ContactLaw, MeasuredError, PartialReloadError, PositiveRetractTangent};
use gw_surface::GwHistory;
use serde::Serialize;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// The default grid of histories starts this many sigma_s below the deepest end of impact
/// of the scene's cycles, so that a cycle's own d_min (and a slightly harder impact) lies
/// inside the table rather than on its edge.
pub const BELOW_IMPACT_SIGMAS: f64 = 0.5;

/// The pressure floor of the law's error metric, and the "first touch" that ends the
/// default grid of histories: this fraction of the pressure scale of the deepest history
/// (the larger of its virgin pressure and its pull-out). The first touch is the largest
/// separation at which the virgin pressure or the pull-out reaches the floor: shallower
/// histories carry pressures below it (the law blends them to zero, region `above_table`);
/// taking the geometric first touch instead (the highest asperity, 9 sigma_s) would spend
/// branches on pressures down to 1e-30 Pa.
pub const FLOOR_FRACTION: f64 = DEFAULT_FLOOR_FRACTION;

/// Partial reloads measured: the reload turns at d_min + f (approach reach - d_min) for
/// each of these f.
pub const TURN_FRACTIONS: [f64; 4] = [0.005, 0.02, 0.05, 0.15];

/// Start points per branch: the branches reach the jump-in of the highest asperity (9
/// sigma_s), so 96 points space the start grid by about 0.08 sigma_s. With 48 the
/// midpoint test of the refinement let one branch in 500 of the paper's law keep an
/// interval 2 sigma_s/10 wide with an error of 1.7e-3 between its quarter points; with 96
/// none above 6.5e-4 in 300 points per branch (docs/contact-law.md section 7).
pub const DEFAULT_POINTS: usize = 96;

/// The accuracy mode of `stiction law` unless `--accuracy` says otherwise: the table's
/// tolerance (2e-4 of |p| + |p_pull_out|) is 13 times the fast mode's measured pull-out
/// error, and the tabulation makes about half a million surface evaluations.
pub const DEFAULT_ACCURACY: Accuracy = Accuracy::Fast;

/// Cap on the tabulated histories of the adaptive grid.
pub const MAX_BRANCHES: usize = 1000;

/// Separations per turning point of the partial-reload measurement.
pub const RELOAD_POINTS: usize = 24;

/// The scene's rough surface seen by the tabulator: one-number histories
/// `GwHistory::Flat { deepest: d_min }`, with a count of surface evaluations for the
/// progress bar.
/// `Sync`: the tabulator evaluates it from several threads.
pub struct SceneSurface<'a> {
    gw: &'a RoughSurface,
    precision: switch_1d::Precision,
    evaluations: AtomicU64,
    stop: &'a dyn Progress,
}

impl<'a> SceneSurface<'a> {
    /// The source for `gw`; pull-outs are searched to `precision`.
    pub fn new(gw: &'a RoughSurface, precision: switch_1d::Precision) -> Self {
        Self {
            gw,
            precision,
            evaluations: AtomicU64::new(0),
            stop: &Silent,
        }
    }

    /// The same source, stopped by `progress`: once it asks, every evaluation is
    /// [`ModelError::Cancelled`].
    pub fn stopped_by(mut self, progress: &'a dyn Progress) -> Self {
        self.stop = progress;
        self
    }

    /// Surface pressure evaluations so far (tabulation, pull-out searches, measurements;
    /// a pull-out search counts 48).
    pub fn evaluations(&self) -> u64 {
        self.evaluations.load(Ordering::Relaxed)
    }

    /// Counts `n` evaluations, or refuses them once the caller stops the run.
    fn tick(&self, n: u64) -> Result<(), ModelError> {
        crate::check_cancelled(self.stop)?;
        self.evaluations.fetch_add(n, Ordering::Relaxed);
        Ok(())
    }

    fn history(d_min: f64) -> GwHistory {
        GwHistory::Flat { deepest: d_min }
    }
}

impl LawSource for SceneSurface<'_> {
    type Error = ModelError;

    fn pressure(&self, d: f64, d_min: f64, branch: Branch) -> Result<f64, ModelError> {
        self.tick(1)?;
        let (history, path) = match branch {
            Branch::Virgin => (GwHistory::VIRGIN, SurfacePath::Approach),
            Branch::Approach => (Self::history(d_min), SurfacePath::Approach),
            Branch::Retract => (Self::history(d_min), SurfacePath::Retract { from: d_min }),
        };
        Ok(self.gw.pressure(d, &history, path)?)
    }

    fn reach(&self, d_min: f64, branch: Branch) -> Result<f64, ModelError> {
        crate::check_cancelled(self.stop)?;
        let (history, path) = match branch {
            Branch::Virgin => (GwHistory::VIRGIN, SurfacePath::Approach),
            Branch::Approach => (Self::history(d_min), SurfacePath::Approach),
            Branch::Retract => (Self::history(d_min), SurfacePath::Retract { from: d_min }),
        };
        Ok(self.gw.reach(&history, path)?)
    }

    /// The robust pull-out search of the switch model (`switch_1d::unload`): a scan of the
    /// retract branch and golden-section refinement of its most tensile point.
    fn pull_out(&self, d_min: f64) -> Result<(f64, f64), ModelError> {
        // the scan and refinement cost a few dozen evaluations; counted roughly
        self.tick(48)?;
        let stoppable = crate::Cancellable::new(self.gw, self.stop);
        let u = switch_1d::unload(&stoppable, &Self::history(d_min), d_min, 0, self.precision)?;
        Ok((u.pull_out_separation, -u.pull_out_pressure))
    }

    fn length_scale(&self) -> f64 {
        self.gw.sigma_s()
    }
}

impl ReloadSource for SceneSurface<'_> {
    /// The surface itself after a partial reload: every asperity still remembers
    /// delta_max = h - d_min, and the excursion that is now retracting reached d_turn, so
    /// only the asperities that jumped in on the way down to d_turn are attached
    /// (`Path::Retract { from: d_turn }`). Exact for this model: the history after a
    /// reload from far that turned above d_min is still the one-number `Flat { d_min }`.
    fn retract_after_reload(&self, d: f64, d_min: f64, d_turn: f64) -> Result<f64, ModelError> {
        self.tick(1)?;
        Ok(self.gw.pressure(
            d,
            &Self::history(d_min),
            SurfacePath::Retract { from: d_turn },
        )?)
    }
}

/// How the tabulated histories were chosen.
#[derive(Debug, Clone, Serialize)]
pub struct Histories {
    /// `adaptive` (the default range) or `uniform FROM:TO:N` (the user's grid).
    pub rule: String,
    /// Deepest tabulated history (m).
    pub d_min_lo: f64,
    /// Shallowest tabulated history (m).
    pub d_min_hi: f64,
    /// The deepest end-of-impact separation d_e of the scene's cycles (m), default range.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub deepest_d_e: Option<f64>,
    /// The cycles' d_e (m), default range.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub cycles_d_e: Vec<f64>,
    /// How far below the deepest d_e the grid starts (m), default range.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub below_deepest_d_e: Option<f64>,
    /// The pressure scale of the deepest history (Pa): the larger of its virgin pressure
    /// and its pull-out (default range: the reference of the first touch).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_touch_reference: Option<f64>,
    /// The first touch's fraction of it, default range.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_touch_fraction: Option<f64>,
    /// The pressure floor of the error metric (Pa): [`FLOOR_FRACTION`] of the pressure
    /// scale of the deepest history.
    pub pressure_floor: f64,
    /// Where the first asperity (at 9 sigma_s) jumps in on a virgin approach (m): the
    /// virgin envelope is tabulated up to it, and zero beyond.
    pub virgin_reach: f64,
    /// In words.
    pub description: String,
}

/// One tabulated history, for the summary.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct BranchSummary {
    /// The history (m).
    pub d_min: f64,
    /// Virgin (= both branches') pressure at d_min (Pa).
    pub start_pressure: f64,
    /// Most tensile point of the retract branch: separation (m) ...
    pub pull_out_d: f64,
    /// ... and pressure (Pa, negative: tensile).
    pub pull_out_pressure: f64,
    /// Most tensile point of the approach branch (the pull-in well): separation (m) ...
    pub approach_most_tensile_d: f64,
    /// ... and pressure (Pa).
    pub approach_most_tensile_pressure: f64,
    /// Where the approach branch begins (the first asperity jumps in, m).
    pub approach_reach: f64,
    /// Where the retract branch ends (the last asperity jumps out, m).
    pub retract_reach: f64,
    /// Nodes of the approach and retract branches.
    pub nodes: usize,
    /// Largest measured error of this history and the interval up to the next one, on the
    /// approach ...
    #[serde(serialize_with = "error_number")]
    pub measured_error_approach: f64,
    /// ... and on the retract branches.
    #[serde(serialize_with = "error_number")]
    pub measured_error_retract: f64,
    /// The largest positive tangent of the retract branch before its pull-out (Pa/m),
    /// absent when the branch falls monotonically.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub positive_retract_tangent: Option<f64>,
    /// The rise of the pressure on that branch, relative to its start.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub retract_relative_rise: Option<f64>,
}

/// A law tabulation.
#[derive(Debug, Clone, Serialize)]
pub struct LawResult {
    /// Plot and table title.
    pub title: String,
    /// The laws and modelling choices.
    pub laws: Laws,
    /// Whether the model holds at the deepest history tabulated.
    pub validity: Validity,
    /// Accuracy mode of the surface evaluations.
    pub accuracy: Targets,
    /// sigma_s (m).
    pub sigma_s: f64,
    /// The tabulated histories.
    pub histories: Histories,
    /// Number of tabulated histories.
    pub branches: usize,
    /// Nodes of the virgin envelope.
    pub virgin_nodes: usize,
    /// Nodes of all curves.
    pub nodes: usize,
    /// Tolerance on the measured error.
    pub tolerance: f64,
    /// The pressure floor of the error metric (Pa).
    pub pressure_floor: f64,
    /// The retract branches that rise before their pull-out, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub positive_retract_tangent: Option<PositiveRetractTangent>,
    /// Interpolation error measured against the surface at points off every grid.
    pub measured_error: MeasuredError,
    /// Error of the one-number history after a partial reload (the law retracts along the
    /// branch of d_min; the surface along its own path from the turning point).
    pub partial_reload: PartialReloadError,
    /// Turning fractions of the partial-reload measurement.
    pub partial_reload_turn_fractions: Vec<f64>,
    /// Surface pressure evaluations of the tabulation and its measurement.
    pub source_evaluations: usize,
    /// Every measured error is within the tolerance (no cap stopped a refinement).
    pub converged: bool,
    /// Wall time of the whole command (s).
    pub seconds: f64,
    /// Size of law.json (bytes).
    pub law_json_bytes: usize,
    /// The tabulated histories, one line each.
    pub summary: Vec<BranchSummary>,
    /// Guards raised.
    pub warnings: Vec<Warning>,
    /// law.json as text.
    #[serde(skip)]
    pub law_json: String,
    /// The tabulated law (law.json, law.csv are written from it).
    #[serde(skip)]
    pub law: ContactLaw,
}

/// What a tabulation takes besides the scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawOptions {
    /// The histories as a uniform grid; None: adaptive over the default range.
    pub d_min: Option<GridSpec>,
    /// Start points per branch, 4..=100000.
    pub points: usize,
    /// Refinement tolerance on |p_table - p_direct| / (|p_direct| + |p_pull_out(d_min)|),
    /// in (0, 0.1].
    pub tolerance: f64,
    /// The accuracy mode of the surface evaluations (None: [`DEFAULT_ACCURACY`]).
    pub accuracy: Option<Accuracy>,
}

impl Default for LawOptions {
    fn default() -> Self {
        Self {
            d_min: None,
            points: DEFAULT_POINTS,
            tolerance: 2e-4,
            accuracy: None,
        }
    }
}

impl LawOptions {
    /// Checks the options (errors name `points`, `tolerance`).
    pub fn check(&self) -> Result<(), ModelError> {
        if !(4..=100_000).contains(&self.points) {
            return Err(ModelError::argument(
                "points",
                self.points.to_string(),
                "an integer in [4, 100000]",
            ));
        }
        if !(self.tolerance > 0.0 && self.tolerance <= 0.1) {
            return Err(ModelError::argument(
                "tolerance",
                num(self.tolerance),
                "in (0, 0.1]",
            ));
        }
        Ok(())
    }
}

/// The scene a law is tabulated from: a switch (its impacts set the default depth) or a
/// surface (its `unload_from`).
#[derive(Debug, Clone, Copy)]
pub enum LawScene<'a> {
    /// A switch scene.
    Switch(&'a SwitchSpec),
    /// A surface scene.
    Surface(&'a SurfaceSpec),
}

impl<'a> LawScene<'a> {
    /// The law scene of a spec (an asperity scene has no surface).
    pub fn of(spec: &'a Spec) -> Result<Self, ModelError> {
        match spec {
            Spec::Switch(s) => Ok(LawScene::Switch(s)),
            Spec::Surface(s) => Ok(LawScene::Surface(s)),
            Spec::Asperity(_) => Err(ModelError::argument(
                "scene",
                spec.common().scene.file(),
                "a switch or surface scene (an asperity scene has no rough surface)",
            )),
        }
    }

    fn parts(&self) -> (&'a crate::spec::Common, &'a ContactSpec, RoughnessSpec) {
        match *self {
            LawScene::Switch(s) => (&s.common, &s.contact, s.roughness),
            LawScene::Surface(s) => (&s.common, &s.contact, s.roughness),
        }
    }
}

/// Tabulates the law of `scene` with `options`, reporting its work to `progress` (in
/// thousandths), which can stop it ([`ModelError::Cancelled`], polled at every surface
/// evaluation).
pub fn tabulate(
    scene: LawScene,
    options: &LawOptions,
    progress: &dyn Progress,
) -> Result<LawResult, ModelError> {
    let (common, _, _) = scene.parts();
    crate::check_cancelled(progress)?;
    tabulate_inner(scene, options, progress)
        .and_then(|r| crate::check_cancelled(progress).map(|()| r))
        .map_err(|e| e.or_cancelled(progress).in_scene(common.scene.file()))
}

fn tabulate_inner(
    scene: LawScene,
    opts: &LawOptions,
    progress: &dyn Progress,
) -> Result<LawResult, ModelError> {
    opts.check()?;
    let start = Instant::now();
    let (common, c, roughness) = scene.parts();
    let accuracy = opts.accuracy.unwrap_or(DEFAULT_ACCURACY);
    let laws = Laws::of(c);
    // the surface exactly as `stiction surface` builds it (no absolute floor)
    let gw = rough_surface(c, roughness, accuracy, 0.0, false)?;
    let precision = accuracy.precision();
    let sigma = gw.sigma_s();
    let virgin_reach = gw.reach(&GwHistory::VIRGIN, SurfacePath::Approach)?;
    let histories = match opts.d_min {
        Some(g) => user_histories(g, &gw, precision, virgin_reach)?,
        None => default_histories(scene, accuracy, &gw, precision, virgin_reach, progress)?,
    };
    let mut options = match opts.d_min {
        Some(g) => Tabulation::uniform(g),
        None => Tabulation::adaptive(histories.d_min_lo, histories.d_min_hi),
    };
    options.points_per_branch = opts.points;
    options.tolerance = opts.tolerance;
    options.max_branches = MAX_BRANCHES;
    options.pressure_floor = Some(histories.pressure_floor);

    let source = SceneSurface::new(&gw, precision).stopped_by(progress);
    // the bar: the tabulator's fraction of its work to 900, the partial reloads to 1000
    progress.start(1000, "tabulating the contact law");
    let done = AtomicU64::new(0);
    let report = |f: f64| {
        let v = (900.0 * f.clamp(0.0, 1.0)) as u64;
        let before = done.fetch_max(v, Ordering::Relaxed);
        if v > before {
            progress.set(v);
        }
    };
    // the bar is removed whether the tabulation succeeds or not
    let result = tabulate::tabulate_with_progress(&source, &options, &report).and_then(|law| {
        let partial =
            tabulate::measure_partial_reload(&law, &source, &TURN_FRACTIONS, RELOAD_POINTS)?;
        progress.set(1000);
        Ok((law, partial))
    });
    progress.finish();
    let (mut law, partial) = result?;
    let measured_error = law.measured_error().cloned().ok_or_else(|| {
        contact_law::LawError::BadSource("the tabulator recorded no measured error".into())
    })?;
    law.set_partial_reload(partial.clone());
    law.set_scene(scene_echo(common, &laws, accuracy, &histories))?;

    let law_json = law.to_json_string();
    let summary = branch_summary(&law);
    let nodes = law.virgin().d().len() + summary.iter().map(|b| b.nodes).sum::<usize>();
    let mut warnings = law_guards(c, &gw, &histories, &summary)?;
    let tab = law.tabulation().cloned();
    let converged = tab.as_ref().is_some_and(|t| t.converged);
    if !converged {
        warnings.push(Warning::note(
            "law_not_converged",
            format!(
                "the table misses the tolerance {:e}: its largest measured error is {:.3e} (law.json, interpolation.measured_error and each branch's measured_error say where); a cap on nodes or branches stopped the refinement, or a user's uniform grid of histories (not refined) is too coarse: give more of them or use the adaptive default",
                opts.tolerance,
                measured_error.max()
            ),
        ));
    }
    let positive = law.positive_retract_tangent().copied();
    if let Some(p) = &positive {
        let remedy = if laws.reload == "bounded" {
            "the reload reading is already bounded: the rise is the surface's own (near yield onset or in the adhesive part); use min(dp/dd, 0) as the Newton stiffness there"
        } else {
            "its cause is the eq-12 reload overshoot of asperities pressed beyond about 16 delta_CP (docs/theory.md section 2.5): tabulate with contact.reload = \"bounded\" to remove it, or use min(dp/dd, 0) as the Newton stiffness on retract branches"
        };
        warnings.push(Warning::note(
            "positive_retract_tangent",
            format!(
                "{} of {} retract branches (d_min {:.4e} to {:.4e} m) rise before their pull-out: the pressure grows by up to {:.1} % as the gap opens, a tangent up to {:.3e} Pa/m (d_min = {:.4e} m, d = {:.4e} m), which an implicit FE code receives as a negative unloading stiffness; {remedy}",
                p.branches,
                law.branches().len(),
                p.d_min_range[0],
                p.d_min_range[1],
                100.0 * p.largest_relative_rise,
                p.worst.tangent,
                p.worst_d_min,
                p.worst.d
            ),
        ));
    }
    Ok(LawResult {
        title: common.title.clone(),
        laws,
        validity: Validity::of(&warnings),
        accuracy: accuracy.targets(),
        sigma_s: sigma,
        branches: law.branches().len(),
        virgin_nodes: law.virgin().d().len(),
        nodes,
        tolerance: opts.tolerance,
        pressure_floor: law.pressure_floor(),
        positive_retract_tangent: positive,
        measured_error,
        partial_reload: partial,
        partial_reload_turn_fractions: TURN_FRACTIONS.to_vec(),
        source_evaluations: tab.as_ref().map_or(0, |t| t.source_evaluations),
        converged,
        seconds: start.elapsed().as_secs_f64(),
        law_json_bytes: law_json.len(),
        summary,
        warnings,
        law_json,
        law,
        histories,
    })
}

/// The default range of histories: from the first touch down to BELOW_IMPACT_SIGMAS
/// below the deepest end of impact of a switch scene's cycles, or down to a surface
/// scene's `unload_from`.
fn default_histories(
    scene: LawScene,
    accuracy: Accuracy,
    gw: &RoughSurface,
    precision: switch_1d::Precision,
    virgin_reach: f64,
    progress: &dyn Progress,
) -> Result<Histories, ModelError> {
    let sigma = gw.sigma_s();
    let (lo, deepest, cycles_d_e) = match scene {
        LawScene::Switch(s) => {
            // the same switch, pull-outs only, validated again with those settings
            let quick = s.with_values(&[
                ("points", crate::spec::count_value(0)),
                ("accuracy", crate::spec::accuracy_value(accuracy)),
                ("elastic_comparison", toml::Value::Boolean(false)),
            ])?;
            let sw = SwitchModel::build(&quick)?.run(&crate::CancelOnly(progress))?;
            let cycles_d_e: Vec<f64> = sw.cycles.iter().map(|c| c.d_e).collect();
            let Some(deepest) = cycles_d_e.iter().copied().reduce(f64::min) else {
                return Err(ModelError::argument(
                    "d_min",
                    "the default range",
                    "a grid FROM:TO:N: the scene's switch does not close, so its impacts reach no depth to tabulate down to",
                ));
            };
            (deepest - BELOW_IMPACT_SIGMAS * sigma, Some(deepest), cycles_d_e)
        }
        LawScene::Surface(s) => match s.unload_from {
            Some(u) => (u, None, Vec::new()),
            None => {
                return Err(ModelError::argument(
                    "d_min",
                    "the default range",
                    "a grid FROM:TO:N, or unload_from in the surface scene (the depth to tabulate down to)",
                ))
            }
        },
    };
    if lo >= virgin_reach {
        return Err(ModelError::argument(
            "d_min",
            format!("{} m (the deepest history)", num(lo)),
            format!(
                "below the virgin reach {} m, where the first asperity touches",
                num(virgin_reach)
            ),
        ));
    }
    let (reference, floor) = pressure_scale(gw, lo, precision)?;
    let hi = first_touch(gw, lo, virgin_reach, floor, precision)?;
    let down_to = match deepest {
        Some(d) => format!(
            "{} sigma_s = {:e} m below the deepest end-of-impact separation d_e = {:e} m of the scene's cycles, so that their own histories lie inside the table",
            BELOW_IMPACT_SIGMAS,
            BELOW_IMPACT_SIGMAS * sigma,
            d
        ),
        None => "the surface scene's unload_from".into(),
    };
    let description = format!(
        "adaptive grid of histories from the first touch d_min_hi = {:e} m (the largest separation at which the virgin pressure or the pull-out reaches the pressure floor {:e} Pa, {:e} of the pressure scale {:e} Pa of the deepest history; shallower histories carry less) down to d_min_lo = {:e} m, {down_to}; refined where the law changes fastest. Histories above d_min_hi blend to zero at the virgin reach {:e} m (region above_table, not measured).",
        hi, floor, FLOOR_FRACTION, reference, lo, virgin_reach
    );
    Ok(Histories {
        rule: "adaptive".into(),
        d_min_lo: lo,
        d_min_hi: hi,
        deepest_d_e: deepest,
        cycles_d_e,
        below_deepest_d_e: deepest.map(|_| BELOW_IMPACT_SIGMAS * sigma),
        first_touch_reference: Some(reference),
        first_touch_fraction: Some(FLOOR_FRACTION),
        pressure_floor: floor,
        virgin_reach,
        description,
    })
}

/// The pressure scale of the history `lo` (the larger of |p_V(lo)| and |p_pull_out(lo)|,
/// Pa) and the pressure floor, [`FLOOR_FRACTION`] of it.
fn pressure_scale(
    gw: &RoughSurface,
    lo: f64,
    precision: switch_1d::Precision,
) -> Result<(f64, f64), ModelError> {
    let p_v = gw.pressure(lo, &GwHistory::VIRGIN, SurfacePath::Approach)?;
    let pull = switch_1d::unload(gw, &GwHistory::Flat { deepest: lo }, lo, 0, precision)?
        .pull_out_pressure;
    let reference = p_v.abs().max(pull.abs());
    if !(reference > 0.0 && reference.is_finite()) {
        return Err(ModelError::argument(
            "d_min",
            format!("{} m (the deepest history)", num(lo)),
            "a history in contact: the surface carries no pressure there",
        ));
    }
    Ok((reference, FLOOR_FRACTION * reference))
}

/// The first touch: the largest separation below the virgin reach at which the virgin
/// pressure or the pull-out of that history reaches `floor` (at least a little above
/// `lo`).
fn first_touch(
    gw: &RoughSurface,
    lo: f64,
    virgin_reach: f64,
    floor: f64,
    precision: switch_1d::Precision,
) -> Result<f64, ModelError> {
    let sigma = gw.sigma_s();
    let virgin = GwHistory::VIRGIN;
    let p_v =
        |d: f64| -> Result<f64, ModelError> { Ok(gw.pressure(d, &virgin, SurfacePath::Approach)?) };
    let pull = |d: f64| -> Result<f64, ModelError> {
        Ok(
            switch_1d::unload(gw, &GwHistory::Flat { deepest: d }, d, 0, precision)?
                .pull_out_pressure
                .abs(),
        )
    };
    // the largest root of g = |p(d)| - floor below the reach, stepping down by sigma_s/4
    let largest_root = |g: &dyn Fn(f64) -> Result<f64, ModelError>,
                        from: f64|
     -> Result<Option<f64>, ModelError> {
        let top = Sample {
            x: from,
            f: g(from)?,
        };
        if top.f >= 0.0 {
            return Ok(Some(from));
        }
        match expand_bracket(
            "first touch",
            g,
            top,
            from - 0.25 * sigma,
            Expansion::Linear,
            lo,
        )? {
            Some((above, below)) => Ok(Some(brent_from(
                "first touch",
                g,
                below,
                above,
                Tolerance::absolute(1e-6 * sigma),
            )?)),
            None => Ok(None),
        }
    };
    let g_v = |d: f64| -> Result<f64, ModelError> { Ok(p_v(d)?.abs() - floor) };
    let d_v = largest_root(&g_v, virgin_reach)?.unwrap_or(lo);
    // the pull-out of a light touch can exceed its virgin pressure (strong adhesion)
    let g_p = |d: f64| -> Result<f64, ModelError> { Ok(pull(d)? - floor) };
    let d_p = if d_v < virgin_reach && g_p(d_v)? > 0.0 {
        largest_root(&g_p, 0.5 * (d_v + virgin_reach))?.unwrap_or(d_v)
    } else {
        d_v
    };
    let mut hi = d_v.max(d_p);
    if hi >= virgin_reach {
        hi = lo + 0.9 * (virgin_reach - lo);
    }
    if hi <= lo + 0.01 * sigma {
        hi = (lo + 0.5 * sigma).min(lo + 0.5 * (virgin_reach - lo));
    }
    Ok(hi)
}

/// The user's grid, checked against the surface: inside 20 sigma_s of the mean plane and
/// below the virgin reach (no history is shallower than the first touch).
fn user_histories(
    grid: GridSpec,
    gw: &RoughSurface,
    precision: switch_1d::Precision,
    virgin_reach: f64,
) -> Result<Histories, ModelError> {
    let sigma = gw.sigma_s();
    let nodes = grid.nodes();
    let (lo, hi) = (nodes[0], nodes[nodes.len() - 1]);
    let lim = 20.0 * sigma;
    if lo < -lim || hi > lim {
        return Err(ModelError::argument(
            "d_min",
            grid.to_string(),
            format!(
                "histories within 20 sigma_s = {} m of the mean plane",
                num(lim)
            ),
        ));
    }
    if hi >= virgin_reach {
        return Err(ModelError::argument(
            "d_min",
            grid.to_string(),
            format!(
                "histories below the virgin reach {} m, where the first asperity touches (the shallowest is {} m)",
                num(virgin_reach),
                num(hi)
            ),
        ));
    }
    let (reference, floor) = pressure_scale(gw, lo, precision)?;
    Ok(Histories {
        rule: format!("uniform {grid}"),
        d_min_lo: lo,
        d_min_hi: hi,
        deepest_d_e: None,
        cycles_d_e: Vec::new(),
        below_deepest_d_e: None,
        first_touch_reference: Some(reference),
        first_touch_fraction: None,
        pressure_floor: floor,
        virgin_reach,
        description: format!(
            "the user's uniform grid of {} histories from {:e} m to {:e} m; histories above the last blend to zero at the virgin reach {:e} m (region above_table, not measured)",
            grid.n, lo, hi, virgin_reach
        ),
    })
}

/// The scene echo of a law file: the resolved scene with what the law was made from.
fn scene_echo(
    common: &crate::spec::Common,
    laws: &Laws,
    accuracy: Accuracy,
    histories: &Histories,
) -> serde_json::Value {
    let mut scene = common.echo();
    let kind = common
        .resolved
        .get("kind")
        .and_then(|k| k.as_str())
        .unwrap_or("switch")
        .to_string();
    let resolved = serde_json::json!({
        "file": common.scene.file(),
        "kind": kind,
        "laws": laws,
        "eq1_yield_modulus": laws.yield_modulus,
        "reload": laws.reload,
        "surface": "Greenwood-Williamson surface of the scene's contact and surface sections; history one number, d_min (GwHistory::Flat { deepest: d_min })",
        "accuracy": accuracy.targets(),
        "histories": histories,
    });
    if let serde_json::Value::Object(o) = &mut scene {
        o.insert("resolved".into(), resolved);
    }
    scene
}

/// One row per history: where it starts, its pull-out, its reaches, its size.
fn branch_summary(law: &ContactLaw) -> Vec<BranchSummary> {
    law.branches()
        .iter()
        .map(|b| BranchSummary {
            d_min: b.d_min(),
            start_pressure: b.retract().pressure()[0],
            pull_out_d: b.pull_out().d,
            pull_out_pressure: b.pull_out().pressure,
            approach_most_tensile_d: b.approach().most_tensile().d,
            approach_most_tensile_pressure: b.approach().most_tensile().pressure,
            approach_reach: b.approach().reach(),
            retract_reach: b.retract().reach(),
            nodes: b.approach().d().len() + b.retract().d().len(),
            measured_error_approach: b.measured_error().map_or(f64::NAN, |e| e.approach),
            measured_error_retract: b.measured_error().map_or(f64::NAN, |e| e.retract),
            positive_retract_tangent: b.positive_retract_tangent().map(|t| t.tangent),
            retract_relative_rise: b.positive_retract_tangent().map(|t| t.relative_rise),
        })
        .collect()
}

/// An error value for serde: a number when finite, else `"inf"` or `"nan"` (never null).
fn error_number<S: serde::Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    if v.is_finite() {
        s.serialize_f64(*v)
    } else if v.is_nan() {
        s.serialize_str("nan")
    } else {
        s.serialize_str("inf")
    }
}

/// The guards at the deepest history tabulated.
fn law_guards(
    c: &ContactSpec,
    gw: &RoughSurface,
    histories: &Histories,
    summary: &[BranchSummary],
) -> Result<Vec<Warning>, ModelError> {
    let lo = histories.d_min_lo;
    let mut warnings = Vec::new();
    if let Some(hi) = guards::fit_range_max(c) {
        let share = gw.load_share_beyond(lo, &GwHistory::VIRGIN, SurfacePath::Approach, hi)?;
        warnings.extend(guards::surface_beyond_fit(c, share, lo));
    }
    let compressive = gw
        .pressure(lo, &GwHistory::VIRGIN, SurfacePath::Approach)?
        .max(0.0);
    let deepest_pull = summary
        .first()
        .map_or(0.0, |b| -b.pull_out_pressure.min(0.0));
    warnings.extend(guards::pressures(c, compressive, deepest_pull));
    warnings.extend(guards::adhesion_yields(c)?);
    Ok(warnings)
}
