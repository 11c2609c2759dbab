//! `cargo xtask tradeoff`: the speed/accuracy trade on the paper's switch (10 cycles and
//! the elastic comparison, pull-out only): each mode's time (best of 3) and its largest
//! error against the reference mode, printed as a table and plotted to
//! docs/figures/tradeoff.svg.

use std::time::Instant;
use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene;
use stiction_model::spec::SwitchSpec;
use stiction_model::switch::{SwitchModel, SwitchResult};
use stiction_model::{Accuracy, Silent};
use stiction_report::plot::{self, Panel, Series};

fn solve(s: &SwitchSpec, mode: Accuracy) -> Result<SwitchResult, String> {
    let s = s.with_accuracy(mode).map_err(|e| e.to_string())?;
    SwitchModel::build(&s)
        .and_then(|m| m.run(&Silent))
        .map_err(|e| e.to_string())
}

pub fn main() -> Result<(), String> {
    let mut scene = Scene::paper(Kind::Switch);
    scene.set_number("points", 0.0).map_err(|e| e.to_string())?;
    let s = SwitchSpec::new(&scene, &LawRegistry::builtin()).map_err(|e| e.to_string())?;
    let reference = solve(&s, Accuracy::Reference)?;
    let sigma = s.roughness().sigma_s();
    println!("| mode | time, 10 cycles + elastic (s) | max d_e error (sigma_s) | max relative pull-out error |");
    println!("|---|---|---|---|");
    let mut pts = Vec::new();
    for mode in [
        Accuracy::Reference,
        Accuracy::Accurate,
        Accuracy::Balanced,
        Accuracy::Fast,
    ] {
        let mut best = f64::INFINITY;
        let mut r = None;
        for _ in 0..3 {
            let t = Instant::now();
            r = Some(solve(&s, mode)?);
            best = best.min(t.elapsed().as_secs_f64());
        }
        let r = r.expect("three runs");
        let (mut de, mut po) = (0.0f64, 0.0f64);
        for (a, b) in reference.cycles.iter().zip(&r.cycles) {
            de = de.max((a.d_e - b.d_e).abs() / sigma);
            po = po.max((a.pull_out_pressure - b.pull_out_pressure).abs() / a.pull_out_pressure);
        }
        println!("| {mode} | {best:.3} | {de:.1e} | {po:.1e} |");
        if mode != Accuracy::Reference {
            pts.push((best.log10(), po.max(1e-16).log10()));
        }
    }
    let svg = plot::svg(
        "Paper switch scene: pull-out error against time, one point per accuracy mode",
        &[Panel {
            caption: "accurate, balanced, fast (errors against the reference mode)".into(),
            x_label: "log10 time [s]".into(),
            y_label: "log10 max relative pull-out error".into(),
            series: vec![Series {
                name: "modes".into(),
                points: pts,
                ..Default::default()
            }],
            x_range: None,
            y_range: None,
            ..Default::default()
        }],
    )?;
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/figures/tradeoff.svg");
    std::fs::write(path, svg).map_err(|e| e.to_string())?;
    println!("\nwrote docs/figures/tradeoff.svg");
    Ok(())
}
