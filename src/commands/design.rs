//! `stiction design`: the designer's question made a command (the model library's
//! `design`): the critical value of one scene field (`design threshold`), 1-D and 2-D
//! maps of the pull-out ratio (`design map`, shardable) and the merge of a map's shards
//! (`design merge`). User guide: `docs/design.md`.

pub use super::probability::ProbabilityCommand;
use super::switch::AccuracyArg;
use super::{argument_error, finish, preflight, Ctx, Outputs, SceneArgs};
use crate::error::Error;
use crate::progress::Bar;
use crate::render::{self, Format, Render};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use stiction_model::design::{self, Map};
use stiction_model::design_sweep::{merge, merge_probability, Probability};
use stiction_model::keys::Kind;
use stiction_report::design::MapReport;
use stiction_report::probability::ProbabilityReport;
use stiction_report::Report;

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
    /// A 1-D or 2-D map of the pull-out ratio over one or two scene fields (numbers, or
    /// words: law names and choices), written as map.csv, map.json and map.svg (points in
    /// parallel; --shard for a cluster array).
    Map(MapCommand),
    /// The probability that a switch sticks (by cycle, after accommodation) and that it
    /// does not close when design fields scatter (FIELD=DIST): Monte Carlo with exact
    /// binomial intervals, rank correlations, and the exact answer for a single field.
    Probability(ProbabilityCommand),
    /// Join the shards of one map (folders of `design map --shard K/N`), or of one
    /// probability run (`design probability --shard K/N`), into exactly the result of an
    /// unsharded run.
    Merge(MergeCommand),
}

impl DesignCommand {
    /// Runs the subcommand and returns what it prints on standard output.
    pub fn execute(&self, ctx: Ctx) -> Result<String, Error> {
        match &self.action {
            DesignAction::Threshold(c) => c.execute(ctx),
            DesignAction::Map(c) => c.execute(ctx),
            DesignAction::Probability(c) => c.execute(ctx),
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

// ------------------------------------------------------------------ threshold

/// `stiction design threshold`.
#[derive(Debug, Clone, clap::Args)]
pub struct ThresholdCommand {
    /// The switch scene, `--set`, `--strict`.
    #[command(flatten)]
    pub scene: SceneArgs,
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
    pub accuracy: Option<AccuracyArg>,
    /// A second requirement beside freedom from stiction, `QUANTITY<LIMIT` or
    /// `QUANTITY>LIMIT`: contact_resistance (ohm; needs contact.resistivity,
    /// contact.mean_free_path and switch.electrode_area) or real_contact_fraction (-), under
    /// the hold voltage after the last cycle; reports the window where both hold.
    #[arg(long, value_name = "QUANTITY<LIMIT")]
    pub require: Option<String>,
    /// `check`: the critical value under every combination of the credible published
    /// model forms too (replaces the scene's `model_form`).
    #[arg(long, value_enum)]
    pub model_form: Option<super::switch::ModelFormArg>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = DesignFormat::Table)]
    pub format: DesignFormat,
}

impl ThresholdCommand {
    /// Runs the search.
    pub fn execute(&self, ctx: Ctx) -> Result<String, Error> {
        let edits: Vec<_> = super::switch::model_form_edit(self.model_form)
            .into_iter()
            .collect();
        let loaded = self.scene.load(Kind::Switch, &edits)?;
        loaded.refuse_set_of(&self.vary, "--vary")?;
        let r = design::threshold_with(
            &loaded.scene,
            ctx.registry,
            &self.vary,
            self.from,
            self.to,
            self.accuracy.map(Into::into),
            self.require.as_deref(),
            &Bar::new(),
        )
        .map_err(|e| loaded.blame(e))?;
        let format = match self.format {
            DesignFormat::Json => Format::Json,
            DesignFormat::Table => Format::Table,
        };
        finish(&r, format, false, self.scene.strict, Outputs::default())
    }
}

// ------------------------------------------------------------------ map

/// `stiction design map`.
#[derive(Debug, Clone, clap::Args)]
pub struct MapCommand {
    /// The switch scene, `--set`, `--strict`.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// A varied field and its values: FIELD=FROM:TO:lin|log:N for a number (FROM, TO in the
    /// field's SI unit; N values, both ends included), or FIELD=WORD,WORD,... for a law name
    /// or a choice (contact.plasticity_law=etsion_kadin,kogut_etsion; no colon: the words
    /// in the order given). Once for a 1-D map, twice for 2-D (the first varies slowest).
    #[arg(
        long,
        value_name = "FIELD=FROM:TO:lin|log:N|FIELD=WORD,...",
        required = true
    )]
    pub vary: Vec<String>,
    /// Write map.csv, map.json and map.svg to this folder (replaced as a whole; it may
    /// hold only those files).
    #[arg(long)]
    pub out: PathBuf,
    /// Run part K of N interleaved parts of the grid (K = 1..N; point i is in part
    /// i % N + 1); join the parts with `design merge`.
    #[arg(long, value_name = "K/N", allow_hyphen_values = true)]
    pub shard: Option<String>,
    /// Accuracy mode (replaces the scene's).
    #[arg(long, value_enum)]
    pub accuracy: Option<AccuracyArg>,
    /// A second requirement beside freedom from stiction, `QUANTITY<LIMIT` or
    /// `QUANTITY>LIMIT`: contact_resistance (ohm; needs contact.resistivity,
    /// contact.mean_free_path and switch.electrode_area) or real_contact_fraction (-), under
    /// the hold voltage after the last cycle; reports the window where both hold.
    #[arg(long, value_name = "QUANTITY<LIMIT")]
    pub require: Option<String>,
    /// `check`: the same map under every combination of the credible published model
    /// forms, and at each point the share of them under which the switch sticks
    /// (model_form.json; replaces the scene's `model_form`).
    #[arg(long, value_enum)]
    pub model_form: Option<super::switch::ModelFormArg>,
}

impl MapCommand {
    /// Runs the map (or one shard of it).
    pub fn execute(&self, ctx: Ctx) -> Result<String, Error> {
        let edits: Vec<_> = super::switch::model_form_edit(self.model_form)
            .into_iter()
            .collect();
        let loaded = self.scene.load(Kind::Switch, &edits)?;
        for v in &self.vary {
            loaded.refuse_set_of(v.split('=').next().unwrap_or(v), "--vary")?;
        }
        let accuracy = self.accuracy.map(Into::into);
        // everything checked before the first point runs, the output folder included
        design::map_request_with(
            &loaded.scene,
            ctx.registry,
            &self.vary,
            self.shard.as_deref(),
            accuracy,
            self.require.as_deref(),
        )
        .map_err(|e| loaded.blame(e))?;
        preflight(Some(&self.out), MapReport::FILES, None)?;
        let r = design::map_with(
            &loaded.scene,
            ctx.registry,
            &self.vary,
            self.shard.as_deref(),
            accuracy,
            self.require.as_deref(),
            &Bar::new(),
        )
        .map_err(argument_error)?;
        let report = MapReport::new(r);
        let set = report.files(&self.out)?;
        finish(
            &report,
            Format::Table,
            false,
            self.scene.strict,
            Outputs {
                folder: Some(set),
                plots: Vec::new(),
            },
        )
    }
}

// ------------------------------------------------------------------ merge

/// `stiction design merge`.
#[derive(Debug, Clone, clap::Args)]
pub struct MergeCommand {
    /// The folders of the parts (each written by `design map --shard K/N`, or all by
    /// `design probability --shard K/N`), in any order.
    #[arg(value_name = "DIR", required = true)]
    pub dirs: Vec<PathBuf>,
    /// Write the merged map.csv, map.json and map.svg (or samples.csv, probability.json
    /// and probability.svg) to this folder (replaced as a whole; it may hold only those
    /// files, and it may not be one of the parts).
    #[arg(long)]
    pub out: PathBuf,
}

impl MergeCommand {
    /// Reads the parts, merges them and writes the map; returns the summary table.
    pub fn execute(&self) -> Result<String, Error> {
        let out = absolute(&self.out);
        // a folder of `design probability` holds probability.json and no map.json
        let probability = |d: &PathBuf| {
            d.join("probability.json").symlink_metadata().is_ok()
                && d.join("map.json").symlink_metadata().is_err()
        };
        if let Some(first) = self.dirs.iter().find(|d| probability(d)) {
            if let Some(map) = self.dirs.iter().find(|d| !probability(d)) {
                return Err(Error::usage(
                    "DIR",
                    format!(
                        "{} holds no probability.json while {} holds a probability run: parts of one run only (a map and a probability run do not merge)",
                        map.display(),
                        first.display()
                    ),
                ));
            }
            return self.execute_probability(&out);
        }
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
        let checks = self.model_form_parts(&parts)?;
        preflight(Some(&self.out), MapReport::FILES, None)?;
        let map = merge(parts.clone())?;
        let model_form = checks
            .map(|c| merged_model_form(&parts, c, &map))
            .transpose()?;
        let report = MapReport::merged(map);
        let mut text = report.table();
        let mut set = report.files(&self.out)?;
        if let Some(v) = &model_form {
            set.add("model_form.json", render::json(v));
            let _ = write!(
                text,
                "\nmodel form: {} of {} points keep their verdict under every combination (merged from the parts' model_form.json)\n",
                v["robust_points"],
                v["share_sticking"].as_array().map_or(0, |a| a.iter().filter(|x| !x.is_null()).count())
            );
        }
        let written = set.commit()?;
        let list: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
        let _ = write!(text, "\nwrote {}\n", list.join(", "));
        Ok(text)
    }
}

impl MergeCommand {
    /// The parts' model-form checks of a map: all or none of the parts have one.
    fn model_form_parts(
        &self,
        parts: &[(String, Map)],
    ) -> Result<Option<Vec<serde_json::Value>>, Error> {
        let Some(found) = self.model_form_checks("map")? else {
            return Ok(None);
        };
        if found.len() != parts.len() {
            return Err(Error::usage(
                "DIR",
                format!(
                    "{} of {} parts hold a model_form.json: the parts of one map are all checked (--model-form check) or none is",
                    found.len(),
                    parts.len()
                ),
            ));
        }
        Ok(Some(found))
    }

    /// The parts' `model_form.json` files (None when none has one), each a regular file of
    /// at most 64 MiB, of the same combinations and mode; `what` names the question.
    fn model_form_checks(&self, what: &str) -> Result<Option<Vec<serde_json::Value>>, Error> {
        let mut found = Vec::new();
        for dir in &self.dirs {
            let path = dir.join("model_form.json");
            if path.symlink_metadata().is_err() {
                continue;
            }
            let bad = |m: String| Error::usage("DIR", format!("{}: {m}", path.display()));
            let meta = std::fs::metadata(&path).map_err(|e| bad(e.to_string()))?;
            if !meta.is_file() || meta.len() > 64 << 20 {
                return Err(bad("not a regular file of at most 64 MiB".into()));
            }
            let text = std::fs::read_to_string(&path).map_err(|e| bad(e.to_string()))?;
            let v: serde_json::Value =
                serde_json::from_str(&text).map_err(|e| bad(format!("not JSON: {e}")))?;
            found.push(v);
        }
        if found.is_empty() {
            return Ok(None);
        }
        // a map's check lists its combinations, a probability run's its runs' laws
        let laws = |v: &serde_json::Value| -> serde_json::Value {
            match v.get("combinations") {
                Some(c) => c.clone(),
                None => v["runs"]
                    .as_array()
                    .map(|r| r.iter().map(|x| x["laws"].clone()).collect())
                    .unwrap_or_default(),
            }
        };
        for v in &found[1..] {
            if laws(v) != laws(&found[0]) || v["accuracy"] != found[0]["accuracy"] {
                return Err(Error::usage(
                    "DIR",
                    format!(
                        "the parts' model-form checks ran other combinations or modes: parts of one checked {what} only"
                    ),
                ));
            }
        }
        Ok(Some(found))
    }
}

/// The merged probability run's model-form check: each combination's counts summed over
/// the parts, its probability and Clopper-Pearson interval (at the parts' confidence)
/// recomputed, and the range over the combinations.
fn merged_probability_check(checks: Vec<serde_json::Value>) -> Result<serde_json::Value, Error> {
    let mut out = checks[0].clone();
    let confidence = out["confidence"].as_f64().unwrap_or(0.95);
    let runs = out["runs"].as_array().cloned().unwrap_or_default();
    let mut merged = Vec::with_capacity(runs.len());
    let mut ps = Vec::new();
    for (k, run) in runs.into_iter().enumerate() {
        let (mut x, mut n) = (0u64, 0u64);
        for c in &checks {
            let r = &c["runs"][k];
            let (Some(s), Some(d)) = (r["sticking"].as_u64(), r["counted"].as_u64()) else {
                return Err(Error::usage(
                    "DIR",
                    "a part's model_form.json lacks its counts (sticking, counted)",
                ));
            };
            x += s;
            n += d;
        }
        let mut r = run;
        let (lo, hi) = stiction_model::design_sweep::stats::clopper_pearson(
            x as usize, n as usize, confidence,
        )
        .unwrap_or((0.0, 1.0));
        r["sticking"] = serde_json::json!(x);
        r["counted"] = serde_json::json!(n);
        r["interval"] = serde_json::json!([lo, hi]);
        if n > 0 {
            let p = x as f64 / n as f64;
            ps.push(p);
            r["stiction_probability"] = serde_json::json!(p);
        } else if let Some(o) = r.as_object_mut() {
            o.remove("stiction_probability");
        }
        merged.push(r);
    }
    let range = if ps.is_empty() {
        [0.0, 1.0]
    } else {
        [
            ps.iter().copied().fold(f64::INFINITY, f64::min),
            ps.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        ]
    };
    out["summary"] = serde_json::json!(stiction_model::model_form::probability_summary(
        range,
        merged.len()
    ));
    out["runs"] = serde_json::Value::Array(merged);
    out["stiction_probability_range"] = serde_json::json!(range);
    Ok(out)
}

/// The merged map's model-form check: each part's share at each of its points, by the
/// point's index in the grid, in the merged map's order; a point keeps its verdict under
/// every combination where its share is 0 or 1.
fn merged_model_form(
    parts: &[(String, Map)],
    checks: Vec<serde_json::Value>,
    merged: &Map,
) -> Result<serde_json::Value, Error> {
    let mut share = std::collections::BTreeMap::new();
    for ((label, map), check) in parts.iter().zip(&checks) {
        let shares = check["share_sticking"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        if shares.len() != map.points().len() {
            return Err(Error::usage(
                "DIR",
                format!(
                    "{label}: model_form.json holds {} shares for {} map points",
                    shares.len(),
                    map.points().len()
                ),
            ));
        }
        for (p, v) in map.points().iter().zip(shares) {
            share.insert(p.index, v);
        }
    }
    let ordered: Vec<serde_json::Value> = merged
        .points()
        .iter()
        .map(|p| {
            share
                .get(&p.index)
                .cloned()
                .unwrap_or(serde_json::Value::Null)
        })
        .collect();
    let robust = ordered
        .iter()
        .filter_map(|v| v.as_f64())
        .filter(|&s| s == 0.0 || s == 1.0)
        .count();
    let mut out = checks[0].clone();
    out["share_sticking"] = serde_json::Value::Array(ordered);
    out["robust_points"] = serde_json::json!(robust);
    Ok(out)
}

impl MergeCommand {
    /// Merges the parts of a probability run.
    fn execute_probability(&self, out: &Path) -> Result<String, Error> {
        let mut parts = Vec::with_capacity(self.dirs.len());
        for dir in &self.dirs {
            let label = dir.display().to_string();
            if absolute(dir) == out {
                return Err(Error::usage(
                    "--out",
                    format!("{label} is one of the parts: give the merged run its own folder"),
                ));
            }
            let run = Probability::read_path(dir.join("probability.json")).map_err(|e| {
                Error::usage(
                    "DIR",
                    format!("{e} (a folder of `design probability --shard K/N`)"),
                )
            })?;
            parts.push((label, run));
        }
        let checks = self.model_form_checks("probability run")?;
        if checks.as_ref().is_some_and(|c| c.len() != parts.len()) {
            return Err(Error::usage(
                "DIR",
                "some parts hold a model_form.json and others not: the parts of one run are all checked (--model-form check) or none is",
            ));
        }
        preflight(Some(&self.out), ProbabilityReport::FILES, None)?;
        let report = ProbabilityReport::merged(merge_probability(parts)?);
        let mut text = report.table();
        let mut set = report.files(&self.out)?;
        if let Some(checks) = checks {
            let merged = merged_probability_check(checks)?;
            let _ = write!(
                text,
                "\nmodel form: {} (merged from the parts' model_form.json)\n",
                merged["summary"].as_str().unwrap_or("")
            );
            set.add("model_form.json", render::json(&merged));
        }
        let written = set.commit()?;
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
