//! `cargo xtask tradeoff`: the speed/accuracy trade of the height quadrature on the
//! paper's switch scene (10 cycles, pull-out only, elastic comparison), measured in this
//! process. Prints a Markdown table and writes docs/figures/tradeoff.svg.

use std::time::Instant;
use stiction::contact_core::SurfaceLaw;
use stiction::gw_surface::{GreenwoodWilliamson, Quadrature};
use stiction::model;
use stiction::output::{plot, Series};
use stiction::scene::{self, SwitchScene};
use stiction::switch_1d::{end_of_impact, run_cycles, unload, CycleOptions, ImpactFilm};

struct Row {
    label: String,
    seconds: f64,
    error: f64,
}

fn solve(s: &SwitchScene, q: Quadrature) -> Result<(Vec<f64>, f64), String> {
    let asp = model::asperity(&s.contact, false).map_err(|e| e.to_string())?;
    let el = model::asperity(&s.contact, true).map_err(|e| e.to_string())?;
    let gw = GreenwoodWilliamson::new(asp, s.surface.sigma_s, s.surface.asperity_density, q)
        .map_err(|e| e.to_string())?;
    let gwe = GreenwoodWilliamson::new(el, s.surface.sigma_s, s.surface.asperity_density, q)
        .map_err(|e| e.to_string())?;
    let g = &s.switch;
    // the embedded switch scene gives E_I directly (K_s only sets the verdict, not timed here)
    let e_i = g
        .impact_energy
        .ok_or("tradeoff needs a scene with impact_energy")?;
    let film = ImpactFilm {
        thickness: g.film_thickness,
        youngs_modulus: s.contact.youngs_modulus,
    };
    let opts = CycleOptions {
        cycles: 10,
        unloading_points: 0,
        loading_points: 0,
        ..Default::default()
    };
    let run = run_cycles(&gw, gw.virgin(), e_i, film, opts).map_err(|e| e.to_string())?;
    let d_e = end_of_impact(&gwe, &gwe.virgin(), e_i, film).map_err(|e| e.to_string())?;
    let u = unload(&gwe, &gwe.load(&gwe.virgin(), d_e), d_e, 0).map_err(|e| e.to_string())?;
    Ok((
        run.cycles
            .iter()
            .map(|c| c.unloading.pull_out_pressure)
            .collect(),
        u.pull_out_pressure,
    ))
}

pub fn main() -> Result<(), String> {
    let s: SwitchScene =
        scene::parse("switch", scene::DEFAULT_SWITCH).map_err(|e| e.to_string())?;
    let reference = solve(&s, Quadrature::Adaptive { rel_tol: 1e-12 })?.0;
    let mut configs: Vec<(String, Quadrature)> = vec![
        (
            "adaptive 1e-10 (accurate)".into(),
            Quadrature::Adaptive { rel_tol: 1e-10 },
        ),
        (
            "adaptive 1e-8".into(),
            Quadrature::Adaptive { rel_tol: 1e-8 },
        ),
        (
            "adaptive 1e-6".into(),
            Quadrature::Adaptive { rel_tol: 1e-6 },
        ),
    ];
    for (nodes, panel) in [
        (16, 0.5),
        (12, 0.5),
        (8, 0.5),
        (8, 1.0),
        (6, 1.0),
        (4, 1.0),
        (3, 1.0),
        (2, 2.0),
    ] {
        configs.push((
            format!("Gauss-Legendre {nodes} nodes / {panel} sigma"),
            Quadrature::GaussLegendre {
                nodes,
                panel_sigmas: panel,
            },
        ));
    }
    let mut rows = Vec::new();
    for (label, q) in configs {
        let mut best = f64::INFINITY;
        let mut pulls = Vec::new();
        for _ in 0..3 {
            let t = Instant::now();
            pulls = solve(&s, q)?.0;
            best = best.min(t.elapsed().as_secs_f64());
        }
        let error = reference
            .iter()
            .zip(&pulls)
            .map(|(a, b)| ((a - b) / a).abs())
            .fold(0.0, f64::max);
        rows.push(Row {
            label,
            seconds: best,
            error,
        });
    }
    println!("| height quadrature | time, 10 cycles + elastic (s) | max relative pull-out error |");
    println!("|---|---|---|");
    for r in &rows {
        println!("| {} | {:.3} | {:.1e} |", r.label, r.seconds, r.error);
    }
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r.seconds.log10(), r.error.max(1e-16).log10()))
        .collect();
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/figures/tradeoff.svg");
    plot(
        std::path::Path::new(path),
        "Switch scene: pull-out error against time (each point a quadrature setting)",
        "log10 time [s]",
        "log10 max relative pull-out error",
        &[Series {
            name: "height quadrature settings".into(),
            points: pts,
        }],
    )?;
    println!("\nwrote docs/figures/tradeoff.svg");
    Ok(())
}
