//! The probability of stiction under process scatter (`stiction_model::probability`, as
//! `stiction design probability`): the samples run here with rayon; the run's files
//! (`probability.json`, `samples.csv`) exactly as the command writes them; shards read
//! back and merged by the library (`design_sweep::merge_probability`).

use crate::convert::result_to_py;
use crate::design::warnings_to_py;
use crate::errors::OrRaise;
use crate::run::accuracy_arg;
use crate::scene::{registry, scene_from_py};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use stiction_model::design_sweep::{self, Probability};
use stiction_model::guards::{Validity, Warning};
use stiction_model::probability::{run, ProbabilityRequest};
use stiction_model::{ModelError, Silent};

/// A computed probability run (whole, one shard, or merged), with the guards its samples
/// raised (none for a run read back or merged: the files do not hold them).
#[pyclass(name = "NativeProbability", module = "stiction._stiction", frozen)]
pub struct PyProbability {
    run: Probability,
    warnings: Vec<Warning>,
    validity: Option<Validity>,
    model_form: Option<stiction_model::model_form::ProbabilityModelForm>,
}

impl PyProbability {
    fn read(run: Probability) -> Self {
        Self {
            run,
            warnings: Vec::new(),
            validity: None,
            model_form: None,
        }
    }
}

#[pymethods]
impl PyProbability {
    /// `probability.json` exactly as `stiction design probability --out` writes it (the
    /// statistics, the exact answer, the question and every sample).
    fn to_json(&self) -> String {
        self.run.to_json()
    }

    /// What `stiction design probability --format json` prints: `probability.json`
    /// without the samples.
    fn summary_json(&self) -> String {
        // as the command prints it: the run's view, then the validity of its samples
        #[derive(serde::Serialize)]
        struct Out<'a> {
            #[serde(flatten)]
            run: design_sweep::ProbabilityView<'a>,
            #[serde(skip_serializing_if = "Option::is_none")]
            validity: Option<&'a Validity>,
        }
        let mut s = serde_json::to_string_pretty(&Out {
            run: self.run.view(false),
            validity: self.validity.as_ref(),
        })
        .expect("a probability run always serialises");
        s.push('\n');
        s
    }

    /// `samples.csv` exactly as `stiction design probability --out` writes it.
    fn to_csv(&self) -> PyResult<String> {
        self.run.to_csv().map_err(ModelError::from).or_raise()
    }

    /// The run as Python data: probability.json's keys (the samples under `points`), plus
    /// `warnings` and `validity`.
    fn data<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let out = result_to_py(py, &self.run)?.into_bound(py);
        let d = out.cast::<PyDict>()?;
        d.set_item("warnings", warnings_to_py(py, &self.warnings)?)?;
        match &self.validity {
            Some(v) => d.set_item("validity", result_to_py(py, v)?)?,
            None => d.set_item("validity", py.None())?,
        }
        if let Some(m) = &self.model_form {
            d.set_item("model_form", result_to_py(py, m)?)?;
        }
        Ok(out)
    }
}

/// `stiction.design_probability`: the samples of the request run here in parallel
/// (rayon), with the GIL released. The arguments are those of `stiction design
/// probability` (`scatter` its `--scatter` strings, `correlate` its `--correlate`
/// strings), checked by the library before any sample runs.
#[pyfunction]
#[pyo3(signature = (
    scene,
    scatter,
    samples = 1000,
    seed = 0,
    correlate = None,
    confidence = 0.95,
    accuracy = None,
    shard = None,
    target_halfwidth = None,
    exact = true
))]
#[allow(clippy::too_many_arguments)]
pub fn design_probability(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    scatter: Vec<String>,
    samples: usize,
    seed: u64,
    correlate: Option<Vec<String>>,
    confidence: f64,
    accuracy: Option<&str>,
    shard: Option<String>,
    target_halfwidth: Option<f64>,
    exact: bool,
) -> PyResult<PyProbability> {
    let scene = scene_from_py(scene)?;
    let request = ProbabilityRequest {
        scatter,
        correlate: correlate.unwrap_or_default(),
        samples,
        seed,
        confidence,
        shard,
        target_halfwidth,
        accuracy: accuracy_arg(accuracy)?,
        exact,
    };
    let r =
        crate::pool::detach(py, move || run(&scene, &registry(), &request, &Silent)).or_raise()?;
    Ok(PyProbability {
        run: r.probability,
        warnings: r.warnings,
        validity: Some(r.validity),
        model_form: r.model_form,
    })
}

/// Reads a `probability.json` (of `stiction design probability`, whole, merged or a
/// shard), checked as `stiction design merge` checks it (every sample's values are those
/// its seed gives).
#[pyfunction]
pub fn read_probability(path: PathBuf) -> PyResult<PyProbability> {
    let run = Probability::read_path(&path)
        .map_err(ModelError::from)
        .or_raise()?;
    Ok(PyProbability::read(run))
}

/// Joins the shards of one probability run (`stiction design merge`): each a
/// NativeProbability or the path of a `probability.json`.
#[pyfunction]
pub fn design_merge_probability(parts: &Bound<'_, PyList>) -> PyResult<PyProbability> {
    let mut shards = Vec::new();
    for (i, p) in parts.iter().enumerate() {
        if let Ok(r) = p.cast::<PyProbability>() {
            shards.push((format!("part {}", i + 1), r.get().run.clone()));
        } else {
            let path: PathBuf = p.extract()?;
            let run = Probability::read_path(&path)
                .map_err(ModelError::from)
                .or_raise()?;
            shards.push((path.display().to_string(), run));
        }
    }
    let run = design_sweep::merge_probability(shards)
        .map_err(ModelError::from)
        .or_raise()?;
    Ok(PyProbability::read(run))
}
