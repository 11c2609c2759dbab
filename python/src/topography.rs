//! A measured height map to the scene's Greenwood-Williamson parameters
//! (`stiction_model::topography::run`, as `stiction topography FILE`).

use crate::convert::{array_out, result_to_py};
use crate::errors::OrRaise;
use crate::report::Kept;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use stiction_model::topography::{run, TopographyRequest};
use stiction_report::topography::TopographyResult;

/// `stiction.topography(path, ...)`: the report (the command's JSON), the height map as
/// read (m, rows = y, `dx`, `dy`), the `[surface]` scene fragment and its warnings; the
/// options as the command line's (`file_format`, `spacing`, `height_unit`, `xy_unit`,
/// `detrend`, `route`, `undefined`, `channel`, `cutoff`, `contact_radius`), errors naming
/// them.
#[pyfunction]
#[pyo3(signature = (path, file_format = None, spacing = None, height_unit = None, xy_unit = None, detrend = None, route = None, undefined = None, channel = None, cutoff = None, contact_radius = None))]
#[allow(clippy::too_many_arguments)]
pub fn topography<'py>(
    py: Python<'py>,
    path: PathBuf,
    file_format: Option<String>,
    spacing: Option<f64>,
    height_unit: Option<String>,
    xy_unit: Option<String>,
    detrend: Option<String>,
    route: Option<String>,
    undefined: Option<String>,
    channel: Option<String>,
    cutoff: Option<f64>,
    contact_radius: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let request = TopographyRequest {
        file_format,
        spacing,
        height_unit,
        xy_unit,
        detrend,
        route,
        undefined,
        channel,
        cutoff,
        contact_radius,
    };
    let r = crate::pool::detach(py, move || run(&path, &request)).or_raise()?;
    let d = PyDict::new(py);
    let kept = TopographyResult::new(r.clone());
    d.set_item(
        "_report",
        crate::report::handle(py, Kept::Topography(Box::new(kept)))?,
    )?;
    d.set_item("report", result_to_py(py, &r.report)?)?;
    let m = &r.map;
    d.set_item(
        "heights",
        array_out(py, m.heights().to_vec(), &[m.ny(), m.nx()])?,
    )?;
    d.set_item("dx", m.dx())?;
    d.set_item("dy", m.dy())?;
    d.set_item("fragment", r.fragment)?;
    let warnings: Vec<(String, String)> = r
        .warnings
        .iter()
        .map(|w| (w.code.to_string(), w.message.clone()))
        .collect();
    d.set_item("warnings", warnings)?;
    Ok(d)
}
