//! `stiction law`: the adhesive-contact law p(d; d_min, path) of a switch scene's rough
//! surface, tabulated for a finite-element code (`law.json`, `law.csv`, `law.svg`), and
//! `stiction law eval`, which evaluates a law file at one point.
//!
//! The surface is the scene's contact and surface sections at the scene's accuracy. Its
//! whole history is one number, d_min, the deepest separation reached
//! (`GwHistory::Flat { deepest: d_min }`), so the law is a family of curves in d (m,
//! separation from the mean plane of asperity heights to the flat): the virgin envelope,
//! and for each tabulated d_min the approach (reload) branch and the retract branch. The
//! tabulator of `contact-law` samples them from the surface directly and measures its
//! interpolation error; this module supplies the surface ([`SceneSurface`]), the default
//! range of histories (from the first touch down to the depth the scene's impacts reach)
//! and the measured error of the one-number history after a partial reload.

use super::switch::{self, Laws};
use super::Command;
use crate::accuracy::{Accuracy, Targets};
use crate::error::Error;
use crate::guards;
use crate::model::{self, RoughSurface};
use crate::plot::{self, Panel, Series};
use crate::progress::Progress;
use crate::render::{self, Format, OutputSet, Render, Warning};
use crate::scene::{Loaded, SwitchScene};
use asperity_plastic::FIT_RANGE_MAX;
use contact_core::{Path as SurfacePath, SurfaceLaw};
use contact_law::tabulate::{self, Branch, GridSpec, LawSource, ReloadSource, Tabulation};
use contact_law::{ContactLaw, MeasuredError, PartialReloadError, Path as LawPath};
use gw_surface::GwHistory;
use serde::Serialize;
use std::cell::{Cell, RefCell};
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

/// The files `stiction law --out` writes.
pub const FILES: &[&str] = &["law.json", "law.csv", "law.svg"];

/// The default grid of histories starts this many sigma_s below the deepest end of impact
/// of the scene's cycles, so that a cycle's own d_min (and a slightly harder impact) lies
/// inside the table rather than on its edge.
pub const BELOW_IMPACT_SIGMAS: f64 = 0.5;

/// The "first touch" that ends the default grid of histories: the largest separation at
/// which the virgin approach pressure reaches this fraction of the reference pressure (the
/// pull-out pressure of the deepest history; the virgin pressure there for a law without
/// adhesion). Shallower histories carry pressures below the error the law is allowed at
/// the deepest history (1e-3 of its pull-out); taking the geometric first touch instead
/// (the highest asperity, 9 sigma_s) would spend most branches on pressures below 1e-9 Pa
/// (the rule in d_min is relative, and the Gaussian tail changes fastest there).
pub const TOUCH_FRACTION: f64 = 1e-3;

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

/// Tabulate the scene's rough-surface contact law for an FE code (law.json, law.csv,
/// law.svg); `stiction law eval` evaluates a law file.
#[derive(Debug, Clone, clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct LawCommand {
    /// Evaluate a law file instead of tabulating one.
    #[command(subcommand)]
    pub action: Option<LawAction>,
    /// Switch scene file (TOML); the paper's switch if absent. Its contact and surface
    /// sections give the rough surface, its impacts the default range of histories.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Write law.json, law.csv and law.svg to this folder (replaced as a whole; it may hold
    /// only those files).
    #[arg(long, required = true)]
    pub out: Option<PathBuf>,
    /// The histories d_min as a uniform grid FROM:TO:N (m, m, count; either order), e.g.
    /// 8e-9:2e-9:25. Default: adaptive, from the first touch down to 0.5 sigma_s below the
    /// deepest end of impact of the scene's cycles, refined where the law changes fastest.
    #[arg(long, value_name = "FROM:TO:N", allow_hyphen_values = true)]
    pub d_min: Option<GridSpec>,
    /// Start points per branch (uniform up to the branch's reach, before adaptive
    /// refinement), 4..100000.
    #[arg(long, default_value_t = DEFAULT_POINTS)]
    pub points: usize,
    /// Refinement tolerance on |p_table - p_direct| / (|p_direct| + |p_pull_out(d_min)|),
    /// in (0, 0.1].
    #[arg(long, default_value_t = 2e-4)]
    pub tolerance: f64,
    /// Accuracy mode of the surface evaluations and of the impact depth [default: fast,
    /// whatever the scene says: its measured pressure error, 1.5e-5, is far below the
    /// table's tolerance, and balanced and accurate take 1.6 and 3 times as long].
    #[arg(long, value_enum)]
    pub accuracy: Option<Accuracy>,
    /// Output format of the summary on standard output.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// What `stiction law` does besides tabulating.
#[derive(Debug, Clone, clap::Subcommand)]
pub enum LawAction {
    /// Evaluate a law file at one point: pressure (Pa, compressive positive), tangent
    /// dp/dd (Pa/m) and the history d_min (m) after the call.
    Eval(EvalCommand),
}

impl LawCommand {
    /// Runs `stiction law` or `stiction law eval`.
    pub fn execute(&self) -> Result<String, Error> {
        match &self.action {
            Some(LawAction::Eval(e)) => e.execute(),
            None => super::pipeline(self),
        }
    }
}

// ---------------------------------------------------------------------------------------
// The surface as a law source

/// The scene's rough surface seen by the tabulator: one-number histories
/// `GwHistory::Flat { deepest: d_min }`, with a count of surface evaluations for the
/// progress bar.
pub struct SceneSurface<'a> {
    gw: &'a RoughSurface,
    precision: switch_1d::Precision,
    evaluations: Cell<u64>,
    progress: RefCell<Option<Progress>>,
}

impl<'a> SceneSurface<'a> {
    /// The source for `gw`; pull-outs are searched to `precision`.
    pub fn new(gw: &'a RoughSurface, precision: switch_1d::Precision) -> Self {
        Self {
            gw,
            precision,
            evaluations: Cell::new(0),
            progress: RefCell::new(None),
        }
    }

    /// Surface pressure evaluations so far (tabulation, pull-out searches, measurements).
    pub fn evaluations(&self) -> u64 {
        self.evaluations.get()
    }

    fn tick(&self, n: u64) {
        let done = self.evaluations.get() + n;
        self.evaluations.set(done);
        if done % 64 < n {
            if let Some(p) = self.progress.borrow_mut().as_mut() {
                p.set(done);
            }
        }
    }

    fn history(d_min: f64) -> GwHistory {
        GwHistory::Flat { deepest: d_min }
    }
}

impl LawSource for SceneSurface<'_> {
    type Error = Error;

    fn pressure(&self, d: f64, d_min: f64, branch: Branch) -> Result<f64, Error> {
        self.tick(1);
        let (history, path) = match branch {
            Branch::Virgin => (GwHistory::VIRGIN, SurfacePath::Approach),
            Branch::Approach => (Self::history(d_min), SurfacePath::Approach),
            Branch::Retract => (Self::history(d_min), SurfacePath::Retract { from: d_min }),
        };
        Ok(self.gw.pressure(d, &history, path)?)
    }

    fn reach(&self, d_min: f64, branch: Branch) -> Result<f64, Error> {
        let (history, path) = match branch {
            Branch::Virgin => (GwHistory::VIRGIN, SurfacePath::Approach),
            Branch::Approach => (Self::history(d_min), SurfacePath::Approach),
            Branch::Retract => (Self::history(d_min), SurfacePath::Retract { from: d_min }),
        };
        Ok(self.gw.reach(&history, path)?)
    }

    /// The robust pull-out search of the switch model (`switch_1d::unload`): a scan of the
    /// retract branch and golden-section refinement of its most tensile point.
    fn pull_out(&self, d_min: f64) -> Result<(f64, f64), Error> {
        let u = switch_1d::unload(self.gw, &Self::history(d_min), d_min, 0, self.precision)?;
        // the scan and refinement cost a few dozen evaluations; counted roughly
        self.tick(48);
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
    fn retract_after_reload(&self, d: f64, d_min: f64, d_turn: f64) -> Result<f64, Error> {
        self.tick(1);
        Ok(self.gw.pressure(
            d,
            &Self::history(d_min),
            SurfacePath::Retract { from: d_turn },
        )?)
    }
}

// ---------------------------------------------------------------------------------------
// The tabulation

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
    /// The reference pressure of the first touch (Pa), default range.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_touch_reference: Option<f64>,
    /// The first touch's fraction of it, default range.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_touch_fraction: Option<f64>,
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
}

/// `stiction law`.
#[derive(Debug, Clone, Serialize)]
pub struct LawReport {
    /// Plot and table title.
    pub title: String,
    /// The laws and the reading of eq 1.
    pub laws: Laws,
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
    /// Refinement tolerance.
    pub tolerance: f64,
    /// Interpolation error measured against the surface at points off every grid.
    pub measured_error: MeasuredError,
    /// Error of the one-number history after a partial reload (the law retracts along the
    /// branch of d_min; the surface along its own path from the turning point).
    pub partial_reload: PartialReloadError,
    /// Turning fractions of the partial-reload measurement.
    pub partial_reload_turn_fractions: Vec<f64>,
    /// Surface pressure evaluations of the tabulation and its measurement.
    pub source_evaluations: usize,
    /// All refinements met the tolerance before a cap.
    pub converged: bool,
    /// Wall time of the whole command (s).
    pub seconds: f64,
    /// Size of law.json (bytes).
    pub law_json_bytes: usize,
    /// The tabulated histories, one line each.
    pub summary: Vec<BranchSummary>,
    /// Guards raised.
    pub warnings: Vec<Warning>,
    /// law.json.
    #[serde(skip)]
    pub law_json: String,
    /// law.csv.
    #[serde(skip)]
    pub law_csv: String,
    /// law.svg, or why it could not be drawn.
    #[serde(skip)]
    pub law_svg: Result<String, String>,
}

impl Command for LawCommand {
    type Scene = SwitchScene;
    type Report = LawReport;

    fn scene_path(&self) -> Option<&std::path::Path> {
        self.scene.as_deref()
    }

    fn apply(&self, scene: &mut SwitchScene) -> Result<(), Error> {
        scene.accuracy = self.accuracy.unwrap_or(DEFAULT_ACCURACY);
        Ok(())
    }

    fn run(&self, loaded: &Loaded<SwitchScene>) -> Result<LawReport, Error> {
        tabulate_scene(self, loaded)
    }

    fn outputs(&self, r: &LawReport) -> Result<Option<OutputSet>, Error> {
        let Some(dir) = &self.out else {
            return Ok(None);
        };
        let mut set = OutputSet::new(dir, FILES);
        set.add("law.json", r.law_json.as_bytes());
        set.add("law.csv", r.law_csv.as_bytes());
        let svg = r.law_svg.clone().map_err(|message| Error::Plot {
            path: dir.join("law.svg").display().to_string(),
            message,
        })?;
        set.add("law.svg", svg);
        Ok(Some(set))
    }

    fn format(&self) -> Format {
        self.format
    }
}

fn check_options(cmd: &LawCommand) -> Result<(), Error> {
    if !(4..=100_000).contains(&cmd.points) {
        return Err(Error::usage(
            "--points",
            format!("{}: must be between 4 and 100000", cmd.points),
        ));
    }
    if !(cmd.tolerance > 0.0 && cmd.tolerance <= 0.1) {
        return Err(Error::usage(
            "--tolerance",
            format!("{}: must be in (0, 0.1]", crate::scene::num(cmd.tolerance)),
        ));
    }
    Ok(())
}

/// The default range of histories: from the first touch down to BELOW_IMPACT_SIGMAS
/// below the deepest end of impact of the scene's cycles.
fn default_histories(
    loaded: &Loaded<SwitchScene>,
    gw: &RoughSurface,
    precision: switch_1d::Precision,
    virgin_reach: f64,
) -> Result<Histories, Error> {
    let mut quick = loaded.clone();
    quick.scene.points = 0;
    quick.scene.elastic_comparison = false;
    let sw = switch::run(&quick, false)?;
    let cycles_d_e: Vec<f64> = sw.cycles.iter().map(|c| c.d_e).collect();
    let Some(deepest) = cycles_d_e.iter().copied().reduce(f64::min) else {
        return Err(Error::usage(
            "--d-min",
            "the scene's switch does not close, so its impacts reach no depth to tabulate down to: give the histories as --d-min FROM:TO:N",
        ));
    };
    let sigma = gw.sigma_s();
    let lo = deepest - BELOW_IMPACT_SIGMAS * sigma;
    let virgin = GwHistory::VIRGIN;
    let p_v = |d: f64| gw.pressure(d, &virgin, SurfacePath::Approach);
    let pull = switch_1d::unload(gw, &GwHistory::Flat { deepest: lo }, lo, 0, precision)?
        .pull_out_pressure;
    let reference = if pull > 0.0 { pull } else { p_v(lo)?.abs() };
    let threshold = TOUCH_FRACTION * reference;
    // from the reach down in quarter sigma_s until the virgin pressure reaches the
    // threshold, then bisect
    let step = 0.25 * sigma;
    let mut below = virgin_reach;
    let mut above = virgin_reach;
    while below > lo {
        above = below;
        below = (below - step).max(lo);
        if p_v(below)?.abs() >= threshold {
            break;
        }
    }
    let mut hi = if p_v(below)?.abs() >= threshold {
        for _ in 0..40 {
            let mid = 0.5 * (below + above);
            if p_v(mid)?.abs() >= threshold {
                below = mid;
            } else {
                above = mid;
            }
            if above - below <= 1e-6 * sigma {
                break;
            }
        }
        below
    } else {
        lo + 0.5 * (virgin_reach - lo)
    };
    if hi <= lo + 0.01 * sigma {
        hi = (lo + 0.5 * sigma).min(lo + 0.5 * (virgin_reach - lo));
    }
    let description = format!(
        "adaptive grid of histories from the first touch d_min_hi = {:e} m (the largest separation at which the virgin approach pressure reaches {:e} of the reference pressure {:e} Pa, the pull-out pressure of the deepest history; shallower histories carry less) down to d_min_lo = {:e} m, {} sigma_s = {:e} m below the deepest end-of-impact separation d_e = {:e} m of the scene's cycles, so that their own histories lie inside the table; refined where the law changes fastest. Histories above d_min_hi blend to zero at the virgin reach {:e} m (not measured).",
        hi, TOUCH_FRACTION, reference, lo, BELOW_IMPACT_SIGMAS, BELOW_IMPACT_SIGMAS * sigma, deepest, virgin_reach
    );
    Ok(Histories {
        rule: "adaptive".into(),
        d_min_lo: lo,
        d_min_hi: hi,
        deepest_d_e: Some(deepest),
        cycles_d_e,
        below_deepest_d_e: Some(BELOW_IMPACT_SIGMAS * sigma),
        first_touch_reference: Some(reference),
        first_touch_fraction: Some(TOUCH_FRACTION),
        virgin_reach,
        description,
    })
}

/// The user's grid, checked against the surface: inside 20 sigma_s of the mean plane and
/// below the virgin reach (no history is shallower than the first touch).
fn user_histories(grid: GridSpec, sigma: f64, virgin_reach: f64) -> Result<Histories, Error> {
    let nodes = grid.nodes();
    let (lo, hi) = (nodes[0], nodes[nodes.len() - 1]);
    let lim = 20.0 * sigma;
    if lo < -lim || hi > lim {
        return Err(Error::usage(
            "--d-min",
            format!(
                "{grid}: the histories must lie within 20 sigma_s = {} m of the mean plane",
                crate::scene::num(lim)
            ),
        ));
    }
    if hi >= virgin_reach {
        return Err(Error::usage(
            "--d-min",
            format!(
                "{grid}: the shallowest history {} m is at or above the virgin reach {} m, where the first asperity touches: tabulate histories below it",
                crate::scene::num(hi),
                crate::scene::num(virgin_reach)
            ),
        ));
    }
    Ok(Histories {
        rule: format!("uniform {grid}"),
        d_min_lo: lo,
        d_min_hi: hi,
        deepest_d_e: None,
        cycles_d_e: Vec::new(),
        below_deepest_d_e: None,
        first_touch_reference: None,
        first_touch_fraction: None,
        virgin_reach,
        description: format!(
            "the user's uniform grid of {} histories from {:e} m to {:e} m; histories above the last blend to zero at the virgin reach {:e} m (not measured)",
            grid.n, lo, hi, virgin_reach
        ),
    })
}

/// JSON of the scene with every non-finite number (a yield stress `inf`) as the string
/// `"inf"`: a law file holds no null.
fn scene_echo(
    loaded: &Loaded<SwitchScene>,
    laws: &Laws,
    histories: &Histories,
) -> Result<serde_json::Value, Error> {
    fn no_null(v: &mut serde_json::Value) {
        match v {
            serde_json::Value::Null => *v = serde_json::Value::String("inf".into()),
            serde_json::Value::Array(a) => a.iter_mut().for_each(no_null),
            serde_json::Value::Object(o) => o.values_mut().for_each(no_null),
            _ => {}
        }
    }
    let mut scene =
        serde_json::to_value(&loaded.scene).map_err(|e| Error::usage("--scene", e.to_string()))?;
    let mut resolved = serde_json::json!({
        "file": loaded.file,
        "kind": "switch",
        "laws": laws,
        "eq1_yield_modulus": laws.yield_modulus,
        "surface": "Greenwood-Williamson surface of the scene's contact and surface sections; history one number, d_min (GwHistory::Flat { deepest: d_min })",
        "accuracy": loaded.scene.accuracy.targets(),
        "histories": histories,
    });
    no_null(&mut scene);
    no_null(&mut resolved);
    if let serde_json::Value::Object(o) = &mut scene {
        o.insert("resolved".into(), resolved);
    }
    Ok(scene)
}

fn tabulate_scene(cmd: &LawCommand, loaded: &Loaded<SwitchScene>) -> Result<LawReport, Error> {
    check_options(cmd)?;
    let start = Instant::now();
    let s = &loaded.scene;
    let c = &s.contact;
    let laws = Laws {
        adhesion: model::adhesion_name(c.adhesion_law),
        plasticity: model::plasticity_name(c.plasticity_law),
        yield_modulus: c.yield_modulus().as_str(),
    };
    // the surface exactly as `stiction surface` builds it (no absolute floor)
    let gw = model::surface(c, &s.surface, s.accuracy, 0.0, false)?;
    let precision = s.accuracy.precision(0.0);
    let sigma = gw.sigma_s();
    let virgin_reach = gw.reach(&GwHistory::VIRGIN, SurfacePath::Approach)?;
    let histories = match cmd.d_min {
        Some(g) => user_histories(g, sigma, virgin_reach)?,
        None => default_histories(loaded, &gw, precision, virgin_reach)?,
    };
    let mut options = match cmd.d_min {
        Some(g) => Tabulation::uniform(g),
        None => Tabulation::adaptive(histories.d_min_lo, histories.d_min_hi),
    };
    options.points_per_branch = cmd.points;
    options.tolerance = cmd.tolerance;
    options.max_branches = MAX_BRANCHES;

    let source = SceneSurface::new(&gw, precision);
    // a rough expectation of the surface evaluations, for the bar only
    let expected = match cmd.d_min {
        Some(g) => 400 * g.n as u64 + 60_000,
        None => 550_000,
    };
    *source.progress.borrow_mut() = Some(Progress::new(expected, "surface evaluations"));
    // the bar is removed whether the tabulation succeeds or not
    let result = tabulate::tabulate(&source, &options).and_then(|law| {
        let partial =
            tabulate::measure_partial_reload(&law, &source, &TURN_FRACTIONS, RELOAD_POINTS)?;
        Ok((law, partial))
    });
    if let Some(p) = source.progress.borrow_mut().take() {
        p.finish();
    }
    let (mut law, partial) = result?;
    let measured_error = law.measured_error().cloned().ok_or_else(|| {
        contact_law::LawError::BadSource("the tabulator recorded no measured error".into())
    })?;
    law.set_partial_reload(partial.clone());
    law.set_scene(scene_echo(loaded, &laws, &histories)?)?;

    let (law_json, law_csv) = law_files(&law)?;
    let summary = branch_summary(&law);
    let nodes = law.virgin().d().len() + summary.iter().map(|b| b.nodes).sum::<usize>();
    let warnings = law_guards(c, &gw, &histories, &summary)?;

    let tab = law.tabulation().cloned();
    let mut report = LawReport {
        title: loaded.title(),
        laws,
        accuracy: s.accuracy.targets(),
        sigma_s: sigma,
        branches: law.branches().len(),
        virgin_nodes: law.virgin().d().len(),
        nodes,
        tolerance: cmd.tolerance,
        measured_error,
        partial_reload: partial,
        partial_reload_turn_fractions: TURN_FRACTIONS.to_vec(),
        source_evaluations: tab.as_ref().map_or(0, |t| t.source_evaluations),
        converged: tab.as_ref().is_some_and(|t| t.converged),
        seconds: 0.0,
        law_json_bytes: law_json.len(),
        summary,
        warnings,
        law_svg: plot_svg(&law, &histories, &loaded.title(), sigma),
        law_json,
        law_csv,
        histories,
    };
    if !report.converged {
        report.warnings.push(Warning {
            code: "law_not_converged",
            message: format!(
                "the table misses the tolerance {:e} where it could not refine (a cap on nodes or branches, or a --d-min grid, whose histories are not refined: give more of them or omit --d-min); the measured error (largest {:.2e}) says by how much",
                cmd.tolerance,
                report.measured_error.max()
            ),
        });
    }
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// law.json and law.csv as text.
fn law_files(law: &ContactLaw) -> Result<(String, String), Error> {
    let mut csv = Vec::new();
    law.write_csv(&mut csv).map_err(|e| Error::Write {
        path: "law.csv".into(),
        source: e,
    })?;
    let law_csv = String::from_utf8(csv).map_err(|e| Error::Write {
        path: "law.csv".into(),
        source: std::io::Error::other(e),
    })?;
    Ok((law.to_json_string(), law_csv))
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
        })
        .collect()
}

/// The guards at the deepest history tabulated.
fn law_guards(
    c: &crate::scene::Contact,
    gw: &model::RoughSurface,
    histories: &Histories,
    summary: &[BranchSummary],
) -> Result<Vec<Warning>, Error> {
    let lo = histories.d_min_lo;
    let mut warnings = Vec::new();
    let share =
        gw.load_share_beyond(lo, &GwHistory::VIRGIN, SurfacePath::Approach, FIT_RANGE_MAX)?;
    warnings.extend(guards::surface_beyond_fit(share, lo));
    let compressive = gw
        .pressure(lo, &GwHistory::VIRGIN, SurfacePath::Approach)?
        .max(0.0);
    let deepest_pull = summary
        .first()
        .map_or(0.0, |b| -b.pull_out_pressure.min(0.0));
    warnings.extend(guards::pressure_above_hardness(
        c,
        compressive,
        deepest_pull,
    ));
    let plastic = model::asperity(c, false)?;
    let elastic = model::asperity(c, true)?;
    warnings.extend(guards::adhesion_yields(c, &plastic, &elastic)?);
    Ok(warnings)
}

/// The law (MPa against nm): the virgin envelope and the branches of three histories, whole
/// and zoomed on the adhesive part.
fn plot_svg(law: &ContactLaw, h: &Histories, title: &str, sigma: f64) -> Result<String, String> {
    let x_end = (h.d_min_hi + sigma)
        .min(h.d_min_lo + 3.0 * sigma)
        .min(h.virgin_reach);
    let pts = |d: &[f64], p: &[f64]| -> Vec<(f64, f64)> {
        d.iter()
            .zip(p)
            .filter(|(&d, _)| d <= x_end)
            .map(|(&d, &p)| (d * 1e9, p * 1e-6))
            .collect()
    };
    let mut series = vec![Series {
        name: "virgin envelope".into(),
        points: pts(law.virgin().d(), law.virgin().pressure()),
    }];
    let grid = law.d_min_grid();
    let mut picks: Vec<usize> = Vec::new();
    let mut targets = vec![grid[0]];
    if let Some(d) = h.deepest_d_e {
        targets.push(d);
    }
    let top = grid[grid.len() - 1].min(x_end);
    targets.push(grid[0] + 0.5 * (top - grid[0]));
    for t in targets {
        let k = grid.partition_point(|&g| g < t).min(grid.len() - 1);
        if !picks.contains(&k) {
            picks.push(k);
        }
    }
    picks.sort_unstable();
    let mut tensile: f64 = 0.0;
    for &k in &picks {
        let b = &law.branches()[k];
        let label = render::si(b.d_min(), "m", 3);
        series.push(Series {
            name: format!("approach, d_min = {label}"),
            points: pts(b.approach().d(), b.approach().pressure()),
        });
        series.push(Series {
            name: format!("retract, d_min = {label}"),
            points: pts(b.retract().d(), b.retract().pressure()),
        });
        tensile = tensile.max(-b.pull_out().pressure);
    }
    let whole_y = (
        series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .fold(0.0, f64::min),
        law.virgin().pressure().iter().copied().fold(0.0, f64::max) * 1e-6,
    );
    let mut panels = vec![Panel {
        caption: "whole law".into(),
        x_label: "separation d [nm]".into(),
        y_label: "pressure [MPa]".into(),
        series: series.clone(),
        x_range: Some((h.d_min_lo * 1e9, x_end * 1e9)),
        y_range: (whole_y.1 > whole_y.0).then_some((1.05 * whole_y.0, 1.05 * whole_y.1)),
    }];
    if tensile > 0.0 {
        let y = 1.5 * tensile * 1e-6;
        panels.push(Panel {
            caption: "adhesive part".into(),
            x_label: "separation d [nm]".into(),
            y_label: "pressure [MPa]".into(),
            series,
            x_range: Some((h.d_min_lo * 1e9, x_end * 1e9)),
            y_range: Some((-y, y)),
        });
    }
    plot::svg(&format!("{title}: contact law"), &panels)
}

impl Render for LawReport {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{}: contact law p(d; d_min, path)", self.title);
        let _ = writeln!(
            s,
            "laws: {} adhesion, {} plasticity, eq 1 {}; sigma_s = {}; accuracy {}",
            self.laws.adhesion,
            self.laws.plasticity,
            self.laws.yield_modulus,
            render::si(self.sigma_s, "m", 4),
            self.accuracy.mode
        );
        let h = &self.histories;
        let _ = writeln!(
            s,
            "histories: {} branches, d_min from {} to {} ({}); virgin reach {}",
            self.branches,
            render::si(h.d_min_lo, "m", 4),
            render::si(h.d_min_hi, "m", 4),
            h.rule,
            render::si(h.virgin_reach, "m", 4)
        );
        if let Some(d) = h.deepest_d_e {
            let _ = writeln!(
                s,
                "  deepest end of impact d_e = {} (the grid starts {} below it); first touch where p_V = {:e} x {}",
                render::si(d, "m", 4),
                render::si(h.below_deepest_d_e.unwrap_or(0.0), "m", 3),
                h.first_touch_fraction.unwrap_or(0.0),
                render::pressure(h.first_touch_reference.unwrap_or(0.0))
            );
        }
        let m = &self.measured_error;
        let _ = writeln!(
            s,
            "measured interpolation error |p_table - p_surface| / (|p_surface| + |p_pull_out(d_min)|), tolerance {:e}:",
            self.tolerance
        );
        for (name, e) in [
            ("virgin", &m.virgin),
            ("approach", &m.approach),
            ("retract", &m.retract),
        ] {
            let _ = writeln!(
                s,
                "  {name:<9} max {:.2e}  p99 {:.2e}  ({} points; worst at d = {}, d_min = {})",
                e.max,
                e.p99,
                e.samples,
                render::si(e.worst_d, "m", 4),
                render::si(e.worst_d_min, "m", 4)
            );
        }
        let r = &self.partial_reload;
        let _ = writeln!(
            s,
            "partial reload then retraction (law: the retract branch of d_min; surface: its own path from d_turn): max {:.2e}, p99 {:.2e} ({} points; worst at d = {}, d_min = {}, d_turn = {})",
            r.stats.max,
            r.stats.p99,
            r.stats.samples,
            render::si(r.stats.worst_d, "m", 4),
            render::si(r.stats.worst_d_min, "m", 4),
            render::si(r.worst_d_turn, "m", 4)
        );
        let _ = writeln!(
            s,
            "{} nodes ({} on the envelope), {} surface evaluations, converged: {}, law.json {:.2} MB, {:.1} s",
            self.nodes,
            self.virgin_nodes,
            self.source_evaluations,
            self.converged,
            self.law_json_bytes as f64 / 1e6,
            self.seconds
        );
        let _ = writeln!(
            s,
            "{:>11} {:>12} {:>11} {:>12} {:>11} {:>12}",
            "d_min", "p_V(d_min)", "pull-out d", "pull-out p", "pull-in d", "pull-in p"
        );
        let stride = self.summary.len().div_ceil(12).max(1);
        for (i, b) in self.summary.iter().enumerate() {
            if i % stride != 0 && i + 1 != self.summary.len() {
                continue;
            }
            let _ = writeln!(
                s,
                "{:>11} {:>12} {:>11} {:>12} {:>11} {:>12}",
                render::si(b.d_min, "m", 4),
                render::pressure(b.start_pressure),
                render::si(b.pull_out_d, "m", 4),
                render::pressure(b.pull_out_pressure),
                render::si(b.approach_most_tensile_d, "m", 4),
                render::pressure(b.approach_most_tensile_pressure)
            );
        }
        s
    }

    fn csv(&self) -> String {
        let mut s = String::from(
            "d_min_m,start_pressure_pa,pull_out_d_m,pull_out_pressure_pa,approach_most_tensile_d_m,approach_most_tensile_pressure_pa,approach_reach_m,retract_reach_m,nodes\n",
        );
        for b in &self.summary {
            let _ = writeln!(
                s,
                "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{}",
                b.d_min,
                b.start_pressure,
                b.pull_out_d,
                b.pull_out_pressure,
                b.approach_most_tensile_d,
                b.approach_most_tensile_pressure,
                b.approach_reach,
                b.retract_reach,
                b.nodes
            );
        }
        s
    }

    fn warnings(&self) -> &[Warning] {
        &self.warnings
    }
}

// ---------------------------------------------------------------------------------------
// `stiction law eval`

/// The path argument of `stiction law eval`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PathArg {
    /// Coming from far or reloading: the approach branch of d_min.
    Approach,
    /// Moving away after the deepest point: the retract branch of d_min.
    Retract,
}

impl From<PathArg> for LawPath {
    fn from(p: PathArg) -> Self {
        match p {
            PathArg::Approach => LawPath::Approach,
            PathArg::Retract => LawPath::Retract,
        }
    }
}

/// Evaluate a law file at one point (stateless): d < d_min deepens the history (the
/// virgin envelope, d_min becomes d); otherwise the branch `--path` of d_min.
#[derive(Debug, Clone, clap::Args)]
pub struct EvalCommand {
    /// The law file (law.json written by `stiction law`).
    #[arg(long)]
    pub law: PathBuf,
    /// Separation d (m) from the mean plane of asperity heights to the flat.
    #[arg(long, allow_hyphen_values = true)]
    pub d: f64,
    /// The deepest separation reached before (m); absent: a virgin surface.
    #[arg(long, allow_hyphen_values = true)]
    pub d_min: Option<f64>,
    /// The path at d: approach (from far or reloading) or retract.
    #[arg(long, value_enum, default_value_t = PathArg::Approach)]
    pub path: PathArg,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// Units of `stiction law eval`.
#[derive(Debug, Clone, Serialize)]
pub struct EvalUnits {
    /// Of d and d_min.
    pub d: &'static str,
    /// Of the pressure.
    pub pressure: &'static str,
    /// Of the tangent.
    pub tangent: &'static str,
}

/// `stiction law eval`.
#[derive(Debug, Clone, Serialize)]
pub struct EvalReport {
    /// Pressure (Pa), compressive positive, adhesive negative.
    pub pressure: f64,
    /// dp/dd (Pa/m) at fixed history.
    pub tangent: f64,
    /// The history after the call (m): d if the call deepened it.
    pub d_min: f64,
    /// The path after the call (`approach` when the history deepened).
    pub path: &'static str,
    /// The curve evaluated: `virgin`, `approach` or `retract`.
    pub curve: &'static str,
    /// The separation asked (m).
    pub d: f64,
    /// The history given (m), absent for a virgin surface.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub d_min_given: Option<f64>,
    /// The path given.
    pub path_given: &'static str,
    /// The tabulated histories of the law (m).
    pub law_d_min_range: [f64; 2],
    /// The law file.
    pub law: String,
    /// Units.
    pub units: EvalUnits,
}

impl EvalCommand {
    /// Reads the law and evaluates it.
    pub fn execute(&self) -> Result<String, Error> {
        let file = self.law.display().to_string();
        let law = ContactLaw::from_path(&self.law).map_err(|source| Error::LawFile {
            file: file.clone(),
            source,
        })?;
        let d_min = self.d_min.unwrap_or(f64::INFINITY);
        let e = law.evaluate(self.d, d_min, self.path.into())?;
        let deepened = self.d < d_min;
        let report = EvalReport {
            pressure: e.pressure,
            tangent: e.tangent,
            d_min: e.d_min,
            path: e.path.as_str(),
            curve: if deepened { "virgin" } else { e.path.as_str() },
            d: self.d,
            d_min_given: self.d_min.filter(|v| v.is_finite()),
            path_given: LawPath::from(self.path).as_str(),
            law_d_min_range: {
                let (lo, hi) = law.d_min_range();
                [lo, hi]
            },
            law: file,
            units: EvalUnits {
                d: "m",
                pressure: "Pa",
                tangent: "Pa/m",
            },
        };
        Ok(super::show(&report, self.format))
    }
}

impl Render for EvalReport {
    fn table(&self) -> String {
        let mut s = String::new();
        let given = self.d_min_given.map_or("virgin surface".to_string(), |v| {
            format!("d_min = {}", render::si(v, "m", 6))
        });
        let _ = writeln!(
            s,
            "law {} at d = {}, {}, path {}",
            self.law,
            render::si(self.d, "m", 6),
            given,
            self.path_given
        );
        let curve = match self.curve {
            "virgin" => "the virgin envelope (the history deepens)",
            "approach" => "the approach branch of d_min",
            _ => "the retract branch of d_min",
        };
        let _ = writeln!(s, "on {curve}");
        let _ = writeln!(
            s,
            "pressure = {:e} Pa ({}, compressive positive)",
            self.pressure,
            render::pressure(self.pressure)
        );
        let _ = writeln!(
            s,
            "tangent  = {:e} Pa/m (dp/dd at fixed history)",
            self.tangent
        );
        let _ = writeln!(
            s,
            "d_min    = {:e} m, path {} after the call",
            self.d_min, self.path
        );
        s
    }

    fn csv(&self) -> String {
        format!(
            "d_m,d_min_m,path,pressure_pa,tangent_pa_per_m\n{:e},{:e},{},{:e},{:e}\n",
            self.d, self.d_min, self.path, self.pressure, self.tangent
        )
    }
}
