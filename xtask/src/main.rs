//! `cargo xtask verify [--update]`: solves every embedded scene and compares its curves
//! and figures with the insta snapshots in `xtask/snapshots/`.
//! `cargo xtask tradeoff`: the speed/accuracy trade of the paper's switch, per mode.
//! `cargo xtask docs`: the scene-key table of docs/validation.md from the key registry.
//! `cargo xtask accuracy [--scenes N] [--seed S] [--no-stopping-rule] [--times FILE] [--scene-files DIR [--no-runs]]`: each mode's error and speed-up over
//! random scenes of the documented domains (docs/performance.md).
//!
//! Tolerance: snapshots store numbers rounded to 7 significant digits. A scene passes when
//! every number agrees with its snapshot within 1e-6 relative, or within 1e-10 of the
//! largest magnitude in that snapshot (the tails of a curve sit near zero); otherwise
//! insta prints a readable line diff and verify exits non-zero. `--update` rewrites the
//! snapshots that are out of tolerance (review the diff in git).

mod accuracy;
mod law;
mod tradeoff;

fn report(r: Result<(), String>) -> ExitCode {
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}

use serde_json::Value;
use std::process::ExitCode;
use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene;
use stiction_model::spec::{AsperitySpec, SurfaceSpec, SwitchSpec};
use stiction_model::switch::SwitchModel;
use stiction_model::{asperity, md, surface, Silent};

const DIGITS: i32 = 7;
/// Points per curve in the snapshots: enough to see every branch, few enough to review.
const POINTS: usize = 41;

/// Rounds every number in a JSON tree to `DIGITS` significant digits.
fn round(v: Value) -> Value {
    match v {
        Value::Number(n) => {
            let x = n.as_f64().unwrap_or(0.0);
            if x == 0.0 || !x.is_finite() {
                return Value::Number(n);
            }
            let r: f64 = format!("{:.*e}", (DIGITS - 1) as usize, x)
                .parse()
                .unwrap_or(x);
            serde_json::Number::from_f64(r).map_or(Value::Null, Value::Number)
        }
        Value::Array(a) => Value::Array(a.into_iter().map(round).collect()),
        Value::Object(o) => Value::Object(o.into_iter().map(|(k, v)| (k, round(v))).collect()),
        other => other,
    }
}

const RTOL: f64 = 1e-6;
const ATOL_OF_MAX: f64 = 1e-10;

fn max_abs(v: &Value) -> f64 {
    match v {
        Value::Number(n) => n.as_f64().unwrap_or(0.0).abs(),
        Value::Array(a) => a.iter().map(max_abs).fold(0.0, f64::max),
        Value::Object(o) => o.values().map(max_abs).fold(0.0, f64::max),
        _ => 0.0,
    }
}

/// Same shape, same strings and flags, numbers within tolerance.
fn close(a: &Value, b: &Value, atol: f64) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (
                x.as_f64().unwrap_or(f64::NAN),
                y.as_f64().unwrap_or(f64::NAN),
            );
            (x - y).abs() <= RTOL * x.abs().max(y.abs()) + atol
        }
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(p, q)| close(p, q, atol))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len()
                && x.iter()
                    .all(|(k, p)| y.get(k).is_some_and(|q| close(p, q, atol)))
        }
        _ => a == b,
    }
}

/// The JSON body of a committed insta snapshot, if there is one.
fn committed(name: &str) -> Option<Value> {
    let path = format!("{}/snapshots/{name}.snap", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).ok()?;
    // header: "---", metadata lines, "---", then the body
    let body = text.splitn(3, "---\n").nth(2)?;
    serde_json::from_str(body).ok()
}

/// Every embedded scene solved as the CLI solves it, with `POINTS`-point curves; the
/// scene echo is left out (it is the committed scene file itself).
fn scenes() -> Result<Vec<(String, Value)>, String> {
    let err = |e: stiction_model::ModelError| e.to_string();
    let json = |v: Result<Value, serde_json::Error>| v.map_err(|e| e.to_string());
    let strip = |mut v: Value| {
        if let Some(o) = v.as_object_mut() {
            o.remove("scene");
        }
        v
    };
    // the paper's scene of `kind` with `POINTS`-point curves
    let paper = |kind: Kind| -> Result<Scene, String> {
        let mut s = Scene::paper(kind);
        s.set_number("points", POINTS as f64)
            .map_err(|e| e.to_string())?;
        Ok(s)
    };
    let registry = LawRegistry::builtin();
    let mut out = Vec::new();
    for lambda in [0.01, 0.1, 0.5, 0.9, 1.0, 2.0, 10.0, 100.0] {
        let r = md::curve(lambda, POINTS, 5.0).map_err(err)?;
        out.push((
            format!("md_lambda_{lambda}"),
            json(serde_json::to_value(r))?,
        ));
    }
    let spec = AsperitySpec::new(&paper(Kind::Asperity)?, &registry).map_err(err)?;
    let r = asperity::run(&spec).map_err(err)?;
    out.push((
        "asperity_fig2".into(),
        strip(json(serde_json::to_value(r))?),
    ));
    let spec = SurfaceSpec::new(&paper(Kind::Surface)?, &registry).map_err(err)?;
    let r = surface::run(&spec).map_err(err)?;
    out.push(("surface_ru".into(), strip(json(serde_json::to_value(r))?)));
    let spec = SwitchSpec::new(&paper(Kind::Switch)?, &registry).map_err(err)?;
    let r = SwitchModel::build(&spec)
        .and_then(|m| m.run(&Silent))
        .map_err(err)?;
    let mut v = strip(json(serde_json::to_value(&r))?);
    // the elastic comparison gets a snapshot of its own
    let elastic = v
        .as_object_mut()
        .and_then(|o| o.remove("elastic"))
        .unwrap_or(Value::Null);
    out.push(("switch_fig4".into(), v));
    out.push(("switch_elastic_comparison".into(), elastic));
    Ok(out)
}

/// `cargo xtask docs`: rewrites the scene-key table of docs/validation.md from the key
/// registry (`tests/domains.rs` fails while the two differ).
fn field_table() -> Result<(), String> {
    const BEGIN: &str = "<!-- scene fields: begin -->";
    const END: &str = "<!-- scene fields: end -->";
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/validation.md");
    let doc = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let (Some(a), Some(b)) = (doc.find(BEGIN), doc.find(END)) else {
        return Err(format!("{path}: no {BEGIN} ... {END} markers"));
    };
    let table = stiction_model::keys::markdown_table();
    let new = format!(
        "{}{BEGIN}\n{table}{END}{}",
        &doc[..a],
        &doc[b + END.len()..]
    );
    std::fs::write(path, new).map_err(|e| format!("{path}: {e}"))?;
    println!("wrote the scene-key table of docs/validation.md");
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let update = match args
        .iter()
        .map(String::as_str)
        .collect::<Vec<_>>()
        .as_slice()
    {
        ["verify"] => false,
        ["verify", "--update"] => true,
        ["tradeoff"] => return report(tradeoff::main()),
        ["docs"] => return report(field_table()),
        ["accuracy", rest @ ..] => return report(accuracy::main(rest)),
        ["law", rest @ ..] => return report(law::main(rest)),
        _ => {
            eprintln!("usage: cargo xtask verify [--update] | cargo xtask tradeoff | cargo xtask accuracy [--scenes N] [--seed S] [--no-stopping-rule] [--times FILE] [--scene-files DIR [--no-runs]] | cargo xtask law [--scenes N] [--seed S] [--domain mems|wide] [--held-out K] | cargo xtask docs");
            return ExitCode::from(2);
        }
    };
    // insta reads its mode from the environment: compare only, or accept everything.
    std::env::set_var("INSTA_UPDATE", if update { "always" } else { "no" });
    std::env::set_var("INSTA_FORCE_PASS", "0");
    let scenes = match scenes() {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: a scene failed to solve: {e}");
            return ExitCode::from(1);
        }
    };
    let mut failed = Vec::new();
    for (name, value) in scenes {
        let value = round(value);
        if let Some(old) = committed(&name) {
            if close(&old, &value, ATOL_OF_MAX * max_abs(&old)) {
                println!("ok       {name}");
                continue;
            }
        }
        let ok = std::panic::catch_unwind(|| {
            let mut settings = insta::Settings::clone_current();
            settings.set_snapshot_path(concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"));
            settings.set_prepend_module_to_snapshot(false);
            settings.set_omit_expression(true);
            settings.bind(|| insta::assert_json_snapshot!(name.as_str(), value));
        });
        match ok {
            Ok(()) => println!("ok       {name}"),
            Err(_) => {
                println!("CHANGED  {name}");
                failed.push(name);
            }
        }
    }
    if update {
        println!("verify --update: snapshots written; review them with `git diff xtask/snapshots`");
        ExitCode::SUCCESS
    } else if failed.is_empty() {
        println!("verify: every scene matches its snapshot (within {RTOL:e} relative)");
        ExitCode::SUCCESS
    } else {
        eprintln!("verify: {} scene(s) changed: {failed:?}; if intended, run `cargo xtask verify --update` and review the diff", failed.len());
        ExitCode::from(1)
    }
}
