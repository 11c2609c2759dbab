//! The micro-switch's result (`stiction switch`, the main job): its table, the CSV of its
//! cycles and curves, its plots; `--out` writes switch.json, cycles.csv, curves.csv,
//! switch.svg and (in time) dynamics.svg.

use crate::output::OutputSet;
use crate::plot::{self, Panel, Series};
use crate::render::{self, csv_num, Render, Validity, Warning};
use crate::{Plot, Report, ReportError};
use std::fmt::Write as _;
use std::path::Path;
use stiction_model::keys::num;
use stiction_model::model_form::ModelFormReport;
use stiction_model::switch::SwitchResult;
use stiction_model::switch_1d::PressurePoint;

/// The files `--out` writes.
const FILES: &[&str] = &[
    "switch.json",
    "cycles.csv",
    "curves.csv",
    "switch.svg",
    "dynamics.svg",
];

/// Every curve in long form.
pub fn curves_csv(r: &SwitchResult) -> String {
    let mut s = String::from("curve,cycle,d_m,pressure_pa\n");
    for p in &r.loading {
        let _ = writeln!(s, "loading,1,{},{}", csv_num(p.d), csv_num(p.pressure));
    }
    for c in &r.cycles {
        for p in &c.unloading {
            let _ = writeln!(
                s,
                "unloading,{},{},{}",
                c.cycle,
                csv_num(p.d),
                csv_num(p.pressure)
            );
        }
    }
    if let Some(e) = &r.elastic {
        for p in &e.unloading {
            let _ = writeln!(
                s,
                "elastic_unloading,,{},{}",
                csv_num(p.d),
                csv_num(p.pressure)
            );
        }
    }
    s
}

/// The switch in time (a `[dynamics]` section with curves): the first closure's
/// displacement and contact pressure against time, and each cycle's impact energy and
/// bounces. None for a quasi-static run or without curves (`points = 0`).
fn plot_dynamics_svg(r: &SwitchResult) -> Option<Result<String, String>> {
    let d = r.dynamics.as_ref()?;
    if d.trace.is_empty() {
        return None;
    }
    let t = |p: &stiction_model::switch_dynamics::TracePoint| p.t * 1e6;
    let cycles =
        |f: &dyn Fn(&stiction_model::switch::CycleResult) -> Option<f64>| -> Vec<(f64, f64)> {
            r.cycles
                .iter()
                .filter_map(|c| f(c).map(|v| (c.cycle as f64, v)))
                .collect()
        };
    let n = r.cycles.len() as f64;
    let panels = vec![
        Panel {
            caption: format!(
                "cycle 1: the flight, the impact and {} bounce(s), m'' = {:.4e} kg/m^2, gas {} Pa",
                r.cycles[0].bounces.unwrap_or(0),
                d.areal_mass,
                d.gas_pressure
            ),
            x_label: "time [us]".into(),
            y_label: "displacement [um]".into(),
            series: vec![Series {
                name: "displacement toward the substrate".into(),
                points: d
                    .trace
                    .iter()
                    .map(|p| (t(p), p.displacement * 1e6))
                    .collect(),
                ..Default::default()
            }],
            x_range: None,
            y_range: None,
            ..Default::default()
        },
        Panel {
            caption: "cycle 1: the contact pressure (per contact area)".into(),
            x_label: "time [us]".into(),
            y_label: "contact pressure [MPa]".into(),
            series: vec![Series {
                name: "contact pressure".into(),
                points: d
                    .trace
                    .iter()
                    .map(|p| (t(p), p.contact_pressure * 1e-6))
                    .collect(),
                ..Default::default()
            }],
            x_range: None,
            y_range: None,
            ..Default::default()
        },
        Panel {
            caption: "kinetic energy where each closure's contact begins".into(),
            x_label: "cycle [count]".into(),
            y_label: "impact energy [J/m^2]".into(),
            series: vec![Series {
                name: "impact energy (per electrode area)".into(),
                points: cycles(&|c| c.impact.map(|i| i.energy)),
                ..Default::default()
            }],
            x_range: Some((0.5, n + 0.5)),
            y_range: None,
            ..Default::default()
        },
        Panel {
            caption: "bounces per closure".into(),
            x_label: "cycle [count]".into(),
            y_label: "bounces [count]".into(),
            series: vec![Series {
                name: "bounces".into(),
                points: cycles(&|c| c.bounces.map(|b| b as f64)),
                ..Default::default()
            }],
            x_range: Some((0.5, n + 0.5)),
            y_range: None,
            ..Default::default()
        },
    ];
    Some(crate::plot::svg(&format!("{}: in time", r.title), &panels))
}

/// The cycles a plot draws: 1, 2, 3, the first that sticks, the one accommodation stops
/// at, and the last.
fn drawn_cycles(r: &SwitchResult) -> Vec<usize> {
    let last = r.cycles.last().map_or(0, |c| c.cycle);
    let mut picks = vec![1, 2, 3, last];
    picks.extend(r.first_sticking_cycle);
    picks.extend(r.accommodated_after);
    picks.retain(|&k| k >= 1 && k <= last);
    picks.sort_unstable();
    picks.dedup();
    picks
}

/// Like the paper's Fig 4: loading, unloading of cycles 1, 2, 3, the first sticking one
/// and the last, elastic; the whole curves above, the adhesive wells (sampled on their
/// own, with their minima) below.
fn plot_svg(r: &SwitchResult) -> Result<String, String> {
    let pts = |v: &[PressurePoint]| -> Vec<(f64, f64)> {
        v.iter().map(|p| (p.d * 1e9, p.pressure * 1e-6)).collect()
    };
    let picks = drawn_cycles(r);
    let label = |k: usize| {
        let mut l = format!("cycle {k}");
        if Some(k) == r.first_sticking_cycle {
            l += " (first to stick)";
        }
        if Some(k) == r.accommodated_after {
            l += " (accommodated)";
        }
        l
    };
    // one colour per drawn cycle, the same in both panels; the loading black, the
    // elastic reference and the spring after the cycles
    let colour = |k: usize| {
        let i = picks.iter().position(|&p| p == k).unwrap_or(0);
        plot::SERIES[(1 + i) % plot::SERIES.len()]
    };
    let mut whole = vec![Series {
        name: "loading (cycle 1)".into(),
        points: pts(&r.loading),
        colour: Some(plot::SERIES[0]),
    }];
    let mut wells = Vec::new();
    for c in r.cycles.iter().filter(|c| picks.contains(&c.cycle)) {
        whole.push(Series {
            name: format!("unloading, {}", label(c.cycle)),
            points: pts(&c.unloading),
            colour: Some(colour(c.cycle)),
        });
        wells.push(Series {
            name: format!("unloading, {}", label(c.cycle)),
            points: pts(if c.well.is_empty() {
                &c.unloading
            } else {
                &c.well
            }),
            colour: Some(colour(c.cycle)),
        });
    }
    let after = |k: usize| Some(plot::SERIES[(1 + picks.len() + k) % plot::SERIES.len()]);
    if let Some(e) = &r.elastic {
        let s = Series {
            name: "unloading, elastic asperities".into(),
            points: pts(&e.unloading),
            colour: after(0),
        };
        whole.push(s.clone());
        wells.push(s);
    }
    let restoring = -r.restoring_pressure / r.contact_area_fraction * 1e-6;
    let (x0, x1) = r
        .loading
        .iter()
        .chain(r.cycles.iter().flat_map(|c| c.unloading.iter()))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.d * 1e9), b.max(p.d * 1e9))
        });
    let spring = Series {
        name: "- restoring pressure K_s d0 / phi".into(),
        points: vec![(x0, restoring), (x1, restoring)],
        colour: after(1),
    };
    whole.push(spring.clone());
    wells.push(spring);
    let well = r
        .largest_pull_out
        .max(r.restoring_pressure / r.contact_area_fraction)
        * 1e-6;
    let caption = format!(
        "{} adhesion, {} plasticity, eq 1 {}, reload {}; K_s = {:.4e} Pa/m, E_I = {:.4} J/m^2",
        r.laws.adhesion,
        r.laws.plasticity,
        r.laws.yield_modulus,
        r.laws.reload,
        r.k_s,
        r.impact_energy
    );
    // the zoom spans the wells: from the deepest d_e to 2.5 times the farthest pull-out
    let farthest = r
        .cycles
        .iter()
        .map(|c| c.pull_out_separation * 1e9)
        .fold(x0, f64::max);
    let zoom_x = (x0, (x0 + 2.5 * (farthest - x0)).min(x1).max(x0 + 1e-9));
    let mut panels = vec![
        Panel {
            caption,
            x_label: "separation d [nm]".into(),
            y_label: "pressure [MPa]".into(),
            series: whole,
            x_range: Some((x0, x1)),
            y_range: None,
            ..Default::default()
        },
        Panel {
            caption: format!(
                "adhesive well (pull-out against the spring){}",
                if r.validity.holds {
                    String::new()
                } else {
                    format!("; {}", r.validity.words())
                }
            ),
            x_label: "separation d [nm]".into(),
            y_label: "pressure [MPa]".into(),
            series: wells,
            x_range: Some(zoom_x),
            y_range: Some((-1.6 * well, 1.0 * well)),
            ..Default::default()
        },
    ];
    panels.extend(contact_panels(r));
    plot::svg(&r.title, &panels)
}

/// The hold as the scene gave it: a force (N) when `hold_force` was given, else the
/// voltage (V).
fn hold_words(r: &SwitchResult) -> String {
    match r.hold_force {
        Some(f) => format!("{} N", crate::plot::map::fmt_sig(f, 4)),
        None => format!("{:.4} V", r.hold_voltage),
    }
}

/// The contact against cycle: real contact area (and, with conduction, the contact
/// resistance) under the hold voltage and at the end of impact. None without states.
fn contact_panels(r: &SwitchResult) -> Vec<Panel> {
    type Pick = fn(&stiction_model::switch::ContactState) -> Option<f64>;
    let series = |name: &str, pick: Pick, scale: f64| -> Vec<Series> {
        let hold: Vec<(f64, f64)> = r
            .cycles
            .iter()
            .filter_map(|c| Some((c.cycle as f64, pick(c.hold.as_ref()?)? * scale)))
            .collect();
        let end: Vec<(f64, f64)> = r
            .cycles
            .iter()
            .filter_map(|c| Some((c.cycle as f64, pick(c.end_of_impact.as_ref()?)? * scale)))
            .collect();
        [
            (format!("{name} under the hold ({})", hold_words(r)), hold),
            (format!("{name} at the end of impact"), end),
        ]
        .into_iter()
        .filter(|(_, p)| !p.is_empty())
        .map(|(name, points)| Series {
            name,
            points,
            ..Default::default()
        })
        .collect()
    };
    let last = r.cycles.last().map_or(1.0, |c| c.cycle as f64);
    let x_range = Some((0.5, last + 0.5));
    let mut out = Vec::new();
    let mut area = series("A_r / A", |c| Some(c.real_contact_fraction), 100.0);
    if !area.is_empty() {
        // more real contact than contact area is impossible: flagged, with the 100 % line
        let most = area
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .fold(f64::NEG_INFINITY, f64::max);
        let mut flags = Vec::new();
        if most > 100.0 {
            flags.push(format!(
                "IMPOSSIBLE: A_r / A reaches {} %, more real contact than contact area: \
                 the model is outside its validity here",
                crate::plot::map::fmt_sig(most, 3)
            ));
            area.push(Series {
                name: "A_r = A (100 %): above is impossible".into(),
                points: vec![(0.5, 100.0), (last + 0.5, 100.0)],
                colour: Some(plot::REFERENCE),
            });
        }
        out.push(Panel {
            flags,
            caption: "real contact area against cycle".into(),
            x_label: "cycle [count]".into(),
            y_label: "real contact area [% of the contact area]".into(),
            series: area,
            x_range,
            y_range: None,
            ..Default::default()
        });
    }
    let resistance = series("R", |c| c.contact_resistance, 1e3);
    if !resistance.is_empty() {
        out.push(Panel {
            caption: "contact resistance against cycle (spots in parallel, Holm-Sharvin)".into(),
            x_label: "cycle [count]".into(),
            y_label: "contact resistance [mOhm]".into(),
            series: resistance,
            x_range,
            y_range: None,
            ..Default::default()
        });
    }
    out
}

impl Render for SwitchResult {
    fn table(&self) -> String {
        let mut s = table_header(self);
        if !self.closes {
            if self
                .warnings
                .iter()
                .any(|w| w.code == stiction_model::guards::code::DOES_NOT_CLOSE)
            {
                // in time, the gas and the spring stopped it (warning does_not_close)
                let _ = writeln!(
                    s,
                    "\nverdict: the switch does not close: in time the squeeze film and the spring stop the electrode short of the contact at U = {:.4} V (above the vacuum's dynamic pull-in voltage {:.4} V); no stiction",
                    self.voltage, self.dynamic_pull_in_voltage
                );
                return s;
            }
            let _ = writeln!(
                s,
                "\nverdict: the switch does not close: U = {:.4} V is below the dynamic pull-in voltage {:.4} V (released from rest under a step voltage, the electrode meets an energy barrier before contact); no stiction",
                self.voltage, self.dynamic_pull_in_voltage
            );
            return s;
        }
        s += &table_cycles(self);
        s += &table_dynamics(self);
        s += &table_contact(self);
        s += &table_verdict(self);
        if let Some(m) = &self.model_form {
            s += &table_model_form(m);
        }
        s
    }

    fn csv(&self) -> String {
        let mut s = String::from(
            "cycle,d_e_m,pull_out_pressure_pa,pull_out_separation_m,sticks,pull_out_ratio,deepened,hold_status,hold_separation_m,hold_real_contact_fraction,hold_spot_density_per_m2,hold_mean_spot_radius_m,hold_contact_resistance_ohm,end_real_contact_fraction,end_spot_density_per_m2,end_mean_spot_radius_m,end_contact_resistance_ohm\n",
        );
        let opt = |v: Option<f64>| v.map_or(String::new(), csv_num);
        for c in &self.cycles {
            let h = c.hold.as_ref();
            let e = c.end_of_impact.as_ref();
            let _ = writeln!(
                s,
                "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                c.cycle,
                csv_num(c.d_e),
                csv_num(c.pull_out_pressure),
                csv_num(c.pull_out_separation),
                c.sticks,
                csv_num(c.pull_out_ratio),
                c.deepened,
                c.hold_status,
                opt(h.map(|h| h.separation)),
                opt(h.map(|h| h.real_contact_fraction)),
                opt(h.map(|h| h.spot_density)),
                opt(h.map(|h| h.mean_spot_radius)),
                opt(h.and_then(|h| h.contact_resistance)),
                opt(e.map(|e| e.real_contact_fraction)),
                opt(e.map(|e| e.spot_density)),
                opt(e.map(|e| e.mean_spot_radius)),
                opt(e.and_then(|e| e.contact_resistance)),
            );
        }
        if let Some(e) = &self.elastic {
            // the elastic comparison has no hold or contact state: its row is as wide as
            // the header, the cells it has not empty
            let fields = s.lines().next().map_or(0, |h| h.split(',').count());
            let row = format!(
                "elastic,{},{},{},{},{}",
                csv_num(e.d_e),
                csv_num(e.pull_out_pressure),
                csv_num(e.pull_out_separation),
                e.sticks,
                csv_num(e.pull_out_ratio)
            );
            let pad = fields.saturating_sub(row.split(',').count());
            let _ = writeln!(s, "{row}{}", ",".repeat(pad));
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

/// "laws: ... adhesion, ... plasticity, eq 1 ..., reload ..."
pub fn laws_line(l: &stiction_model::switch::Laws) -> String {
    format!(
        "laws: {} adhesion, {} plasticity, eq 1 {} (yield_modulus), reload {}",
        l.adhesion, l.plasticity, l.yield_modulus, l.reload
    )
}

/// The laws line of a resolved scene echo (a map's or a probability run's `scene`), when
/// the echo has the contact's four choices.
pub fn laws_line_of_echo(scene: &serde_json::Value) -> Option<String> {
    laws_of_echo(scene).map(|l| laws_line(&l))
}

/// The laws and modelling choices a resolved scene echo states (its contact section),
/// when it has all four.
pub fn laws_of_echo(scene: &serde_json::Value) -> Option<stiction_model::switch::Laws> {
    let c = scene.get("contact")?;
    let word = |k: &str| c.get(k).and_then(|v| v.as_str()).map(str::to_owned);
    Some(stiction_model::switch::Laws {
        adhesion: word("adhesion_law")?,
        plasticity: word("plasticity_law")?,
        yield_modulus: static_word(&word("yield_modulus")?, &["as_printed", "composite"])?,
        reload: static_word(&word("reload")?, &["as_printed", "bounded"])?,
    })
}

/// `w` as the one of `words` it equals.
fn static_word(w: &str, words: &[&'static str]) -> Option<&'static str> {
    words.iter().copied().find(|&x| x == w)
}

/// A pull-out ratio for tables: four decimals, scientific notation beyond 1e4.
fn ratio_text(r: f64) -> String {
    if r.abs() >= 1e4 {
        format!("{r:.4e}")
    } else {
        format!("{r:.4}")
    }
}

/// Title, laws and accuracy, drive, restoring pressure.
/// The switch in time (a `[dynamics]` section): each closure's impact, bounces, capture,
/// energy ledger and release.
fn table_dynamics(r: &SwitchResult) -> String {
    let Some(d) = &r.dynamics else {
        return String::new();
    };
    let si = stiction_model::guards::si;
    let mut s = format!(
        "\nin time: m'' = {:.4e} kg/m^2, f0 = {}, gas {} (squeeze film at contact c'' = {}), integration tolerance {:.0e}\n",
        d.areal_mass,
        si(d.natural_frequency, "Hz", 4),
        if d.gas_pressure > 0.0 {
            si(d.gas_pressure, "Pa", 4)
        } else {
            "none (vacuum)".to_string()
        },
        si(d.squeeze_film_coefficient_at_contact, "Pa s/m", 4),
        d.tolerance,
    );
    let _ = writeln!(
        s,
        "   cycle    impact v   impact E [J/m^2]      flight   bounces     capture   ledger residual   release"
    );
    for c in &r.cycles {
        let (Some(i), Some(l), Some(rel)) = (&c.impact, &c.energy_ledger, &c.release) else {
            continue;
        };
        let release = match rel.opening_time {
            Some(t) => format!("opens in {}", si(t, "s", 4)),
            None => "held".to_string(),
        };
        let _ = writeln!(
            s,
            "{:>8} {:>11} {:>18.6e} {:>11} {:>9} {:>11} {:>17.2e}   {release}",
            c.cycle,
            si(i.velocity, "m/s", 4),
            i.energy,
            si(i.flight_time, "s", 4),
            c.bounces.unwrap_or(0),
            si(c.capture_time.unwrap_or(0.0), "s", 4),
            l.residual,
        );
    }
    s
}

fn table_header(r: &SwitchResult) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{}", r.title);
    let _ = writeln!(
        s,
        "{}; accuracy {} (d_e to {:e} sigma_s, pull-out to {:e})",
        laws_line(&r.laws),
        r.accuracy.mode,
        r.accuracy.d_e_tolerance_sigma,
        r.accuracy.pull_out_tolerance
    );
    let mark = |key: &str| {
        if r.drive.given.contains(&key) {
            "given"
        } else {
            "derived"
        }
    };
    let _ = writeln!(
        s,
        "drive: K_s = {:.5e} Pa/m ({}), U = {} V ({}), E_I = {} J/m^2 ({}); V_PI = {} V, dynamic pull-in {} V",
        r.k_s,
        mark("k_s"),
        format_args!("{:.4}", r.voltage),
        mark("voltage"),
        // a derived energy to six digits (the given one as given)
        if mark("impact_energy") == "derived" {
            num(format!("{:.5e}", r.impact_energy)
                .parse()
                .unwrap_or(r.impact_energy))
        } else {
            num(r.impact_energy)
        },
        mark("impact_energy"),
        format_args!("{:.4}", r.v_pull_in),
        format_args!("{:.4}", r.dynamic_pull_in_voltage),
    );
    let _ = writeln!(
        s,
        "restoring pressure K_s d0 = {}; contact on {}",
        render::pressure(r.restoring_pressure),
        if r.contact_area_fraction == 1.0 {
            "the whole electrode (phi = 1)".to_string()
        } else {
            format!(
                "a fraction phi = {} of the electrode",
                r.contact_area_fraction
            )
        }
    );
    s
}

/// One row per cycle, and the elastic comparison.
fn table_cycles(r: &SwitchResult) -> String {
    let mut s = String::new();
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "{:>8} {:>12} {:>14} {:>12} {:>8} {:>10}",
        "cycle", "d_e", "pull-out", "change [%]", "ratio", "verdict"
    );
    let mut prev: Option<f64> = None;
    for c in &r.cycles {
        let change = prev.map_or("-".to_string(), |p| {
            if p == 0.0 {
                "-".to_string()
            } else {
                format!("{:+.4}", 100.0 * (c.pull_out_pressure - p) / p)
            }
        });
        let note = if c.cycle > 1 && !c.deepened && c.shallower_by > 0.0 {
            format!(
                "  impact {} shallower than the deepest so far",
                render::si(c.shallower_by, "m", 3)
            )
        } else {
            String::new()
        };
        let _ = writeln!(
            s,
            "{:>8} {:>12} {:>14} {:>12} {:>8} {:>10}{note}",
            c.cycle,
            render::si(c.d_e, "m", 6),
            render::pressure(c.pull_out_pressure),
            change,
            ratio_text(c.pull_out_ratio),
            if c.sticks { "sticks" } else { "releases" }
        );
        prev = Some(c.pull_out_pressure);
    }
    if let Some(e) = &r.elastic {
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

/// The contact under the hold voltage, per cycle computed (none when none was).
fn table_contact(r: &SwitchResult) -> String {
    let rows: Vec<_> = r
        .cycles
        .iter()
        .filter(|c| c.hold_status != "not_computed")
        .collect();
    if rows.is_empty() {
        return String::new();
    }
    let mut s = String::new();
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "closed under {}: {} per contact area{}",
        match r.hold_force {
            Some(f) => format!(
                "the hold force {} (hold_force over phi x electrode_area)",
                render::si(f, "N", 4)
            ),
            None => format!(
                "the hold voltage {:.4} V (eps0 eps_r^2 U^2/(2 t_d^2) - K_s d0, over phi)",
                r.hold_voltage
            ),
        },
        render::pressure(r.hold_pressure),
        if rows.iter().any(|c| c.has_resistance()) {
            ""
        } else {
            "; contact resistance: give contact.resistivity, contact.mean_free_path and switch.electrode_area"
        }
    );
    let _ = writeln!(
        s,
        "{:>8} {:>20} {:>12} {:>12} {:>14} {:>12} {:>14} {:>14}",
        "cycle", "rest d", "A_r/A hold", "A_r/A end", "spots [1/um^2]", "mean a", "R hold", "R end"
    );
    let ohm = |v: Option<f64>| v.map_or("-".to_string(), |v| render::si(v, "Ohm", 4));
    for c in rows {
        let h = c.hold.as_ref();
        let e = c.end_of_impact.as_ref();
        let rest = match (c.hold_status, h) {
            ("deeper_than_impact", Some(h)) => {
                format!("{} (deeper)", render::si(h.separation, "m", 4))
            }
            (_, Some(h)) => render::si(h.separation, "m", 4),
            (status, None) => status.replace('_', " "),
        };
        let _ = writeln!(
            s,
            "{:>8} {:>20} {:>12} {:>12} {:>14} {:>12} {:>14} {:>14}",
            c.cycle,
            rest,
            h.map_or("-".into(), |h| format!(
                "{:.4}%",
                100.0 * h.real_contact_fraction
            )),
            e.map_or("-".into(), |e| format!(
                "{:.4}%",
                100.0 * e.real_contact_fraction
            )),
            h.map_or("-".into(), |h| format!("{:.4}", h.spot_density * 1e-12)),
            h.map_or("-".into(), |h| render::si(h.mean_spot_radius, "m", 4)),
            ohm(h.and_then(|h| h.contact_resistance)),
            ohm(e.and_then(|e| e.contact_resistance)),
        );
    }
    if let Some(i) = r
        .cycles
        .iter()
        .find_map(|c| c.hold.as_ref().and_then(|h| h.interaction_resistance))
    {
        let _ = writeln!(
            s,
            "R: the spots in parallel (Holm-Sharvin, Wexler); their interaction over the contact area adds {} (Greenwood 1966, uniform spots over phi x electrode_area as one circle; contact_resistance_with_interaction)",
            render::si(i, "Ohm", 4)
        );
    }
    s
}

/// Accommodation, the verdict, its validity and the error estimates.
/// The model-form check: the verdict in words, then one row per combination.
pub fn table_model_form(m: &ModelFormReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\nmodel form: {} (combinations run in {} mode; flips alone: {})",
        m.summary,
        m.accuracy,
        if m.flips.is_empty() {
            "none".to_string()
        } else {
            m.flips.join(", ")
        }
    );
    let _ = writeln!(
        s,
        "  ratio range {} to {}",
        ratio_text(m.ratio_range[0]),
        ratio_text(m.ratio_range[1])
    );
    let _ = writeln!(
        s,
        "  {:<16} {:<11} {:<11} {:<12} {:>12}  {:<8} valid",
        "plasticity", "eq 1", "reload", "adhesion", "ratio", "verdict"
    );
    for r in &m.runs {
        let _ = writeln!(
            s,
            "  {:<16} {:<11} {:<11} {:<12} {:>12}  {:<8} {}{}",
            r.laws.plasticity,
            r.laws.yield_modulus,
            r.laws.reload,
            r.laws.adhesion,
            ratio_text(r.pull_out_ratio),
            if !r.closes {
                "no close"
            } else if r.stiction {
                "sticks"
            } else {
                "free"
            },
            if r.validity_holds { "yes" } else { "no" },
            if r.decided {
                ""
            } else {
                "  (within the mode's error of 1)"
            }
        );
    }
    for e in &m.excluded {
        let _ = writeln!(s, "  left out: {} {}: {}", e.choice, e.value, e.reason);
    }
    s
}

fn table_verdict(r: &SwitchResult) -> String {
    let mut s = String::new();
    let _ = writeln!(s);
    match r.accommodated_after {
        Some(k) => {
            let why = match r.accommodation_cause {
                Some("non_deepening") => ": the next impact did not go deeper, so the history stopped changing (not a settled surface; see the warning)",
                _ => ": the impacts still deepen, by less than the tolerance",
            };
            let _ = writeln!(
                s,
                "accommodated after cycle {k} (next cycle changes by < {:e}){why}",
                r.accommodation_tolerance
            );
        }
        None => {
            let _ = writeln!(
                s,
                "not accommodated within {} cycles (tolerance {:e})",
                r.cycles.len(),
                r.accommodation_tolerance
            );
        }
    }
    let _ = writeln!(
        s,
        "verdict: {} (pull-out ratio {}: largest pull-out {} x {} of the area vs restoring {}){}",
        if r.stiction {
            "STICTION - the spring cannot pull the switch open"
        } else {
            "no stiction - the spring opens the switch"
        },
        ratio_text(r.pull_out_ratio),
        render::pressure(r.largest_pull_out),
        r.contact_area_fraction,
        render::pressure(r.restoring_pressure),
        if r.validity.holds {
            String::new()
        } else {
            format!("; {}", r.validity.words())
        }
    );
    let _ = writeln!(
        s,
        "error estimates: d_e {}, pull-out {}{}",
        render::si(r.error_estimate.d_e, "m", 2),
        render::pressure(r.error_estimate.pull_out),
        if r.error_estimate.accommodation > 0.0 {
            format!(
                " (of which {} from stopping at accommodation)",
                render::pressure(r.error_estimate.accommodation)
            )
        } else {
            String::new()
        }
    );
    s
}

impl Plot for SwitchResult {
    /// `switch.svg`: like the paper's Fig 4 (an empty figure without curves, `points = 0`).
    fn svg(&self) -> Result<String, ReportError> {
        plot_svg(self).map_err(|m| ReportError::plot("switch.svg".as_ref(), m))
    }
}

/// `dynamics.svg`: the switch in time (None for a quasi-static run or without curves).
pub fn dynamics_svg(r: &SwitchResult) -> Option<Result<String, ReportError>> {
    plot_dynamics_svg(r).map(|svg| svg.map_err(|m| ReportError::plot("dynamics.svg".as_ref(), m)))
}

impl Report for SwitchResult {
    const FILES: &'static [&'static str] = FILES;

    fn files(&self, dir: &Path) -> Result<OutputSet, ReportError> {
        let mut set = OutputSet::new(dir, FILES);
        set.add("switch.json", render::json(self));
        set.add("cycles.csv", self.csv());
        set.add("curves.csv", curves_csv(self));
        if !self.loading.is_empty() {
            let svg = plot_svg(self)
                .map_err(|message| ReportError::plot(&dir.join("switch.svg"), message))?;
            set.add("switch.svg", svg);
        }
        if let Some(svg) = plot_dynamics_svg(self) {
            let svg =
                svg.map_err(|message| ReportError::plot(&dir.join("dynamics.svg"), message))?;
            set.add("dynamics.svg", svg);
        }
        Ok(set)
    }
}
