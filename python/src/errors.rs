//! The library's errors as Python exceptions: `ModelError::category()` decides the class
//! (`stiction.InputError` for bad input, `stiction.NumericalError` for a numerical
//! failure), the message is the library's own text.

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use stiction_model::contact_core::{Categorized, Category};
use stiction_model::ModelError;

/// The Python exception of a library error (a run its caller stopped: `KeyboardInterrupt`,
/// when no exception of the caller's own says why).
pub fn raise(e: ModelError) -> PyErr {
    if e.category() == Category::Interrupted {
        return pyo3::exceptions::PyKeyboardInterrupt::new_err(e.to_string());
    }
    let key = match e.cause() {
        ModelError::Scene(s) => s.key().map(str::to_string),
        _ => None,
    };
    exception(e.category(), e.to_string(), key)
}

/// An exception of `category` with `message` (and the scene key it is about).
pub fn exception(category: Category, message: String, key: Option<String>) -> PyErr {
    Python::attach(|py| {
        let class = match category {
            Category::Input => "InputError",
            _ => "NumericalError",
        };
        let made = py
            .import("stiction._errors")
            .and_then(|m| m.getattr(class))
            .and_then(|c| c.call1((message.clone(), key)));
        match made {
            Ok(obj) => PyErr::from_value(obj),
            // the package's Python files are missing: still an exception with the message
            Err(_) => PyRuntimeError::new_err(message),
        }
    })
}

/// An argument outside its domain, named as the library names arguments.
pub fn argument(name: &str, value: impl Into<String>, allowed: impl Into<String>) -> PyErr {
    raise(ModelError::argument(name, value, allowed))
}

/// `Result<T, ModelError>` (or an error that converts to one) to a Python result.
pub trait OrRaise<T> {
    /// The value, or the library's error as its Python exception.
    fn or_raise(self) -> PyResult<T>;
}

impl<T, E: Into<ModelError>> OrRaise<T> for Result<T, E> {
    fn or_raise(self) -> PyResult<T> {
        self.map_err(|e| raise(e.into()))
    }
}
