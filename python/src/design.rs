//! Stiction-free design: thresholds and maps (`stiction_model::design`), run here with
//! rayon, or point by point elsewhere (a Dask cluster): the plan of a map (its base scene
//! and points), one point as a worker evaluates it, and the assembly of the workers'
//! answers into exactly the map `stiction design map` writes (`design_sweep::run_map` over
//! the answers, so statuses and checks are the library's).

use crate::convert::{py_to_json, result_to_py, value_to_py};
use crate::errors::{argument, OrRaise};
use crate::run::accuracy_arg;
use crate::scene::{registry, scene_from_py};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::collections::HashMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use stiction_model::design::{
    self, design_point as reduce, map_labels, DesignPoint, Evaluator, Grid, Level, Map, MapResult,
    PointError,
};
use stiction_model::design_sweep;
use stiction_model::guards::{code, Validity, Warning};
use stiction_model::scene::Scene;
use stiction_model::ModelError;

/// `stiction.design_threshold`: the critical value of one field (`stiction design
/// threshold`), `progress(done, total)` called as design points complete.
#[pyfunction]
#[pyo3(signature = (scene, vary, from_, to, accuracy = None, require = None, progress = None))]
#[allow(clippy::too_many_arguments)]
pub fn design_threshold(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    vary: &str,
    from_: f64,
    to: f64,
    accuracy: Option<&str>,
    require: Option<String>,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<Py<PyAny>> {
    let scene = scene_from_py(scene)?;
    let acc = accuracy_arg(accuracy)?;
    let vary = vary.to_string();
    let r = crate::pool::run_reported(py, progress, true, move |p| {
        design::threshold_with(
            &scene,
            &registry(),
            &vary,
            from_,
            to,
            acc,
            require.as_deref(),
            p,
        )
    })?;
    let out = result_to_py(py, &r)?;
    let d = out.bind(py).cast::<PyDict>()?;
    d.set_item("warnings", warnings_to_py(py, &r.warnings)?)?;
    crate::report::with_handle(py, out, crate::report::Kept::Threshold(Box::new(r)))
}

pub(crate) fn warnings_to_py<'py>(py: Python<'py>, w: &[Warning]) -> PyResult<Bound<'py, PyAny>> {
    let v: Vec<serde_json::Value> = w
        .iter()
        .map(|w| {
            serde_json::json!({
                "code": w.code,
                "message": w.message,
                "breaks_validity": w.breaks_validity,
            })
        })
        .collect();
    let list = PyList::empty(py);
    for x in &v {
        list.append(value_to_py(py, x)?)?;
    }
    Ok(list.into_any())
}

/// A computed design map (whole, one shard, or merged), with the guards its points raised.
#[pyclass(name = "NativeMap", module = "stiction._stiction", frozen)]
pub struct PyMap {
    map: Map,
    warnings: Vec<Warning>,
    validity: Option<Validity>,
    model_form: Option<stiction_model::model_form::MapModelForm>,
}

impl PyMap {
    /// The map as the command line presents it (units from the map, as every map's).
    fn report(&self) -> stiction_report::design::MapReport {
        stiction_report::design::MapReport {
            warnings: self.warnings.clone(),
            validity: self.validity.clone(),
            model_form: self.model_form.clone(),
            ..stiction_report::design::MapReport::merged(self.map.clone())
        }
    }

    fn of(r: MapResult) -> Self {
        Self {
            map: r.map,
            warnings: r.warnings,
            validity: Some(r.validity),
            model_form: r.model_form,
        }
    }
}

#[pymethods]
impl PyMap {
    /// `map.json` exactly as `stiction design map` writes it.
    fn to_json(&self) -> String {
        self.map.to_json()
    }

    /// `map.csv` exactly as `stiction design map` writes it.
    fn to_csv(&self) -> PyResult<String> {
        stiction_report::csv::map_csv(&self.map).map_err(crate::report::report_error)
    }

    /// `map.svg` exactly as `stiction design map` writes it.
    fn to_svg(&self) -> PyResult<String> {
        use stiction_report::Plot;
        self.report().svg().map_err(crate::report::report_error)
    }

    /// The table `stiction design map` prints.
    fn table(&self) -> String {
        use stiction_report::Render;
        self.report().table()
    }

    /// The files of `stiction design map --out` (and of a merge), byte for byte, written
    /// to `dir` as the command writes them; the paths written.
    fn save(&self, py: Python<'_>, dir: PathBuf) -> PyResult<Vec<String>> {
        crate::report::save(py, &self.report(), dir)
    }

    /// The SI unit of each varied field (`switch.k_s` -> `Pa/m`), as the plot labels it.
    fn units(&self) -> std::collections::BTreeMap<String, String> {
        map_labels(&self.map).units
    }

    /// The base scene's laws and modelling choices (its echo's contact section), or None.
    fn laws<'py>(&self, py: Python<'py>) -> PyResult<Option<Py<PyAny>>> {
        stiction_report::switch::laws_of_echo(self.map.scene())
            .map(|l| result_to_py(py, &l))
            .transpose()
    }

    /// The map as Python data: map.json's keys (`scene`, `grid`, `accuracy`, `points`,
    /// `shard`), plus `warnings` and `validity`.
    fn data<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let out = result_to_py(py, &self.map)?.into_bound(py);
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

/// `stiction.design_map` without a cluster: the points in parallel here (rayon),
/// `progress(done, total)` called as they complete.
#[pyfunction]
#[pyo3(signature = (scene, vary, accuracy = None, shard = None, require = None, progress = None))]
pub fn design_map(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    vary: Vec<String>,
    accuracy: Option<&str>,
    shard: Option<&str>,
    require: Option<String>,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyMap> {
    let scene = scene_from_py(scene)?;
    let acc = accuracy_arg(accuracy)?;
    let shard = shard.map(str::to_string);
    let r = crate::pool::run_reported(py, progress, true, move |p| {
        design::map_with(
            &scene,
            &registry(),
            &vary,
            shard.as_deref(),
            acc,
            require.as_deref(),
            p,
        )
    })?;
    Ok(PyMap::of(r))
}

/// A field value of a design point as Python gives and takes it: a float, or the word of
/// a categorical axis (a law name, a choice).
#[derive(Debug, Clone, FromPyObject, IntoPyObject)]
pub enum FieldValue {
    /// A number (SI).
    Number(f64),
    /// A word.
    Word(String),
}

impl FieldValue {
    fn level(&self) -> Level<'_> {
        match self {
            FieldValue::Number(x) => Level::Number(*x),
            FieldValue::Word(w) => Level::Word(w),
        }
    }
}

impl From<Level<'_>> for FieldValue {
    fn from(l: Level<'_>) -> Self {
        match l {
            Level::Number(x) => FieldValue::Number(x),
            Level::Word(w) => FieldValue::Word(w.to_owned()),
        }
    }
}

/// The plan of a map for a cluster: the base scene of every point (the design settings
/// applied) as TOML text, and the points to run, `(index, [(field, value), ...])` (a value
/// a float, or a word on a categorical axis), checked as `stiction design map` checks them
/// before any point runs.
#[pyfunction]
#[pyo3(signature = (scene, vary, accuracy = None, shard = None, require = None))]
#[allow(clippy::type_complexity)]
pub fn design_map_plan(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    vary: Vec<String>,
    accuracy: Option<&str>,
    shard: Option<&str>,
    require: Option<String>,
) -> PyResult<(String, Vec<(usize, Vec<(String, FieldValue)>)>)> {
    let scene = scene_from_py(scene)?;
    let acc = accuracy_arg(accuracy)?;
    let shard = shard.map(str::to_string);
    let (base, request, _) = crate::pool::detach(py, move || {
        design::map_request_with(
            &scene,
            &registry(),
            &vary,
            shard.as_deref(),
            acc,
            require.as_deref(),
        )
    })
    .or_raise()?;
    let text = toml::to_string(base.tree()).map_err(|e| {
        argument(
            "scene",
            base.file().to_string(),
            format!("writable as TOML: {e}"),
        )
    })?;
    let grid = &request.grid;
    let indices: Vec<usize> = match request.shard {
        Some(s) => s.indices(grid.len()).collect(),
        None => (0..grid.len()).collect(),
    };
    let points = indices
        .into_iter()
        .map(|i| {
            let values = grid
                .axes()
                .iter()
                .map(|a| a.field.clone())
                .zip(grid.levels(i).into_iter().map(FieldValue::from))
                .collect();
            (i, values)
        })
        .collect();
    Ok((text, points))
}

/// What a worker answers for one point: (status, design point as a dict or None, message
/// or None, warnings as (code, message, breaks_validity)).
type Answer = (
    &'static str,
    Option<Py<PyAny>>,
    Option<String>,
    Vec<(String, String, bool)>,
);

/// A worker's answer for point or sample `index` as the library's: the design point (or
/// why there is none) and the guards it raised.
pub(crate) fn answer_of(
    index: usize,
    (status, point, message, warnings): AnswerIn<'_>,
) -> PyResult<(Result<DesignPoint, PointError>, Vec<Warning>)> {
    let result = match (status.as_str(), point) {
        ("ok", Some(p)) => {
            let v = py_to_json(&p, "<answer>", "point")?;
            let d: DesignPoint = serde_json::from_value(v).map_err(|e| {
                argument(
                    "answers",
                    format!("point {index}"),
                    format!("a design point: {e}"),
                )
            })?;
            Ok(d)
        }
        ("out_of_domain", _) => Err(PointError::OutOfDomain(message.unwrap_or_default())),
        _ => Err(PointError::Failed(message.unwrap_or_default())),
    };
    let w = warnings
        .into_iter()
        .map(|(c, m, b)| Warning {
            code: static_code(&c),
            message: m,
            breaks_validity: b,
        })
        .collect();
    Ok((result, w))
}

/// The forms of a checked design question for a cluster (`model_form = "check"`): the mode
/// the other combinations run in, each one's form (a dict of its four choices) and scene,
/// and what is left out (as JSON text, handed back to the `with_*_model_form` functions);
/// None when the scene does not ask for a check.
#[pyfunction]
#[pyo3(signature = (scene, accuracy = None))]
#[allow(clippy::type_complexity)]
pub fn model_form_scenes(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    accuracy: Option<&str>,
) -> PyResult<
    Option<(
        &'static str,
        Vec<(Py<PyAny>, crate::scene::PyScene)>,
        String,
    )>,
> {
    let scene = scene_from_py(scene)?;
    let acc = accuracy_arg(accuracy)?;
    let Some((mode, forms, excluded)) =
        stiction_model::model_form::design_forms(&scene, &registry(), acc).or_raise()?
    else {
        return Ok(None);
    };
    let mut out = Vec::new();
    for (form, s) in forms {
        out.push((result_to_py(py, &form)?, crate::scene::PyScene { scene: s }));
    }
    let excluded = serde_json::to_string(&excluded)
        .map_err(|e| argument("scene", "a check", format!("its exclusions as JSON: {e}")))?;
    Ok(Some((mode.as_str(), out, excluded)))
}

/// A map with its model-form check from the maps of the other combinations (each with its
/// form, as `model_form_scenes` gave it), run elsewhere: the share of the combinations that
/// stick at each point.
#[pyfunction]
pub fn with_map_model_form(
    own: &PyMap,
    accuracy: &str,
    forms: Vec<(Bound<'_, PyAny>, PyRef<'_, PyMap>)>,
    excluded: &str,
) -> PyResult<PyMap> {
    let mode = accuracy_arg(Some(accuracy))?.unwrap_or_default();
    let own_laws = stiction_model::model_form::form_of_echo(own.map.scene())
        .map(|f| f.laws())
        .ok_or_else(|| argument("own", "a map", "a map whose scene names its laws"))?;
    let mut maps = vec![(own_laws, &own.map)];
    let mut laws = Vec::new();
    for (f, _) in &forms {
        let v = py_to_json(f, "<form>", "form")?;
        let form: stiction_model::model_form::Form = serde_json::from_value(v)
            .map_err(|e| argument("forms", "a form", format!("a model form: {e}")))?;
        laws.push(form.laws());
    }
    for (l, (_, m)) in laws.into_iter().zip(&forms) {
        maps.push((l, &m.map));
    }
    let excluded = serde_json::from_str(excluded)
        .map_err(|e| argument("excluded", "text", format!("what a check left out: {e}")))?;
    Ok(PyMap {
        map: own.map.clone(),
        warnings: own.warnings.clone(),
        validity: own.validity.clone(),
        model_form: Some(stiction_model::model_form::MapModelForm::of(
            mode, &maps, excluded,
        )),
    })
}

/// An [`Answer`] as the assembly reads it back.
pub(crate) type AnswerIn<'py> = (
    String,
    Option<Bound<'py, PyAny>>,
    Option<String>,
    Vec<(String, String, bool)>,
);

/// One design point, as a worker evaluates it: `base` the plan's TOML text, `values` the
/// point's fields and values (floats, or words). The library's evaluator
/// (`Evaluator::result_at` reduced by `design_point`), with the GIL released; a panic is
/// answered as the map would record it.
#[pyfunction]
pub fn design_point(
    py: Python<'_>,
    base: &str,
    values: Vec<(String, FieldValue)>,
) -> PyResult<Answer> {
    let scene = Scene::from_toml_str(design::POINT, base).or_raise()?;
    let answer = crate::pool::detach(py, move || {
        let args: Vec<(&str, Level<'_>)> = values
            .iter()
            .map(|(k, v)| (k.as_str(), v.level()))
            .collect();
        let registry = registry();
        let ev = Evaluator::new(scene, &registry);
        match catch_unwind(AssertUnwindSafe(|| ev.result_at(&args))) {
            Ok(Ok(r)) => Ok((reduce(&r), r.warnings)),
            Ok(Err(e)) => Err(e),
            Err(payload) => {
                let msg = payload
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "unknown panic".into());
                Err(PointError::Failed(format!("evaluator panicked: {msg}")))
            }
        }
    });
    Ok(match answer {
        Ok((point, warnings)) => {
            let w = warnings
                .into_iter()
                .map(|w| (w.code.to_string(), w.message, w.breaks_validity))
                .collect();
            ("ok", Some(result_to_py(py, &point)?), None, w)
        }
        Err(PointError::OutOfDomain(m)) => ("out_of_domain", None, Some(m), Vec::new()),
        Err(PointError::Failed(m)) => ("failed", None, Some(m), Vec::new()),
    })
}

/// A guard's code as the library spells it (`&'static str`).
fn static_code(c: &str) -> &'static str {
    match code::ALL.iter().find(|k| **k == c) {
        Some(k) => k,
        // a code this build does not know (a newer worker): kept, once per distinct code
        None => Box::leak(c.to_string().into_boxed_str()),
    }
}

/// The key of a grid point by its values: each number's bits, a word's position on its
/// axis.
fn key(grid: &Grid, levels: &[Level<'_>]) -> Vec<u64> {
    levels
        .iter()
        .zip(grid.axes())
        .map(|(l, a)| match l {
            Level::Number(x) => x.to_bits(),
            Level::Word(w) => a
                .words
                .iter()
                .position(|x| x == w)
                .map_or(u64::MAX, |k| k as u64),
        })
        .collect()
}

/// Assembles the workers' answers (`(index, answer)` per point of the plan) into the map:
/// the request is made again from the same arguments, and `design_sweep::run_map` records
/// each point's answer as it records a local evaluation (the same checks and statuses), so
/// the map equals `stiction design map`'s on the same grid.
#[pyfunction]
#[pyo3(signature = (scene, vary, answers, accuracy = None, shard = None, require = None))]
pub fn design_map_assemble(
    _py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    vary: Vec<String>,
    answers: &Bound<'_, PyList>,
    accuracy: Option<&str>,
    shard: Option<&str>,
    require: Option<&str>,
) -> PyResult<PyMap> {
    let scene = scene_from_py(scene)?;
    let acc = accuracy_arg(accuracy)?;
    let (base, request, require) =
        design::map_request_with(&scene, &registry(), &vary, shard, acc, require).or_raise()?;
    // the answers as Rust values, by the point's grid values
    type Got = (Result<DesignPoint, PointError>, Vec<Warning>);
    let mut got: HashMap<Vec<u64>, Got> = HashMap::new();
    for item in answers.iter() {
        let (index, (status, point, message, warnings)): (usize, AnswerIn<'_>) = item.extract()?;
        if index >= request.grid.len() {
            return Err(argument(
                "answers",
                format!("a point of index {index}"),
                format!("indices of the grid's {} points", request.grid.len()),
            ));
        }
        let answer = answer_of(index, (status, point, message, warnings))?;
        got.insert(key(&request.grid, &request.grid.levels(index)), answer);
    }
    let registry = registry();
    let ev = Evaluator::new(base, &registry);
    let grid = request.grid.clone();
    let map = design_sweep::run_map(
        request,
        |args: &[(&str, Level<'_>)]| -> Result<DesignPoint, PointError> {
            let levels: Vec<Level<'_>> = args.iter().map(|(_, v)| *v).collect();
            match got.get(&key(&grid, &levels)) {
                Some((r, _)) => r.clone(),
                None => Err(PointError::Failed(
                    "no answer came back for this point".into(),
                )),
            }
        },
        |_, _| {},
    )
    .with_requirement(require);
    // the guards in index order (deterministic)
    for p in map.points() {
        let levels = grid.levels(p.index);
        if let Some((_, w)) = got.get(&key(&grid, &levels)) {
            let args: Vec<(&str, Level<'_>)> = grid
                .axes()
                .iter()
                .map(|a| a.field.as_str())
                .zip(levels.iter().copied())
                .collect();
            ev.record_at(&args, w);
        }
    }
    let warnings = ev.warnings(map.points().len());
    // (a map assembled from a cluster's points carries no model-form check: the check
    // runs through `design_map` without a client)
    Ok(PyMap {
        validity: Some(Validity::of(&warnings)),
        map,
        warnings,
        model_form: None,
    })
}

/// Reads a `map.json` (of `stiction design map`, whole or a shard).
#[pyfunction]
pub fn read_map(path: PathBuf) -> PyResult<PyMap> {
    let map = Map::read_path(&path).or_raise()?;
    Ok(PyMap {
        map,
        warnings: Vec::new(),
        validity: None,
        model_form: None,
    })
}

/// Joins the shards of one map (`stiction design merge`): each a NativeMap or the path of
/// a `map.json`.
#[pyfunction]
pub fn design_merge(parts: &Bound<'_, PyList>) -> PyResult<PyMap> {
    let mut shards = Vec::new();
    for (i, p) in parts.iter().enumerate() {
        if let Ok(m) = p.cast::<PyMap>() {
            shards.push((format!("part {}", i + 1), m.get().map.clone()));
        } else {
            let path: PathBuf = p.extract()?;
            let map = Map::read_path(&path).or_raise()?;
            shards.push((path.display().to_string(), map));
        }
    }
    let map = design_sweep::merge(shards)
        .map_err(ModelError::from)
        .or_raise()?;
    Ok(PyMap {
        map,
        warnings: Vec::new(),
        validity: None,
        model_form: None,
    })
}
