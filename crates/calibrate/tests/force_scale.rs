//! Forces far off the model's scale (finite, but in other units or of another asperity)
//! are refused naming the line, column and value; forces within reach of the model give
//! a report of finite numbers only (never an overflowing RMS, a null or an inf).

mod common;

use asperity_plastic::YieldModulus;
use calibrate::{
    CalibError, Curve, CurvePoint, DataProblem, FeData, FitOptions, FitReport, FORCE_SCALE_LIMIT,
};
use common::*;

/// The synthetic curves with every force multiplied by `factor`.
fn scaled(factor: f64) -> FeData {
    let cal = ru(YieldModulus::AsPrinted);
    let data = cal
        .synthesize(truth(), &spec(&cal, &OMEGAS, 15, 15, 0.0, 7))
        .unwrap();
    let curves: Vec<Curve> = data
        .curves()
        .iter()
        .map(|c| Curve {
            points: c
                .points
                .iter()
                .map(|p| CurvePoint {
                    force: p.force * factor,
                    ..*p
                })
                .collect(),
            ..c.clone()
        })
        .collect();
    FeData::from_curves(curves).unwrap()
}

/// Every number of the report, through its JSON form: all must be finite numbers.
fn assert_all_finite(report: &FitReport) {
    fn walk(v: &serde_json::Value, at: &str) {
        match v {
            serde_json::Value::Null => panic!("{at}: null"),
            serde_json::Value::Number(n) => {
                assert!(n.as_f64().is_some_and(f64::is_finite), "{at}: {n}")
            }
            serde_json::Value::Array(a) => {
                for (i, x) in a.iter().enumerate() {
                    walk(x, &format!("{at}[{i}]"));
                }
            }
            serde_json::Value::Object(m) => {
                for (k, x) in m {
                    walk(x, &format!("{at}.{k}"));
                }
            }
            _ => {}
        }
    }
    walk(&serde_json::to_value(report).unwrap(), "report");
    assert!(report.residual_rms_n.is_finite() && report.cost.is_finite());
    for c in &report.curves {
        assert!(c.rms_n.is_finite() && c.rms_relative.is_finite(), "{c:?}");
    }
}

#[test]
fn forces_far_off_the_model_scale_are_refused_naming_line_column_and_value() {
    let cal = ru(YieldModulus::AsPrinted);
    for factor in [1e300, 1e-300, 1e150, 1e-150, 3e7, 2e-7, -1e300] {
        let data = scaled(factor);
        let e = cal.fit(&data, &FitOptions::default()).unwrap_err();
        let CalibError::Data {
            line,
            column,
            problem,
        } = &e
        else {
            panic!("x{factor:e}: not a data error: {e}");
        };
        assert_eq!(column, "force_n", "x{factor:e}");
        let DataProblem::ForceScale { force, .. } = problem else {
            panic!("x{factor:e}: {problem}");
        };
        // the line named is the peak of its curve, and the message gives its value
        let point = data
            .curves()
            .iter()
            .flat_map(|c| &c.points)
            .find(|p| p.line == *line)
            .unwrap();
        assert_eq!(point.force, *force);
        let m = e.to_string();
        assert!(
            m.contains(&format!("line {line}")) && m.contains(&format!("{force:e}")),
            "{m}"
        );
    }
}

#[test]
fn forces_within_the_limit_give_a_finite_report() {
    let cal = ru(YieldModulus::AsPrinted);
    for factor in [
        1.0,
        10.0,
        0.1,
        0.5 * FORCE_SCALE_LIMIT,
        2.0 / FORCE_SCALE_LIMIT,
    ] {
        let report = cal
            .fit(&scaled(factor), &FitOptions::default())
            .unwrap_or_else(|e| panic!("x{factor:e}: {e}"));
        assert_all_finite(&report);
        if factor != 1.0 {
            // the model cannot follow: said by the misfit, in finite numbers
            assert!(
                report.curves.iter().any(|c| c.rms_relative > 0.05),
                "x{factor:e}"
            );
        }
    }
}
