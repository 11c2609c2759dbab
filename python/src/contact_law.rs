//! `stiction.ContactLaw`: the tabulated law p(d; d_min, path) of a rough surface for FE
//! codes (crate `contact-law`: reader, evaluator), and its tabulation from a scene
//! (`stiction_model::law`, `stiction law`).

use crate::convert::{array_out, bool_array_out, result_to_py, value_to_py, ArrayIn};
use crate::errors::{argument, OrRaise};
use crate::run::accuracy_arg;
use crate::scene::{registry, scene_from_py};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString, PyTuple};
use std::path::PathBuf;
use stiction_model::contact_law::tabulate::GridSpec;
use stiction_model::contact_law::{ContactLaw, LawError, Path as LawPath, State};
use stiction_model::law::{self, LawOptions, LawScene, DEFAULT_POINTS};
use stiction_model::spec::Spec;
use stiction_model::ModelError;

fn law_path(word: &str) -> PyResult<LawPath> {
    match word {
        "approach" => Ok(LawPath::Approach),
        "retract" => Ok(LawPath::Retract),
        other => Err(argument(
            "path",
            format!("\"{other}\""),
            "\"approach\" or \"retract\"",
        )),
    }
}

/// The path argument of a vectorised call: one word, or one per point.
enum Paths {
    One(LawPath),
    Each(Vec<LawPath>),
}

impl Paths {
    fn new(obj: &Bound<'_, PyAny>, n: usize) -> PyResult<Self> {
        if let Ok(s) = obj.cast::<PyString>() {
            return Ok(Paths::One(law_path(&s.extract::<String>()?)?));
        }
        // a numpy array of any shape, in C order; else a sequence of words
        let words: Vec<String> = match obj.call_method0("ravel") {
            Ok(flat) => flat.call_method0("tolist")?.extract()?,
            Err(_) => obj.extract()?,
        };
        if words.len() != n && words.len() != 1 {
            return Err(argument(
                "path",
                format!("{} words", words.len()),
                format!("one word, or one per separation ({n})"),
            ));
        }
        let paths = words
            .iter()
            .map(|w| law_path(w))
            .collect::<PyResult<Vec<_>>>()?;
        Ok(if paths.len() == 1 {
            Paths::One(paths[0])
        } else {
            Paths::Each(paths)
        })
    }

    fn at(&self, i: usize) -> LawPath {
        match self {
            Paths::One(p) => *p,
            Paths::Each(v) => v[i],
        }
    }
}

/// A tabulated contact law (law.json): pressure p (Pa, compressive positive) of a rough
/// surface at separation d (m) with history d_min (m, the deepest separation reached) on
/// the approach or retract branch, with its tangent dp/dd (Pa/m).
#[pyclass(name = "ContactLaw", module = "stiction", frozen)]
pub struct PyContactLaw {
    pub law: ContactLaw,
}

fn law_error(e: LawError) -> PyErr {
    crate::errors::raise(ModelError::ContactLaw(e))
}

#[pymethods]
impl PyContactLaw {
    /// Reads a law file (law.json of `stiction law` or `stiction.tabulate_law`).
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let law =
            crate::pool::detach_serial(py, || ContactLaw::from_path(&path)).map_err(law_error)?;
        Ok(Self { law })
    }

    /// A law from the text of a law.json.
    #[staticmethod]
    fn from_json(py: Python<'_>, text: &str) -> PyResult<Self> {
        let law = crate::pool::detach_serial(py, || ContactLaw::from_json_str(text))
            .map_err(law_error)?;
        Ok(Self { law })
    }

    /// Stateless evaluation at each separation of `d` (m) with history `d_min` (m, one
    /// value or one per point; None or inf: a virgin surface) on `path` ("approach" or
    /// "retract", one word or one per point). Where d < d_min the history deepens: the
    /// value is the virgin envelope's, the history after the call is d and the path
    /// approach. Returns (pressure Pa, tangent Pa/m, d_min after the call m, retract after
    /// the call), arrays of d's shape.
    #[pyo3(signature = (d, d_min = None, path = None))]
    #[allow(clippy::type_complexity)]
    fn evaluate(
        &self,
        py: Python<'_>,
        d: &Bound<'_, PyAny>,
        d_min: Option<&Bound<'_, PyAny>>,
        path: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<(Py<PyAny>, Py<PyAny>, Py<PyAny>, Py<PyAny>)> {
        let d = ArrayIn::new(d)?;
        let dm = match d_min {
            Some(x) if !x.is_none() => ArrayIn::new(x)?,
            _ => ArrayIn {
                values: vec![f64::INFINITY],
                shape: Vec::new(),
            },
        };
        dm.broadcast_to("d_min", &d, "d")?;
        let paths = match path {
            Some(p) if !p.is_none() => Paths::new(p, d.len())?,
            _ => Paths::One(LawPath::Approach),
        };
        let law = &self.law;
        let n = d.len();
        let out = crate::pool::detach_serial(py, || -> Result<_, LawError> {
            let mut p = Vec::with_capacity(n);
            let mut t = Vec::with_capacity(n);
            let mut m = Vec::with_capacity(n);
            let mut r = Vec::with_capacity(n);
            for i in 0..n {
                let e = law.evaluate(d.values[i], dm.at(i), paths.at(i))?;
                p.push(e.pressure);
                t.push(e.tangent);
                m.push(e.d_min);
                r.push(e.path == LawPath::Retract);
            }
            Ok((p, t, m, r))
        });
        let (p, t, m, r) = out.map_err(law_error)?;
        Ok((
            array_out(py, p, &d.shape)?,
            array_out(py, t, &d.shape)?,
            array_out(py, m, &d.shape)?,
            bool_array_out(py, r, &d.shape)?,
        ))
    }

    /// Follows a sequence of separations `d` (m) in order, as an FE code calls the law
    /// increment by increment: the history (d_min, path, reversals) is updated by each
    /// call, starting from a virgin surface or from `state` (a dict of d_min, retract,
    /// last_d, d_turn as returned). Returns (pressure Pa, tangent Pa/m, d_min m, retract,
    /// final state).
    #[pyo3(signature = (d, state = None))]
    #[allow(clippy::type_complexity)]
    fn follow<'py>(
        &self,
        py: Python<'py>,
        d: &Bound<'py, PyAny>,
        state: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<(
        Py<PyAny>,
        Py<PyAny>,
        Py<PyAny>,
        Py<PyAny>,
        Bound<'py, PyDict>,
    )> {
        let d = ArrayIn::new(d)?;
        let mut st = State::VIRGIN;
        if let Some(s) = state {
            // a key the state does not have (`path` for `retract`, a typo) would be ignored
            // and the law followed from another history without a word
            const KEYS: [&str; 5] = ["d_min", "last_d", "d_turn", "retract", "history_exact"];
            for k in s.keys() {
                let name: String = k.str()?.extract()?;
                if !KEYS.contains(&name.as_str()) {
                    return Err(argument(
                        "state",
                        format!("a dict with the key {name:?}"),
                        format!(
                            "a state as follow() returns it, with the keys {}",
                            KEYS.join(", ")
                        ),
                    ));
                }
            }
            let get = |k: &str, default: f64| -> PyResult<f64> {
                Ok(match s.get_item(k)? {
                    Some(v) => v.extract()?,
                    None => default,
                })
            };
            st.d_min = get("d_min", f64::INFINITY)?;
            st.last_d = get("last_d", f64::INFINITY)?;
            st.d_turn = get("d_turn", f64::INFINITY)?;
            if let Some(r) = s.get_item("retract")? {
                if r.extract::<bool>()? {
                    st.path = LawPath::Retract;
                }
            }
        }
        let law = &self.law;
        let out = crate::pool::detach_serial(py, || -> Result<_, LawError> {
            let n = d.len();
            let (mut p, mut t, mut m, mut r) = (
                Vec::with_capacity(n),
                Vec::with_capacity(n),
                Vec::with_capacity(n),
                Vec::with_capacity(n),
            );
            for &x in &d.values {
                let (pp, tt) = law.pressure(x, &mut st)?;
                p.push(pp);
                t.push(tt);
                m.push(st.d_min);
                r.push(st.path == LawPath::Retract);
            }
            Ok((p, t, m, r, st))
        });
        let (p, t, m, r, st) = out.map_err(law_error)?;
        let state = PyDict::new(py);
        state.set_item("d_min", st.d_min)?;
        state.set_item("retract", st.path == LawPath::Retract)?;
        state.set_item("last_d", st.last_d)?;
        state.set_item("d_turn", st.d_turn)?;
        state.set_item("history_exact", law.is_history_exact(&st))?;
        Ok((
            array_out(py, p, &d.shape)?,
            array_out(py, t, &d.shape)?,
            array_out(py, m, &d.shape)?,
            bool_array_out(py, r, &d.shape)?,
            state,
        ))
    }

    /// The virgin envelope p_V(d) (Pa) and its slope (Pa/m) at each separation of `d` (m).
    fn virgin_pressure(
        &self,
        py: Python<'_>,
        d: &Bound<'_, PyAny>,
    ) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
        let d = ArrayIn::new(d)?;
        let law = &self.law;
        let v = crate::pool::detach_serial(py, || {
            d.values
                .iter()
                .map(|&x| law.virgin_pressure(x))
                .collect::<Result<Vec<_>, _>>()
        })
        .map_err(law_error)?;
        let (p, s): (Vec<f64>, Vec<f64>) = v.into_iter().unzip();
        Ok((array_out(py, p, &d.shape)?, array_out(py, s, &d.shape)?))
    }

    /// The separation (m) beyond which the branch `path` of history `d_min` (m) is zero.
    #[pyo3(signature = (d_min, path = "approach"))]
    fn reach(&self, d_min: f64, path: &str) -> PyResult<f64> {
        self.law.reach(d_min, law_path(path)?).map_err(law_error)
    }

    /// (deepest, shallowest) tabulated history d_min (m).
    #[getter]
    fn d_min_range(&self) -> (f64, f64) {
        self.law.d_min_range()
    }

    /// The tabulated histories d_min (m), increasing.
    #[getter]
    fn d_min_grid<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.law.d_min_grid())
    }

    /// The length scale of the law (m; sigma_s of the surface), if recorded.
    #[getter]
    fn length_scale(&self) -> Option<f64> {
        self.law.length_scale()
    }

    /// The scene the law was tabulated from (its resolved keys), as a dict.
    #[getter]
    fn scene<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        value_to_py(py, self.law.scene())
    }

    /// The measured interpolation error (dict), if recorded.
    #[getter]
    fn measured_error(&self, py: Python<'_>) -> PyResult<Option<Py<PyAny>>> {
        self.law
            .measured_error()
            .map(|m| result_to_py(py, m))
            .transpose()
    }

    /// law.json as text.
    fn to_json(&self) -> String {
        self.law.to_json_string()
    }

    /// law.csv as text (one row per node of every curve).
    fn to_csv(&self) -> PyResult<String> {
        let mut out = Vec::new();
        self.law
            .write_csv(&mut out)
            .map_err(|e| argument("law", "law.csv", format!("writable: {e}")))?;
        Ok(String::from_utf8_lossy(&out).into_owned())
    }

    /// Writes law.json to `path`.
    fn save(&self, path: PathBuf) -> PyResult<()> {
        self.law.write_json(&path).map_err(law_error)
    }

    /// Pickled as its JSON text (bit-identical when read back).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let text = slf.get().law.to_json_string();
        let ctor = py.get_type::<PyContactLaw>().getattr("from_json")?;
        PyTuple::new(py, [ctor.into_any(), PyTuple::new(py, [text])?.into_any()])
    }

    fn __repr__(&self) -> String {
        let (lo, hi) = self.law.d_min_range();
        format!(
            "<stiction.ContactLaw {} histories, d_min from {lo:e} to {hi:e} m>",
            self.law.branches().len()
        )
    }
}

/// `stiction.tabulate_law` (`stiction law`): the law of a switch or surface scene. Returns
/// (the summary as Python data, the law); `progress(done, total)` is called with the
/// work done in thousandths.
#[pyfunction]
#[pyo3(signature = (scene, d_min = None, points = DEFAULT_POINTS as i64, tolerance = 2e-4, accuracy = None, progress = None))]
pub fn tabulate_law(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    d_min: Option<&str>,
    points: i64,
    tolerance: f64,
    accuracy: Option<&str>,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<(Py<PyAny>, PyContactLaw)> {
    let scene = scene_from_py(scene)?;
    if points < 0 {
        return Err(argument(
            "points",
            points.to_string(),
            "an integer in [4, 100000]",
        ));
    }
    let grid = d_min
        .map(|g| g.parse::<GridSpec>())
        .transpose()
        .map_err(law_error)?;
    let options = LawOptions {
        d_min: grid,
        points: points as usize,
        tolerance,
        accuracy: accuracy_arg(accuracy)?,
    };
    options.check().or_raise()?;
    let r = crate::pool::run_reported(py, progress, false, move |p| -> Result<_, ModelError> {
        let spec = Spec::new(&scene, &registry())?;
        let ls = LawScene::of(&spec)?;
        law::tabulate(ls, &options, p)
    })?;
    let law = r.law.clone();
    let summary = crate::report::result(py, crate::report::Kept::Law(Box::new(r)))?;
    Ok((summary, PyContactLaw { law }))
}
