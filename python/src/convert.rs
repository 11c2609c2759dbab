//! Conversions between Python values and the library's data: results (their serde form) to
//! dicts, lists and numpy arrays; Python values to scene values; numpy arrays in and out.

use numpy::{AllowTypeChange, PyArray1, PyArrayLikeDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde_json::Value;
use stiction_model::{ModelError, SceneError};

// ------------------------------------------------------------------ results to Python

/// A result as Python data: objects become dicts; lists of numbers numpy arrays; lists of
/// flat records (numbers, booleans, words) `stiction._results.Table`s of numpy columns;
/// other lists Python lists.
pub fn result_to_py<T: serde::Serialize>(py: Python<'_>, r: &T) -> PyResult<Py<PyAny>> {
    let v = serde_json::to_value(r).map_err(|e| {
        crate::errors::exception(
            stiction_model::contact_core::Category::Numerical,
            format!("a result did not serialise: {e}"),
            None,
        )
    })?;
    Ok(value_to_py(py, &v)?.unbind())
}

/// A JSON value as Python data (see [`result_to_py`]).
pub fn value_to_py<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Value::Number(n) => number_to_py(py, n)?,
        Value::String(s) => PyString::new(py, s).into_any(),
        Value::Array(a) => array_to_py(py, a)?,
        Value::Object(o) => {
            let d = PyDict::new(py);
            for (k, x) in o {
                d.set_item(k, value_to_py(py, x)?)?;
            }
            d.into_any()
        }
    })
}

/// A JSON value as plain Python data: dicts, lists, numbers, strings, booleans, None
/// (what a scene's keys are written as).
pub fn value_to_plain<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Array(a) => {
            let list = PyList::empty(py);
            for x in a {
                list.append(value_to_plain(py, x)?)?;
            }
            list.into_any()
        }
        Value::Object(o) => {
            let d = PyDict::new(py);
            for (k, x) in o {
                d.set_item(k, value_to_plain(py, x)?)?;
            }
            d.into_any()
        }
        other => value_to_py(py, other)?,
    })
}

fn number_to_py<'py>(py: Python<'py>, n: &serde_json::Number) -> PyResult<Bound<'py, PyAny>> {
    Ok(if let Some(i) = n.as_i64() {
        i.into_pyobject(py)?.into_any()
    } else if let Some(u) = n.as_u64() {
        u.into_pyobject(py)?.into_any()
    } else {
        PyFloat::new(py, n.as_f64().unwrap_or(f64::NAN)).into_any()
    })
}

/// A number of a result, with the names results give non-finite numbers (`"inf"`).
fn as_number(v: &Value) -> Option<f64> {
    match v {
        Value::Number(n) => n.as_f64(),
        Value::String(s) => match s.as_str() {
            "inf" => Some(f64::INFINITY),
            "-inf" => Some(f64::NEG_INFINITY),
            "nan" | "NaN" => Some(f64::NAN),
            _ => None,
        },
        _ => None,
    }
}

fn is_integer(v: &Value) -> bool {
    matches!(v, Value::Number(n) if n.is_i64() || n.is_u64())
}

fn is_scalar(v: &Value) -> bool {
    !matches!(v, Value::Array(_) | Value::Object(_))
}

fn array_to_py<'py>(py: Python<'py>, a: &[Value]) -> PyResult<Bound<'py, PyAny>> {
    if !a.is_empty() && a.iter().all(|x| matches!(x, Value::Number(_))) {
        return column(py, a.iter().map(Some).collect::<Vec<_>>().as_slice());
    }
    let flat_records = !a.is_empty()
        && a.iter()
            .all(|x| matches!(x, Value::Object(o) if o.values().all(is_scalar)));
    if flat_records {
        // columns in the order of first appearance; a record without a key has None there
        let mut names: Vec<&str> = Vec::new();
        for x in a {
            if let Value::Object(o) = x {
                for k in o.keys() {
                    if !names.contains(&k.as_str()) {
                        names.push(k);
                    }
                }
            }
        }
        let columns = PyDict::new(py);
        for name in names {
            let cells: Vec<Option<&Value>> = a
                .iter()
                .map(|x| x.get(name).filter(|v| !v.is_null()))
                .collect();
            columns.set_item(name, column(py, &cells)?)?;
        }
        let table = py.import("stiction._results")?.getattr("Table")?;
        return table.call1((columns,));
    }
    let list = PyList::empty(py);
    for x in a {
        list.append(value_to_py(py, x)?)?;
    }
    Ok(list.into_any())
}

/// One column: int64 when every cell is an integer, float64 when every cell is a number
/// or absent (NaN), bool when every cell is a boolean, else a list.
fn column<'py>(py: Python<'py>, cells: &[Option<&Value>]) -> PyResult<Bound<'py, PyAny>> {
    if cells.iter().all(|c| c.is_some_and(is_integer)) {
        let v: Vec<i64> = cells
            .iter()
            .map(|c| c.and_then(Value::as_i64).unwrap_or(i64::MAX))
            .collect();
        return Ok(PyArray1::from_vec(py, v).into_any());
    }
    if cells
        .iter()
        .all(|c| c.is_none_or(|v| as_number(v).is_some()))
    {
        let v: Vec<f64> = cells
            .iter()
            .map(|c| c.and_then(as_number).unwrap_or(f64::NAN))
            .collect();
        return Ok(PyArray1::from_vec(py, v).into_any());
    }
    if cells.iter().all(|c| c.is_some_and(Value::is_boolean)) {
        let v: Vec<bool> = cells
            .iter()
            .map(|c| c.and_then(Value::as_bool).unwrap_or(false))
            .collect();
        return Ok(PyArray1::from_vec(py, v).into_any());
    }
    let list = PyList::empty(py);
    for c in cells {
        match c {
            Some(v) => list.append(value_to_py(py, v)?)?,
            None => list.append(py.None())?,
        }
    }
    Ok(list.into_any())
}

// ------------------------------------------------------------------ Python to scene values

/// A Python value as a JSON value of a scene: dicts (string keys), lists and tuples (and
/// numpy arrays), strings, booleans, integers, floats (infinity as the scene's `"inf"`),
/// None (refused by the library with its message). `at` is the key, for errors.
pub fn py_to_json(obj: &Bound<'_, PyAny>, file: &str, at: &str) -> PyResult<Value> {
    let bad = |what: String| {
        crate::errors::raise(ModelError::Scene(SceneError::Field {
            file: file.to_string(),
            key: if at.is_empty() {
                "(top)".into()
            } else {
                at.into()
            },
            value: what,
            line: String::new(),
            allowed: "a scene value: a number, a string, a boolean, a list or a table".into(),
        }))
    };
    if obj.is_none() {
        return Ok(Value::Null);
    }
    if obj.is_instance_of::<PyBool>() {
        return Ok(Value::Bool(obj.extract::<bool>()?));
    }
    if obj.is_instance_of::<PyInt>() {
        return match obj.extract::<i64>() {
            Ok(i) => Ok(Value::from(i)),
            // beyond i64 as a float (refused by the key's domain); beyond any float (an
            // OverflowError of Python's) refused here, naming the key
            Err(_) => match obj.extract::<f64>() {
                Ok(x) => Ok(float_value(x)),
                Err(_) => Err(bad(format!(
                    "an integer of {} bits (beyond any number)",
                    obj.call_method0("bit_length")?.extract::<u64>()?
                ))),
            },
        };
    }
    if obj.is_instance_of::<PyFloat>() {
        return Ok(float_value(obj.extract::<f64>()?));
    }
    if let Ok(s) = obj.cast::<PyString>() {
        return Ok(Value::String(s.extract::<String>()?));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut map = serde_json::Map::new();
        for (k, v) in d.iter() {
            let Ok(k) = k.cast::<PyString>() else {
                return Err(bad(format!("a table with the key {}", k.repr()?)));
            };
            let k: String = k.extract()?;
            let key = if at.is_empty() {
                k.clone()
            } else {
                format!("{at}.{k}")
            };
            map.insert(k, py_to_json(&v, file, &key)?);
        }
        return Ok(Value::Object(map));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut out = Vec::new();
        for (i, x) in obj.try_iter()?.enumerate() {
            out.push(py_to_json(&x?, file, &format!("{at}[{i}]"))?);
        }
        return Ok(Value::Array(out));
    }
    // numpy scalars and arrays: their Python equivalents
    if obj.hasattr("tolist")? && obj.hasattr("dtype")? {
        let plain = obj.call_method0("tolist")?;
        return py_to_json(&plain, file, at);
    }
    // a Mapping that is not a dict
    if obj.hasattr("keys")? && obj.hasattr("__getitem__")? {
        let d = PyDict::new(obj.py());
        for k in obj.call_method0("keys")?.try_iter()? {
            let k = k?;
            d.set_item(&k, obj.get_item(&k)?)?;
        }
        return py_to_json(d.as_any(), file, at);
    }
    let type_name = obj.get_type().name()?.to_string();
    Err(bad(format!("a {type_name}")))
}

fn float_value(x: f64) -> Value {
    if x.is_finite() {
        serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number)
    } else if x.is_nan() {
        Value::String("nan".into())
    } else if x > 0.0 {
        Value::String("inf".into())
    } else {
        Value::String("-inf".into())
    }
}

// ------------------------------------------------------------------ arrays

/// An array argument: any array-like of numbers (a scalar, a list, an ndarray of any shape
/// and numeric dtype), as float64 values in C order with its shape.
pub struct ArrayIn {
    /// The values, flattened in C order.
    pub values: Vec<f64>,
    /// The shape (empty for a scalar).
    pub shape: Vec<usize>,
}

impl ArrayIn {
    /// Reads `obj` as float64.
    pub fn new(obj: &Bound<'_, PyAny>) -> PyResult<Self> {
        let a: PyArrayLikeDyn<'_, f64, AllowTypeChange> = obj.extract()?;
        let shape = a.shape().to_vec();
        let values = match a.as_slice() {
            Ok(s) => s.to_vec(),
            Err(_) => a.as_array().iter().copied().collect(),
        };
        Ok(Self { values, shape })
    }

    /// The number of values.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Refuses a NaN (always) or an infinite value (unless `infinite_allowed`: a history
    /// that means "virgin") of this argument (`name`), naming the argument and the value:
    /// a NaN history would otherwise read as a virgin surface.
    pub fn finite(&self, name: &str, infinite_allowed: bool) -> PyResult<&Self> {
        if let Some(&v) = self
            .values
            .iter()
            .find(|v| v.is_nan() || (v.is_infinite() && !infinite_allowed))
        {
            return Err(crate::errors::argument(
                name,
                format!("{v}"),
                if infinite_allowed {
                    "a number (inf: none, a virgin history)"
                } else {
                    "a finite number"
                },
            ));
        }
        Ok(self)
    }

    /// Refuses a retraction point deeper than its excursion's extreme `from` (`deeper`
    /// says which side is deeper: larger interferences for a sphere or an asperity,
    /// smaller separations for a surface).
    pub fn within_excursion(
        &self,
        name: &str,
        from: f64,
        deeper: fn(f64, f64) -> bool,
    ) -> PyResult<()> {
        if let Some(&v) = self.values.iter().find(|&&v| deeper(v, from)) {
            return Err(crate::errors::argument(
                name,
                format!("{v:e}"),
                format!("within the retraction's excursion from {from:e} (a deeper point is on the approach)"),
            ));
        }
        Ok(())
    }

    /// The value at `i` of an argument that is either one value or one per point of an
    /// array of `n` (checked by [`ArrayIn::broadcast_to`]).
    pub fn at(&self, i: usize) -> f64 {
        if self.values.len() == 1 {
            self.values[0]
        } else {
            self.values[i]
        }
    }

    /// Checks that this argument (`name`) is one value or has the shape of `other`.
    pub fn broadcast_to(&self, name: &str, other: &ArrayIn, other_name: &str) -> PyResult<()> {
        if self.values.len() == 1 || self.shape == other.shape {
            return Ok(());
        }
        Err(crate::errors::argument(
            name,
            format!("an array of shape {:?}", self.shape),
            format!(
                "one value or an array of the shape of {other_name}, {:?}",
                other.shape
            ),
        ))
    }
}

/// Values computed for `like`'s points, as an array of its shape (a float for a scalar).
pub fn array_out(py: Python<'_>, values: Vec<f64>, like: &[usize]) -> PyResult<Py<PyAny>> {
    if like.is_empty() {
        return Ok(
            PyFloat::new(py, values.first().copied().unwrap_or(f64::NAN))
                .into_any()
                .unbind(),
        );
    }
    let a = PyArray1::from_vec(py, values);
    Ok(a.reshape(like.to_vec())?.into_any().unbind())
}

/// Booleans for `like`'s points, as an array of its shape (a bool for a scalar).
pub fn bool_array_out(py: Python<'_>, values: Vec<bool>, like: &[usize]) -> PyResult<Py<PyAny>> {
    if like.is_empty() {
        let b = values.first().copied().unwrap_or(false);
        return Ok(PyBool::new(py, b).to_owned().into_any().unbind());
    }
    let a = PyArray1::from_vec(py, values);
    Ok(a.reshape(like.to_vec())?.into_any().unbind())
}
