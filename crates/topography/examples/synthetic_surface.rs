//! docs/topography.md section 13: from a synthetic surface to the scene fragment.
//!
//! `cargo run --release -p topography --example synthetic_surface -- OUT_DIR` synthesises a
//! self-affine surface, writes it as an x3p file, reads it back, analyses it and writes
//! `OUT_DIR/surface.x3p`, `OUT_DIR/report.json` and `OUT_DIR/fragment.toml`.

use std::path::PathBuf;

use topography::{
    analyze_measurement, io::write_path, read_path, scene_fragment, synthesize, Amplitudes,
    AnalysisOptions, Format, Normalization, ReadOptions, Route, SelfAffinePsd, SynthesisOptions,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "topography-example".into()),
    );
    std::fs::create_dir_all(&out)?;
    // A sputtered-film-like spectrum: H = 0.8 from 2.56 um down to 160 nm, rms 8 nm,
    // sampled like an AFM scan of 5.12 um at 10 nm (512 x 512).
    let psd = SelfAffinePsd::new(0.8, 2.56e-6, None, 160e-9, Normalization::RmsHeight(8e-9))?;
    let analytic = psd.gw_parameters();
    let m = psd.moments();
    println!(
        "analytic: m0 {:.4e} m^2, m2 {:.4e}, m4 {:.4e} 1/m^2, alpha {:.2}",
        m.m0,
        m.m2,
        m.m4,
        m.alpha()
    );
    println!(
        "analytic GW: sigma_s {:.4e} m, N {:.4e} 1/m^2, R {:.4e} m, offset {:.4e} m",
        analytic.sigma_s, analytic.asperity_density, analytic.radius, analytic.offset
    );
    let o = SynthesisOptions {
        nx: 512,
        ny: 512,
        dx: 10e-9,
        dy: 10e-9,
        seed: 2026,
        amplitudes: Amplitudes::Gaussian,
    };
    let map = synthesize(&psd, &o)?;
    let file = out.join("surface.x3p");
    write_path(&file, &map, Format::X3p)?;
    let measured = read_path(&file, &ReadOptions::default())?;
    let r = analyze_measurement(&measured, &AnalysisOptions::default())?;
    println!(
        "map: rms {:.4e} m, m2 {:.4e}, m4 {:.4e} 1/m^2, alpha {:.2}",
        r.rms_height, r.m2, r.m4, r.alpha
    );
    let s = r.summits.as_ref().ok_or("no summits")?;
    println!(
        "{:>10} {:>12} {:>12} {:>12} {:>12}",
        "route", "sigma_s (m)", "N (1/m^2)", "R (m)", "offset (m)"
    );
    for (name, g) in [("spectral", r.spectral.gw), ("summits", s.gw)] {
        println!(
            "{name:>10} {:>12.4e} {:>12.4e} {:>12.4e} {:>12.4e}",
            g.sigma_s, g.asperity_density, g.radius, g.offset
        );
    }
    println!(
        "summits: {}, skewness {:.2}, kurtosis {:.2}",
        s.count, s.skewness, s.kurtosis
    );
    println!(
        "{:>6} {:>10} | {:>11} {:>11} {:>11} | {:>11} {:>11} {:>11}",
        "factor", "dx (m)", "sp sigma_s", "sp N", "sp R", "su sigma_s", "su N", "su R"
    );
    for row in r.sampling.iter().chain(r.scan_size.iter().skip(1)) {
        let su = row.summits.unwrap_or(row.spectral);
        println!(
            "{:>6} {:>10.3e} | {:>11.4e} {:>11.4e} {:>11.4e} | {:>11.4e} {:>11.4e} {:>11.4e}  ({} tile(s), scan {:.3e} m)",
            row.factor, row.dx, row.spectral.sigma_s, row.spectral.asperity_density, row.spectral.radius,
            su.sigma_s, su.asperity_density, su.radius, row.tiles, row.scan_x
        );
    }
    for w in &r.warnings {
        println!("warning [{}]: {}", w.code, w.message);
    }
    std::fs::write(out.join("report.json"), serde_json::to_string_pretty(&r)?)?;
    let fragment = scene_fragment(&r, Route::Summits)?;
    std::fs::write(out.join("fragment.toml"), &fragment)?;
    println!("\n{fragment}");
    Ok(())
}
