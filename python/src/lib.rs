//! `stiction._stiction`: the extension module of the Python package `stiction`, a thin
//! layer over the model library `stiction-model` (scene -> spec -> model -> run -> result).
//!
//! No physics here: every value is computed by the library; this crate converts Python
//! values to scenes and arrays, releases the GIL around every computation
//! (`Python::detach`), and converts the library's typed results (their serde form) to
//! Python dicts, lists and numpy arrays, which the Python layer (`stiction/_results.py`)
//! wraps in typed result classes. Errors become `stiction.InputError` or
//! `stiction.NumericalError` by the library's own category.

mod contact_law;
mod convert;
mod design;
mod errors;
mod laws;
mod pool;
mod probability;
mod report;
mod run;
mod scene;
mod topography;

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _stiction(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<scene::PyScene>()?;
    m.add_class::<report::PyReport>()?;
    m.add_function(wrap_pyfunction!(scene::load_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene::variable_fields, m)?)?;
    m.add_function(wrap_pyfunction!(scene::scene_keys, m)?)?;
    m.add_function(wrap_pyfunction!(run::run, m)?)?;
    m.add_function(wrap_pyfunction!(run::md_curve, m)?)?;
    m.add_function(wrap_pyfunction!(run::calibrate, m)?)?;
    m.add_function(wrap_pyfunction!(laws::maugis_kim_force, m)?)?;
    m.add_class::<laws::PyAdhesionLaw>()?;
    m.add_class::<laws::PyAsperity>()?;
    m.add_class::<laws::PySurface>()?;
    m.add_function(wrap_pyfunction!(design::design_threshold, m)?)?;
    m.add_class::<design::PyMap>()?;
    m.add_function(wrap_pyfunction!(design::design_map, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_map_plan, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_point, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_map_assemble, m)?)?;
    m.add_function(wrap_pyfunction!(design::model_form_scenes, m)?)?;
    m.add_function(wrap_pyfunction!(design::with_map_model_form, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_merge, m)?)?;
    m.add_function(wrap_pyfunction!(design::read_map, m)?)?;
    m.add_class::<probability::PyProbability>()?;
    m.add_function(wrap_pyfunction!(probability::design_probability, m)?)?;
    m.add_function(wrap_pyfunction!(probability::design_probability_plan, m)?)?;
    m.add_function(wrap_pyfunction!(
        probability::design_probability_assemble,
        m
    )?)?;
    m.add_function(wrap_pyfunction!(
        probability::with_probability_model_form,
        m
    )?)?;
    m.add_function(wrap_pyfunction!(probability::design_merge_probability, m)?)?;
    m.add_function(wrap_pyfunction!(probability::read_probability, m)?)?;
    m.add_class::<contact_law::PyContactLaw>()?;
    m.add_function(wrap_pyfunction!(contact_law::tabulate_law, m)?)?;
    m.add_function(wrap_pyfunction!(topography::topography, m)?)?;
    Ok(())
}
