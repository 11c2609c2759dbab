//! The laws, vectorised over numpy arrays with the GIL released: the nondimensional
//! Maugis-Kim force, the SI adhesion laws of a sphere (Maugis-Kim, JKR, DMT, Hertz, or a
//! scene's), the elasto-plastic asperity and the rough surface's pressure.

use crate::convert::{array_out, bool_array_out, ArrayIn};
use crate::errors::{argument, OrRaise};
use crate::run::accuracy_arg;
use crate::scene::{registry, scene_from_py};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::Arc;
use stiction_model::contact_core::{
    par, AdhesionLaw, AsperityHistory, AsperityModel, LawError, Path, SurfaceLaw,
};
use stiction_model::gw_surface::GwHistory;
use stiction_model::laws::DynAdhesion;
use stiction_model::maugis_kim::{Dmt, DugdaleParams, Hertz, Jkr, JkrParams, MaugisKim};
use stiction_model::spec::{check_delta_max, Asperity, RoughSurface, Spec};
use stiction_model::switch::rough_surface;
use stiction_model::{md, Accuracy, ModelError};

/// Points per parallel task of a vectorised evaluation.
const CHUNK: usize = 256;

/// The path of a law from its Python arguments: `"approach"`, or `"retract"` from the
/// extreme `from_` (or `default_from` when the caller has one).
pub fn core_path(path: &str, from: Option<f64>, default_from: Option<f64>) -> PyResult<Path> {
    match path {
        "approach" => match from {
            None => Ok(Path::Approach),
            Some(_) => Err(argument(
                "from",
                "given with path = \"approach\"",
                "given with path = \"retract\" only",
            )),
        },
        "retract" => match from.or(default_from) {
            Some(f) => Ok(Path::Retract { from: f }),
            None => Err(argument(
                "from",
                "missing with path = \"retract\"",
                "the extreme of the excursion retracted from (from_=...)",
            )),
        },
        other => Err(argument(
            "path",
            format!("\"{other}\""),
            "\"approach\" or \"retract\"",
        )),
    }
}

/// `f(i)` for every point `i < n`, in parallel chunks; the first error in input order.
fn par_points<F>(n: usize, f: F) -> Result<Vec<f64>, ModelError>
where
    F: Fn(usize) -> Result<f64, ModelError> + Sync,
{
    let starts: Vec<usize> = (0..n).step_by(CHUNK).collect();
    let chunks = par::map(&starts, |&s| {
        (s..(s + CHUNK).min(n))
            .map(&f)
            .collect::<Result<Vec<f64>, ModelError>>()
    })?;
    Ok(chunks.into_iter().flatten().collect())
}

/// Runs `f` over `n` points with the GIL released: on the pool when there is more than one
/// chunk, else on this thread.
fn detach_points<T: Send, F: FnOnce() -> T + Send>(py: Python<'_>, n: usize, f: F) -> T {
    if n <= CHUNK {
        crate::pool::detach_serial(py, f)
    } else {
        crate::pool::detach(py, f)
    }
}

/// `stiction.maugis_kim_force`: the nondimensional Maugis-Kim force Fbar at each
/// interference Delta of `delta` (paper eq 7 with the Kim extension; the units of
/// `stiction md`), on one curve of `lam` whose landmarks are computed once.
#[pyfunction]
#[pyo3(signature = (lam, delta, path = "approach", from_ = None))]
pub fn maugis_kim_force(
    py: Python<'_>,
    lam: f64,
    delta: &Bound<'_, PyAny>,
    path: &str,
    from_: Option<f64>,
) -> PyResult<Py<PyAny>> {
    let d = ArrayIn::new(delta)?;
    let p = core_path(path, from_, None)?;
    let values = &d.values;
    if values.len() <= CHUNK {
        // one chunk: on this thread (the pool's hand-over would cost more than the work)
        let forces = crate::pool::detach_serial(py, || {
            md::curve_for(lam).and_then(|c| md::forces(&c, values, p))
        })
        .or_raise()?;
        return array_out(py, forces, &d.shape);
    }
    let forces = crate::pool::detach(py, || -> Result<Vec<f64>, ModelError> {
        let curve = md::curve_for(lam)?;
        let starts: Vec<usize> = (0..values.len()).step_by(CHUNK).collect();
        let chunks = par::map(&starts, |&s| {
            md::forces(&curve, &values[s..(s + CHUNK).min(values.len())], p)
        })?;
        Ok(chunks.into_iter().flatten().collect())
    })
    .or_raise()?;
    array_out(py, forces, &d.shape)
}

// ------------------------------------------------------------------ adhesion laws

/// An adhesion law of one elastic sphere against a flat, in SI units: force (N,
/// compressive positive) at interference delta (m) for a sphere of radius R (m).
#[pyclass(name = "AdhesionLaw", module = "stiction", frozen)]
pub struct PyAdhesionLaw {
    law: DynAdhesion,
    name: String,
    description: String,
}

#[pymethods]
impl PyAdhesionLaw {
    /// Maugis-Dugdale with the Kim extension (paper eqs 6-11): K = 4/3 E* (Pa), work of
    /// adhesion w (J/m^2), Dugdale range z0 (m; sigma0 = w/z0).
    #[staticmethod]
    fn maugis_kim(k: f64, work_of_adhesion: f64, z0: f64) -> PyResult<Self> {
        let law = MaugisKim::new(DugdaleParams {
            k,
            work_of_adhesion,
            z0,
        })
        .or_raise()?;
        Ok(Self {
            law: Arc::new(law),
            name: "maugis_kim".into(),
            description: format!(
                "k={k:e} Pa, work_of_adhesion={work_of_adhesion:e} J/m^2, z0={z0:e} m"
            ),
        })
    }

    /// JKR (the large-lambda limit): K = 4/3 E* (Pa), work of adhesion w (J/m^2); pull-off
    /// -3/2 pi w R under load control.
    #[staticmethod]
    fn jkr(k: f64, work_of_adhesion: f64) -> PyResult<Self> {
        let law = Jkr::new(JkrParams {
            k,
            work_of_adhesion,
        })
        .or_raise()?;
        Ok(Self {
            law: Arc::new(law),
            name: "jkr".into(),
            description: format!("k={k:e} Pa, work_of_adhesion={work_of_adhesion:e} J/m^2"),
        })
    }

    /// DMT (the small-lambda limit): Hertz plus the Dugdale attraction outside the contact;
    /// K = 4/3 E* (Pa), w (J/m^2), z0 (m); pull-off -2 pi w R.
    #[staticmethod]
    fn dmt(k: f64, work_of_adhesion: f64, z0: f64) -> PyResult<Self> {
        let law = Dmt::new(DugdaleParams {
            k,
            work_of_adhesion,
            z0,
        })
        .or_raise()?;
        Ok(Self {
            law: Arc::new(law),
            name: "dmt".into(),
            description: format!(
                "k={k:e} Pa, work_of_adhesion={work_of_adhesion:e} J/m^2, z0={z0:e} m"
            ),
        })
    }

    /// Hertz: F = K sqrt(R) delta^(3/2) for delta > 0, zero otherwise; K = 4/3 E* (Pa).
    #[staticmethod]
    fn hertz(k: f64) -> PyResult<Self> {
        let law = Hertz::new(k).or_raise()?;
        Ok(Self {
            law: Arc::new(law),
            name: "hertz".into(),
            description: format!("k={k:e} Pa"),
        })
    }

    /// The adhesion law a scene names (`contact.adhesion_law`) with its pair and
    /// parameters, built by the library's law registry.
    #[staticmethod]
    fn of_scene(py: Python<'_>, scene: &Bound<'_, PyAny>) -> PyResult<Self> {
        let scene = scene_from_py(scene)?;
        let spec = crate::pool::detach(py, move || Spec::new(&scene, &registry())).or_raise()?;
        let c = spec.contact();
        Ok(Self {
            law: c.adhesion().law().clone(),
            name: c.adhesion().name().to_string(),
            description: format!(
                "of the scene: k={:e} Pa, work_of_adhesion={:e} J/m^2, z0={:e} m",
                c.pair().k(),
                c.work_of_adhesion(),
                c.z0()
            ),
        })
    }

    /// The law's name (`maugis_kim`, `jkr`, `dmt`, `hertz`, or a scene's).
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Force F (N, compressive positive) at each interference delta (m) of `delta` for a
    /// sphere of `radius` (m, one value or one per point) on `path` ("approach", or
    /// "retract" after the largest interference `from_`, m).
    #[pyo3(signature = (delta, radius, path = "approach", from_ = None))]
    fn force(
        &self,
        py: Python<'_>,
        delta: &Bound<'_, PyAny>,
        radius: &Bound<'_, PyAny>,
        path: &str,
        from_: Option<f64>,
    ) -> PyResult<Py<PyAny>> {
        let d = ArrayIn::new(delta)?;
        d.finite("delta", false)?;
        let r = ArrayIn::new(radius)?;
        r.broadcast_to("radius", &d, "delta")?;
        let p = core_path(path, from_, None)?;
        if let Path::Retract { from } = p {
            d.within_excursion("delta", from, |v, f| v > f)?;
        }
        let law = &self.law;
        let f = detach_points(py, d.len(), || {
            par_points(d.len(), |i| {
                law.force(r.at(i), d.values[i], p).map_err(ModelError::from)
            })
        })
        .or_raise()?;
        array_out(py, f, &d.shape)
    }

    /// (jump_in, jump_out): the interferences (m) at which a sphere of `radius` (m) jumps
    /// into contact on approach and out of contact on retraction.
    fn jumps(&self, py: Python<'_>, radius: f64) -> PyResult<(f64, f64)> {
        let law = &self.law;
        let j = crate::pool::detach_serial(py, || law.jumps(radius))
            .map_err(ModelError::from)
            .or_raise()?;
        Ok((j.jump_in, j.jump_out))
    }

    fn __repr__(&self) -> String {
        format!(
            "<stiction.AdhesionLaw {} ({})>",
            self.name, self.description
        )
    }
}

// ------------------------------------------------------------------ asperity

/// One elasto-plastic adhesive asperity of a scene's contact section (the paper's Fig 2
/// model): its plasticity law (yield onset eq 1, residual shape eqs 4-5, effective radius
/// eqs 12-13) composed with its adhesion law. SI units: interference delta (m), force (N,
/// compressive positive).
#[pyclass(name = "Asperity", module = "stiction", frozen)]
pub struct PyAsperity {
    asperity: Asperity,
    elastic: bool,
}

impl PyAsperity {
    /// Every value of `delta_max` in the asperity scene's domain of `delta_max`, (0, 1e3
    /// radius]: the model library's check, shared with the scenes.
    fn check_delta_max(&self, delta_max: &ArrayIn) -> PyResult<()> {
        let radius = self.asperity.radius();
        for &x in &delta_max.values {
            check_delta_max("delta_max", x, radius).or_raise()?;
        }
        Ok(())
    }

    fn history(delta_max: Option<&ArrayIn>, i: usize) -> AsperityHistory {
        match delta_max {
            Some(a) => AsperityHistory { delta_max: a.at(i) },
            None => AsperityHistory::VIRGIN,
        }
    }
}

#[pymethods]
impl PyAsperity {
    /// The asperity of `scene`'s contact section (any kind of scene); `elastic`: the same
    /// asperity with a plasticity law that never yields (the elastic comparison).
    #[new]
    #[pyo3(signature = (scene, elastic = false))]
    fn new(py: Python<'_>, scene: &Bound<'_, PyAny>, elastic: bool) -> PyResult<Self> {
        let scene = scene_from_py(scene)?;
        let spec = crate::pool::detach(py, move || Spec::new(&scene, &registry())).or_raise()?;
        let c = spec.contact();
        Ok(Self {
            asperity: if elastic {
                c.elastic_asperity()
            } else {
                c.asperity()
            },
            elastic,
        })
    }

    /// Yield onset delta_CP (m), eq 1 (inf if it never yields).
    #[getter]
    fn delta_cp(&self) -> f64 {
        self.asperity.delta_cp()
    }

    /// Initial tip radius R (m).
    #[getter]
    fn radius(&self) -> f64 {
        self.asperity.radius()
    }

    /// Force F (N, compressive positive) at each interference of `delta` (m) after the
    /// asperity was loaded to `delta_max` (m, one value or one per point; None: virgin),
    /// on `path`: "approach" (loading, reloading), or "retract" from `from_` (m; default
    /// `delta_max`).
    #[pyo3(signature = (delta, delta_max = None, path = "approach", from_ = None))]
    fn force(
        &self,
        py: Python<'_>,
        delta: &Bound<'_, PyAny>,
        delta_max: Option<&Bound<'_, PyAny>>,
        path: &str,
        from_: Option<f64>,
    ) -> PyResult<Py<PyAny>> {
        let d = ArrayIn::new(delta)?;
        d.finite("delta", false)?;
        // no deeper than an asperity scene's delta_max may reach (1e3 R): beyond, the
        // effective radius overflows inside the laws
        let deepest = stiction_model::spec::DELTA_MAX_RADII * self.asperity.radius();
        if let Some(&v) = d.values.iter().find(|&&v| v > deepest) {
            return Err(crate::errors::argument(
                "delta",
                format!("{v:e}"),
                format!("finite and at most 1e3 radius = {deepest:e} m"),
            ));
        }
        let dm = delta_max.map(ArrayIn::new).transpose()?;
        if let Some(m) = &dm {
            m.finite("delta_max", false)?;
            self.check_delta_max(m)?;
            m.broadcast_to("delta_max", &d, "delta")?;
        }
        if path == "retract" {
            match (from_, &dm) {
                (Some(f), _) => d.within_excursion("delta", f, |v, f| v > f)?,
                // retracting from each point's own delta_max
                (None, Some(m)) => {
                    for i in 0..d.len() {
                        if d.values[i] > m.at(i) {
                            return Err(crate::errors::argument(
                                "delta",
                                format!("{:e}", d.values[i]),
                                format!(
                                    "at most delta_max = {:e} on a retraction from it (a deeper point is on the approach)",
                                    m.at(i)
                                ),
                            ));
                        }
                    }
                }
                (None, None) => {}
            }
        }
        // the path is checked once; a retraction without from_ goes from each delta_max
        let retract = match (path, from_, &dm) {
            ("retract", None, Some(_)) => true,
            _ => {
                core_path(path, from_, None)?;
                false
            }
        };
        let a = &self.asperity;
        let dm_ref = dm.as_ref();
        let f = detach_points(py, d.len(), || {
            par_points(d.len(), |i| {
                let hist = Self::history(dm_ref, i);
                let p = if retract {
                    Path::Retract {
                        from: hist.delta_max,
                    }
                } else {
                    match (path, from_) {
                        ("retract", Some(f)) => Path::Retract { from: f },
                        _ => Path::Approach,
                    }
                };
                a.force(d.values[i], hist, p).map_err(ModelError::from)
            })
        })
        .or_raise()?;
        array_out(py, f, &d.shape)
    }

    /// The pull-off after loading to each `delta_max` (m): the most tensile force on the
    /// unloading path. Returns (force in N, negative when adhesive; interference in m).
    fn pull_off(
        &self,
        py: Python<'_>,
        delta_max: &Bound<'_, PyAny>,
    ) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
        let dm = ArrayIn::new(delta_max)?;
        dm.finite("delta_max", false)?;
        self.check_delta_max(&dm)?;
        let a = &self.asperity;
        let res = crate::pool::detach(py, || {
            let idx: Vec<usize> = (0..dm.len()).collect();
            par::map(&idx, |&i| {
                a.pull_off(dm.values[i])
                    .map(|p| (p.force, p.delta))
                    .map_err(ModelError::from)
            })
        })
        .or_raise()?;
        let (f, d): (Vec<f64>, Vec<f64>) = res.into_iter().unzip();
        Ok((array_out(py, f, &dm.shape)?, array_out(py, d, &dm.shape)?))
    }

    /// The plastic state after loading to each `delta_max` (m): a dict of `delta_res` (m,
    /// residual height loss, eq 4), `r_res` (m, residual radius, eq 5), `extrapolated`
    /// (beyond the fits' range).
    fn state<'py>(
        &self,
        py: Python<'py>,
        delta_max: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let dm = ArrayIn::new(delta_max)?;
        dm.finite("delta_max", false)?;
        self.check_delta_max(&dm)?;
        let states: Vec<_> = dm
            .values
            .iter()
            .map(|&x| {
                self.asperity
                    .plastic_state(AsperityHistory { delta_max: x })
            })
            .collect();
        let d = PyDict::new(py);
        d.set_item(
            "delta_res",
            array_out(py, states.iter().map(|s| s.delta_res).collect(), &dm.shape)?,
        )?;
        d.set_item(
            "r_res",
            array_out(py, states.iter().map(|s| s.r_res).collect(), &dm.shape)?,
        )?;
        d.set_item(
            "extrapolated",
            bool_array_out(
                py,
                states.iter().map(|s| s.extrapolated).collect(),
                &dm.shape,
            )?,
        )?;
        Ok(d)
    }

    /// (jump_in, jump_out) interferences (m) after loading to `delta_max` (m; None:
    /// virgin).
    #[pyo3(signature = (delta_max = None))]
    fn jumps(&self, py: Python<'_>, delta_max: Option<f64>) -> PyResult<(f64, f64)> {
        if let Some(v) = delta_max.filter(|v| !v.is_finite()) {
            return Err(crate::errors::argument(
                "delta_max",
                format!("{v}"),
                "a finite number (None: virgin)",
            ));
        }
        if let Some(v) = delta_max {
            check_delta_max("delta_max", v, self.asperity.radius()).or_raise()?;
        }
        let hist = delta_max.map_or(AsperityHistory::VIRGIN, |d| AsperityHistory {
            delta_max: d,
        });
        let a = &self.asperity;
        let j = crate::pool::detach_serial(py, || a.jumps(hist))
            .map_err(ModelError::from)
            .or_raise()?;
        Ok((j.jump_in, j.jump_out))
    }

    fn __repr__(&self) -> String {
        format!(
            "<stiction.Asperity R={:e} m, delta_CP={:e} m{}>",
            self.asperity.radius(),
            self.asperity.delta_cp(),
            if self.elastic { ", elastic" } else { "" }
        )
    }
}

// ------------------------------------------------------------------ rough surface

/// The Greenwood-Williamson rough surface of a surface or switch scene (paper eqs 14-16)
/// against a rigid flat, as `stiction surface` builds it: nominal pressure p (Pa,
/// compressive positive) at separation d (m, from the mean plane of asperity heights to
/// the flat). Its history is one number, d_min: the deepest separation reached (every
/// asperity of height h remembers delta_max = h - d_min).
#[pyclass(name = "Surface", module = "stiction", frozen)]
pub struct PySurface {
    gw: RoughSurface,
    accuracy: Accuracy,
    sigma_s: f64,
}

fn surface_history(d_min: f64) -> GwHistory {
    GwHistory::Flat { deepest: d_min }
}

impl PySurface {
    fn path_at(path: &str, from: Option<f64>, d_min: f64) -> PyResult<Path> {
        let default = (path == "retract" && from.is_none()).then_some(d_min);
        core_path(path, from, default)
    }

    fn eval<T: Send>(
        &self,
        py: Python<'_>,
        d: &ArrayIn,
        d_min: &ArrayIn,
        path: &str,
        from: Option<f64>,
        f: impl Fn(&RoughSurface, f64, &GwHistory, Path) -> Result<T, LawError> + Sync,
    ) -> PyResult<Vec<T>> {
        d_min.broadcast_to("d_min", d, "d")?;
        if path == "retract" && from.is_none() {
            if let Some(bad) = d_min.values.iter().find(|x| !x.is_finite()) {
                return Err(argument(
                    "d_min",
                    format!("{bad:e} with path = \"retract\" and no from_"),
                    "finite: the deepest separation retracted from (or give from_)",
                ));
            }
        }
        // checks the path word once
        Self::path_at(path, from, d_min.at(0))?;
        let gw = &self.gw;
        let idx: Vec<usize> = (0..d.len()).collect();
        crate::pool::detach(py, || {
            par::map(&idx, |&i| {
                let dm = d_min.at(i);
                let p = match (path, from) {
                    ("retract", Some(f)) => Path::Retract { from: f },
                    ("retract", None) => Path::Retract { from: dm },
                    _ => Path::Approach,
                };
                f(gw, d.values[i], &surface_history(dm), p).map_err(ModelError::from)
            })
        })
        .or_raise()
    }
}

#[pymethods]
impl PySurface {
    /// The rough surface of a surface or switch scene (its contact and surface sections)
    /// at `accuracy` (None: the scene's); `elastic`: asperities that never yield.
    #[new]
    #[pyo3(signature = (scene, accuracy = None, elastic = false))]
    fn new(
        py: Python<'_>,
        scene: &Bound<'_, PyAny>,
        accuracy: Option<&str>,
        elastic: bool,
    ) -> PyResult<Self> {
        let scene = scene_from_py(scene)?;
        let acc = accuracy_arg(accuracy)?;
        let file = scene.file().to_string();
        let (gw, accuracy, sigma_s) = crate::pool::detach(py, move || -> Result<_, ModelError> {
            let spec = Spec::new(&scene, &registry())?;
            let (common, c, roughness) = match &spec {
                Spec::Switch(s) => (s.common(), s.contact(), s.roughness()),
                Spec::Surface(s) => (s.common(), s.contact(), s.roughness()),
                _ => {
                    return Err(ModelError::argument(
                        "scene",
                        file,
                        "a switch or surface scene (an asperity scene has no rough surface)",
                    ))
                }
            };
            let accuracy = acc.unwrap_or(common.accuracy());
            let gw = rough_surface(c, roughness, accuracy, 0.0, elastic)?;
            Ok((gw, accuracy, roughness.sigma_s()))
        })
        .or_raise()?;
        Ok(Self {
            gw,
            accuracy,
            sigma_s,
        })
    }

    /// RMS of the asperity heights sigma_s (m).
    #[getter]
    fn sigma_s(&self) -> f64 {
        self.sigma_s
    }

    /// The accuracy mode of the quadrature.
    #[getter]
    fn accuracy(&self) -> &'static str {
        self.accuracy.as_str()
    }

    /// Nominal pressure p (Pa, compressive positive, adhesive negative) at each separation
    /// of `d` (m), with the history `d_min` (m, the deepest separation reached, one value
    /// or one per point; inf: a virgin surface) on `path`: "approach" (first loading, or
    /// reloading), or "retract" from `from_` (m; default d_min). Eq 15 integrated over the
    /// Gaussian heights (eq 14), each asperity with its own history; points in parallel.
    #[pyo3(signature = (d, d_min = None, path = "approach", from_ = None))]
    fn pressure(
        &self,
        py: Python<'_>,
        d: &Bound<'_, PyAny>,
        d_min: Option<&Bound<'_, PyAny>>,
        path: &str,
        from_: Option<f64>,
    ) -> PyResult<Py<PyAny>> {
        let d = ArrayIn::new(d)?;
        let dm = match d_min {
            Some(x) => ArrayIn::new(x)?,
            None => ArrayIn {
                values: vec![f64::INFINITY],
                shape: Vec::new(),
            },
        };
        d.finite("d", false)?;
        dm.finite("d_min", true)?;
        within_reach_of_the_heights(self.sigma_s, &d, &dm)?;
        let p = self.eval(py, &d, &dm, path, from_, |gw, x, h, p| gw.pressure(x, h, p))?;
        array_out(py, p, &d.shape)
    }

    /// (pressure, error estimate), both in Pa, as `pressure` computes them: the adaptive
    /// quadrature's estimate of its own error at each point.
    #[pyo3(signature = (d, d_min = None, path = "approach", from_ = None))]
    fn pressure_estimate(
        &self,
        py: Python<'_>,
        d: &Bound<'_, PyAny>,
        d_min: Option<&Bound<'_, PyAny>>,
        path: &str,
        from_: Option<f64>,
    ) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
        let d = ArrayIn::new(d)?;
        let dm = match d_min {
            Some(x) => ArrayIn::new(x)?,
            None => ArrayIn {
                values: vec![f64::INFINITY],
                shape: Vec::new(),
            },
        };
        d.finite("d", false)?;
        dm.finite("d_min", true)?;
        within_reach_of_the_heights(self.sigma_s, &d, &dm)?;
        let e = self.eval(py, &d, &dm, path, from_, |gw, x, h, p| {
            gw.pressure_estimate(x, h, p)
        })?;
        let (v, err): (Vec<f64>, Vec<f64>) = e.into_iter().map(|e| (e.value, e.error)).unzip();
        Ok((array_out(py, v, &d.shape)?, array_out(py, err, &d.shape)?))
    }

    /// The separation (m) beyond which the pressure of history `d_min` (m; None: virgin)
    /// on `path` is zero: where the first asperity touches on approach, the last lets go on
    /// retraction.
    #[pyo3(signature = (d_min = None, path = "approach", from_ = None))]
    fn reach(
        &self,
        py: Python<'_>,
        d_min: Option<f64>,
        path: &str,
        from_: Option<f64>,
    ) -> PyResult<f64> {
        let dm = d_min.unwrap_or(f64::INFINITY);
        if dm.is_nan() {
            return Err(crate::errors::argument(
                "d_min",
                "NaN",
                "a number (None or inf: a virgin surface)",
            ));
        }
        let p = Self::path_at(path, from_, dm)?;
        let gw = &self.gw;
        crate::pool::detach(py, || gw.reach(&surface_history(dm), p))
            .map_err(ModelError::from)
            .or_raise()
    }

    /// The pull-out after the surface was pressed to `d_min` (m) and retracts: a dict of
    /// `pressure` (Pa, the magnitude of the most tensile pressure, >= 0), `separation` (m,
    /// where) and `error` (Pa), by the switch model's search (`switch_1d::unload`).
    fn pull_out<'py>(&self, py: Python<'py>, d_min: f64) -> PyResult<Bound<'py, PyDict>> {
        // pressed to d_min: within 20 sigma_s of the mean plane, as `stiction surface
        // --unload-from` (beyond, the Gaussian heights hold no asperity)
        let lim = 20.0 * self.sigma_s;
        if !(d_min.is_finite() && d_min.abs() <= lim) {
            return Err(crate::errors::argument(
                "d_min",
                format!("{d_min:e}"),
                format!("finite and within 20 sigma_s = {lim:e} m of the mean plane"),
            ));
        }
        let gw = &self.gw;
        let precision = self.accuracy.precision();
        let u = crate::pool::detach(py, || {
            stiction_model::switch_1d::unload(gw, &surface_history(d_min), d_min, 0, precision)
        })
        .map_err(ModelError::from)
        .or_raise()?;
        let d = PyDict::new(py);
        d.set_item("pressure", u.pull_out_pressure)?;
        d.set_item("separation", u.pull_out_separation)?;
        d.set_item("error", u.pull_out_error)?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "<stiction.Surface sigma_s={:e} m, accuracy {}>",
            self.sigma_s,
            self.accuracy.as_str()
        )
    }
}

/// Separations no deeper than 20 sigma_s below the mean plane, as `stiction surface`
/// takes them (beyond, the Gaussian heights hold no asperity, and the asperity laws
/// overflow): an error naming `d` or `d_min` otherwise.
fn within_reach_of_the_heights(sigma_s: f64, d: &ArrayIn, d_min: &ArrayIn) -> PyResult<()> {
    let lim = -20.0 * sigma_s;
    for (name, a) in [("d", d), ("d_min", d_min)] {
        if let Some(&v) = a.values.iter().find(|&&v| v < lim) {
            return Err(crate::errors::argument(
                name,
                format!("{v:e}"),
                format!("at least -20 sigma_s = {lim:e} m (no asperity reaches deeper)"),
            ));
        }
    }
    Ok(())
}
