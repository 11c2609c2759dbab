//! Runs: a scene of any kind, the Maugis-Kim curve, a calibration. Each computes with the
//! GIL released and returns the library's typed result as Python data (a dict tree with
//! numpy arrays), which `stiction/_results.py` wraps.

use crate::convert::{result_to_py, value_to_py};
use crate::errors::{argument, OrRaise};
use crate::report::{self, Kept};
use crate::scene::{registry, scene_from_py};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use stiction_model::calibration::{self, CalibError, Selection};
use stiction_model::spec::{AsperitySpec, Spec};
use stiction_model::{asperity, md, surface, ModelError};

/// Sets the accuracy mode on a copy of the scene, as the CLI's `--accuracy` does.
pub fn with_accuracy(
    mut scene: stiction_model::scene::Scene,
    accuracy: Option<&str>,
) -> PyResult<stiction_model::scene::Scene> {
    if let Some(a) = accuracy {
        scene
            .set("accuracy", toml::Value::String(a.to_string()))
            .or_raise()?;
    }
    Ok(scene)
}

/// The accuracy mode argument (`None`: the scene's).
pub fn accuracy_arg(accuracy: Option<&str>) -> PyResult<Option<stiction_model::Accuracy>> {
    accuracy
        .map(|a| {
            stiction_model::Accuracy::from_name(a).ok_or_else(|| {
                argument(
                    "accuracy",
                    format!("\"{a}\""),
                    "one of accurate, balanced, fast, reference",
                )
            })
        })
        .transpose()
}

enum Ran {
    Asperity(Box<asperity::AsperityResult>),
    Surface(Box<surface::SurfaceResult>),
    Switch(Box<stiction_model::switch::SwitchResult>),
}

/// Runs a scene of any kind: `(kind, result)` with the result of `stiction asperity`,
/// `stiction surface` or `stiction switch` on that scene; `progress(done, total)` is
/// called as cycles (and model-form combinations) complete, and Ctrl-C stops the run.
#[pyfunction]
#[pyo3(signature = (scene, accuracy = None, progress = None))]
pub fn run(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    accuracy: Option<&str>,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<(&'static str, Py<PyAny>)> {
    let scene = with_accuracy(scene_from_py(scene)?, accuracy)?;
    let ran = crate::pool::run_reported(py, progress, true, move |p| -> Result<Ran, ModelError> {
        Ok(match Spec::new(&scene, &registry())? {
            // one step: these runs take a fraction of a second
            Spec::Asperity(s) => {
                p.start(1, "run");
                let r = asperity::run(&s)?;
                p.finish();
                Ran::Asperity(Box::new(r))
            }
            Spec::Surface(s) => {
                p.start(1, "run");
                let r = surface::run(&s)?;
                p.finish();
                Ran::Surface(Box::new(r))
            }
            Spec::Switch(s) => Ran::Switch(Box::new(stiction_model::model_form::run_switch(
                &s,
                &registry(),
                p,
            )?)),
            _ => {
                return Err(ModelError::argument(
                    "scene",
                    scene.file(),
                    "an asperity, surface or switch scene",
                ))
            }
        })
    })?;
    Ok(match ran {
        Ran::Asperity(r) => ("asperity", report::result(py, Kept::Asperity(r))?),
        Ran::Surface(r) => ("surface", report::result(py, Kept::Surface(r))?),
        Ran::Switch(r) => ("switch", report::result(py, Kept::Switch(r))?),
    })
}

/// The nondimensional Maugis-Kim curve of `lam` (`stiction md --lambda`).
#[pyfunction]
#[pyo3(signature = (lam, points = 200, delta_end = 5.0))]
pub fn md_curve(py: Python<'_>, lam: f64, points: i64, delta_end: f64) -> PyResult<Py<PyAny>> {
    if points < 0 {
        return Err(argument("points", points.to_string(), "in [4, 100000]"));
    }
    let r =
        crate::pool::detach(py, move || md::curve(lam, points as usize, delta_end)).or_raise()?;
    crate::report::result(py, crate::report::Kept::Md(Box::new(r)))
}

/// Calibration of eq 13 (`stiction calibrate`): `fe` a CSV path, or `fe_text` CSV text
/// named `fe_name`; `fit` as `--fit` (c1, c2, all, a1 ... b3, comma-separated).
#[pyfunction]
#[pyo3(signature = (scene, fe = None, fe_text = None, fe_name = "<columns>", fit = "c1,c2", overlay = false))]
pub fn calibrate(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    fe: Option<PathBuf>,
    fe_text: Option<String>,
    fe_name: &str,
    fit: &str,
    overlay: bool,
) -> PyResult<Py<PyAny>> {
    let scene = scene_from_py(scene)?;
    let select: Selection = fit.parse().map_err(|e: CalibError| {
        let reason = match e {
            CalibError::Selection { reason, .. } => reason,
            other => other.to_string(),
        };
        crate::errors::raise(ModelError::Option {
            name: "fit".into(),
            message: format!("\"{fit}\": {reason}"),
        })
    })?;
    let fe_file = match &fe {
        Some(p) => p.display().to_string(),
        None => fe_name.to_string(),
    };
    let in_file = |e: CalibError| ModelError::InScene {
        file: fe_file.clone(),
        source: Box::new(ModelError::Calibrate(e)),
    };
    let data = match (&fe, fe_text) {
        (Some(p), None) => calibration::read_fe(p).map_err(|e| match e {
            e @ CalibError::Io { .. } => ModelError::from(e),
            e => in_file(e),
        }),
        (None, Some(t)) => calibration::FeData::parse_csv(&t).map_err(in_file),
        _ => {
            return Err(argument(
                "fe",
                "both or neither of a file and columns",
                "a CSV file of finite-element curves, or its columns",
            ))
        }
    }
    .or_raise()?;
    if data.len() < select.len() {
        return Err(crate::errors::raise(in_file(CalibError::TooFewPoints {
            line: calibration::last_line(&data),
            points: data.len(),
            constants: select.len(),
        })));
    }
    let fe_file2 = fe_file.clone();
    let r = crate::pool::detach(py, move || -> Result<_, ModelError> {
        let spec = AsperitySpec::new(&scene, &registry())?;
        calibration::calibrate(&spec, &data, &fe_file2, select, overlay)
    })
    .or_raise()?;
    let out = result_to_py(py, &r)?;
    let d = out.bind(py).cast::<PyDict>()?;
    d.set_item(
        "_report",
        report::handle(py, Kept::Calibration(Box::new(r.clone())))?,
    )?;
    let points = serde_json::to_value(&r.points).unwrap_or_default();
    d.set_item("points", value_to_py(py, &points)?)?;
    let ov = serde_json::to_value(&r.overlay).unwrap_or_default();
    d.set_item("overlay", value_to_py(py, &ov)?)?;
    Ok(out)
}
