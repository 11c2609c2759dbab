//! `stiction law`: the adhesive-contact law p(d; d_min, path) of a switch or surface
//! scene's rough surface, tabulated for a finite-element code (`law.json`, `law.csv`,
//! `law.svg`; the model library's `law`), and `stiction law eval`, which evaluates a law
//! file.

use super::switch::AccuracyArg;
use super::{argument_error, finish, preflight, Ctx, Outputs, SceneArgs};
use crate::error::Error;
use crate::progress::Bar;
use crate::render::{Format, Render};
use std::path::PathBuf;
use stiction_model::contact_law::tabulate::GridSpec;
use stiction_model::contact_law::{ContactLaw, LawError, Path as LawPath};
use stiction_model::keys::Kind;
use stiction_model::law::{self, LawOptions, LawResult, LawScene, DEFAULT_POINTS};
use stiction_model::spec::Spec;
use stiction_report::law_eval::{EvalBatch, EvalPoint, EvalReport, UNITS};
use stiction_report::Report;

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
        preflight(Some(out), LawResult::FILES, None)?;
        let result = law::tabulate(law_scene, &options, &Bar::new()).map_err(argument_error)?;
        let set = result.files(out)?;
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
