//! What a result looks like from Python: its table, its plots and the files the command
//! line's `--out` writes, drawn and written by `stiction-report` (the command line's own
//! presentation layer), never re-implemented here.
//!
//! A run keeps the library's typed result behind an opaque handle ([`PyReport`], the
//! result dict's `_report`): the Python result classes read their fields from the dict and
//! hand the handle back to save or draw, so the bytes are the command line's by
//! construction.

use crate::convert::result_to_py;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use stiction_model::asperity::AsperityResult;
use stiction_model::calibration::CalibrationResult;
use stiction_model::contact_core::Category;
use stiction_model::design::ThresholdResult;
use stiction_model::law::LawResult;
use stiction_model::md::MdResult;
use stiction_model::surface::SurfaceResult;
use stiction_model::switch::SwitchResult;
use stiction_report::topography::TopographyResult;
use stiction_report::{Plot, Render, Report, ReportError};

/// A presentation error as a Python exception: a path that cannot take the files is bad
/// input (`stiction.InputError`, as the command line's exit status 2), a plot that
/// cannot be drawn a numerical failure.
pub fn report_error(e: ReportError) -> PyErr {
    let category = match e {
        ReportError::Plot { .. } | ReportError::Csv(_) => Category::Numerical,
        _ => Category::Input,
    };
    crate::errors::exception(category, e.to_string(), None)
}

/// The typed result a handle keeps.
pub enum Kept {
    /// `stiction switch`.
    Switch(Box<SwitchResult>),
    /// `stiction surface`.
    Surface(Box<SurfaceResult>),
    /// `stiction asperity`.
    Asperity(Box<AsperityResult>),
    /// `stiction law`.
    Law(Box<LawResult>),
    /// `stiction calibrate`.
    Calibration(Box<CalibrationResult>),
    /// `stiction topography`.
    Topography(Box<TopographyResult>),
    /// `stiction design threshold` (a table, no figure).
    Threshold(Box<ThresholdResult>),
    /// `stiction md` (a table, no figure).
    Md(Box<MdResult>),
}

/// A result of the library kept for its presentation.
#[pyclass(name = "NativeReport", module = "stiction._stiction", frozen)]
pub struct PyReport {
    kept: Kept,
}

/// Writes `report`'s `--out` files to `dir` (replaced as a whole; it may hold only the
/// command's files) and returns the paths written.
pub fn save<R: Report + Sync>(py: Python<'_>, report: &R, dir: PathBuf) -> PyResult<Vec<String>> {
    let written = py.detach(|| report.save(&dir)).map_err(report_error)?;
    Ok(written.iter().map(|p| p.display().to_string()).collect())
}

/// `$body` with `$r` bound to the kept result, whatever its kind; `$other` for the kinds
/// that have no figure (with `drawn`).
macro_rules! each {
    ($kept:expr, $r:ident => $body:expr) => {
        each!($kept, $r => $body, drawn $r => $body)
    };
    ($kept:expr, $r:ident => $body:expr, drawn $d:ident => $other:expr) => {
        match $kept {
            Kept::Switch($r) => $body,
            Kept::Surface($r) => $body,
            Kept::Asperity($r) => $body,
            Kept::Law($r) => $body,
            Kept::Calibration($r) => $body,
            Kept::Topography($r) => $body,
            Kept::Threshold($d) => $other,
            Kept::Md($d) => $other,
        }
    };
}

/// The error of `to_svg()` on a result whose command draws no figure.
fn no_figure() -> PyErr {
    crate::errors::exception(
        Category::Input,
        "this result has no figure: its command prints a table only (table())".into(),
        None,
    )
}

#[pymethods]
impl PyReport {
    /// What the command prints (`--format table`).
    fn table(&self) -> String {
        each!(&self.kept, r => r.table())
    }

    /// What the command prints with `--format csv`.
    fn csv(&self) -> String {
        each!(&self.kept, r => r.csv())
    }

    /// The figure: `switch.svg`, `surface.svg` (`--plot`), `asperity.svg` (`--plot`),
    /// `law.svg`, the calibration overlay (`--plot`), `topography.svg`.
    fn to_svg(&self) -> PyResult<String> {
        each!(&self.kept, r => r.svg().map_err(report_error), drawn _r => Err(no_figure()))
    }

    /// `dynamics.svg` of a switch in time (None for a quasi-static run, without curves,
    /// or for another kind of result).
    fn dynamics_svg(&self) -> PyResult<Option<String>> {
        match &self.kept {
            Kept::Switch(r) => stiction_report::switch::dynamics_svg(r)
                .transpose()
                .map_err(report_error),
            _ => Ok(None),
        }
    }

    /// The files `--out` may write, or None for a result whose command has no `--out`
    /// folder.
    fn file_names(&self) -> Option<Vec<&'static str>> {
        match &self.kept {
            Kept::Switch(_) => Some(SwitchResult::FILES.to_vec()),
            Kept::Law(_) => Some(LawResult::FILES.to_vec()),
            Kept::Topography(_) => Some(TopographyResult::FILES.to_vec()),
            _ => None,
        }
    }

    /// Writes the command line's `--out` files to `dir`, byte for byte: the folder is
    /// replaced as a whole (it may hold only the command's files), each file whole, a
    /// symbolic link to a folder followed, a FIFO or device never replaced. Returns the
    /// paths written.
    fn save(&self, py: Python<'_>, dir: PathBuf) -> PyResult<Vec<String>> {
        match &self.kept {
            Kept::Switch(r) => save(py, r.as_ref(), dir),
            Kept::Law(r) => save(py, r.as_ref(), dir),
            Kept::Topography(r) => save(py, r.as_ref(), dir),
            _ => Err(crate::errors::exception(
                Category::Input,
                "this result has no --out folder: its command writes a plot only (to_svg())".into(),
                None,
            )),
        }
    }
}

/// The result as Python data (its serde form) with its handle under `_report`.
pub fn with_handle(py: Python<'_>, data: Py<PyAny>, kept: Kept) -> PyResult<Py<PyAny>> {
    let d = data.bind(py).cast::<PyDict>()?;
    d.set_item("_report", Py::new(py, PyReport { kept })?)?;
    Ok(data)
}

/// [`with_handle`] of a result converted from its serde form.
pub fn result(py: Python<'_>, kept: Kept) -> PyResult<Py<PyAny>> {
    let data = each!(&kept, r => result_to_py(py, r.as_ref())?);
    with_handle(py, data, kept)
}

/// The handle alone (for a result whose dict is built elsewhere).
pub fn handle(py: Python<'_>, kept: Kept) -> PyResult<Py<PyReport>> {
    Py::new(py, PyReport { kept })
}
