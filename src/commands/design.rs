//! `stiction design`: the designer's question made a command. A **design point** is a
//! switch scene run until accommodated (at most the scene's `cycles`), reduced to the
//! pull-out ratio phi x largest pull-out / K_s d0 (> 1 sticks), and the engine of the crate
//! `design-sweep` turns design points into the critical value of one scene field
//! (`design threshold`), a 1-D or 2-D map over one or two fields (`design map`, shardable)
//! and the merge of a map's shards (`design merge`). User guide: `docs/design.md`.
//!
//! Every design point starts from the scene as given (before validation, so that defaults
//! derived from other keys, such as `switch.film_youngs_modulus`, follow a varied key),
//! with `until_accommodated = true`, `points = 0`, `elastic_comparison = false` and the
//! accuracy mode of `--accuracy` (else the scene's); the varied fields are written into the
//! scene's TOML tree ([`scene::with_field`]) and the result is validated like a scene file.

use super::{switch, Command};
use crate::accuracy::Accuracy;
use crate::error::Error;
use crate::progress::Progress;
use crate::render::{Format, OutputSet, Render, Warning};
use crate::scene::{self, fields, CounterKind, Loaded, Scene, SceneError, SwitchScene};
use design_sweep::{
    map_table, merge, run_map, threshold, threshold_table, DesignPoint, Grid, Labels, Map,
    MapRequest, PointError, Shard, Threshold, ThresholdOptions,
};
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

/// The files `design map` and `design merge` write.
pub const MAP_FILES: &[&str] = &["map.csv", "map.json", "map.svg"];

/// The name design points carry in messages (they have no file of their own).
const POINT: &str = "design point";

/// Stiction-free design: the critical value of a scene field, maps of the pull-out ratio,
/// and the merge of sharded maps.
#[derive(Debug, Clone, clap::Args)]
pub struct DesignCommand {
    /// What to compute.
    #[command(subcommand)]
    pub action: DesignAction,
}

/// The `design` subcommands.
#[derive(Debug, Clone, clap::Subcommand)]
pub enum DesignAction {
    /// The critical value of one scene field at which the pull-out ratio (largest pull-out
    /// after accommodation / K_s d0) crosses 1: a scan of the range, then a bracketed root.
    Threshold(ThresholdCommand),
    /// A 1-D or 2-D map of the pull-out ratio over one or two scene fields, written as
    /// map.csv, map.json and map.svg (points in parallel; --shard for a cluster array).
    Map(MapCommand),
    /// Join the shards of one map (folders of `design map --shard K/N`) into exactly the
    /// map of an unsharded run.
    Merge(MergeCommand),
}

impl DesignCommand {
    /// Runs the subcommand and returns what it prints on standard output.
    pub fn execute(&self) -> Result<String, Error> {
        match &self.action {
            DesignAction::Threshold(c) => super::pipeline(c),
            DesignAction::Map(c) => super::pipeline(c),
            DesignAction::Merge(c) => c.execute(),
        }
    }
}

/// The output formats of `design threshold`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DesignFormat {
    /// Pretty-printed JSON.
    Json,
    /// A table for people.
    Table,
}

// ------------------------------------------------------------------ design points

/// Runs design points of one scene: the field values are written into the scene, which is
/// validated and run until accommodated. Shareable between threads; it keeps a tally of
/// the physics guards the points raise.
pub struct Evaluator {
    base: SwitchScene,
    guards: Mutex<BTreeMap<&'static str, GuardTally>>,
}

#[derive(Debug, Clone)]
struct GuardTally {
    points: usize,
    example: String,
}

impl Evaluator {
    /// An evaluator for `base`: a switch scene as read (not validated), with the design
    /// overrides applied (see [`design_overrides`]).
    pub fn new(base: SwitchScene) -> Self {
        Self {
            base,
            guards: Mutex::new(BTreeMap::new()),
        }
    }

    /// The scene of one point: `values` (`section.key`, value in the key's SI unit)
    /// written into the base scene, validated. A value outside a key's domain, or a rule
    /// between keys it breaks, is [`PointError::OutOfDomain`] with the scene's message.
    pub fn scene(&self, values: &[(&str, f64)]) -> Result<SwitchScene, PointError> {
        let mut s = self.base.clone();
        for &(key, v) in values {
            s = scene::with_field(&s, key, v)
                .map_err(|e| PointError::OutOfDomain(scene_message(&e)))?;
        }
        s.validate(POINT)
            .map_err(|e| PointError::OutOfDomain(scene_message(&e)))?;
        Ok(s)
    }

    /// One design point. Errors of the run that are bad input (exit status 2, such as a
    /// derived impact energy out of its range), and a scene for which the model has no end
    /// of impact (the surface cannot absorb the impact energy, mostly where adhesion pulls
    /// harder than the asperities push back), are `OutOfDomain`; the others `Failed`.
    pub fn point(&self, values: &[(&str, f64)]) -> Result<DesignPoint, PointError> {
        let s = self.scene(values)?;
        let loaded = Loaded {
            file: POINT.into(),
            scene: s,
            is_paper: false,
        };
        let r = switch::run(&loaded, false).map_err(|e| {
            let m = error_message(&e);
            let no_end_of_impact = matches!(
                e.cause(),
                Error::Switch(switch_1d::SwitchError::EnergyNotAbsorbed { .. })
            );
            if e.exit_code() == 2 || no_end_of_impact {
                PointError::OutOfDomain(m)
            } else {
                PointError::Failed(m)
            }
        })?;
        if !r.warnings.is_empty() {
            let at = values
                .iter()
                .map(|(k, v)| format!("{k} = {}", scene::num(*v)))
                .collect::<Vec<_>>()
                .join(", ");
            if let Ok(mut g) = self.guards.lock() {
                for w in &r.warnings {
                    g.entry(w.code)
                        .and_modify(|t| t.points += 1)
                        .or_insert_with(|| GuardTally {
                            points: 1,
                            example: format!("at {at}: {}", w.message),
                        });
                }
            }
        }
        Ok(design_point(&r))
    }

    /// The guards raised so far, one warning per kind with the number of points that
    /// raised it out of `evaluated` and one example.
    pub fn warnings(&self, evaluated: usize) -> Vec<Warning> {
        let g = match self.guards.lock() {
            Ok(g) => g,
            Err(p) => p.into_inner(),
        };
        g.iter()
            .map(|(code, t)| Warning {
                code,
                message: format!(
                    "{} of {evaluated} design points raised it; e.g. {}",
                    t.points, t.example
                ),
            })
            .collect()
    }
}

/// A switch report reduced to a design point: a switch that does not close has ratio 0.
pub fn design_point(r: &switch::SwitchReport) -> DesignPoint {
    if !r.closes {
        return DesignPoint::does_not_close(r.restoring_pressure);
    }
    DesignPoint {
        pull_out_ratio: r.pull_out_ratio,
        largest_pull_out_pa: r.largest_pull_out,
        restoring_pressure_pa: r.restoring_pressure,
        cycles_to_accommodation: r.accommodated_after,
        first_sticking_cycle: r.first_sticking_cycle,
        sticks: r.stiction,
        closes: true,
    }
}

/// The settings of a design point, applied to a scene before validation: run until
/// accommodated (capped by the scene's `cycles`), no curves, no elastic comparison, and
/// `accuracy` if given.
pub fn design_overrides(scene: &mut SwitchScene, accuracy: Option<Accuracy>) {
    scene.until_accommodated = true;
    scene.points = 0;
    scene.elastic_comparison = false;
    if let Some(a) = accuracy {
        scene.accuracy = a;
    }
}

/// A scene error without the file name (a design point has none).
fn scene_message(e: &SceneError) -> String {
    match e {
        SceneError::Field {
            key,
            value,
            allowed,
            ..
        } => format!("invalid `{key}` = {value}: must be {allowed}"),
        SceneError::Missing {
            key, explanation, ..
        } => format!("missing `{key}`: {explanation}"),
        SceneError::Parse { message, .. } => message.clone(),
        other => other.to_string(),
    }
}

fn error_message(e: &Error) -> String {
    match e {
        Error::Scene(s) => scene_message(s),
        other => other.to_string(),
    }
}

// ------------------------------------------------------------------ fields

/// Whether a registry key is a field `design` may vary: a numeric key of a switch scene
/// written `section.key`.
fn variable(f: &fields::Field) -> bool {
    f.domain.is_numeric() && f.key.contains('.') && f.scenes.contains(&fields::Kind::Switch)
}

/// The fields `design` may vary, in registry order.
pub fn variable_fields() -> impl Iterator<Item = &'static fields::Field> {
    fields::FIELDS.iter().filter(|f| variable(f))
}

/// Checks that `field` may be varied on `base`: a known numeric key of a switch scene, and
/// not in conflict with the scene's drive or counter-surface. The error says what to give.
pub fn check_field(
    option: &str,
    field: &str,
    base: &SwitchScene,
) -> Result<&'static fields::Field, Error> {
    let list = || {
        variable_fields()
            .map(|f| f.key)
            .collect::<Vec<_>>()
            .join(", ")
    };
    let Some(f) = fields::field(field).filter(|f| variable(f)) else {
        let why = match fields::field(field) {
            Some(f) if !f.key.contains('.') => format!(
                "`{field}` is a top-level setting of the scene, not a design field (set it in the scene file)"
            ),
            Some(_) => format!("`{field}` is not a numeric key of a switch scene"),
            None => format!("unknown field `{field}`"),
        };
        return Err(Error::usage(
            option,
            format!("{why}; the fields that can be varied are: {}", list()),
        ));
    };
    let drive = |message: String| Err(Error::usage(option, message));
    match field {
        "switch.k_s" | "switch.voltage" if base.switch.k_s.is_none() => {
            return drive(format!(
                "{field} conflicts with the scene's drive: it gives switch.impact_energy, from which K_s is derived (at U = V_PI); give `k_s = <Pa/m>` instead of `impact_energy` in [switch] to vary {field}{}",
                if field == "switch.k_s" {
                    ", or vary switch.impact_energy"
                } else {
                    " (voltage is then the step voltage, default V_PI)"
                }
            ))
        }
        "switch.impact_energy" if base.switch.impact_energy.is_none() => {
            return drive(
                "switch.impact_energy conflicts with the scene's drive: it gives switch.k_s, from which E_I is derived (with the voltage); vary switch.k_s or switch.voltage, or give `impact_energy = <J/m^2>` instead of `k_s` (and no `voltage`) in [switch]"
                    .into(),
            )
        }
        "contact.counter_youngs_modulus"
        | "contact.counter_poisson_ratio"
        | "contact.counter_yield_stress"
            if base.contact.counter != CounterKind::Material =>
        {
            return drive(format!(
                "{field} applies only to a counter-surface of another material: give `counter = \"material\"` with counter_youngs_modulus and counter_poisson_ratio in [contact], or vary contact.youngs_modulus"
            ))
        }
        _ => {}
    }
    Ok(f)
}

/// Plot title and SI units of the varied fields. It depends only on the map (the scene
/// echo's title and the grid), so a merged map is drawn exactly like an unsharded one.
pub fn map_labels(map: &Map) -> Labels {
    let mut l = field_labels(map.grid().axes().iter().map(|a| a.field.as_str()));
    if let Some(t) = map.scene().get("title").and_then(|t| t.as_str()) {
        l = l.with_title(format!(
            "{t}: pull-out ratio after accommodation ({})",
            map.accuracy()
        ));
    }
    l
}

fn field_labels<'a>(keys: impl Iterator<Item = &'a str>) -> Labels {
    keys.fold(Labels::new(), |l, k| match unit(k) {
        Some(u) => l.with_unit(k, u),
        None => l,
    })
}

/// The SI unit of a field, if it has one (not for pure numbers).
fn unit(field: &str) -> Option<&'static str> {
    fields::field(field)
        .map(|f| f.unit)
        .filter(|u| !u.is_empty() && *u != "-")
}

/// The base scene stored by `apply` (before validation).
fn stored(cell: &OnceLock<Box<SwitchScene>>, loaded: &Loaded<SwitchScene>) -> SwitchScene {
    cell.get()
        .map(|b| (**b).clone())
        .unwrap_or_else(|| loaded.scene.clone())
}

// ------------------------------------------------------------------ threshold

/// `stiction design threshold`.
#[derive(Debug, Clone, clap::Args)]
pub struct ThresholdCommand {
    /// Scene file (TOML); the paper's switch if absent.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// The scene field to vary, `section.key` (switch.k_s, surface.sigma_s, ...).
    #[arg(long, value_name = "FIELD")]
    pub vary: String,
    /// One end of the range, in the field's SI unit.
    #[arg(long, allow_hyphen_values = true)]
    pub from: f64,
    /// The other end of the range, in the field's SI unit.
    #[arg(long, allow_hyphen_values = true)]
    pub to: f64,
    /// Accuracy mode (replaces the scene's); its pull-out tolerance sets the uncertainty.
    #[arg(long, value_enum)]
    pub accuracy: Option<Accuracy>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = DesignFormat::Table)]
    pub format: DesignFormat,
    /// The scene as read, with the design overrides (set by `apply`).
    #[arg(skip)]
    pub base: OnceLock<Box<SwitchScene>>,
}

/// The answer of `design threshold`: the crate's [`Threshold`] (parameter, critical_value,
/// free_side, kind, uncertainty, ratio_at_from, ratio_at_to, evaluations, crossings, scan),
/// the accuracy mode and the field's unit.
#[derive(Debug, Clone, Serialize)]
pub struct ThresholdReport {
    /// The search.
    #[serde(flatten)]
    pub threshold: Threshold,
    /// The accuracy mode of the design points.
    pub accuracy: &'static str,
    /// The SI unit of the parameter, its critical value and uncertainty.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unit: Option<&'static str>,
    /// Units for the table.
    #[serde(skip)]
    pub labels: Labels,
    /// Guards the design points raised (printed on standard error).
    #[serde(skip)]
    pub warnings: Vec<Warning>,
}

/// The relative tolerance of the root on the critical value: a tenth of the mode's
/// relative error of the ratio (no point refining below what the ratio can tell), within
/// [1e-9, 1e-3].
pub fn root_tolerance(accuracy: Accuracy) -> f64 {
    (0.1 * accuracy.targets().pull_out_tolerance).clamp(1e-9, 1e-3)
}

impl Command for ThresholdCommand {
    type Scene = SwitchScene;
    type Report = ThresholdReport;

    fn scene_path(&self) -> Option<&Path> {
        self.scene.as_deref()
    }

    fn apply(&self, scene: &mut SwitchScene) -> Result<(), Error> {
        design_overrides(scene, self.accuracy);
        let _ = self.base.set(Box::new(scene.clone()));
        Ok(())
    }

    fn run(&self, loaded: &Loaded<SwitchScene>) -> Result<ThresholdReport, Error> {
        let base = stored(&self.base, loaded);
        let field = check_field("--vary", &self.vary, &base)?;
        for (option, v) in [("--from", self.from), ("--to", self.to)] {
            if !field.domain.contains(v) {
                return Err(Error::usage(
                    option,
                    format!(
                        "{} {} is outside the domain of {}: must be {}",
                        option,
                        scene::num(v),
                        field.key,
                        field.domain.describe()
                    ),
                ));
            }
        }
        let accuracy = base.accuracy;
        let options = ThresholdOptions {
            tolerance: root_tolerance(accuracy),
            ratio_rel_error: accuracy.targets().pull_out_tolerance,
            scan_points: None,
        };
        let ev = Evaluator::new(base);
        let t = threshold(
            field.key,
            self.from,
            self.to,
            |x| ev.point(&[(field.key, x)]),
            &options,
        )?;
        let warnings = ev.warnings(t.evaluations);
        Ok(ThresholdReport {
            labels: field_labels(std::iter::once(field.key)),
            unit: unit(field.key),
            accuracy: accuracy.as_str(),
            threshold: t,
            warnings,
        })
    }

    fn format(&self) -> Format {
        match self.format {
            DesignFormat::Json => Format::Json,
            DesignFormat::Table => Format::Table,
        }
    }
}

impl Render for ThresholdReport {
    fn table(&self) -> String {
        let mut s = threshold_table(&self.threshold, &self.labels);
        let _ = writeln!(
            s,
            "{:<16}{} (ratio to {:e}); root to {:e} of the value",
            "accuracy", self.accuracy, self.threshold.ratio_rel_error, self.threshold.tolerance
        );
        s
    }

    fn csv(&self) -> String {
        let mut s = String::from("value,status,pull_out_ratio\n");
        for p in &self.threshold.scan {
            let _ = writeln!(
                s,
                "{:e},{},{}",
                p.value,
                p.status,
                p.pull_out_ratio
                    .map(|r| format!("{r:e}"))
                    .unwrap_or_default()
            );
        }
        s
    }

    fn warnings(&self) -> &[Warning] {
        &self.warnings
    }
}

// ------------------------------------------------------------------ map

/// `stiction design map`.
#[derive(Debug, Clone, clap::Args)]
pub struct MapCommand {
    /// Scene file (TOML); the paper's switch if absent.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// A varied field and its values, FIELD=FROM:TO:lin|log:N (FROM, TO in the field's SI
    /// unit; N values, both ends included). Once for a 1-D map, twice for 2-D (the first
    /// varies slowest).
    #[arg(long, value_name = "FIELD=FROM:TO:lin|log:N", required = true)]
    pub vary: Vec<String>,
    /// Write map.csv, map.json and map.svg to this folder (replaced as a whole; it may
    /// hold only those files).
    #[arg(long)]
    pub out: PathBuf,
    /// Run part K of N interleaved parts of the grid (K = 1..N; point i is in part
    /// i % N + 1); join the parts with `design merge`.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
    /// Accuracy mode (replaces the scene's).
    #[arg(long, value_enum)]
    pub accuracy: Option<Accuracy>,
    /// The scene as read, with the design overrides (set by `apply`).
    #[arg(skip)]
    pub base: OnceLock<Box<SwitchScene>>,
}

/// A computed map (whole or one shard) with its files.
#[derive(Debug, Clone, Serialize)]
#[serde(transparent)]
pub struct MapReport {
    /// The map.
    pub map: Map,
    /// Units and title.
    #[serde(skip)]
    pub labels: Labels,
    /// `map.csv`.
    #[serde(skip)]
    pub csv: String,
    /// `map.svg`.
    #[serde(skip)]
    pub svg: String,
    /// Guards the design points raised (printed on standard error).
    #[serde(skip)]
    pub warnings: Vec<Warning>,
}

impl MapReport {
    /// Renders the files of `map`; `dir` names the folder in a plot error.
    pub fn new(map: Map, dir: &Path, warnings: Vec<Warning>) -> Result<MapReport, Error> {
        let labels = map_labels(&map);
        let csv = map.to_csv()?;
        let svg = map.to_svg(&labels).map_err(|e| Error::Plot {
            path: dir.join("map.svg").display().to_string(),
            message: e.to_string(),
        })?;
        Ok(MapReport {
            map,
            labels,
            csv,
            svg,
            warnings,
        })
    }

    /// The files, to be written to `dir` together.
    pub fn files(&self, dir: &Path) -> OutputSet {
        let mut set = OutputSet::new(dir, MAP_FILES);
        set.add("map.csv", self.csv.as_bytes());
        set.add("map.json", self.map.to_json());
        set.add("map.svg", self.svg.as_bytes());
        set
    }
}

impl Command for MapCommand {
    type Scene = SwitchScene;
    type Report = MapReport;

    fn scene_path(&self) -> Option<&Path> {
        self.scene.as_deref()
    }

    fn apply(&self, scene: &mut SwitchScene) -> Result<(), Error> {
        design_overrides(scene, self.accuracy);
        let _ = self.base.set(Box::new(scene.clone()));
        Ok(())
    }

    fn run(&self, loaded: &Loaded<SwitchScene>) -> Result<MapReport, Error> {
        let base = stored(&self.base, loaded);
        let grid = Grid::parse(&self.vary)?;
        for a in grid.axes() {
            check_field("--vary", &a.field, &base)?;
        }
        let shard = self.shard.as_deref().map(Shard::parse).transpose()?;
        let scene_echo = serde_json::to_value(&base).map_err(|e| {
            Error::usage(
                "--scene",
                format!("the scene cannot be echoed as JSON: {e}"),
            )
        })?;
        let request = MapRequest {
            scene: scene_echo,
            grid,
            accuracy: base.accuracy.as_str().into(),
            shard,
        };
        let ev = Evaluator::new(base);
        let total = match shard {
            Some(s) => s.indices(request.grid.len()).count(),
            None => request.grid.len(),
        };
        let bar = Mutex::new((Progress::new(total as u64, "design points"), 0u64));
        let map = run_map(
            request,
            |values| ev.point(values),
            |done, _| {
                if let Ok(mut b) = bar.lock() {
                    // workers report out of order: the bar only moves forward
                    b.1 = b.1.max(done as u64);
                    let at = b.1;
                    b.0.set(at);
                }
            },
        );
        if let Ok(b) = bar.lock() {
            b.0.finish();
        }
        let warnings = ev.warnings(map.points().len());
        MapReport::new(map, &self.out, warnings)
    }

    fn outputs(&self, report: &MapReport) -> Result<Option<OutputSet>, Error> {
        Ok(Some(report.files(&self.out)))
    }

    fn format(&self) -> Format {
        Format::Table
    }
}

impl Render for MapReport {
    fn table(&self) -> String {
        map_table(&self.map, &self.labels)
    }

    fn csv(&self) -> String {
        self.csv.clone()
    }

    fn warnings(&self) -> &[Warning] {
        &self.warnings
    }
}

// ------------------------------------------------------------------ merge

/// `stiction design merge`.
#[derive(Debug, Clone, clap::Args)]
pub struct MergeCommand {
    /// The folders of the parts (each written by `design map --shard K/N`), in any order.
    #[arg(value_name = "DIR", required = true)]
    pub dirs: Vec<PathBuf>,
    /// Write the merged map.csv, map.json and map.svg to this folder (replaced as a
    /// whole; it may hold only those files, and it may not be one of the parts).
    #[arg(long)]
    pub out: PathBuf,
}

impl MergeCommand {
    /// Reads the parts, merges them and writes the map; returns the summary table.
    pub fn execute(&self) -> Result<String, Error> {
        let out = absolute(&self.out);
        let mut parts = Vec::with_capacity(self.dirs.len());
        for dir in &self.dirs {
            let label = dir.display().to_string();
            if absolute(dir) == out {
                return Err(Error::usage(
                    "--out",
                    format!("{label} is one of the parts: give the merged map its own folder"),
                ));
            }
            let path = dir.join("map.json");
            // bounded read (design_sweep::MAX_MAP_BYTES), regular files only
            let map = Map::read_path(&path).map_err(|e| {
                Error::usage("DIR", format!("{e} (a folder of `design map --shard K/N`)"))
            })?;
            parts.push((label, map));
        }
        let map = merge(parts)?;
        let report = MapReport::new(map, &self.out, Vec::new())?;
        let mut text = report.table();
        let written = report.files(&self.out).commit()?;
        let list: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
        let _ = write!(text, "\nwrote {}\n", list.join(", "));
        Ok(text)
    }
}

/// `p` made absolute and cleaned lexically (no file system access beyond the current
/// folder), to tell whether two folder arguments name the same folder.
fn absolute(p: &Path) -> PathBuf {
    let p = if p.is_absolute() {
        p.to_path_buf()
    } else {
        std::env::current_dir()
            .map(|d| d.join(p))
            .unwrap_or_else(|_| p.to_path_buf())
    };
    let p = p.canonicalize().unwrap_or(p);
    let mut clean = PathBuf::new();
    for c in p.components() {
        match c {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir => {
                clean.pop();
            }
            c => clean.push(c),
        }
    }
    clean
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper(edit: impl FnOnce(&mut SwitchScene)) -> SwitchScene {
        let mut s: SwitchScene = scene::parse("test", scene::DEFAULT_SWITCH).unwrap();
        edit(&mut s);
        s
    }

    #[test]
    fn every_variable_field_is_a_numeric_switch_key_with_a_section() {
        let keys: Vec<&str> = variable_fields().map(|f| f.key).collect();
        for k in [
            "switch.k_s",
            "switch.voltage",
            "switch.impact_energy",
            "surface.sigma_s",
            "surface.asperity_density",
            "contact.work_of_adhesion",
            "contact.yield_stress",
            "switch.contact_area_fraction",
        ] {
            assert!(keys.contains(&k), "{k} missing from {keys:?}");
        }
        for k in [
            "cycles",
            "points",
            "contact.adhesion_law",
            "delta_max",
            "d_start",
        ] {
            assert!(!keys.contains(&k), "{k} must not be variable");
        }
    }

    #[test]
    fn the_drive_decides_which_stiffness_keys_may_vary() {
        let energy = paper(|_| {});
        let spring = paper(|s| {
            s.switch.impact_energy = None;
            s.switch.k_s = Some(8.44e9);
        });
        assert!(check_field("--vary", "switch.impact_energy", &energy).is_ok());
        assert!(check_field("--vary", "switch.k_s", &spring).is_ok());
        assert!(check_field("--vary", "switch.voltage", &spring).is_ok());
        for (field, scene, give) in [
            ("switch.k_s", &energy, "`k_s = <Pa/m>`"),
            ("switch.voltage", &energy, "`k_s = <Pa/m>`"),
            ("switch.impact_energy", &spring, "`impact_energy = <J/m^2>`"),
        ] {
            let e = check_field("--vary", field, scene).unwrap_err();
            assert_eq!(e.exit_code(), 2);
            assert!(e.to_string().contains(give), "{e}");
        }
        let e = check_field("--vary", "contact.counter_poisson_ratio", &energy).unwrap_err();
        assert!(e.to_string().contains("counter = \"material\""), "{e}");
    }

    #[test]
    fn a_point_follows_derived_defaults_and_reports_its_domain() {
        let mut base = paper(|s| s.switch.film_youngs_modulus = None);
        design_overrides(&mut base, Some(Accuracy::Fast));
        let ev = Evaluator::new(base);
        // the film modulus of eq 17 follows a varied contact modulus (it defaults to it)
        let s = ev.scene(&[("contact.youngs_modulus", 2e11)]).unwrap();
        assert_eq!(s.switch.film_youngs_modulus, Some(2e11));
        assert_eq!(
            (s.points, s.elastic_comparison, s.until_accommodated),
            (0, false, true)
        );
        match ev.scene(&[("surface.sigma_s", 1e-12)]) {
            Err(PointError::OutOfDomain(m)) => {
                assert!(m.contains("surface.sigma_s") && m.contains("1e-11"), "{m}")
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn the_root_tolerance_follows_the_mode() {
        assert_eq!(root_tolerance(Accuracy::Fast), 1e-5);
        assert_eq!(root_tolerance(Accuracy::Accurate), 1e-9);
        assert!(root_tolerance(Accuracy::Reference) >= 1e-9);
    }
}
