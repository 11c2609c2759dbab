//! `stiction.Scene`: a scene as written (`stiction_model::scene::Scene`), read from a TOML
//! or JSON file, a dict, or text, and validated by the library's key and law registries.

use crate::convert::{py_to_json, value_to_plain};
use crate::errors::{argument, OrRaise};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use std::path::PathBuf;
use stiction_model::keys::{self, Kind};
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene;
use stiction_model::spec::{toml_to_json, Spec};
use stiction_model::ModelError;

/// The name a scene made from a Python dict carries in messages.
pub const DICT_FILE: &str = "<dict>";

/// A scene: the keys and values of a TOML or JSON scene file (SI units: m, N, Pa, J/m^2),
/// with the name of its source for messages. Made by `stiction.load_scene` (validated),
/// `Scene.paper(kind)`, `Scene.from_toml(text)`, `Scene.from_json(text)`.
#[pyclass(name = "Scene", module = "stiction")]
#[derive(Clone)]
pub struct PyScene {
    pub scene: Scene,
}

/// The law registry of every scene: the built-in laws.
pub fn registry() -> LawRegistry {
    LawRegistry::builtin()
}

/// Validates `scene` (every key against the registries) without running it.
pub fn validate(scene: &Scene) -> PyResult<Spec> {
    Spec::new(scene, &registry()).or_raise()
}

fn kind_of(name: &str) -> PyResult<Kind> {
    Kind::ALL
        .into_iter()
        .find(|k| k.as_str() == name)
        .ok_or_else(|| argument("kind", format!("\"{name}\""), "asperity, surface or switch"))
}

/// A scene from what `load_scene` accepts: a path (str or os.PathLike), a dict, a Scene.
pub fn scene_from_py(obj: &Bound<'_, PyAny>) -> PyResult<Scene> {
    if let Ok(s) = obj.cast::<PyScene>() {
        return Ok(s.borrow().scene.clone());
    }
    if obj.is_instance_of::<PyDict>() || (obj.hasattr("keys")? && !obj.hasattr("__fspath__")?) {
        let v = py_to_json(obj, DICT_FILE, "")?;
        return Scene::from_json_value(DICT_FILE, &v).or_raise();
    }
    let path: PathBuf =
        match obj.extract() {
            Ok(p) => p,
            Err(_) => return Err(argument(
                "scene",
                format!("a {}", obj.get_type().name()?),
                "a path to a TOML or JSON scene file, a dict of scene keys, or a stiction.Scene",
            )),
        };
    Scene::read(&path).or_raise()
}

/// `stiction.load_scene(path_or_dict)`: reads a scene file (TOML, or JSON when it ends in
/// `.json` or starts with `{`), or takes a dict of the same keys and sections (an infinite
/// yield stress as `float("inf")` or `"inf"`), and validates every key with the library:
/// unknown, missing or out-of-domain keys raise `stiction.InputError` naming the file, the
/// key, the value and what is allowed.
#[pyfunction]
pub fn load_scene(py: Python<'_>, source: &Bound<'_, PyAny>) -> PyResult<PyScene> {
    let scene = scene_from_py(source)?;
    let checked = scene.clone();
    crate::pool::detach(py, move || Spec::new(&checked, &registry()).map(|_| ())).or_raise()?;
    Ok(PyScene { scene })
}

/// The scene keys a design map or threshold may vary (numeric keys of a switch scene).
#[pyfunction]
pub fn variable_fields() -> Vec<&'static str> {
    stiction_model::design::variable_fields()
        .map(|f| f.key)
        .collect()
}

fn toml_value_to_py<'py>(py: Python<'py>, v: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    match v {
        toml::Value::Float(f) if !f.is_finite() => Ok(pyo3::types::PyFloat::new(py, *f).into_any()),
        toml::Value::Array(a) => {
            let list = PyList::empty(py);
            for x in a {
                list.append(toml_value_to_py(py, x)?)?;
            }
            Ok(list.into_any())
        }
        toml::Value::Table(t) => {
            let d = PyDict::new(py);
            for (k, x) in t {
                d.set_item(k, toml_value_to_py(py, x)?)?;
            }
            Ok(d.into_any())
        }
        _ => value_to_plain(py, &toml_to_json(v)),
    }
}

fn value_from_py(obj: &Bound<'_, PyAny>, file: &str, key: &str) -> PyResult<toml::Value> {
    // through the library's JSON-to-scene conversion, so that its messages (a null, a
    // number out of range) are the same as a JSON file's
    let v = py_to_json(obj, file, key)?;
    let mut wrapper = serde_json::Map::new();
    wrapper.insert("v".into(), v);
    let s = Scene::from_json_value(file, &serde_json::Value::Object(wrapper)).map_err(|e| {
        // the message names the key as `v`: name the real one
        match e {
            stiction_model::SceneError::Field {
                file,
                value,
                line,
                allowed,
                ..
            } => ModelError::Scene(stiction_model::SceneError::Field {
                file,
                key: key.to_string(),
                value,
                line,
                allowed,
            }),
            e => e.into(),
        }
    });
    let s = s.or_raise()?;
    Ok(s.tree()
        .get("v")
        .cloned()
        .unwrap_or(toml::Value::Boolean(false)))
}

#[pymethods]
impl PyScene {
    /// The embedded paper scene of `kind` ("asperity": Fig 2; "surface"; "switch": Fig 4,
    /// the main job).
    #[staticmethod]
    #[pyo3(signature = (kind = "switch"))]
    fn paper(kind: &str) -> PyResult<Self> {
        Ok(Self {
            scene: Scene::paper(kind_of(kind)?),
        })
    }

    /// A scene from TOML text (`file` names it in messages); not validated (see
    /// `validate`).
    #[staticmethod]
    #[pyo3(signature = (text, file = "<toml>"))]
    fn from_toml(text: &str, file: &str) -> PyResult<Self> {
        Ok(Self {
            scene: Scene::from_toml_str(file, text).or_raise()?,
        })
    }

    /// A scene from JSON text (an object of the TOML form's keys; infinity as `"inf"`);
    /// not validated (see `validate`).
    #[staticmethod]
    #[pyo3(signature = (text, file = "<json>"))]
    fn from_json(text: &str, file: &str) -> PyResult<Self> {
        Ok(Self {
            scene: Scene::from_json_str(file, text).or_raise()?,
        })
    }

    /// The scene's kind: "asperity", "surface" or "switch" (its `kind` key, else inferred).
    #[getter]
    fn kind(&self) -> PyResult<&'static str> {
        Ok(self.scene.kind().or_raise()?.as_str())
    }

    /// The name of the source in messages (the file, "<dict>", "<default scene>").
    #[getter]
    fn file(&self) -> &str {
        self.scene.file()
    }

    /// The title of plots and tables: the scene's `title`, else the file name.
    #[getter]
    fn title(&self) -> String {
        self.scene.display_title()
    }

    /// The value of `key` (`section.key`) as written, or `default` when absent.
    #[pyo3(signature = (key, default = None))]
    fn get<'py>(
        &self,
        py: Python<'py>,
        key: &str,
        default: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        match self.scene.get(key) {
            Some(v) => toml_value_to_py(py, v),
            None => Ok(default.unwrap_or_else(|| py.None().into_bound(py))),
        }
    }

    /// Sets `key` (`section.key`, sections made as needed) to `value` in place. Checked
    /// when the scene is validated or run, like a value of the file.
    fn set(&mut self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let v = value_from_py(value, self.scene.file(), key)?;
        self.scene.set(key, v).or_raise()
    }

    /// Removes `key` (`section.key`) in place, if present.
    fn remove(&mut self, key: &str) {
        self.scene.remove(key);
    }

    /// A copy with the keys of `values` set (a value of None removes its key), validated.
    fn with_values(&self, py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<Self> {
        let mut s = self.scene.clone();
        for (k, v) in values.iter() {
            let k: String = k.extract()?;
            if v.is_none() {
                s.remove(&k);
            } else {
                let tv = value_from_py(&v, s.file(), &k)?;
                s.set(&k, tv).or_raise()?;
            }
        }
        let checked = s.clone();
        crate::pool::detach(py, move || Spec::new(&checked, &registry()).map(|_| ())).or_raise()?;
        Ok(Self { scene: s })
    }

    /// Validates every key with the library (raises `InputError` naming the key).
    fn validate(&self, py: Python<'_>) -> PyResult<()> {
        let s = self.scene.clone();
        crate::pool::detach(py, move || Spec::new(&s, &registry()).map(|_| ())).or_raise()
    }

    /// Every key with the value it resolves to (defaults filled in), as a dict.
    fn resolved<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let spec = validate(&self.scene)?;
        value_to_plain(py, &spec.common().echo())
    }

    /// The scene as TOML text (the form of a scene file).
    fn to_toml(&self) -> PyResult<String> {
        toml::to_string(self.scene.tree()).map_err(|e| {
            argument(
                "scene",
                self.scene.file().to_string(),
                format!("a tree TOML can write: {e}"),
            )
        })
    }

    /// The keys and values as a dict (infinity as float("inf")).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        toml_value_to_py(py, &toml::Value::Table(self.scene.tree().clone()))
    }

    /// A copy.
    fn copy(&self) -> Self {
        self.clone()
    }

    fn __copy__(&self) -> Self {
        self.clone()
    }

    fn __deepcopy__(&self, _memo: &Bound<'_, PyAny>) -> Self {
        self.clone()
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyScene>()
            .is_ok_and(|o| o.borrow().scene.tree() == self.scene.tree())
    }

    /// Pickled as its TOML text and file name (for multiprocessing and Dask).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let text = slf.borrow().to_toml()?;
        let file = slf.borrow().scene.file().to_string();
        let ctor = py.get_type::<PyScene>().getattr("from_toml")?;
        PyTuple::new(
            py,
            [ctor.into_any(), PyTuple::new(py, [text, file])?.into_any()],
        )
    }

    fn __repr__(&self) -> String {
        let kind = self
            .scene
            .kind()
            .map(|k| k.as_str().to_string())
            .unwrap_or_else(|_| "?".into());
        format!(
            "<stiction.Scene {kind} {:?} from {}>",
            self.scene.display_title(),
            self.scene.file()
        )
    }
}

/// The key registry as a list of dicts: key, unit, accepts, default, meaning, scenes.
#[pyfunction]
#[pyo3(signature = (kind = None))]
pub fn scene_keys<'py>(py: Python<'py>, kind: Option<&str>) -> PyResult<Bound<'py, PyList>> {
    let kind = kind.map(kind_of).transpose()?;
    let list = PyList::empty(py);
    for k in keys::KEYS
        .iter()
        .filter(|k| kind.is_none_or(|t| k.in_kind(t)))
    {
        let d = PyDict::new(py);
        d.set_item("key", k.key)?;
        d.set_item("unit", k.unit)?;
        d.set_item("accepts", k.domain.describe())?;
        d.set_item("default", k.default.as_written())?;
        d.set_item("meaning", k.help)?;
        d.set_item(
            "scenes",
            k.scenes.iter().map(|s| s.as_str()).collect::<Vec<_>>(),
        )?;
        list.append(d)?;
    }
    Ok(list)
}
