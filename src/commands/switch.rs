//! `stiction switch`: the micro-switch cycle by cycle (the paper's Fig 4, the main job).

use super::Command;
use crate::accuracy::{Accuracy, Targets};
use crate::error::Error;
use crate::guards;
use crate::model;
use crate::plot::{self, Panel, Series};
use crate::progress::Progress;
use crate::render::{self, Format, OutputSet, Render, Warning};
use crate::scene::{self, Checker, Contact, Loaded, SwitchScene};
use asperity_plastic::FIT_RANGE_MAX;
use contact_core::{Path, SurfaceLaw};
use gw_surface::GwHistory;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::PathBuf;
use switch_1d::{
    CycleOptions, CycleRun, Impact, ImpactFilm, PressurePoint, Switch, SwitchGeometry,
};

/// The micro-switch cycle by cycle: d_e, pull-out pressure, accommodation, stiction.
#[derive(Debug, Clone, clap::Args)]
pub struct SwitchCommand {
    /// Scene file (TOML); the paper's switch if absent.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Number of cycles (replaces the scene's), 1..1000.
    #[arg(
        long,
        conflicts_with = "until_accommodated",
        allow_hyphen_values = true,
        value_parser = crate::scene::fields::count_option("cycles")
    )]
    pub cycles: Option<usize>,
    /// Run until accommodation is detected (at most the scene's cycles, or 1000).
    #[arg(long)]
    pub until_accommodated: bool,
    /// Accuracy mode (replaces the scene's).
    #[arg(long, value_enum)]
    pub accuracy: Option<Accuracy>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Write switch.json, cycles.csv, curves.csv and switch.svg to this folder (replaced as
    /// a whole; it may hold only those files).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

impl SwitchCommand {
    /// The main job: the paper's switch, written to out/.
    pub fn main_job() -> Self {
        Self {
            scene: None,
            cycles: None,
            until_accommodated: false,
            accuracy: None,
            format: Format::Table,
            out: Some(PathBuf::from("out")),
        }
    }
}

/// Which of K_s, U and E_I the scene gave and which were derived.
#[derive(Debug, Clone, Serialize)]
pub struct Drive {
    /// `impact_energy` (K_s derived at U = V_PI) or `spring` (E_I derived from K_s, U).
    pub mode: &'static str,
    /// Keys given by the scene.
    pub given: Vec<&'static str>,
    /// Quantities derived from them.
    pub derived: Vec<&'static str>,
}

/// The electrostatics of a scene, resolved from its drive.
#[derive(Debug, Clone, Serialize)]
pub struct Electrostatics {
    /// Spring stiffness per unit area K_s (Pa/m).
    pub k_s: f64,
    /// Static pull-in voltage V_PI (V).
    pub v_pull_in: f64,
    /// Dynamic pull-in voltage (V): the lowest step voltage that closes the switch.
    pub dynamic_pull_in_voltage: f64,
    /// The step voltage U (V).
    pub voltage: f64,
    /// Impact energy per electrode area E_I (J/m^2; 0 when the switch does not close).
    pub impact_energy: f64,
    /// Restoring pressure of the spring at contact, K_s d0 (Pa).
    pub restoring_pressure: f64,
    /// Whether the electrode reaches contact.
    pub closes: bool,
    /// Which were given and which derived.
    pub drive: Drive,
}

/// Resolves the drive of a validated switch scene: K_s, U, E_I, the pull-in voltages and
/// whether the switch closes. A derived impact energy is range-checked like a given one.
pub fn electrostatics(s: &SwitchScene, file: &str) -> Result<(Switch, Electrostatics), Error> {
    let g = &s.switch;
    let sw = Switch::new(SwitchGeometry {
        d0: g.d0,
        t_d: g.t_d,
        epsilon_r: g.epsilon_r,
        epsilon_0: g.epsilon_0,
    })?;
    let resolved = match (g.impact_energy, g.k_s) {
        (Some(e), _) => {
            let k = sw.stiffness_for_impact_energy(e)?;
            Electrostatics {
                k_s: k,
                v_pull_in: sw.pull_in_voltage(k),
                dynamic_pull_in_voltage: sw.dynamic_pull_in_voltage(k),
                voltage: sw.pull_in_voltage(k),
                impact_energy: e,
                restoring_pressure: sw.restoring_pressure(k),
                closes: true,
                drive: Drive {
                    mode: "impact_energy",
                    given: vec!["impact_energy"],
                    derived: vec!["k_s", "voltage (= V_PI)"],
                },
            }
        }
        (None, Some(k)) => {
            let u = g.voltage.unwrap_or_else(|| sw.pull_in_voltage(k));
            let closes = sw.closes(k, u);
            let e = if closes { sw.impact_energy(k, u) } else { 0.0 };
            if closes {
                let c = Checker::new(file);
                if !fields_contain("switch.impact_energy", e) {
                    return Err(c
                        .fail(
                            "switch.impact_energy",
                            format!(
                                "{} (derived from k_s = {} Pa/m and voltage = {} V)",
                                scene::num(e),
                                scene::num(k),
                                scene::num(u)
                            ),
                            scene::fields::field("switch.impact_energy")
                                .map(|f| f.domain.describe())
                                .unwrap_or_default(),
                        )
                        .into());
                }
            }
            let mut given = vec!["k_s"];
            let mut derived = vec!["impact_energy"];
            if g.voltage.is_some() {
                given.push("voltage");
            } else {
                derived.push("voltage (= V_PI)");
            }
            Electrostatics {
                k_s: k,
                v_pull_in: sw.pull_in_voltage(k),
                dynamic_pull_in_voltage: sw.dynamic_pull_in_voltage(k),
                voltage: u,
                impact_energy: e,
                restoring_pressure: sw.restoring_pressure(k),
                closes,
                drive: Drive {
                    mode: "spring",
                    given,
                    derived,
                },
            }
        }
        (None, None) => unreachable!("validated scenes have a drive"),
    };
    Ok((sw, resolved))
}

fn fields_contain(key: &str, v: f64) -> bool {
    scene::fields::field(key).is_some_and(|f| f.domain.contains(v))
}

/// One cycle.
#[derive(Debug, Clone, Serialize)]
pub struct CycleReport {
    /// 1-based.
    pub cycle: usize,
    /// End-of-impact separation (m).
    pub d_e: f64,
    /// Its error estimate (m).
    pub d_e_error: f64,
    /// Approach pressure at d_e (Pa, per contact area).
    pub contact_pressure: f64,
    /// Pull-out pressure (Pa, per contact area, >= 0).
    pub pull_out_pressure: f64,
    /// Its error estimate (Pa).
    pub pull_out_error: f64,
    /// Where (m).
    pub pull_out_separation: f64,
    /// phi pull-out / (K_s d0).
    pub pull_out_ratio: f64,
    /// Ratio above 1: the spring cannot open the switch.
    pub sticks: bool,
    /// Unloading curve (empty with points = 0).
    pub unloading: Vec<PressurePoint>,
}

/// The elastic comparison: the same surface with asperities that never yield, one cycle.
#[derive(Debug, Clone, Serialize)]
pub struct ElasticReport {
    /// End-of-impact separation (m).
    pub d_e: f64,
    /// Pull-out pressure (Pa).
    pub pull_out_pressure: f64,
    /// Where (m).
    pub pull_out_separation: f64,
    /// phi pull-out / (K_s d0).
    pub pull_out_ratio: f64,
    /// Ratio above 1.
    pub sticks: bool,
    /// Unloading curve.
    pub unloading: Vec<PressurePoint>,
}

/// Error estimates of the reported quantities.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct SwitchErrors {
    /// The largest d_e error estimate over the cycles (m).
    pub d_e: f64,
    /// The largest pull-out error estimate (Pa).
    pub pull_out: f64,
}

/// The laws a switch scene uses, for the table.
#[derive(Debug, Clone, Serialize)]
pub struct Laws {
    /// Adhesion law.
    pub adhesion: &'static str,
    /// Plasticity law.
    pub plasticity: &'static str,
    /// Reading of eq 1.
    pub yield_modulus: &'static str,
}

/// `stiction switch`.
#[derive(Debug, Clone, Serialize)]
pub struct SwitchReport {
    /// Plot and table title.
    pub title: String,
    /// The laws and the reading of eq 1.
    pub laws: Laws,
    /// Accuracy mode and targets.
    pub accuracy: Targets,
    /// Error estimates.
    pub error_estimate: SwitchErrors,
    /// Spring stiffness per unit area (Pa/m).
    pub k_s: f64,
    /// Static pull-in voltage (V).
    pub v_pull_in: f64,
    /// Dynamic pull-in voltage (V).
    pub dynamic_pull_in_voltage: f64,
    /// Step voltage (V).
    pub voltage: f64,
    /// Impact energy per electrode area (J/m^2).
    pub impact_energy: f64,
    /// K_s d0 (Pa).
    pub restoring_pressure: f64,
    /// Fraction of the electrode in contact.
    pub contact_area_fraction: f64,
    /// Whether the electrode reaches contact.
    pub closes: bool,
    /// What the scene gave and what was derived.
    pub drive: Drive,
    /// Relative change that counts as accommodated.
    pub accommodation_tolerance: f64,
    /// Virgin loading curve of cycle 1 (empty with points = 0).
    pub loading: Vec<PressurePoint>,
    /// The cycles (none when the switch does not close).
    pub cycles: Vec<CycleReport>,
    /// The elastic comparison.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub elastic: Option<ElasticReport>,
    /// The cycle after which nothing changes within the tolerance.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub accommodated_after: Option<usize>,
    /// The largest pull-out of all cycles (Pa).
    pub largest_pull_out: f64,
    /// phi largest pull-out / (K_s d0): above 1 the switch sticks.
    pub pull_out_ratio: f64,
    /// The first cycle that sticks.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_sticking_cycle: Option<usize>,
    /// Some cycle sticks.
    pub stiction: bool,
    /// Fraction of asperities (by count) loaded beyond delta_max/delta_CP = 110 after the
    /// last cycle.
    pub extrapolated_fraction: f64,
    /// Guards raised.
    pub warnings: Vec<Warning>,
    /// The resolved scene.
    pub scene: SwitchScene,
}

/// Runs a validated switch scene (`show_progress`: a bar on a terminal for long runs).
pub fn run(loaded: &Loaded<SwitchScene>, show_progress: bool) -> Result<SwitchReport, Error> {
    let s = &loaded.scene;
    let (_, es) = electrostatics(s, &loaded.file)?;
    let mut report = empty_report(loaded, &es);
    if !es.closes {
        return Ok(report);
    }
    let c = &s.contact;
    let phi = s.switch.contact_area_fraction;
    // a pressure error below 1e-9 K_s d0 (per electrode area) does not matter
    let floor = s.accuracy.targets().pull_out_floor_of_restoring * es.restoring_pressure / phi;
    let gw = model::surface(c, &s.surface, s.accuracy, floor, false)?;
    let impact = Impact {
        energy: es.impact_energy,
        film: ImpactFilm {
            thickness: s.switch.film_thickness,
            youngs_modulus: s.switch.film_youngs_modulus.unwrap_or(c.youngs_modulus),
        },
        contact_area_fraction: phi,
        restoring_pressure: es.restoring_pressure,
    };
    let options = CycleOptions {
        cycles: s.cycles,
        until_accommodated: s.until_accommodated,
        accommodation_tolerance: s.accommodation_tolerance,
        unloading_points: s.points,
        loading_points: s.points,
        precision: s.accuracy.precision(es.restoring_pressure / phi),
    };
    // the elastic comparison is independent of the cycles: both at once
    let (run, elastic) = contact_core::par::join(
        || {
            let mut progress = show_progress.then(|| Progress::new(s.cycles as u64, "cycles"));
            let run = switch_1d::run_cycles(&gw, gw.virgin(), impact, options, &mut |cy| {
                if let Some(p) = progress.as_mut() {
                    p.set(cy.cycle as u64);
                }
            });
            if let Some(p) = &progress {
                p.finish();
            }
            run
        },
        || {
            s.elastic_comparison
                .then(|| elastic_comparison(s, floor, impact, options))
                .transpose()
        },
    );
    let run = run?;
    report.elastic = elastic?;
    report.warnings = physics_guards(c, &gw, &run)?;
    let last = run.cycles.last().expect("at least one cycle");
    report.extrapolated_fraction = gw.fraction_beyond(&last.history, FIT_RANGE_MAX);
    record(&mut report, run);
    Ok(report)
}

/// The report of a scene before any cycle: the laws, the drive, the targets.
fn empty_report(loaded: &Loaded<SwitchScene>, es: &Electrostatics) -> SwitchReport {
    let s = &loaded.scene;
    let c = &s.contact;
    SwitchReport {
        title: loaded.title(),
        laws: Laws {
            adhesion: model::adhesion_name(c.adhesion_law),
            plasticity: model::plasticity_name(c.plasticity_law),
            yield_modulus: c.yield_modulus().as_str(),
        },
        accuracy: s.accuracy.targets(),
        error_estimate: SwitchErrors {
            d_e: 0.0,
            pull_out: 0.0,
        },
        k_s: es.k_s,
        v_pull_in: es.v_pull_in,
        dynamic_pull_in_voltage: es.dynamic_pull_in_voltage,
        voltage: es.voltage,
        impact_energy: es.impact_energy,
        restoring_pressure: es.restoring_pressure,
        contact_area_fraction: s.switch.contact_area_fraction,
        closes: es.closes,
        drive: es.drive.clone(),
        accommodation_tolerance: s.accommodation_tolerance,
        loading: Vec::new(),
        cycles: Vec::new(),
        elastic: None,
        accommodated_after: None,
        largest_pull_out: 0.0,
        pull_out_ratio: 0.0,
        first_sticking_cycle: None,
        stiction: false,
        extrapolated_fraction: 0.0,
        warnings: Vec::new(),
        scene: s.clone(),
    }
}

/// The same surface with asperities that never yield, one cycle through `run_cycles`.
fn elastic_comparison(
    s: &SwitchScene,
    floor: f64,
    impact: Impact,
    options: CycleOptions,
) -> Result<ElasticReport, Error> {
    let el = model::surface(&s.contact, &s.surface, s.accuracy, floor, true)?;
    let one = CycleOptions {
        cycles: 1,
        loading_points: 0,
        ..options
    };
    let e = switch_1d::run_cycles(&el, el.virgin(), impact, one, &mut |_| {})?;
    let cy = &e.cycles[0];
    Ok(ElasticReport {
        d_e: cy.d_e(),
        pull_out_pressure: cy.unloading.pull_out_pressure,
        pull_out_separation: cy.unloading.pull_out_separation,
        pull_out_ratio: cy.pull_out_ratio,
        sticks: cy.sticks,
        unloading: cy.unloading.curve.clone(),
    })
}

/// The guards of a run: the load beyond the fits at the deepest end of impact (with the
/// history before that cycle), adhesion that yields a virgin asperity, pressures above the
/// hardness or the interface's strength.
fn physics_guards(
    c: &Contact,
    gw: &model::RoughSurface,
    run: &CycleRun<GwHistory>,
) -> Result<Vec<Warning>, Error> {
    let mut warnings = Vec::new();
    let deepest = run
        .cycles
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.d_e().total_cmp(&b.1.d_e()))
        .map(|(i, _)| i)
        .unwrap_or(0);
    let before = if deepest == 0 {
        gw.virgin()
    } else {
        run.cycles[deepest - 1].history.clone()
    };
    let at = run.cycles[deepest].d_e();
    let share = gw.load_share_beyond(at, &before, Path::Approach, FIT_RANGE_MAX)?;
    warnings.extend(guards::surface_beyond_fit(share, at));
    let plastic = model::asperity(c, false)?;
    let elastic = model::asperity(c, true)?;
    warnings.extend(guards::adhesion_yields(c, &plastic, &elastic)?);
    let compressive = run
        .cycles
        .iter()
        .map(|cy| cy.end.pressure)
        .fold(0.0, f64::max);
    warnings.extend(guards::pressure_above_hardness(
        c,
        compressive,
        run.largest_pull_out,
    ));
    Ok(warnings)
}

/// The cycles, the verdict and the error estimates of a run, into the report.
fn record(report: &mut SwitchReport, run: CycleRun<GwHistory>) {
    report.error_estimate = SwitchErrors {
        d_e: run.cycles.iter().map(|cy| cy.end.error).fold(0.0, f64::max),
        pull_out: run
            .cycles
            .iter()
            .map(|cy| cy.unloading.pull_out_error)
            .fold(0.0, f64::max),
    };
    report.cycles = run
        .cycles
        .iter()
        .map(|cy| CycleReport {
            cycle: cy.cycle,
            d_e: cy.d_e(),
            d_e_error: cy.end.error,
            contact_pressure: cy.end.pressure,
            pull_out_pressure: cy.unloading.pull_out_pressure,
            pull_out_error: cy.unloading.pull_out_error,
            pull_out_separation: cy.unloading.pull_out_separation,
            pull_out_ratio: cy.pull_out_ratio,
            sticks: cy.sticks,
            unloading: cy.unloading.curve.clone(),
        })
        .collect();
    report.loading = run.loading;
    report.accommodated_after = run.accommodated_after;
    report.largest_pull_out = run.largest_pull_out;
    report.pull_out_ratio = run.pull_out_ratio;
    report.first_sticking_cycle = run.first_sticking_cycle;
    report.stiction = run.stiction;
}

/// The files `--out` writes.
pub const FILES: &[&str] = &["switch.json", "cycles.csv", "curves.csv", "switch.svg"];

impl Command for SwitchCommand {
    type Scene = SwitchScene;
    type Report = SwitchReport;

    fn scene_path(&self) -> Option<&std::path::Path> {
        self.scene.as_deref()
    }

    fn apply(&self, scene: &mut SwitchScene) -> Result<(), Error> {
        if let Some(n) = self.cycles {
            scene.cycles = n;
        }
        if self.until_accommodated {
            scene.until_accommodated = true;
            if self.scene.is_none() && self.cycles.is_none() {
                scene.cycles = 1000;
            }
        }
        if let Some(a) = self.accuracy {
            scene.accuracy = a;
        }
        Ok(())
    }

    fn overrides(&self) -> Vec<(&'static str, &'static str)> {
        match self.cycles {
            Some(_) => vec![("cycles", "--cycles")],
            None => vec![],
        }
    }

    fn run(&self, loaded: &Loaded<SwitchScene>) -> Result<SwitchReport, Error> {
        run(loaded, true)
    }

    fn outputs(&self, r: &SwitchReport) -> Result<Option<OutputSet>, Error> {
        let Some(dir) = &self.out else {
            return Ok(None);
        };
        let mut set = OutputSet::new(dir, FILES);
        set.add("switch.json", render::json(r));
        set.add("cycles.csv", r.csv());
        set.add("curves.csv", curves_csv(r));
        if !r.loading.is_empty() {
            let svg = plot_svg(r).map_err(|message| Error::Plot {
                path: dir.join("switch.svg").display().to_string(),
                message,
            })?;
            set.add("switch.svg", svg);
        }
        Ok(Some(set))
    }

    fn format(&self) -> Format {
        self.format
    }
}

/// Every curve in long form.
pub fn curves_csv(r: &SwitchReport) -> String {
    let mut s = String::from("curve,cycle,d_m,pressure_pa\n");
    for p in &r.loading {
        let _ = writeln!(s, "loading,1,{},{}", p.d, p.pressure);
    }
    for c in &r.cycles {
        for p in &c.unloading {
            let _ = writeln!(s, "unloading,{},{},{}", c.cycle, p.d, p.pressure);
        }
    }
    if let Some(e) = &r.elastic {
        for p in &e.unloading {
            let _ = writeln!(s, "elastic_unloading,,{},{}", p.d, p.pressure);
        }
    }
    s
}

/// Like the paper's Fig 4: loading, unloading of cycles 1, 2, 3 and the last, elastic;
/// the whole curves above, the adhesive well below.
pub fn plot_svg(r: &SwitchReport) -> Result<String, String> {
    let pts = |v: &[PressurePoint]| -> Vec<(f64, f64)> {
        v.iter().map(|p| (p.d * 1e9, p.pressure * 1e-6)).collect()
    };
    let mut series = vec![Series {
        name: "loading (cycle 1)".into(),
        points: pts(&r.loading),
    }];
    let last = r.cycles.last().map_or(0, |c| c.cycle);
    for c in &r.cycles {
        if [1, 2, 3, last].contains(&c.cycle) {
            series.push(Series {
                name: format!("unloading, cycle {}", c.cycle),
                points: pts(&c.unloading),
            });
        }
    }
    if let Some(e) = &r.elastic {
        series.push(Series {
            name: "unloading, elastic asperities".into(),
            points: pts(&e.unloading),
        });
    }
    let restoring = -r.restoring_pressure / r.contact_area_fraction * 1e-6;
    let (x0, x1) = r
        .loading
        .iter()
        .chain(r.cycles.iter().flat_map(|c| c.unloading.iter()))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.d * 1e9), b.max(p.d * 1e9))
        });
    series.push(Series {
        name: "- restoring pressure K_s d0 / phi".into(),
        points: vec![(x0, restoring), (x1, restoring)],
    });
    let well = r
        .largest_pull_out
        .max(r.restoring_pressure / r.contact_area_fraction)
        * 1e-6;
    let caption = format!(
        "{} adhesion, eq 1 {}, K_s = {:.4e} Pa/m, E_I = {:.4} J/m^2",
        r.laws.adhesion, r.laws.yield_modulus, r.k_s, r.impact_energy
    );
    // the zoom spans the wells: from the deepest d_e to twice the farthest pull-out
    let farthest = r
        .cycles
        .iter()
        .map(|c| c.pull_out_separation * 1e9)
        .fold(x0, f64::max);
    let zoom_x = (x0, (x0 + 2.5 * (farthest - x0)).min(x1).max(x0 + 1e-9));
    plot::svg(
        &r.title,
        &[
            Panel {
                caption,
                x_label: "separation d [nm]".into(),
                y_label: "pressure [MPa]".into(),
                series: series.clone(),
                x_range: Some((x0, x1)),
                y_range: None,
            },
            Panel {
                caption: "adhesive well (pull-out against the spring)".into(),
                x_label: "separation d [nm]".into(),
                y_label: "pressure [MPa]".into(),
                series,
                x_range: Some(zoom_x),
                y_range: Some((-1.6 * well, 1.0 * well)),
            },
        ],
    )
}

impl Render for SwitchReport {
    fn table(&self) -> String {
        let mut s = self.table_header();
        if !self.closes {
            let _ = writeln!(
                s,
                "\nverdict: the switch does not close: U = {:.4} V is below the dynamic pull-in voltage {:.4} V (released from rest under a step voltage, the electrode meets an energy barrier before contact); no stiction",
                self.voltage, self.dynamic_pull_in_voltage
            );
            return s;
        }
        s += &self.table_cycles();
        s += &self.table_verdict();
        s
    }

    fn csv(&self) -> String {
        self.cycles_csv()
    }

    fn warnings(&self) -> &[Warning] {
        self.report_warnings()
    }
}

impl SwitchReport {
    /// Title, laws and accuracy, drive, restoring pressure.
    fn table_header(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{}", self.title);
        let _ = writeln!(
            s,
            "laws: {} adhesion, {} plasticity, eq 1 {} (yield_modulus); accuracy {} (d_e to {:e} sigma_s, pull-out to {:e})",
            self.laws.adhesion,
            self.laws.plasticity,
            self.laws.yield_modulus,
            self.accuracy.mode,
            self.accuracy.d_e_tolerance_sigma,
            self.accuracy.pull_out_tolerance
        );
        let mark = |key: &str| {
            if self.drive.given.contains(&key) {
                "given"
            } else {
                "derived"
            }
        };
        let _ = writeln!(
            s,
            "drive: K_s = {:.5e} Pa/m ({}), U = {} V ({}), E_I = {} J/m^2 ({}); V_PI = {} V, dynamic pull-in {} V",
            self.k_s,
            mark("k_s"),
            format_args!("{:.4}", self.voltage),
            mark("voltage"),
            scene::num(self.impact_energy),
            mark("impact_energy"),
            format_args!("{:.4}", self.v_pull_in),
            format_args!("{:.4}", self.dynamic_pull_in_voltage),
        );
        let _ = writeln!(
            s,
            "restoring pressure K_s d0 = {}; contact on {}",
            render::pressure(self.restoring_pressure),
            if self.contact_area_fraction == 1.0 {
                "the whole electrode (phi = 1)".to_string()
            } else {
                format!(
                    "a fraction phi = {} of the electrode",
                    self.contact_area_fraction
                )
            }
        );
        s
    }

    /// One row per cycle, and the elastic comparison.
    fn table_cycles(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s);
        let _ = writeln!(
            s,
            "{:>8} {:>12} {:>14} {:>12} {:>8} {:>10}",
            "cycle", "d_e", "pull-out", "change [%]", "ratio", "verdict"
        );
        let mut prev: Option<f64> = None;
        for c in &self.cycles {
            let change = prev.map_or("-".to_string(), |p| {
                if p == 0.0 {
                    "-".to_string()
                } else {
                    format!("{:+.4}", 100.0 * (c.pull_out_pressure - p) / p)
                }
            });
            let _ = writeln!(
                s,
                "{:>8} {:>12} {:>14} {:>12} {:>8.4} {:>10}",
                c.cycle,
                render::si(c.d_e, "m", 6),
                render::pressure(c.pull_out_pressure),
                change,
                c.pull_out_ratio,
                if c.sticks { "sticks" } else { "releases" }
            );
            prev = Some(c.pull_out_pressure);
        }
        if let Some(e) = &self.elastic {
            let _ = writeln!(
                s,
                "{:>8} {:>12} {:>14} {:>12} {:>8.2e} {:>10}",
                "elastic",
                render::si(e.d_e, "m", 6),
                render::pressure(e.pull_out_pressure),
                "-",
                e.pull_out_ratio,
                if e.sticks { "sticks" } else { "releases" }
            );
        }
        s
    }

    /// Accommodation, the verdict and the error estimates.
    fn table_verdict(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s);
        match self.accommodated_after {
            Some(k) => {
                let _ = writeln!(
                    s,
                    "accommodated after cycle {k} (next cycle changes by < {:e})",
                    self.accommodation_tolerance
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "not accommodated within {} cycles (tolerance {:e})",
                    self.cycles.len(),
                    self.accommodation_tolerance
                );
            }
        }
        let _ = writeln!(
            s,
            "verdict: {} (pull-out ratio {:.4}: largest pull-out {} x {} of the area vs restoring {})",
            if self.stiction {
                "STICTION - the spring cannot pull the switch open"
            } else {
                "no stiction - the spring opens the switch"
            },
            self.pull_out_ratio,
            render::pressure(self.largest_pull_out),
            self.contact_area_fraction,
            render::pressure(self.restoring_pressure)
        );
        let _ = writeln!(
            s,
            "error estimates: d_e {}, pull-out {}",
            render::si(self.error_estimate.d_e, "m", 2),
            render::pressure(self.error_estimate.pull_out)
        );
        s
    }

    /// The cycles as CSV (and the elastic comparison as a row `elastic`).
    fn cycles_csv(&self) -> String {
        let mut s = String::from(
            "cycle,d_e_m,pull_out_pressure_pa,pull_out_separation_m,sticks,pull_out_ratio\n",
        );
        for c in &self.cycles {
            let _ = writeln!(
                s,
                "{},{},{},{},{},{}",
                c.cycle,
                c.d_e,
                c.pull_out_pressure,
                c.pull_out_separation,
                c.sticks,
                c.pull_out_ratio
            );
        }
        if let Some(e) = &self.elastic {
            let _ = writeln!(
                s,
                "elastic,{},{},{},{},{}",
                e.d_e, e.pull_out_pressure, e.pull_out_separation, e.sticks, e.pull_out_ratio
            );
        }
        s
    }

    fn report_warnings(&self) -> &[Warning] {
        &self.warnings
    }
}
