//! `cargo xtask accuracy [--scenes N] [--seed S]`: each accuracy mode's error against the
//! reference mode and its speed-up over the accurate mode, over random switch scenes of
//! the documented domains (half plausible MEMS, half the wide ranges); the table replaces
//! the marked section of docs/performance.md.
//!
//! `--times FILE` also writes every run's wall time as CSV (`domain,scene,mode,seconds,
//! outcome`; scene counts from 1 in each domain, in the generator's order), so that the
//! scenes behind a mode's total time can be found and rerun; `--scene-files DIR` writes
//! each scene as a scene file (`mems-3.toml`, `wide-48.toml`) to rerun alone with
//! `stiction switch --scene`, and `--no-runs` with it writes the files and runs nothing;
//! `--domain mems|wide|soft` runs that domain's share alone.

use std::io::IsTerminal;
use std::time::Instant;
use stiction_model::laws::LawRegistry;
use stiction_model::scenegen::{self, Domain, Rng};
use stiction_model::spec::{count_value, ContactStates, SwitchSpec};
use stiction_model::switch::{SwitchModel, SwitchResult};
use stiction_model::{Accuracy, ModelError, Silent};

const BEGIN: &str = "<!-- xtask accuracy: begin -->";
const END: &str = "<!-- xtask accuracy: end -->";

fn run(s: &SwitchSpec, mode: Accuracy) -> (Result<SwitchResult, ModelError>, f64) {
    let s = match s.with_accuracy(mode) {
        Ok(s) => s,
        Err(e) => return (Err(e), 0.0),
    };
    let t = Instant::now();
    let r = SwitchModel::build(&s).and_then(|m| m.run(&Silent));
    (r, t.elapsed().as_secs_f64())
}

/// Whether a run ended because the model has no end of impact for the scene (the surface
/// cannot absorb the impact energy): an answer about the scene, not a numerical failure.
fn no_end_of_impact(e: &ModelError) -> bool {
    matches!(
        e.cause(),
        ModelError::Switch(stiction_model::switch_1d::SwitchError::EnergyNotAbsorbed { .. })
    )
}

/// Whether a run rejected the scene as input (a derived quantity out of its domain, such
/// as the impact energy per contact area E_I/phi): the generator's scene, not a failure.
fn input_error(e: &ModelError) -> bool {
    use stiction_model::contact_core::{Categorized, Category};
    e.category() == Category::Input
}

/// The largest errors of a run `b` against the reference `a` over every cycle (d_e in
/// sigma_s, the pull-out relative), and the largest ratio of an error to the two runs'
/// error estimates together (above 1: the estimates do not cover it).
fn errors(a: &SwitchResult, b: &SwitchResult, sigma: f64) -> (f64, f64, f64) {
    let floor = 1e-9 * a.restoring_pressure / a.contact_area_fraction;
    let over = |diff: f64, estimate: f64| {
        if diff == 0.0 {
            0.0
        } else if estimate > 0.0 {
            diff / estimate
        } else {
            f64::INFINITY
        }
    };
    a.cycles
        .iter()
        .zip(&b.cycles)
        .fold((0.0f64, 0.0f64, 0.0f64), |(de, po, cover), (x, y)| {
            let dd = (x.d_e - y.d_e).abs();
            let dp = (x.pull_out_pressure - y.pull_out_pressure).abs();
            (
                de.max(dd / sigma),
                po.max(dp / x.pull_out_pressure.abs().max(floor)),
                cover
                    .max(over(dd, x.d_e_error + y.d_e_error))
                    .max(over(dp.max(0.0), x.pull_out_error + y.pull_out_error)),
            )
        })
}

/// A scene the table flags, on stderr as a scene file, so that it can be rerun alone
/// (`stiction switch --scene`).
fn report_scene(s: &SwitchSpec) {
    eprintln!(
        "\n# scene flagged by xtask accuracy\n{}",
        scenegen::to_toml(s.common().scene())
    );
}

fn quantile(v: &mut [f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

#[derive(Default)]
struct Stats {
    de: Vec<f64>,
    po: Vec<f64>,
    time: Vec<f64>,
    failed: usize,
    over: usize,
    /// Runs with a cycle whose error exceeds the mode's and the reference's estimates
    /// together, and the largest such ratio.
    uncovered: usize,
    cover_worst: f64,
    /// Runs until accommodated: scenes compared, and those whose pull-out ratio differs
    /// from the reference's by more than the two error estimates (the stopping rule's
    /// included) allow.
    stop_compared: usize,
    stop_uncovered: usize,
    /// The largest |ratio - reference ratio| / (estimate of the mode + of the reference).
    stop_worst: f64,
}

/// Cycles the error table compares at most: every cycle up to accommodation, as far as
/// this (soft films take a few more than hard ones).
const COMPARED_CYCLES: usize = 8;

/// The same scene run until accommodated (at most 20 cycles), validated again.
fn until_accommodated(s: &SwitchSpec) -> Result<SwitchSpec, ModelError> {
    s.with_values(&[
        ("until_accommodated", toml::Value::Boolean(true)),
        ("cycles", count_value(20)),
    ])
}

pub fn main(args: &[&str]) -> Result<(), String> {
    let mut n = 100usize;
    let mut seed = 20261123u64;
    let mut stopping_rule = true;
    let mut times_path: Option<String> = None;
    let mut scene_dir: Option<std::path::PathBuf> = None;
    let mut only_scenes = false;
    let mut only_domain: Option<Domain> = None;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match *a {
            "--scenes" => {
                n = it
                    .next()
                    .and_then(|v| v.parse().ok())
                    .ok_or("--scenes needs a count")?
            }
            "--seed" => {
                seed = it
                    .next()
                    .and_then(|v| v.parse().ok())
                    .ok_or("--seed needs a number")?
            }
            // the error table alone: the stopping-rule runs (each scene until accommodated,
            // up to 20 cycles, in every mode and the reference) are most of the time
            "--no-stopping-rule" => stopping_rule = false,
            "--times" => {
                times_path = Some(
                    it.next()
                        .ok_or("--times needs a file (CSV of every run's wall time)")?
                        .to_string(),
                )
            }
            "--scene-files" => {
                scene_dir = Some(
                    it.next()
                        .ok_or("--scene-files needs a directory (one scene file per scene)")?
                        .into(),
                )
            }
            // with --scene-files: write the scenes, run nothing
            "--no-runs" => only_scenes = true,
            // one domain's share of the scenes alone (a quick look; the docs' table is
            // rewritten with that domain only)
            "--domain" => {
                only_domain = Some(match it.next().copied() {
                    Some("mems") => Domain::Mems,
                    Some("wide") => Domain::Wide,
                    Some("soft") => Domain::Soft,
                    _ => return Err("--domain needs mems, wide or soft".into()),
                })
            }
            other => return Err(format!("unknown option {other}")),
        }
    }
    if only_scenes && scene_dir.is_none() {
        return Err(
            "--no-runs writes the scene files and runs nothing: it needs --scene-files DIR".into(),
        );
    }
    // a path that cannot take the file is refused now, not after the hours of the run
    if let Some(p) = &times_path {
        stiction_report::output::check_file(std::path::Path::new(p)).map_err(|e| e.to_string())?;
    }
    let modes = [Accuracy::Accurate, Accuracy::Balanced, Accuracy::Fast];
    let registry = LawRegistry::builtin();
    // a counter that rewrites its line only makes sense on a terminal
    let progress = std::io::stderr().is_terminal();
    let mut table = String::new();
    let mut notes = Vec::new();
    // domain, scene, mode, seconds, outcome
    let mut times = String::from("domain,scene,mode,seconds,outcome\n");
    let mut timed = |domain: Domain, scene: usize, mode: Accuracy, t: f64, outcome: &str| {
        times += &format!("{domain:?},{scene},{mode},{t:.6},{outcome}\n");
    };
    // a quarter soft films, the rest half plausible MEMS contacts, half the wide ranges
    let soft = n / 4;
    let mems = (n - soft) / 2;
    let counts = [
        (Domain::Mems, mems),
        (Domain::Wide, n - soft - mems),
        (Domain::Soft, soft),
    ];
    for (domain, count) in counts {
        if only_domain.is_some_and(|d| d != domain) {
            continue;
        }
        let mut rng = Rng::new(
            seed ^ match domain {
                Domain::Mems => 0,
                Domain::Wide => 0xABCD,
                Domain::Soft => 0x50F7,
            },
        );
        let mut stats: Vec<Stats> = modes.iter().map(|_| Stats::default()).collect();
        let (mut scenes, mut unanswered, mut reference_failed, mut rejected) = (0, 0, 0, 0);
        while scenes < count {
            let scene = scenegen::switch_scene(&mut rng, domain, "generated");
            let Ok(s) = SwitchSpec::new(&scene, &registry) else {
                continue;
            };
            // the table compares d_e and the pull-outs: the closed switch's contact state
            // (a rest solve per cycle, the longest part of some reference runs) is not needed
            let s = s
                .with_contact_states(ContactStates::None)
                .map_err(|e| e.to_string())?;
            scenes += 1;
            if let Some(dir) = &scene_dir {
                let path = dir.join(format!("{domain:?}-{scenes}.toml").to_lowercase());
                stiction_report::output::write_file(&path, scenegen::to_toml(&scene).as_bytes())
                    .map_err(|e| e.to_string())?;
            }
            if only_scenes {
                continue;
            }
            // every cycle up to accommodation (at most COMPARED_CYCLES): the reference
            // finds where, the modes run that many cycles
            let compared = s
                .with_values(&[
                    ("cycles", count_value(COMPARED_CYCLES)),
                    ("until_accommodated", toml::Value::Boolean(true)),
                ])
                .map_err(|e| e.to_string())?;
            let (reference, t_ref) = run(&compared, Accuracy::Reference);
            // the modes run as many cycles as the reference ran (all of them)
            let cycles = match &reference {
                Ok(r) => r.cycles.len(),
                Err(_) => COMPARED_CYCLES,
            };
            let s = s
                .with_values(&[
                    ("cycles", count_value(cycles)),
                    ("until_accommodated", toml::Value::Boolean(false)),
                ])
                .map_err(|e| e.to_string())?;
            let reference = match reference {
                Ok(r) => {
                    timed(domain, scenes, Accuracy::Reference, t_ref, "ok");
                    r
                }
                Err(e) if no_end_of_impact(&e) => {
                    timed(
                        domain,
                        scenes,
                        Accuracy::Reference,
                        t_ref,
                        "no end of impact",
                    );
                    unanswered += 1;
                    continue;
                }
                Err(e) if input_error(&e) => {
                    timed(
                        domain,
                        scenes,
                        Accuracy::Reference,
                        t_ref,
                        "rejected as input",
                    );
                    rejected += 1;
                    continue;
                }
                Err(e) => {
                    timed(domain, scenes, Accuracy::Reference, t_ref, "failed");
                    reference_failed += 1;
                    notes.push(format!("{domain:?} reference: failed: {e}"));
                    report_scene(&compared);
                    continue;
                }
            };
            let sigma = s.roughness().sigma_s();
            // the stopping rule: the ratio after accommodation against the reference's,
            // within the sum of the two reported error estimates
            let stop = until_accommodated(&s).map_err(|e| e.to_string())?;
            let reference_stop = if stopping_rule {
                run(&stop, Accuracy::Reference).0.ok()
            } else {
                None
            };
            if let Some(reference_stop) = reference_stop {
                for (k, &mode) in modes.iter().enumerate() {
                    if let (Ok(r), _) = run(&stop, mode) {
                        let allowed = r.error_estimate.pull_out_ratio
                            + reference_stop.error_estimate.pull_out_ratio;
                        let diff = (r.pull_out_ratio - reference_stop.pull_out_ratio).abs();
                        let st = &mut stats[k];
                        st.stop_compared += 1;
                        if diff > allowed {
                            st.stop_uncovered += 1;
                            notes.push(format!(
                                "{domain:?} {mode} until accommodated: ratio {:.6e} vs reference {:.6e}, difference {diff:.1e} above the estimates {allowed:.1e} ({} vs {} cycles)",
                                r.pull_out_ratio,
                                reference_stop.pull_out_ratio,
                                r.cycles.len(),
                                reference_stop.cycles.len()
                            ));
                        }
                        if allowed > 0.0 {
                            st.stop_worst = st.stop_worst.max(diff / allowed);
                        } else if diff > 0.0 {
                            st.stop_worst = f64::INFINITY;
                        }
                    }
                }
            }
            for (k, &mode) in modes.iter().enumerate() {
                let (r, t) = run(&s, mode);
                timed(
                    domain,
                    scenes,
                    mode,
                    t,
                    if r.is_ok() { "ok" } else { "failed" },
                );
                match r {
                    Ok(r) => {
                        let (de, po, cover) = errors(&reference, &r, sigma);
                        if cover > 1.0 {
                            stats[k].uncovered += 1;
                            report_scene(&s);
                            notes.push(format!("{domain:?} {mode}: an error {cover:.1}x the estimates (d_e {de:.1e} sigma_s, pull-out {po:.1e}; {}, {}, eq 1 {}, reload {})", s.contact().adhesion().name(), s.contact().plasticity().name(), s.contact().yield_modulus().as_str(), s.contact().reload().as_str()));
                        }
                        stats[k].cover_worst = stats[k].cover_worst.max(cover);
                        let tg = mode.targets();
                        if de > tg.d_e_tolerance_sigma || po > tg.pull_out_tolerance {
                            stats[k].over += 1;
                            report_scene(&s);
                            notes.push(format!("{domain:?} {mode}: d_e {de:.1e} sigma_s, pull-out {po:.1e} ({}, {}, eq 1 {}, reload {})", s.contact().adhesion().name(), s.contact().plasticity().name(), s.contact().yield_modulus().as_str(), s.contact().reload().as_str()));
                        }
                        stats[k].de.push(de);
                        stats[k].po.push(po);
                        stats[k].time.push(t);
                    }
                    Err(e) => {
                        stats[k].failed += 1;
                        report_scene(&s);
                        notes.push(format!(
                            "{domain:?} {mode}: failed where the reference did not: {e}"
                        ));
                    }
                }
            }
            if progress {
                eprint!("\r{domain:?}: {scenes}/{count} scenes");
            }
        }
        if progress {
            eprintln!();
        }
        let accurate_time: f64 = stats[0].time.iter().sum();
        table += &format!(
            "\n**{}** ({scenes} scenes; {unanswered} where the model has no end of impact: the surface cannot absorb the impact energy, in the wide ranges mostly because adhesion pulls harder than the asperities push back; {rejected} rejected as input when run, a derived quantity such as the impact energy per contact area E_I/phi being outside its domain; {reference_failed} where the reference mode failed numerically):\n\n",
            match domain {
                Domain::Mems => "Plausible MEMS contacts",
                Domain::Wide => "The wide ranges a scene accepts",
                Domain::Soft => "Soft films (E 50-100 GPa, S_Y 0.1-0.5 GPa: gold-like)",
            },
        );
        table += "| mode | target d_e / pull-out | d_e error: median / 99 % / max (sigma_s) | pull-out error: median / 99 % / max | over target | failed | error beyond the estimates: runs / largest error over the estimates | time (s) | speed-up over accurate | until accommodated: ratio outside the estimates / largest difference over the estimates |\n|---|---|---|---|---|---|---|---|---|---|\n";
        for (k, &mode) in modes.iter().enumerate() {
            let st = &mut stats[k];
            let t = mode.targets();
            let total: f64 = st.time.iter().sum();
            let stop_cell = if stopping_rule {
                format!(
                    "{} of {} / {:.2}",
                    st.stop_uncovered, st.stop_compared, st.stop_worst
                )
            } else {
                "not run".to_string()
            };
            table += &format!(
                "| {mode} | {:.0e} / {:.0e} | {:.1e} / {:.1e} / {:.1e} | {:.1e} / {:.1e} / {:.1e} | {} | {} | {} / {:.2} | {:.1} | {:.1}x | {stop_cell} |\n",
                t.d_e_tolerance_sigma,
                t.pull_out_tolerance,
                quantile(&mut st.de.clone(), 0.5),
                quantile(&mut st.de.clone(), 0.99),
                quantile(&mut st.de.clone(), 1.0),
                quantile(&mut st.po.clone(), 0.5),
                quantile(&mut st.po.clone(), 0.99),
                quantile(&mut st.po.clone(), 1.0),
                st.over,
                st.failed,
                st.uncovered,
                st.cover_worst,
                total,
                accurate_time / total.max(1e-12),
            );
        }
    }
    if only_scenes {
        return Ok(());
    }
    let body = format!(
        "{BEGIN}\nMeasured by `cargo xtask accuracy --scenes {n} --seed {seed}{}` (release build, this machine; every cycle up to accommodation, at most {COMPARED_CYCLES}; pull-out only, no contact state; errors against the reference mode, the largest over the cycles; pull-out errors relative, with the floor 1e-9 K_s d0; an error beyond the estimates exceeds the mode's and the reference's reported estimates together):\n{table}\n{}\n{END}",
        if stopping_rule { "" } else { " --no-stopping-rule" },
        if notes.is_empty() {
            "Every mode met its targets on every scene.".to_string()
        } else {
            format!("Scenes over target or failing:\n\n{}", notes.iter().map(|n| format!("- {n}")).collect::<Vec<_>>().join("\n"))
        }
    );
    println!("{body}");
    if let Some(p) = &times_path {
        stiction_report::output::write_file(std::path::Path::new(p), times.as_bytes())
            .map_err(|e| e.to_string())?;
        eprintln!("every run's wall time: {p}");
    }
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/performance.md");
    let doc = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let new = match (doc.find(BEGIN), doc.find(END)) {
        (Some(a), Some(b)) if b > a => format!("{}{body}{}", &doc[..a], &doc[b + END.len()..]),
        _ => format!("{doc}\n{body}\n"),
    };
    std::fs::write(path, new).map_err(|e| e.to_string())?;
    println!("\nwrote docs/performance.md");
    Ok(())
}
