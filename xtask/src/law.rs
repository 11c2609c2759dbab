//! `cargo xtask law [--scenes N] [--seed S] [--domain mems|wide] [--held-out K]`: the
//! contact law (`stiction law`, default options) of random switch scenes: whether the
//! tabulation converged to its tolerance, the error it measured, the time it took, and an
//! independent held-out check: K points per scene at random off-grid histories and
//! separations, the law file read back and evaluated against the surface itself (same
//! accuracy mode, a generator and distribution of its own). Prints a table for
//! docs/performance.md ("The contact law"). `--only K` tabulates scene K alone and prints
//! it as a scene file on standard error.

use std::io::IsTerminal;
use std::time::Instant;
use stiction_model::contact_core::Categorized;
use stiction_model::contact_core::{Path as SurfacePath, SurfaceLaw};
use stiction_model::contact_law::{ContactLaw, Path, Region};
use stiction_model::gw_surface::GwHistory;
use stiction_model::law::{self, LawOptions, LawScene, DEFAULT_ACCURACY};
use stiction_model::laws::LawRegistry;
use stiction_model::scenegen::{self, Domain, Rng};
use stiction_model::spec::SwitchSpec;
use stiction_model::{ModelError, Silent};

/// The held-out check of one law: the largest error over `k` random points.
fn held_out(
    s: &SwitchSpec,
    file: &ContactLaw,
    k: usize,
    rng: &mut Rng,
) -> Result<(f64, usize), ModelError> {
    let gw = stiction_model::switch::surface_of(s, DEFAULT_ACCURACY, 0.0, false)?;
    let (lo, hi) = file.d_min_range();
    let floor = file.pressure_floor();
    let mut worst: f64 = 0.0;
    let mut outside = 0;
    for i in 0..k {
        // histories anywhere in the table, separations concentrated near d_min
        let d_min = lo + (hi - lo) * rng.unit();
        let path = if i % 2 == 0 {
            Path::Approach
        } else {
            Path::Retract
        };
        let reach = file
            .reach(d_min, path)
            .map_err(|e| ModelError::argument("law", e.to_string(), "a law"))?;
        let u = rng.unit();
        let d = d_min + (reach - d_min) * u * u * u;
        let e = file
            .evaluate(d, d_min, path)
            .map_err(|e| ModelError::argument("law", e.to_string(), "a law"))?;
        if e.region != Region::Measured {
            outside += 1;
        }
        let history = GwHistory::Flat { deepest: d_min };
        let sp = match path {
            Path::Approach => SurfacePath::Approach,
            Path::Retract => SurfacePath::Retract { from: d_min },
        };
        let direct = gw.pressure(d, &history, sp)?;
        let po = stiction_model::switch_1d::unload(
            &gw,
            &history,
            d_min,
            0,
            DEFAULT_ACCURACY.precision(),
        )?
        .pull_out_pressure
        .abs();
        let err = (e.pressure - direct).abs() / (direct.abs() + po + floor);
        worst = if err.is_nan() {
            f64::NAN
        } else {
            worst.max(err)
        };
    }
    Ok((worst, outside))
}

fn quantile(v: &[f64], q: f64) -> f64 {
    let mut v = v.to_vec();
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

pub fn main(args: &[&str]) -> Result<(), String> {
    let mut n = 20usize;
    let mut seed = 20261124u64;
    let mut domain = Domain::Mems;
    let mut k = 200usize;
    let mut only: Option<usize> = None;
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
            "--held-out" => {
                k = it
                    .next()
                    .and_then(|v| v.parse().ok())
                    .ok_or("--held-out needs a count")?
            }
            "--only" => {
                only = Some(
                    it.next()
                        .and_then(|v| v.parse().ok())
                        .ok_or("--only needs a scene number")?,
                )
            }
            "--domain" => {
                domain = match it.next().copied() {
                    Some("mems") => Domain::Mems,
                    Some("wide") => Domain::Wide,
                    _ => return Err("--domain needs mems or wide".into()),
                }
            }
            other => return Err(format!("unknown option {other}")),
        }
    }
    let registry = LawRegistry::builtin();
    let progress = std::io::stderr().is_terminal();
    let mut rng = Rng::new(seed);
    let mut check_rng = Rng::new(seed ^ 0x5EED);
    let (mut scenes, mut converged, mut not_converged, mut no_range, mut failed) = (0, 0, 0, 0, 0);
    let mut times = Vec::new();
    let mut measured = Vec::new();
    let mut checks = Vec::new();
    let mut rows = String::new();
    let mut notes = Vec::new();
    while scenes < n {
        let scene = scenegen::switch_scene(&mut rng, domain, "generated");
        let Ok(s) = SwitchSpec::new(&scene, &registry) else {
            continue;
        };
        scenes += 1;
        if only.is_some_and(|o| o != scenes) {
            continue;
        }
        if only.is_some() {
            eprintln!("{}", scenegen::to_toml(s.common().scene()));
        }
        let c = s.contact();
        let what = format!(
            "{} / {} / eq 1 {} / reload {}",
            c.adhesion().name(),
            c.plasticity().name(),
            c.yield_modulus().as_str(),
            c.reload().as_str()
        );
        let t = Instant::now();
        let r = law::tabulate(LawScene::Switch(&s), &LawOptions::default(), &Silent);
        let secs = t.elapsed().as_secs_f64();
        match r {
            Ok(r) => {
                let back = ContactLaw::from_json_str(&r.law_json)
                    .map_err(|e| format!("scene {scenes}: the law rejects its own table: {e}"))?;
                let (check, outside) = held_out(&s, &back, k, &mut check_rng)
                    .map_err(|e| format!("scene {scenes}: held-out check: {e}"))?;
                let m = r.measured_error.max();
                if r.converged {
                    converged += 1;
                } else {
                    not_converged += 1;
                    notes.push(format!(
                        "scene {scenes} ({what}): not converged, measured {m:.2e}\n{}",
                        scenegen::to_toml(s.common().scene())
                    ));
                }
                times.push(secs);
                measured.push(m);
                checks.push(check);
                let codes: Vec<&str> = r.warnings.iter().map(|w| w.code).collect();
                rows += &format!(
                    "| {scenes} | {what} | {} | {} | {m:.1e} | {check:.1e} | {outside} | {} | {secs:.1} | {} |\n",
                    r.branches,
                    r.source_evaluations,
                    r.converged,
                    codes.join(", ")
                );
            }
            Err(e)
                if e.category() == stiction_model::contact_core::Category::Input
                    && e.to_string().contains("does not close") =>
            {
                no_range += 1;
                rows += &format!(
                    "| {scenes} | {what} | | | | | | no default range: {e} | {secs:.1} | |\n"
                );
            }
            Err(e) => {
                failed += 1;
                notes.push(format!(
                    "scene {scenes} ({what}): failed: {e}\n{}",
                    scenegen::to_toml(s.common().scene())
                ));
                rows += &format!("| {scenes} | {what} | | | | | | failed | {secs:.1} | |\n");
            }
        }
        if progress {
            eprint!("\r{scenes}/{n} scenes");
        }
    }
    if progress {
        eprintln!();
    }
    println!(
        "Measured by `cargo xtask law --scenes {n} --seed {seed} --domain {} --held-out {k}` (release build, default options: fast accuracy, tolerance 2e-4):\n",
        if domain == Domain::Mems { "mems" } else { "wide" }
    );
    println!("| scene | laws | branches | surface evaluations | measured max | held-out max | held-out outside measured | converged | time (s) | warnings |\n|---|---|---|---|---|---|---|---|---|---|\n{rows}");
    println!(
        "{scenes} scenes: {converged} converged, {not_converged} not converged, {no_range} without a default range (the switch does not close), {failed} failed; time median {:.1} s, max {:.1} s; measured error max {:.1e}; held-out max {:.1e}",
        quantile(&times, 0.5),
        quantile(&times, 1.0),
        quantile(&measured, 1.0),
        quantile(&checks, 1.0)
    );
    for n in notes {
        println!("\n{n}");
    }
    Ok(())
}
