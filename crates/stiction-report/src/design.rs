//! The design questions' results: the critical value of a field (`stiction design
//! threshold`) and maps of the pull-out ratio (`stiction design map`, `design merge`; `--out`
//! writes map.csv, map.json, map.svg and, with a model-form check, model_form.json and
//! model_form.svg).

use crate::design_table::{map_table, threshold_table};
use crate::output::OutputSet;
use crate::plot::map::map_svg;
use crate::render::{self, Render, Validity, Warning};
use crate::{Plot, Report, ReportError};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;
use stiction_model::design::{Labels, Map, MapResult, ThresholdResult};

/// The files `design map` and `design merge` write.
const MAP_FILES: &[&str] = &[
    "map.csv",
    "map.json",
    "map.svg",
    "model_form.json",
    "model_form.svg",
];

impl Render for ThresholdResult {
    fn table(&self) -> String {
        let mut s = threshold_table(&self.threshold, &self.labels);
        let _ = writeln!(
            s,
            "{:<16}{} (ratio to {:e}); root to {:e} of the value",
            "accuracy", self.accuracy, self.threshold.ratio_rel_error, self.threshold.tolerance
        );
        let _ = writeln!(
            s,
            "{:<16}{}",
            "laws",
            crate::switch::laws_line(&self.laws).trim_start_matches("laws: ")
        );
        let invalid = self
            .threshold
            .scan
            .iter()
            .filter(|p| p.validity_holds == Some(false))
            .count();
        if invalid > 0 {
            let _ = writeln!(
                s,
                "{:<16}{invalid} of {} scan points {}",
                "validity",
                self.threshold.scan.len(),
                self.validity.words()
            );
        }
        if let Some(m) = &self.model_form {
            let _ = writeln!(
                s,
                "\nmodel form: {} (other combinations in {} mode)",
                m.summary, m.accuracy
            );
            for r in &m.runs {
                let _ = writeln!(
                    s,
                    "  {:<16} {:<11} {:<11} {:<12} {}{}",
                    r.laws.plasticity,
                    r.laws.yield_modulus,
                    r.laws.reload,
                    r.laws.adhesion,
                    r.critical_value
                        .map_or("no critical value".to_string(), |v| format!("{v:.6e}")),
                    if r.validity_holds {
                        ""
                    } else {
                        " (outside validity somewhere)"
                    }
                );
            }
            for e in &m.excluded {
                let _ = writeln!(s, "  left out: {} {}: {}", e.choice, e.value, e.reason);
            }
        }
        s
    }

    fn csv(&self) -> String {
        let mut s = String::from(
            "value,status,pull_out_ratio,closes,validity_holds,contact_resistance,real_contact_fraction,meets_requirement\n",
        );
        let opt = |b: Option<bool>| b.map(|b| b.to_string()).unwrap_or_default();
        let num = |v: Option<f64>| v.map(|r| format!("{r:e}")).unwrap_or_default();
        for p in &self.threshold.scan {
            let _ = writeln!(
                s,
                "{:e},{},{},{},{},{},{},{}",
                p.value,
                p.status,
                num(p.pull_out_ratio),
                opt(p.closes),
                opt(p.validity_holds),
                num(p.contact_resistance),
                num(p.real_contact_fraction),
                opt(p.meets_requirement)
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

/// A computed map with its files, for rendering.
#[derive(Debug, Clone, Serialize)]
#[serde(transparent)]
pub struct MapReport {
    /// The map.
    pub map: Map,
    /// Units and title.
    #[serde(skip)]
    pub labels: Labels,
    /// Guards the design points raised (printed on standard error).
    #[serde(skip)]
    pub warnings: Vec<Warning>,
    /// Whether the model holds at every point.
    #[serde(skip)]
    pub validity: Option<Validity>,
    /// The model-form check, when asked for (written as model_form.json).
    #[serde(skip)]
    pub model_form: Option<stiction_model::model_form::MapModelForm>,
}

impl MapReport {
    /// The report of a computed map.
    pub fn new(r: MapResult) -> Self {
        Self {
            map: r.map,
            labels: r.labels,
            warnings: r.warnings,
            validity: Some(r.validity),
            model_form: r.model_form,
        }
    }

    /// The report of a merged map (no warnings, validity unknown, units from the map).
    pub fn merged(map: Map) -> Self {
        Self {
            labels: stiction_model::design::map_labels(&map),
            map,
            warnings: Vec::new(),
            validity: None,
            model_form: None,
        }
    }
}

impl Plot for MapReport {
    /// `map.svg`.
    fn svg(&self) -> Result<String, ReportError> {
        map_svg(&self.map, &self.labels)
    }
}

impl Report for MapReport {
    const FILES: &'static [&'static str] = MAP_FILES;

    fn files(&self, dir: &Path) -> Result<OutputSet, ReportError> {
        let mut set = OutputSet::new(dir, MAP_FILES);
        if let Some(m) = &self.model_form {
            set.add("model_form.json", render::json(m));
            let svg = model_form_svg(&self.map, m)
                .map_err(|message| ReportError::plot(&dir.join("model_form.svg"), message))?;
            set.add("model_form.svg", svg);
        }
        set.add("map.csv", crate::csv::map_csv(&self.map)?);
        set.add("map.json", self.map.to_json());
        let svg = map_svg(&self.map, &self.labels).map_err(|e| match e {
            ReportError::Plot { message, .. } => ReportError::plot(&dir.join("map.svg"), message),
            e => e,
        })?;
        set.add("map.svg", svg);
        Ok(set)
    }
}

/// The most lines `model_form.svg` draws for the second axis of a 2-D map (evenly chosen
/// levels beyond it, said in the title).
const MODEL_FORM_LINES: usize = 8;

/// `model_form.svg`: the share of the combinations of the credible published forms under
/// which the switch sticks, against the map's first field (log10 of it on a log axis, the
/// word's position on a categorical one), one line per level of the second field (at most
/// [`MODEL_FORM_LINES`]); 0 where every combination is free, 1 where every one sticks.
fn model_form_svg(
    map: &Map,
    m: &stiction_model::model_form::MapModelForm,
) -> Result<String, String> {
    use stiction_model::design::Level;
    let g = map.grid();
    let ax = &g.axes()[0];
    let x_of = |l: &Level<'_>| -> f64 {
        match l {
            Level::Number(x) if ax.spacing == stiction_model::design_sweep::Spacing::Log => {
                x.log10()
            }
            Level::Number(x) => *x,
            Level::Word(w) => ax.words.iter().position(|v| v == w).unwrap_or(0) as f64,
        }
    };
    let x_label = if ax.is_categorical() {
        let words: Vec<String> = ax
            .words
            .iter()
            .enumerate()
            .map(|(i, w)| format!("{i} = {w}"))
            .collect();
        format!("{} ({})", ax.field, words.join(", "))
    } else {
        let unit = stiction_model::design::unit(&ax.field).unwrap_or("-");
        if ax.spacing == stiction_model::design_sweep::Spacing::Log {
            format!("log10 {} ({unit})", ax.field)
        } else {
            format!("{} ({unit})", ax.field)
        }
    };
    // one line per level of the second axis
    let second = g.axes().get(1);
    let n2 = second.map_or(1, |a| a.n);
    let picked: Vec<usize> = if n2 <= MODEL_FORM_LINES {
        (0..n2).collect()
    } else {
        let mut v: Vec<usize> = (0..MODEL_FORM_LINES)
            .map(|k| (k * (n2 - 1) + (MODEL_FORM_LINES - 1) / 2) / (MODEL_FORM_LINES - 1))
            .collect();
        v.dedup();
        v
    };
    let mut series = Vec::new();
    for &j in &picked {
        let mut points = Vec::new();
        let mut name = String::from("share of the combinations that stick");
        for (p, share) in map.points().iter().zip(&m.share_sticking) {
            let idx = g.indices(p.index);
            if second.is_some() && idx[1] != j {
                continue;
            }
            let levels = g.levels(p.index);
            if let (Some(s), Some(b)) = (share, second) {
                name = match levels[1] {
                    Level::Number(v) => format!("{} = {v:.4e}", b.field),
                    Level::Word(w) => format!("{} = {w}", b.field),
                };
                points.push((x_of(&levels[0]), *s));
            } else if let Some(s) = share {
                points.push((x_of(&levels[0]), *s));
            }
        }
        if !points.is_empty() {
            series.push(crate::plot::Series {
                name,
                points,
                ..Default::default()
            });
        }
    }
    let title =
        format!(
        "model-form check: the share of {} combinations under which the switch sticks ({} mode){}",
        m.combinations.len(),
        m.accuracy,
        if picked.len() < n2 {
            format!("; {} of {n2} levels of the second field drawn", picked.len())
        } else {
            String::new()
        }
    );
    crate::plot::svg(
        &title,
        &[crate::plot::Panel {
            caption: format!(
                "{} of {} points keep their verdict under every combination",
                m.robust_points,
                m.share_sticking.iter().flatten().count()
            ),
            x_label,
            y_label: "share that sticks [-]".into(),
            series,
            x_range: None,
            y_range: Some((0.0, 1.0)),
            ..Default::default()
        }],
    )
}

impl Render for MapReport {
    fn table(&self) -> String {
        let mut s = map_table(&self.map, &self.labels);
        if let Some(l) = crate::switch::laws_line_of_echo(self.map.scene()) {
            let _ = writeln!(
                s,
                "{:<16}{} (the base scene's; a map axis may vary them)",
                "laws",
                l.trim_start_matches("laws: ")
            );
        }
        let invalid = self
            .map
            .points()
            .iter()
            .filter(|p| p.design.is_some_and(|d| !d.validity_holds))
            .count();
        if invalid > 0 {
            let _ = writeln!(
                s,
                "{:<16}{invalid} of {} points {} (validity_holds = false in map.csv)",
                "validity",
                self.map.points().len(),
                self.validity
                    .as_ref()
                    .map(|v| v.words())
                    .unwrap_or_else(|| "outside the model's validity".into())
            );
        }
        if let Some(m) = &self.model_form {
            let answered = m.share_sticking.iter().flatten().count();
            let _ = writeln!(
                s,
                "\nmodel form: {} of {answered} points keep their verdict under all {} combinations (others in {} mode); the share that sticks at each point is in model_form.json",
                m.robust_points,
                m.combinations.len(),
                m.accuracy
            );
            for e in &m.excluded {
                let _ = writeln!(s, "  left out: {} {}: {}", e.choice, e.value, e.reason);
            }
        }
        s
    }

    fn validity(&self) -> Option<&Validity> {
        self.validity.as_ref()
    }

    fn csv(&self) -> String {
        crate::csv::map_csv(&self.map).unwrap_or_default()
    }

    fn warnings(&self) -> &[Warning] {
        &self.warnings
    }
}
