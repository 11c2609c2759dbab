//! Writes the maps of analytic stand-in evaluators to a directory, to look at:
//! `cargo run -p stiction-report --example analytic_maps -- OUT_DIR`.

use design_sweep::{
    run_map, threshold, DesignPoint, Grid, Labels, Level, MapRequest, PointError, ThresholdOptions,
};
use std::path::PathBuf;
use stiction_report::csv::map_csv;
use stiction_report::design_table::{map_table, threshold_table};
use stiction_report::plot::map::map_svg;

fn point(ratio: f64, restoring: f64, closes: bool) -> DesignPoint {
    DesignPoint {
        pull_out_ratio: if closes { ratio } else { 0.0 },
        largest_pull_out_pa: if closes { ratio * restoring } else { 0.0 },
        restoring_pressure_pa: restoring,
        cycles_to_accommodation: closes.then_some(5),
        first_sticking_cycle: (closes && ratio > 1.0).then_some(1),
        sticks: closes && ratio > 1.0,
        closes,
        validity_holds: true,
        accommodation_cause: None,
        contact_resistance: None,
        real_contact_fraction: None,
    }
}

/// ratio = (2e3/k)^2 (sigma/1e-8); does not close above k = 2e4; fails in one spot.
fn eval(values: &[(&str, Level)]) -> Result<DesignPoint, PointError> {
    let number = |v: &(&str, Level)| v.1.number().ok_or("a numeric axis");
    let k = number(&values[0])?;
    let sigma = values.get(1).map_or(Ok(5e-9), number)?;
    if (k - 1e3).abs() < 1.0 && sigma < 2e-9 {
        return Err(PointError::Failed("stand-in failure".into()));
    }
    Ok(point((2e3 / k).powi(2) * (sigma / 1e-8), k * 2e-6, k < 2e4))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "out/design-demo".into()),
    );
    std::fs::create_dir_all(&out)?;
    let labels = Labels::new()
        .with_unit("switch.k_s", "Pa/m")
        .with_unit("surface.sigma_s", "m");
    let scene = serde_json::json!({"name": "analytic stand-in"});
    for (name, specs) in [
        ("map_1d", vec!["switch.k_s=1e2:1e5:log:31"]),
        ("map_1d_lin", vec!["switch.k_s=500:3000:lin:26"]),
        (
            "map_2d",
            vec![
                "switch.k_s=1e2:1e5:log:31",
                "surface.sigma_s=1e-9:9e-9:lin:17",
            ],
        ),
    ] {
        let request = MapRequest {
            scene: scene.clone(),
            grid: Grid::parse(&specs)?,
            accuracy: "fast".into(),
            shard: None,
        };
        let map = run_map(request, eval, |_, _| {});
        std::fs::write(out.join(format!("{name}.svg")), map_svg(&map, &labels)?)?;
        std::fs::write(out.join(format!("{name}.csv")), map_csv(&map)?)?;
        std::fs::write(out.join(format!("{name}.json")), map.to_json())?;
        println!("{name}:\n{}", map_table(&map, &labels));
    }
    let t = threshold(
        "switch.k_s",
        1e2,
        1e5,
        |k| eval(&[("switch.k_s", Level::Number(k))]),
        &ThresholdOptions::default(),
    )?;
    println!("{}", threshold_table(&t, &labels));
    std::fs::write(out.join("threshold.json"), t.to_json())?;
    Ok(())
}
