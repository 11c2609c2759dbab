//! The design-sweep tests' analytic evaluators and stand-ins (shared, not copied), and the
//! figures the presentation tests draw.
#![allow(dead_code, missing_docs)]

#[path = "../../../design-sweep/tests/common/mod.rs"]
mod evaluators;
pub use evaluators::*;

/// P = 0.5 - 0.3 / n against cycle n = 1..=`cycles` (a count on the x axis), with its
/// +-0.05 band as a shaded interval if `band`; the y range fixed to `y_range` if given.
pub fn against_cycle(cycles: u32, band: bool, y_range: Option<(f64, f64)>) -> String {
    use stiction_report::plot::{self, Band, Panel, Series};
    let p: Vec<(f64, f64)> = (1..=cycles)
        .map(|n| (f64::from(n), 0.5 - 0.3 / f64::from(n)))
        .collect();
    let bands = if band {
        vec![Band {
            name: "95 % interval".into(),
            points: p.iter().map(|&(x, y)| (x, y - 0.05, y + 0.05)).collect(),
            colour: None,
        }]
    } else {
        Vec::new()
    };
    plot::svg(
        "a band, a line, whole cycles",
        &[Panel {
            caption: "P with its interval".into(),
            x_label: "cycle n [count]".into(),
            y_label: "P [-]".into(),
            series: vec![Series {
                name: "P".into(),
                points: p,
                colour: None,
            }],
            bands,
            x_range: Some((0.5, f64::from(cycles) + 0.5)),
            y_range,
            ..Default::default()
        }],
    )
    .unwrap()
}
