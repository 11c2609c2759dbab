//! `stiction law`: the adhesive-contact law p(d; d_min, path) of a switch or surface
//! scene's rough surface, tabulated for a finite-element code (`law.json`, `law.csv`,
//! `law.svg`; the model library's `law`), and `stiction law eval`, which evaluates a law
//! file.

use super::switch::AccuracyArg;
use super::{argument_error, finish, preflight, Ctx, Outputs, SceneArgs};
use crate::error::Error;
use crate::output::OutputSet;
use crate::plot::{self, Panel, Series};
use crate::progress::Bar;
use crate::render::{self, Format, Render, Validity, Warning};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::PathBuf;
use stiction_model::contact_law::tabulate::GridSpec;
use stiction_model::contact_law::{ContactLaw, LawError, Path as LawPath};
use stiction_model::keys::Kind;
use stiction_model::law::{self, Histories, LawOptions, LawResult, LawScene, DEFAULT_POINTS};
use stiction_model::spec::Spec;

/// The files `stiction law --out` writes.
pub const FILES: &[&str] = &["law.json", "law.csv", "law.svg"];

/// Tabulate the scene's rough-surface contact law for an FE code (law.json, law.csv,
/// law.svg); `stiction law eval` evaluates a law file.
#[derive(Debug, Clone, clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct LawCommand {
    /// Evaluate a law file instead of tabulating one.
    #[command(subcommand)]
    pub action: Option<LawAction>,
    /// Switch or surface scene (its contact and surface sections give the rough surface; a
    /// switch's impacts, or a surface's unload_from, the default depth of the histories);
    /// `--set`, `--strict`.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Write law.json, law.csv and law.svg to this folder (replaced as a whole; it may hold
    /// only those files).
    #[arg(long, required = true)]
    pub out: Option<PathBuf>,
    /// The histories d_min as a uniform grid FROM:TO:N (m, m, count; either order), e.g.
    /// 8e-9:2e-9:25. Default: adaptive, from the first touch down to 0.5 sigma_s below the
    /// deepest end of impact of a switch scene's cycles (a surface scene: down to its
    /// unload_from), refined where the law changes fastest.
    #[arg(long, value_name = "FROM:TO:N", allow_hyphen_values = true)]
    pub d_min: Option<GridSpec>,
    /// Start points per branch (uniform up to the branch's reach, before adaptive
    /// refinement), 4..100000.
    #[arg(long, default_value_t = DEFAULT_POINTS as i64, allow_hyphen_values = true)]
    pub points: i64,
    /// Refinement tolerance on |p_table - p_direct| / (|p_direct| + |p_pull_out(d_min)|),
    /// in (0, 0.1].
    #[arg(long, default_value_t = 2e-4, allow_hyphen_values = true)]
    pub tolerance: f64,
    /// Accuracy mode of the surface evaluations and of the impact depth [default: fast,
    /// whatever the scene says: its measured pressure error, 1.5e-5, is far below the
    /// table's tolerance, and balanced and accurate take 1.6 and 3 times as long].
    #[arg(long, value_enum)]
    pub accuracy: Option<AccuracyArg>,
    /// Output format of the summary on standard output.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// What `stiction law` does besides tabulating.
#[derive(Debug, Clone, clap::Subcommand)]
pub enum LawAction {
    /// Evaluate a law file: pressure (Pa, compressive positive), tangent dp/dd (Pa/m) and
    /// the history d_min (m) after the call, at one point or at many (--points-file).
    Eval(EvalCommand),
    /// Write a law file's virgin loading as a pressure-overclosure table for an FE code's
    /// tabular contact (`*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR`), at most 200
    /// rows placed for linear interpolation (docs/contact-law.md section 6).
    Export(ExportCommand),
}

/// The FE codes `stiction law export` writes for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ExportFormat {
    /// CalculiX (ccx).
    Calculix,
    /// Abaqus/Standard.
    Abaqus,
}

/// The units of `stiction law export`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ExportUnits {
    /// Micrometres and megapascals (CalculiX moves table spacings under 1e-10 model units).
    Um,
    /// Metres and pascals.
    Si,
}

/// `stiction law export`.
#[derive(Debug, Clone, clap::Args)]
pub struct ExportCommand {
    /// The law file (law.json written by `stiction law`).
    #[arg(long)]
    pub law: PathBuf,
    /// The FE code.
    #[arg(long, value_enum, default_value_t = ExportFormat::Calculix)]
    pub format: ExportFormat,
    /// The file to write the keyword block to (an include file for the deck).
    #[arg(long)]
    pub out: PathBuf,
    /// Units of the table: um (micrometres and megapascals) or si (metres and pascals).
    #[arg(long, value_enum, default_value_t = ExportUnits::Um)]
    pub units: ExportUnits,
    /// Linear interpolation of the rows within this of the law, in its error metric
    /// |p_lin - p| / (|p| + |p_pull_out| + floor), in (0, 0.1].
    #[arg(long, default_value_t = contact_law::EXPORT_TOLERANCE, allow_hyphen_values = true)]
    pub tolerance: f64,
    /// The most rows, 2..200 (CalculiX resamples a node-to-surface table of more).
    #[arg(long, default_value_t = contact_law::MAX_ROWS as i64, allow_hyphen_values = true)]
    pub rows: i64,
}

impl ExportCommand {
    /// Writes the block and prints what it holds.
    pub fn execute(&self) -> Result<String, Error> {
        if !(2..=contact_law::MAX_ROWS as i64).contains(&self.rows) {
            return Err(Error::usage(
                "--rows",
                format!("{}: must be an integer in [2, 200]", self.rows),
            ));
        }
        if !(self.tolerance > 0.0 && self.tolerance <= 0.1) {
            return Err(Error::usage(
                "--tolerance",
                format!("{}: must be in (0, 0.1]", self.tolerance),
            ));
        }
        if self.out.as_os_str() == "-" {
            return Err(Error::usage(
                "--out",
                "`-`: use a file name; - (standard output) is not supported for --out",
            ));
        }
        crate::output::check_file(&self.out)?;
        let file = self.law.display().to_string();
        let law = ContactLaw::from_path(&self.law).map_err(|source| Error::LawFile {
            file: file.clone(),
            source,
        })?;
        let table = law
            .overclosure_table(self.tolerance, self.rows as usize)
            .map_err(|source| Error::LawFile { file, source })?;
        let (dialect, code) = match self.format {
            ExportFormat::Calculix => (contact_law::InpDialect::Calculix, "CalculiX"),
            ExportFormat::Abaqus => (contact_law::InpDialect::Abaqus, "Abaqus"),
        };
        let units = match self.units {
            ExportUnits::Um => contact_law::InpUnits::MicrometreMegapascal,
            ExportUnits::Si => contact_law::InpUnits::Si,
        };
        crate::output::write_file(&self.out, table.inp_block(dialect, units).as_bytes())?;
        Ok(format!(
            "{code} pressure-overclosure table: {} rows, d_ref = {:e} m, linear interpolation within {:.1e} of the law (largest {:.2e})\nwrote {}\n",
            table.rows.len(),
            table.d_ref,
            table.tolerance,
            table.max_error,
            self.out.display()
        ))
    }
}

impl LawCommand {
    /// Runs `stiction law` or `stiction law eval`.
    pub fn execute(&self, ctx: Ctx) -> Result<String, Error> {
        match &self.action {
            Some(LawAction::Eval(e)) => return e.execute(),
            Some(LawAction::Export(e)) => return e.execute(),
            None => {}
        }
        let out = self
            .out
            .as_ref()
            .ok_or_else(|| Error::usage("--out", "is required"))?;
        if self.points < 0 {
            return Err(Error::usage(
                "--points",
                format!("{}: must be an integer in [4, 100000]", self.points),
            ));
        }
        let options = LawOptions {
            d_min: self.d_min,
            points: self.points as usize,
            tolerance: self.tolerance,
            accuracy: self.accuracy.map(Into::into),
        };
        options.check().map_err(argument_error)?;
        // the paper's switch without --scene; a file says its own kind
        let loaded = self.scene.load(Kind::Switch, &[])?;
        let spec = Spec::new(&loaded.scene, ctx.registry).map_err(|e| loaded.blame(e))?;
        let law_scene = LawScene::of(&spec).map_err(|e| match e {
            stiction_model::ModelError::Argument { value, allowed, .. } => {
                Error::usage("--scene", format!("{value}: must be {allowed}"))
            }
            e => e.into(),
        })?;
        preflight(Some(out), FILES, None)?;
        let result = law::tabulate(law_scene, &options, &Bar::new()).map_err(argument_error)?;
        let mut set = OutputSet::new(out, FILES);
        set.add("law.json", result.law_json.as_bytes());
        let mut csv = Vec::new();
        result.law.write_csv(&mut csv).map_err(|e| Error::Write {
            path: out.join("law.csv").display().to_string(),
            source: e,
        })?;
        set.add("law.csv", csv);
        let svg = plot_svg(
            &result.law,
            &result.histories,
            &result.title,
            result.sigma_s,
        )
        .map_err(|message| Error::Plot {
            path: out.join("law.svg").display().to_string(),
            message,
        })?;
        set.add("law.svg", svg);
        finish(
            &result,
            self.format,
            false,
            self.scene.strict,
            Outputs {
                folder: Some(set),
                plots: Vec::new(),
            },
        )
    }
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

impl Render for LawResult {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{}: contact law p(d; d_min, path)", self.title);
        let _ = writeln!(
            s,
            "{}; sigma_s = {}; accuracy {}",
            super::switch::laws_line(&self.laws),
            render::si(self.sigma_s, "m", 4),
            self.accuracy.mode
        );
        if !self.validity.holds {
            let _ = writeln!(s, "{}", self.validity.words());
        }
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

    fn validity(&self) -> Option<&Validity> {
        Some(&self.validity)
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

/// Evaluate a law file (stateless) at one point (`--d`, `--d-min`, `--path`) or at many
/// (`--points-file`): d < d_min deepens the history (the virgin envelope, d_min becomes d);
/// otherwise the branch `path` of d_min. Each result says its region: `measured` inside
/// the tabulated histories and the curve's reach, else `beyond_reach` (exactly zero) or
/// `above_table` (a history shallower than the table: a blend to zero, not measured); a
/// history deeper than the table is an error.
#[derive(Debug, Clone, clap::Args)]
pub struct EvalCommand {
    /// The law file (law.json written by `stiction law`).
    #[arg(long)]
    pub law: PathBuf,
    /// Separation d (m) from the mean plane of asperity heights to the flat.
    #[arg(
        long,
        allow_hyphen_values = true,
        required_unless_present = "points_file",
        conflicts_with = "points_file"
    )]
    pub d: Option<f64>,
    /// The deepest separation reached before (m); absent: a virgin surface.
    #[arg(long, allow_hyphen_values = true, conflicts_with = "points_file")]
    pub d_min: Option<f64>,
    /// The path at d: approach (from far or reloading) or retract.
    #[arg(long, value_enum, conflicts_with = "points_file")]
    pub path: Option<PathArg>,
    /// Many points in one process: a CSV file (`-`: standard input) with the columns
    /// `d,d_min,path` (m, m, approach|retract); d_min empty or `virgin` for a virgin surface,
    /// path empty for approach; a header line and lines starting with # are skipped.
    #[arg(long, value_name = "FILE")]
    pub points_file: Option<PathBuf>,
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

const UNITS: EvalUnits = EvalUnits {
    d: "m",
    pressure: "Pa",
    tangent: "Pa/m",
};

/// One evaluated point of `stiction law eval`.
#[derive(Debug, Clone, Serialize)]
pub struct EvalPoint {
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
    /// Where the point lies: `measured` (inside the tabulated histories and the curve's
    /// reach: the file's measured error applies), `beyond_reach` (exactly zero: no asperity
    /// in contact) or `above_table` (a history shallower than the table: the law's blend to
    /// zero, not measured). A public contract.
    pub region: &'static str,
    /// The separation asked (m).
    pub d: f64,
    /// The history given (m), absent for a virgin surface.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub d_min_given: Option<f64>,
    /// The path given.
    pub path_given: &'static str,
}

/// `stiction law eval` at one point.
#[derive(Debug, Clone, Serialize)]
pub struct EvalReport {
    /// The point.
    #[serde(flatten)]
    pub point: EvalPoint,
    /// The tabulated histories of the law (m).
    pub law_d_min_range: [f64; 2],
    /// The law file.
    pub law: String,
    /// Units.
    pub units: EvalUnits,
}

/// `stiction law eval --points-file`.
#[derive(Debug, Clone, Serialize)]
pub struct EvalBatch {
    /// The points, in the order of the file.
    pub points: Vec<EvalPoint>,
    /// How many lie outside the measured region.
    pub outside_measured: usize,
    /// The tabulated histories of the law (m).
    pub law_d_min_range: [f64; 2],
    /// The law file.
    pub law: String,
    /// Units.
    pub units: EvalUnits,
}

/// Evaluates one point.
fn eval_point(
    law: &ContactLaw,
    d: f64,
    d_min: Option<f64>,
    path: LawPath,
) -> Result<EvalPoint, LawError> {
    let given = d_min.unwrap_or(f64::INFINITY);
    let e = law.evaluate(d, given, path)?;
    let deepened = d < given;
    Ok(EvalPoint {
        pressure: e.pressure,
        tangent: e.tangent,
        d_min: e.d_min,
        path: e.path.as_str(),
        curve: if deepened { "virgin" } else { e.path.as_str() },
        region: e.region.as_str(),
        d,
        d_min_given: d_min.filter(|v| v.is_finite()),
        path_given: path.as_str(),
    })
}

/// A point of a `--points-file`: its line number, d, d_min (None: virgin) and path.
type PointLine = (usize, f64, Option<f64>, LawPath);

/// The points of a `--points-file`.
fn read_points(name: &str, text: &str) -> Result<Vec<PointLine>, Error> {
    let bad = |line: usize, what: String| {
        Error::usage("--points-file", format!("{name} line {line}: {what}"))
    };
    let mut out = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let n = i + 1;
        let l = raw.trim();
        if l.is_empty() || l.starts_with('#') {
            continue;
        }
        let f: Vec<&str> = l.split(',').map(str::trim).collect();
        if out.is_empty() && f[0].eq_ignore_ascii_case("d") {
            continue; // the header
        }
        if f.len() > 3 {
            return Err(bad(
                n,
                format!("{} columns in {l:?}: at most 3 (d,d_min,path)", f.len()),
            ));
        }
        let d: f64 = f[0]
            .parse()
            .map_err(|_| bad(n, format!("d = {:?}: must be a number (m)", f[0])))?;
        if !d.is_finite() {
            return Err(bad(n, format!("d = {}: must be finite (m)", f[0])));
        }
        let d_min = match f.get(1).copied().unwrap_or("") {
            "" | "virgin" => None,
            v => {
                let x: f64 = v.parse().map_err(|_| {
                    bad(
                        n,
                        format!("d_min = {v:?}: must be a number (m), empty or virgin"),
                    )
                })?;
                if x.is_nan() || x == f64::NEG_INFINITY {
                    return Err(bad(
                        n,
                        format!("d_min = {v}: must be finite, or empty for a virgin surface"),
                    ));
                }
                x.is_finite().then_some(x)
            }
        };
        let path = match f.get(2).copied().unwrap_or("") {
            "" | "approach" => LawPath::Approach,
            "retract" => LawPath::Retract,
            v => return Err(bad(n, format!("path = {v:?}: must be approach or retract"))),
        };
        out.push((n, d, d_min, path));
    }
    if out.is_empty() {
        return Err(Error::usage(
            "--points-file",
            format!("{name}: no points (lines d,d_min,path)"),
        ));
    }
    Ok(out)
}

impl EvalCommand {
    /// Reads the law and evaluates it.
    pub fn execute(&self) -> Result<String, Error> {
        // the points first: a bad points file is refused before the law is read
        let batch = match &self.points_file {
            Some(p) => {
                let (name, text) = if p.as_os_str() == "-" {
                    let mut t = String::new();
                    std::io::Read::read_to_string(&mut std::io::stdin(), &mut t).map_err(|e| {
                        Error::usage("--points-file", format!("standard input: {e}"))
                    })?;
                    ("standard input".to_string(), t)
                } else {
                    let name = p.display().to_string();
                    // the type first: opening a FIFO would wait for a writer (`-` reads
                    // standard input)
                    let meta = std::fs::metadata(p)
                        .map_err(|e| Error::usage("--points-file", format!("{name}: {e}")))?;
                    if let Some(what) = stiction_model::scene::not_regular(&meta) {
                        return Err(Error::usage(
                            "--points-file",
                            format!("{name}: it is {what}, not a file of points (`-` reads standard input)"),
                        ));
                    }
                    let t = std::fs::read_to_string(p)
                        .map_err(|e| Error::usage("--points-file", format!("{name}: {e}")))?;
                    (name, t)
                };
                Some(read_points(&name, &text)?)
            }
            None => None,
        };
        let file = self.law.display().to_string();
        let law = ContactLaw::from_path(&self.law).map_err(|source| Error::LawFile {
            file: file.clone(),
            source,
        })?;
        let range = {
            let (lo, hi) = law.d_min_range();
            [lo, hi]
        };
        match batch {
            None => {
                let d = self.d.ok_or_else(|| Error::usage("--d", "is required"))?;
                let path = self.path.unwrap_or(PathArg::Approach).into();
                let point = eval_point(&law, d, self.d_min, path)?;
                let report = EvalReport {
                    point,
                    law_d_min_range: range,
                    law: file,
                    units: UNITS,
                };
                Ok(report.render(self.format, false))
            }
            Some(points) => {
                let mut out = Vec::with_capacity(points.len());
                for (line, d, d_min, path) in points {
                    let p = eval_point(&law, d, d_min, path).map_err(|e| {
                        Error::usage("--points-file", format!("line {line} (d = {d:e} m): {e}"))
                    })?;
                    out.push(p);
                }
                let outside_measured = out.iter().filter(|p| p.region != "measured").count();
                let batch = EvalBatch {
                    points: out,
                    outside_measured,
                    law_d_min_range: range,
                    law: file,
                    units: UNITS,
                };
                Ok(batch.render(self.format, false))
            }
        }
    }
}

/// The words of a region for the table.
fn region_words(region: &str) -> &'static str {
    match region {
        "measured" => "measured (the file's measured error applies)",
        "beyond_reach" => "beyond_reach (no asperity in contact: exactly zero)",
        _ => "above_table (a history shallower than the table: the law's blend to zero, NOT measured against the surface)",
    }
}

/// The CSV columns: d, the history and path after the call, pressure, tangent, region,
/// the history and path given.
const CSV_HEADER: &str =
    "d_m,d_min_m,path,pressure_pa,tangent_pa_per_m,region,d_min_given_m,path_given\n";

fn csv_row(p: &EvalPoint) -> String {
    format!(
        "{:e},{:e},{},{:e},{:e},{},{},{}\n",
        p.d,
        p.d_min,
        p.path,
        p.pressure,
        p.tangent,
        p.region,
        p.d_min_given
            .map_or("virgin".to_string(), |v| format!("{v:e}")),
        p.path_given
    )
}

impl Render for EvalReport {
    fn table(&self) -> String {
        let p = &self.point;
        let mut s = String::new();
        let given = p.d_min_given.map_or("virgin surface".to_string(), |v| {
            format!("d_min = {}", render::si(v, "m", 6))
        });
        let _ = writeln!(
            s,
            "law {} at d = {}, {}, path {}",
            self.law,
            render::si(p.d, "m", 6),
            given,
            p.path_given
        );
        let curve = match p.curve {
            "virgin" => "the virgin envelope (the history deepens)",
            "approach" => "the approach branch of d_min",
            _ => "the retract branch of d_min",
        };
        let _ = writeln!(s, "on {curve}");
        let _ = writeln!(
            s,
            "pressure = {:e} Pa ({}, compressive positive)",
            p.pressure,
            render::pressure(p.pressure)
        );
        let _ = writeln!(
            s,
            "tangent  = {:e} Pa/m (dp/dd at fixed history)",
            p.tangent
        );
        let _ = writeln!(
            s,
            "d_min    = {:e} m, path {} after the call",
            p.d_min, p.path
        );
        let _ = writeln!(s, "region   = {}", region_words(p.region));
        s
    }

    fn csv(&self) -> String {
        format!("{CSV_HEADER}{}", csv_row(&self.point))
    }
}

impl Render for EvalBatch {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "law {}: {} points, {} outside the measured region",
            self.law,
            self.points.len(),
            self.outside_measured
        );
        let _ = writeln!(
            s,
            "{:>13} {:>13} {:>8} {:>14} {:>14} {:>13} {:>8}  region",
            "d [m]", "d_min [m]", "path", "p [Pa]", "dp/dd [Pa/m]", "d_min after", "path"
        );
        for p in &self.points {
            let _ = writeln!(
                s,
                "{:>13.6e} {:>13} {:>8} {:>14.6e} {:>14.6e} {:>13.6e} {:>8}  {}",
                p.d,
                p.d_min_given
                    .map_or("virgin".to_string(), |v| format!("{v:.6e}")),
                p.path_given,
                p.pressure,
                p.tangent,
                p.d_min,
                p.path,
                p.region
            );
        }
        s
    }

    fn csv(&self) -> String {
        let mut s = String::from(CSV_HEADER);
        for p in &self.points {
            s += &csv_row(p);
        }
        s
    }
}
