//! The worked example of `docs/calibration.md`: finite-element-like curves of a Ru asperity
//! (Table 1, rigid flat, eq 1 as printed, Maugis-Kim) made by the model itself with known
//! constants and 0.5 % noise, written to CSV, read back and fitted.
//!
//! ```text
//! cargo run --release -p calibrate --example worked_example [-- OUT.csv]
//! cargo run --release -p calibrate --example worked_example -- --monte-carlo 300
//! ```

use asperity_plastic::{EffectiveRadiusFit, EtsionKadin, YieldModulus};
use calibrate::{Calibrator, Constant, FeData, FitOptions, SynthSpec};
use contact_core::{paper, Material, Pair};
use maugis_kim::{DugdaleParams, MaugisKim};
use std::error::Error;

fn main() -> Result<(), Box<dyn Error>> {
    let pair = Pair::new(Material::new(paper::RU)?, None, paper::RADIUS)?;
    let cal = Calibrator::new(
        EtsionKadin::new(&pair, YieldModulus::AsPrinted)?,
        MaugisKim::new(DugdaleParams::for_pair(
            &pair,
            paper::WORK_OF_ADHESION,
            paper::Z0,
        ))?,
    );
    let truth = EffectiveRadiusFit::new([0.3, 0.5, 0.12], [8.0, 12.0, 4.0])?;
    let spec = SynthSpec {
        delta_max: [5.0, 10.0, 20.0, 40.0].map(|w| w * cal.delta_cp()).to_vec(),
        loading_points: 30,
        unloading_points: 30,
        noise: 0.005,
        seed: 2024,
    };
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--monte-carlo") {
        let runs = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(300);
        return monte_carlo(&cal, truth, &spec, runs);
    }
    let path = args
        .first()
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("calibration_example.csv"));
    std::fs::write(&path, cal.synthesize(truth, &spec)?.to_csv())?;
    println!("wrote {}", path.display());

    // what `stiction calibrate --fe FILE.csv --scene ASPERITY.toml --format table` will do
    let data = FeData::read_csv(&path)?;
    let report = cal.fit(&data, &FitOptions::default())?;
    println!("{}", report.to_table());
    println!("{}", serde_json::to_string_pretty(&report)?);

    // one delta_max only (omega = 20): b1, b2, b3 cannot be separated
    let one = cal.synthesize(
        truth,
        &SynthSpec {
            delta_max: vec![20.0 * cal.delta_cp()],
            ..spec
        },
    )?;
    println!("{}", cal.fit(&one, &FitOptions::default())?.to_table());
    Ok(())
}

/// Repeat the fit over `runs` noise seeds: scatter of the estimates against the reported
/// standard errors, coverage of +-3 SE, and the refit curves against the noiseless truth.
fn monte_carlo(
    cal: &Calibrator<MaugisKim>,
    truth: EffectiveRadiusFit,
    spec: &SynthSpec,
    runs: u64,
) -> Result<(), Box<dyn Error>> {
    let clean = cal.synthesize(
        truth,
        &SynthSpec {
            noise: 0.0,
            ..spec.clone()
        },
    )?;
    let mut est = Vec::new();
    let mut se = Vec::new();
    let mut worst: f64 = 0.0;
    let (mut it_min, mut it_max) = (usize::MAX, 0);
    let t0 = std::time::Instant::now();
    for seed in 0..runs {
        let data = cal.synthesize(
            truth,
            &SynthSpec {
                seed,
                ..spec.clone()
            },
        )?;
        let rep = cal.fit(&data, &FitOptions::default())?;
        if !rep.converged {
            println!("seed {seed}: not converged ({:?})", rep.stop);
        }
        it_min = it_min.min(rep.iterations);
        it_max = it_max.max(rep.iterations);
        let pred = cal.predict(rep.fit(), &clean)?;
        for (c, p) in clean.curves().iter().zip(&pred) {
            let ss: f64 = c
                .points
                .iter()
                .zip(p)
                .map(|(a, f)| (a.force - f).powi(2))
                .sum();
            worst = worst.max((ss / p.len() as f64).sqrt() / c.peak_force());
        }
        est.push(Constant::ALL.map(|c| c.get(&rep.fit())));
        se.push(Constant::ALL.map(|c| rep.standard_errors.get(c).unwrap_or(f64::NAN)));
    }
    let dt = t0.elapsed().as_secs_f64() / runs as f64;
    println!(
        "{runs} fits, {:.1} ms each, {it_min}..{it_max} iterations",
        dt * 1e3
    );
    println!("constant  truth     mean      scatter     mean SE   scatter/SE  within 3 SE");
    let n = runs as f64;
    for c in Constant::ALL {
        let k = c.index();
        let mean = est.iter().map(|e| e[k]).sum::<f64>() / n;
        let sd = (est.iter().map(|e| (e[k] - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let mse = se.iter().map(|s| s[k]).sum::<f64>() / n;
        let inside = est
            .iter()
            .zip(&se)
            .filter(|(e, s)| (e[k] - c.get(&truth)).abs() <= 3.0 * s[k])
            .count();
        println!(
            "{:<8} {:>6} {:>9.5} {:>11.3e} {:>11.3e} {:>10.3} {:>8}/{runs}",
            c.name(),
            c.get(&truth),
            mean,
            sd,
            mse,
            sd / mse,
            inside
        );
    }
    println!(
        "worst refit curve RMS against the noiseless truth: {:.2e} of its peak",
        worst
    );
    Ok(())
}
