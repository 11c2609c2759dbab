//! What the tabulator writes, its reader accepts: special points lie on their curves in
//! the curves' own coordinates (d and pressure), a large measured error is recorded as it
//! is (and the table as not converged), an infinite one is written as infinite, and the
//! reader checks both, as well as duplicated keys.

mod common;

use common::law;
use contact_law::tabulate::{tabulate, Branch, GridSpec, LawSource, Tabulation};
use contact_law::{ContactLaw, LawError};
use serde_json::{json, Value};
use std::convert::Infallible;

/// A surface without adhesion (Hertz-like asperities): every branch is compressive and
/// falls to zero at its reach, so its most tensile point (the pull-out) is the reach
/// itself. `zero_from` (in units of the length scale before the reach) makes the retract
/// branch end before the reach it reports, with zero pressure in between.
#[derive(Clone, Copy)]
struct NoAdhesion {
    top: f64,
    sigma: f64,
    zero_from: f64,
}

impl NoAdhesion {
    fn p(&self, d: f64, end: f64) -> f64 {
        if d >= end {
            0.0
        } else {
            1e8 * ((end - d) / self.sigma).powf(1.5)
        }
    }
}

impl LawSource for NoAdhesion {
    type Error = Infallible;
    fn pressure(&self, d: f64, _d_min: f64, branch: Branch) -> Result<f64, Infallible> {
        Ok(match branch {
            Branch::Retract => self.p(d, self.top - self.zero_from * self.sigma),
            _ => self.p(d, self.top),
        })
    }
    fn reach(&self, _d_min: f64, _branch: Branch) -> Result<f64, Infallible> {
        Ok(self.top)
    }
    fn pull_out(&self, _d_min: f64) -> Result<(f64, f64), Infallible> {
        // the most tensile retract pressure: zero, first reached at the reported reach
        Ok((self.top, 0.0))
    }
    fn length_scale(&self) -> f64 {
        self.sigma
    }
}

fn options(grid: GridSpec) -> Tabulation {
    Tabulation {
        points_per_branch: 8,
        random_points: 16,
        ..Tabulation::uniform(grid)
    }
}

/// For every history of a grid crossing d = 0, with reaches of many magnitudes: the
/// tabulator places the pull-out at the reach, and the table it writes reads back.
#[test]
fn a_pull_out_at_the_reach_is_written_on_its_branch_for_any_rounding() {
    let mut hazards = 0;
    for (k, top) in [5.539777607836691e-10f64, 3.3e-10, 7.77e-9, 1.234e-8]
        .into_iter()
        .enumerate()
    {
        let sigma = 0.1 * top.abs();
        let src = NoAdhesion {
            top,
            sigma,
            zero_from: 0.0,
        };
        let grid = GridSpec {
            from: -3.0 * top,
            to: 0.8 * top,
            n: 24 + k,
        };
        // the hazard: the reach as a branch writes it, d_min + (reach - d_min), is not
        // the reach (rounding); at least one history per grid must meet it
        hazards += grid
            .nodes()
            .iter()
            .filter(|&&dm| dm + (top - dm) != top)
            .count();
        let law = tabulate(&src, &options(grid))
            .unwrap_or_else(|e| panic!("reach {top:e}: the tabulator refused its table: {e}"));
        for b in law.branches() {
            let po = b.pull_out();
            assert_eq!(po.d, b.retract().reach(), "d_min {:e}", b.d_min());
            assert_eq!(po.pressure, 0.0);
        }
        let back = ContactLaw::from_json_str(&law.to_json_string())
            .unwrap_or_else(|e| panic!("reach {top:e}: the reader refused the table: {e}"));
        assert_eq!(back, law);
    }
    assert!(hazards > 0, "the grids must exercise the rounding");
}

/// A retract branch that is zero over part of its reported reach while the interpolant is
/// not: without a pressure floor (|p_pull_out| = 0) the metric would be infinite there; with
/// the floor it is the true, large error, recorded as it is, and the table is not converged.
#[test]
fn a_source_that_is_zero_where_the_table_is_not_gives_its_true_error_and_not_converged() {
    let src = NoAdhesion {
        top: 1e-8,
        sigma: 1e-9,
        zero_from: 0.37,
    };
    let law = tabulate(
        &src,
        &options(GridSpec {
            from: 2e-9,
            to: 6e-9,
            n: 3,
        }),
    )
    .unwrap();
    let m = law.measured_error().unwrap();
    assert!(law.pressure_floor() > 0.0);
    assert!(m.retract.max.is_finite() && m.retract.max > 1.0, "{m:?}");
    assert!(!law.tabulation().unwrap().converged);
    let text = law.to_json_string();
    let back = ContactLaw::from_json_str(&text).unwrap();
    assert_eq!(back, law);
    assert_eq!(back.measured_error().unwrap().max(), m.max());
}

/// An infinite error (a file written by another tool, or a source returning zero where
/// nothing floors the metric) is written as "inf", never as a finite stand-in, and a
/// table claiming convergence with it is refused.
#[test]
fn an_infinite_measured_error_is_written_as_inf_and_not_converged() {
    let mut v: Value = serde_json::from_str(&law().to_json_string()).unwrap();
    v["interpolation"]["measured_error"]["retract"]["max"] = json!("inf");
    v["interpolation"]["measured_error"]["retract"]["p99"] = json!("inf");
    v["tabulation"]["converged"] = json!(false);
    let law = ContactLaw::from_json_str(&v.to_string()).unwrap();
    let m = law.measured_error().unwrap();
    assert_eq!(m.retract.max, f64::INFINITY, "{m:?}");
    assert!(m.max().is_infinite() && !m.is_finite());
    let text = law.to_json_string();
    let w: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(
        w["interpolation"]["measured_error"]["retract"]["max"],
        "inf"
    );
    assert!(!text.contains("null"));
    // serde output of the statistics (the CLI's --format json) says "inf", not null
    let s = serde_json::to_string(m).unwrap();
    assert!(s.contains("\"max\":\"inf\"") && !s.contains("null"), "{s}");
    let again: contact_law::MeasuredError = serde_json::from_str(&s).unwrap();
    assert_eq!(again.retract.max, f64::INFINITY);

    // a file claiming convergence with an infinite error is refused
    let mut bad = w.clone();
    bad["tabulation"]["converged"] = json!(true);
    let e = ContactLaw::from_json_str(&bad.to_string()).unwrap_err();
    assert!(e.to_string().contains("tabulation.converged"), "{e}");
}

fn format_error(v: &Value) -> (String, String) {
    match ContactLaw::from_json_str(&v.to_string()) {
        Err(LawError::Format { path, message }) => (path, message),
        Err(e) => panic!("not a format error: {e}"),
        Ok(_) => panic!("accepted"),
    }
}

#[test]
fn measured_errors_are_numbers_at_least_0_or_inf() {
    let v: Value = serde_json::from_str(&law().to_json_string()).unwrap();
    let at = |v: &mut Value, key: &str, x: Value| {
        v["interpolation"]["measured_error"]["approach"][key] = x;
    };
    for (key, x, want) in [
        (
            "max",
            json!(-1e-3),
            "interpolation.measured_error.approach.max",
        ),
        (
            "max",
            json!("big"),
            "interpolation.measured_error.approach.max",
        ),
        (
            "max",
            json!("-inf"),
            "interpolation.measured_error.approach.max",
        ),
        (
            "p99",
            json!(1.0),
            "interpolation.measured_error.approach.p99",
        ),
        (
            "samples",
            json!(0),
            "interpolation.measured_error.approach.samples",
        ),
    ] {
        let mut w = v.clone();
        at(&mut w, key, x.clone());
        let (path, message) = format_error(&w);
        assert_eq!(path, want, "{key} = {x}: {message}");
    }
    // "inf" is read (with converged = false)
    let mut w = v.clone();
    at(&mut w, "max", json!("inf"));
    w["tabulation"]["converged"] = json!(false);
    let law = ContactLaw::from_json_str(&w.to_string()).unwrap();
    assert!(law.measured_error().unwrap().approach.max.is_infinite());
}

/// Special points must lie on their curves in pressure as well as in d, and be the most
/// tensile point of the curve.
#[test]
fn special_points_off_their_curves_are_refused() {
    let v: Value = serde_json::from_str(&law().to_json_string()).unwrap();
    let k = 3;
    let b = &v["branches"][k];
    fn node(curve: &Value, i: usize) -> (Value, Value) {
        (curve["d"][i].clone(), curve["pressure"][i].clone())
    }
    // a tensile node of the retract branch that is not its pull-out
    let retract = &b["retract"];
    let po_d = b["pull_out"]["d"].as_f64().unwrap();
    let n = retract["d"].as_array().unwrap().len();
    let other = (1..n)
        .find(|&i| retract["d"][i].as_f64().unwrap() > po_d)
        .unwrap();
    type Edit = Box<dyn Fn(&mut Value)>;
    let cases: Vec<(&str, Edit)> = vec![
        (
            "branches[3].pull_out.pressure",
            Box::new(|v| v["branches"][3]["pull_out"]["pressure"] = json!(1e12)),
        ),
        (
            "branches[3].pull_out.pressure",
            Box::new(|v| {
                let p = v["branches"][3]["pull_out"]["pressure"].as_f64().unwrap();
                v["branches"][3]["pull_out"]["pressure"] = json!(p * (1.0 + 1e-6));
            }),
        ),
        (
            "branches[3].pull_out.pressure",
            Box::new(move |v| {
                let (d, p) = node(&v["branches"][3]["retract"], other);
                v["branches"][3]["pull_out"] = json!({"d": d, "pressure": p});
            }),
        ),
        (
            "branches[3].approach.most_tensile.pressure",
            Box::new(|v| v["branches"][3]["approach"]["most_tensile"]["pressure"] = json!(-1e3)),
        ),
        (
            "virgin.most_tensile.pressure",
            Box::new(|v| {
                let (d, p) = node(&v["virgin"], 0);
                v["virgin"]["most_tensile"] = json!({"d": d, "pressure": p});
            }),
        ),
        (
            "virgin.most_tensile.pressure",
            Box::new(|v| {
                let d = v["virgin"]["most_tensile"]["d"].as_f64().unwrap();
                v["virgin"]["most_tensile"]["d"] = json!(d * 1.01);
            }),
        ),
    ];
    for (want, edit) in cases {
        let mut w = v.clone();
        edit(&mut w);
        let (path, message) = format_error(&w);
        assert_eq!(path, want, "{message}");
        assert!(message.contains("Pa"), "{message}");
    }
    assert!(k < v["branches"].as_array().unwrap().len());
}

#[test]
fn duplicated_keys_are_refused_naming_the_key() {
    let text = law().to_json_string();
    // the second "version" is on line 4 of the file
    let dup_version = text.replacen("\"version\": 2,", "\"version\": 2,\n  \"version\": 2,", 1);
    assert_ne!(dup_version, text);
    let e = ContactLaw::from_json_str(&dup_version).unwrap_err();
    match &e {
        LawError::Format { path, message } => {
            assert_eq!(path, "version");
            assert!(
                message.contains("duplicated key") && message.contains("line 4"),
                "{e}"
            );
        }
        other => panic!("not a format error: {other}"),
    }
    // deep in the tree, and inside the scene (stored, never interpreted, but one value)
    let mut v: Value = serde_json::from_str(&text).unwrap();
    v["scene"] = json!({"contact": {"radius": 1e-6}});
    let with_scene = serde_json::to_string(&v).unwrap();
    for (from, to, want) in [
        (
            "\"pull_out\":{\"d\":",
            "\"pull_out\":{\"pressure\":0,\"d\":",
            "branches[0].pull_out.pressure",
        ),
        (
            "\"radius\":1e-6",
            "\"radius\":1e-6,\"radius\":2e-6",
            "scene.contact.radius",
        ),
    ] {
        let bad = with_scene.replacen(from, to, 1);
        assert_ne!(bad, with_scene, "{from}");
        match ContactLaw::from_json_str(&bad) {
            Err(LawError::Format { path, message }) => {
                assert_eq!(path, want, "{message}");
                assert!(message.contains("duplicated key"));
            }
            other => panic!("{want}: {other:?}"),
        }
    }
    // a file without duplicates still reads, and other JSON errors stay JSON errors
    ContactLaw::from_json_str(&with_scene).unwrap();
    assert!(matches!(
        ContactLaw::from_json_str("{\"format\": 1e400}"),
        Err(LawError::Json(_))
    ));
}
