//! The probability of stiction under process scatter (`stiction_model::probability`, as
//! `stiction design probability`): the samples run here with rayon; the run's files
//! (`probability.json`, `samples.csv`) exactly as the command writes them; shards read
//! back and merged by the library (`design_sweep::merge_probability`).

use crate::convert::result_to_py;
use crate::design::warnings_to_py;
use crate::errors::{argument, OrRaise};
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
    /// The run as the command line presents it (labels from the run alone, as a merged
    /// run's: the same as the run's own).
    fn report(&self) -> stiction_report::probability::ProbabilityReport {
        stiction_report::probability::ProbabilityReport {
            warnings: self.warnings.clone(),
            validity: self.validity.clone(),
            model_form: self.model_form.clone(),
            ..stiction_report::probability::ProbabilityReport::merged(self.run.clone())
        }
    }

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
        stiction_report::render::json(&self.report())
    }

    /// `samples.csv` exactly as `stiction design probability --out` writes it.
    fn to_csv(&self) -> PyResult<String> {
        stiction_report::csv::samples_csv(&self.run).map_err(crate::report::report_error)
    }

    /// `probability.svg` exactly as `stiction design probability --out` writes it.
    fn to_svg(&self) -> PyResult<String> {
        use stiction_report::Plot;
        self.report().svg().map_err(crate::report::report_error)
    }

    /// The table `stiction design probability` prints.
    fn table(&self) -> String {
        use stiction_report::Render;
        self.report().table()
    }

    /// The files of `stiction design probability --out` (and of a merge), byte for byte:
    /// samples.csv, probability.json, probability.svg (and model_form.json with a
    /// model-form check), written to `dir` as the command writes them; the paths written.
    fn save(&self, py: Python<'_>, dir: PathBuf) -> PyResult<Vec<String>> {
        crate::report::save(py, &self.report(), dir)
    }

    /// The base scene's laws and modelling choices (its echo's contact section), or None.
    fn laws<'py>(&self, py: Python<'py>) -> PyResult<Option<Py<PyAny>>> {
        stiction_report::switch::laws_of_echo(&self.run.plan().scene)
            .map(|l| result_to_py(py, &l))
            .transpose()
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
    exact = true,
    count_outside_validity = false,
    progress = None
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
    count_outside_validity: bool,
    progress: Option<&Bound<'_, PyAny>>,
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
        count_outside_validity,
    };
    let r = crate::pool::run_reported(py, progress, true, move |p| {
        run(&scene, &registry(), &request, p)
    })?;
    Ok(PyProbability {
        run: r.probability,
        warnings: r.warnings,
        validity: Some(r.validity),
        model_form: r.model_form,
    })
}

/// The samples of a probability request for a cluster: the design scene of every sample
/// (TOML text) and each sample's `(index, [(field, value), ...])`, checked as
/// `design_probability` checks them before any sample runs.
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
    count_outside_validity = false
))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn design_probability_plan(
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
    count_outside_validity: bool,
) -> PyResult<(String, Vec<(usize, Vec<(String, f64)>)>)> {
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
        exact: false,
        count_outside_validity,
    };
    crate::pool::detach(py, move || {
        stiction_model::probability::samples_to_run(&scene, &registry(), &request)
    })
    .or_raise()
}

/// Assembles the workers' answers (`(index, answer)` per sample of the plan, as
/// `design_point` answers) into the probability run: the library's engine records them as
/// it records local evaluations, so the run equals `design_probability`'s (the exact
/// single-field answer, when asked, is searched here).
#[pyfunction]
#[pyo3(signature = (
    scene,
    scatter,
    answers,
    samples = 1000,
    seed = 0,
    correlate = None,
    confidence = 0.95,
    accuracy = None,
    shard = None,
    target_halfwidth = None,
    exact = true,
    count_outside_validity = false
))]
#[allow(clippy::too_many_arguments)]
pub fn design_probability_assemble(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    scatter: Vec<String>,
    answers: &Bound<'_, pyo3::types::PyList>,
    samples: usize,
    seed: u64,
    correlate: Option<Vec<String>>,
    confidence: f64,
    accuracy: Option<&str>,
    shard: Option<String>,
    target_halfwidth: Option<f64>,
    exact: bool,
    count_outside_validity: bool,
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
        count_outside_validity,
    };
    let (_, points) =
        stiction_model::probability::samples_to_run(&scene, &registry(), &request).or_raise()?;
    let values: std::collections::HashMap<usize, Vec<f64>> = points
        .into_iter()
        .map(|(i, v)| (i, v.into_iter().map(|(_, x)| x).collect()))
        .collect();
    let mut got = std::collections::HashMap::new();
    for item in answers.iter() {
        let (index, answer): (usize, crate::design::AnswerIn<'_>) = item.extract()?;
        let Some(v) = values.get(&index) else {
            return Err(argument(
                "answers",
                format!("a sample of index {index}"),
                "the indices of the plan's samples",
            ));
        };
        got.insert(
            stiction_model::probability::answer_key(v),
            crate::design::answer_of(index, answer)?,
        );
    }
    let r = crate::pool::detach(py, move || {
        stiction_model::probability::run_answered(
            &scene,
            &registry(),
            &request,
            &Silent,
            Some(&got),
        )
    })
    .or_raise()?;
    Ok(PyProbability {
        run: r.probability,
        warnings: r.warnings,
        validity: Some(r.validity),
        model_form: None,
    })
}

/// A probability run with its model-form check from the runs of the other combinations
/// (each with its form, as `model_form_scenes` gave it), run elsewhere.
#[pyfunction]
pub fn with_probability_model_form(
    own: &PyProbability,
    accuracy: &str,
    forms: Vec<(Bound<'_, PyAny>, PyRef<'_, PyProbability>)>,
    excluded: &str,
) -> PyResult<PyProbability> {
    use stiction_model::model_form::{
        form_of_echo, Form, ProbabilityFormRun, ProbabilityModelForm,
    };
    let mode = accuracy_arg(Some(accuracy))?.unwrap_or_default();
    let of = |form: &Form, p: &Probability| {
        let s = p.summary();
        ProbabilityFormRun {
            laws: form.laws(),
            stiction_probability: s.stiction_probability,
            interval: [s.ci_low, s.ci_high],
            sticking: s.stiction.count,
            counted: s.denominator,
        }
    };
    let own_form = form_of_echo(&own.run.plan().scene)
        .ok_or_else(|| argument("own", "a run", "a run whose scene names its laws"))?;
    let mut runs = vec![of(&own_form, &own.run)];
    for (f, r) in &forms {
        let v = crate::convert::py_to_json(f, "<form>", "form")?;
        let form: Form = serde_json::from_value(v)
            .map_err(|e| argument("forms", "a form", format!("a model form: {e}")))?;
        runs.push(of(&form, &r.run));
    }
    let excluded = serde_json::from_str(excluded)
        .map_err(|e| argument("excluded", "text", format!("what a check left out: {e}")))?;
    Ok(PyProbability {
        run: own.run.clone(),
        warnings: own.warnings.clone(),
        validity: own.validity.clone(),
        model_form: Some(ProbabilityModelForm::of(
            mode,
            own.run.summary().confidence,
            runs,
            excluded,
        )),
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
