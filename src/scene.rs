//! Scenes: TOML files in SI units that say what to model and what to compute.
//!
//! Every key is documented on its field; unknown keys are rejected; every value is
//! checked against a stated domain, and an error names the file, the key, the value
//! and the allowed range.

use serde::{Deserialize, Serialize};
use std::fmt;

/// A scene error: a file that could not be read or parsed, or a value out of its domain.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("{file}: cannot read: {message}")]
    Read { file: String, message: String },
    #[error("{file}: {message}")]
    Parse { file: String, message: String },
    #[error("{file}: invalid `{field}` = {value}: must be {allowed}")]
    Field {
        file: String,
        field: String,
        value: String,
        allowed: String,
    },
}

/// Which adhesion law the asperities follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AdhesionKind {
    Hertz,
    Dmt,
    Jkr,
    MaugisKim,
}

/// Which plasticity law the asperities follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PlasticityKind {
    EtsionKadin,
    Elastic,
}

/// The counter-surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CounterKind {
    /// A rigid flat.
    Rigid,
    /// The same material as the asperities (two identical films).
    Same,
    /// Another material: `counter_youngs_modulus`, `counter_poisson_ratio`.
    Material,
}

/// Speed/accuracy trade, see `docs/performance.md`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, clap::ValueEnum)]
#[serde(rename_all = "snake_case")]
pub enum Accuracy {
    /// Adaptive tanh-sinh height integrals to 1e-10, every law point solved.
    #[default]
    Accurate,
    /// Fixed 12-point Gauss-Legendre panels of sigma_s/2.
    Balanced,
    /// Fixed 6-point Gauss-Legendre panels of sigma_s; eq 17 on 8 nodes per sigma_s.
    Fast,
}

/// The contact pair and its laws (shared by every scene kind).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Contact {
    /// Young's modulus of the asperity material E (Pa), in [1e6, 1e13].
    pub youngs_modulus: f64,
    /// Poisson ratio nu, in [0, 0.5).
    pub poisson_ratio: f64,
    /// Yield stress S_Y (Pa), >= 1e3 (inf: never yields, with `plasticity_law = "elastic"`).
    pub yield_stress: f64,
    /// Asperity tip radius R (m), in [1e-9, 1e-2] (the equivalent radius for two rough surfaces).
    pub radius: f64,
    /// Work of adhesion w (J/m^2), in [1e-6, 100].
    pub work_of_adhesion: f64,
    /// Dugdale range z0 (m), in [1e-12, 1e-6]; sigma0 = w/z0.
    pub z0: f64,
    /// `rigid`, `same` or `material`.
    pub counter: CounterKind,
    /// Counter-surface Young's modulus (Pa) when `counter = "material"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub counter_youngs_modulus: Option<f64>,
    /// Counter-surface Poisson ratio when `counter = "material"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub counter_poisson_ratio: Option<f64>,
    /// `maugis_kim` (default), `jkr`, `dmt` or `hertz`.
    #[serde(default = "default_adhesion")]
    pub adhesion_law: AdhesionKind,
    /// `etsion_kadin` (default) or `elastic`.
    #[serde(default = "default_plasticity")]
    pub plasticity_law: PlasticityKind,
    /// Modulus in the yield onset, eq 1: `composite` (E*, default) or `as_printed` (E).
    #[serde(default)]
    pub yield_modulus: asperity_plastic::YieldModulus,
}

fn default_adhesion() -> AdhesionKind {
    AdhesionKind::MaugisKim
}
fn default_plasticity() -> PlasticityKind {
    PlasticityKind::EtsionKadin
}

/// `stiction asperity`: one asperity loaded to each delta_max and unloaded.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AsperityScene {
    pub contact: Contact,
    /// Maximum interferences (m), each > 0.
    pub delta_max: Vec<f64>,
    /// Points per loading and per unloading curve, in [2, 100000].
    #[serde(default = "default_points")]
    pub points: usize,
}

/// `stiction surface`: the Greenwood-Williamson surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceScene {
    pub contact: Contact,
    pub surface: Surface,
    /// Smallest separation of the loading curve (m); defaults to `unload_from`, else 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub d_start: Option<f64>,
    /// Load to this separation (m) and unload from it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unload_from: Option<f64>,
    /// Points per curve, in [2, 100000].
    #[serde(default = "default_points")]
    pub points: usize,
    #[serde(default)]
    pub accuracy: Accuracy,
}

/// Roughness of the equivalent surface against a smooth flat.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Surface {
    /// Standard deviation of asperity heights sigma_s (m), in [1e-11, 1e-6].
    pub sigma_s: f64,
    /// Asperities per unit area N (1/m^2), in [1e9, 1e17] (1e-3 to 1e5 per um^2).
    pub asperity_density: f64,
}

/// `stiction switch`: the micro-switch of Table 2, cycle by cycle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SwitchScene {
    pub contact: Contact,
    pub surface: Surface,
    pub switch: SwitchGeometry,
    /// Number of impact cycles, in [1, 1000].
    #[serde(default = "default_cycles")]
    pub cycles: usize,
    /// Stop as soon as accommodation is detected (at most `cycles`).
    #[serde(default)]
    pub until_accommodated: bool,
    /// Relative change below which the next cycle counts as accommodated, in (0, 0.1].
    #[serde(default = "default_accommodation")]
    pub accommodation_tolerance: f64,
    /// Also run the same surface with elastic asperities.
    #[serde(default = "default_true")]
    pub elastic_comparison: bool,
    /// Points per curve, in [0, 100000]; 0 computes pull-out pressures only.
    #[serde(default = "default_points")]
    pub points: usize,
    #[serde(default)]
    pub accuracy: Accuracy,
}

/// Table 2 and the impact.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SwitchGeometry {
    /// Initial air gap d0 (m), in [1e-9, 1e-3].
    pub d0: f64,
    /// Dielectric thickness t_d (m), in [1e-10, 1e-3].
    pub t_d: f64,
    /// Relative permittivity of the dielectric eps_d/eps_0, in [1, 1e4].
    pub epsilon_r: f64,
    /// Vacuum permittivity (F/m), 8.854e-12 in Table 2.
    #[serde(default = "default_eps0")]
    pub epsilon_0: f64,
    /// Ru film thickness t_s (m), in [1e-10, 1e-3]; stores elastic energy in eq 17.
    pub film_thickness: f64,
    /// Impact energy per unit area E_I (J/m^2), in [1e-9, 100]. Give this, or `k_s`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impact_energy: Option<f64>,
    /// Spring stiffness per unit area K_s (Pa/m), > 0. Give this (with an optional
    /// `voltage`), or `impact_energy`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub k_s: Option<f64>,
    /// Actuation voltage U (V) with `k_s`; defaults to the pull-in voltage.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub voltage: Option<f64>,
}

fn default_points() -> usize {
    200
}
fn default_cycles() -> usize {
    10
}
fn default_accommodation() -> f64 {
    1e-3
}
fn default_true() -> bool {
    true
}
fn default_eps0() -> f64 {
    switch_1d::EPSILON_0
}

/// The paper's scenes, embedded.
pub const DEFAULT_ASPERITY: &str = include_str!("../scenes/asperity.toml");
pub const DEFAULT_SURFACE: &str = include_str!("../scenes/surface.toml");
pub const DEFAULT_SWITCH: &str = include_str!("../scenes/switch.toml");

/// Checks applied to a parsed scene; `file` names the source in messages.
pub struct Checker<'a> {
    pub file: &'a str,
}

impl Checker<'_> {
    fn fail(&self, field: &str, value: impl fmt::Display, allowed: &str) -> SceneError {
        SceneError::Field {
            file: self.file.to_string(),
            field: field.to_string(),
            value: value.to_string(),
            allowed: allowed.to_string(),
        }
    }

    /// value finite and in (lo, hi] (or [lo, hi] when `closed`).
    pub fn range(
        &self,
        field: &str,
        v: f64,
        lo: f64,
        hi: f64,
        closed: bool,
    ) -> Result<(), SceneError> {
        let ok = v.is_finite() && (if closed { v >= lo } else { v > lo }) && v <= hi;
        if ok {
            Ok(())
        } else {
            let open = if closed { "[" } else { "(" };
            Err(self.fail(field, v, &format!("finite and in {open}{lo:e}, {hi:e}]")))
        }
    }

    pub fn count(&self, field: &str, v: usize, lo: usize, hi: usize) -> Result<(), SceneError> {
        if (lo..=hi).contains(&v) {
            Ok(())
        } else {
            Err(self.fail(field, v, &format!("an integer in [{lo}, {hi}]")))
        }
    }

    pub fn contact(&self, c: &Contact) -> Result<(), SceneError> {
        self.range("contact.youngs_modulus", c.youngs_modulus, 1e6, 1e13, true)?;
        if !(c.poisson_ratio.is_finite() && (0.0..0.5).contains(&c.poisson_ratio)) {
            return Err(self.fail("contact.poisson_ratio", c.poisson_ratio, "in [0, 0.5)"));
        }
        if c.yield_stress.is_nan() || c.yield_stress <= 0.0 {
            return Err(self.fail(
                "contact.yield_stress",
                c.yield_stress,
                "> 0 (inf for a material that never yields)",
            ));
        }
        self.range("contact.radius", c.radius, 1e-9, 1e-2, true)?;
        self.range(
            "contact.work_of_adhesion",
            c.work_of_adhesion,
            0.0,
            100.0,
            false,
        )?;
        self.range("contact.z0", c.z0, 1e-12, 1e-6, true)?;
        match c.counter {
            CounterKind::Material => {
                let e = c.counter_youngs_modulus.ok_or_else(|| {
                    self.fail(
                        "contact.counter_youngs_modulus",
                        "missing",
                        "given when counter = \"material\"",
                    )
                })?;
                self.range("contact.counter_youngs_modulus", e, 1e6, 1e13, true)?;
                let nu = c.counter_poisson_ratio.ok_or_else(|| {
                    self.fail(
                        "contact.counter_poisson_ratio",
                        "missing",
                        "given when counter = \"material\"",
                    )
                })?;
                if !(nu.is_finite() && (0.0..0.5).contains(&nu)) {
                    return Err(self.fail("contact.counter_poisson_ratio", nu, "in [0, 0.5)"));
                }
            }
            _ => {
                if let Some(e) = c.counter_youngs_modulus {
                    return Err(self.fail(
                        "contact.counter_youngs_modulus",
                        e,
                        "absent unless counter = \"material\"",
                    ));
                }
                if let Some(nu) = c.counter_poisson_ratio {
                    return Err(self.fail(
                        "contact.counter_poisson_ratio",
                        nu,
                        "absent unless counter = \"material\"",
                    ));
                }
            }
        }
        if c.plasticity_law == PlasticityKind::EtsionKadin && !c.yield_stress.is_finite() {
            return Err(self.fail(
                "contact.yield_stress",
                c.yield_stress,
                "finite with plasticity_law = \"etsion_kadin\" (use \"elastic\" for no yield)",
            ));
        }
        Ok(())
    }

    pub fn surface(&self, s: &Surface) -> Result<(), SceneError> {
        self.range("surface.sigma_s", s.sigma_s, 1e-11, 1e-6, true)?;
        self.range(
            "surface.asperity_density",
            s.asperity_density,
            1e9,
            1e17,
            true,
        )
    }

    pub fn switch(&self, s: &SwitchGeometry) -> Result<(), SceneError> {
        self.range("switch.d0", s.d0, 1e-9, 1e-3, true)?;
        self.range("switch.t_d", s.t_d, 1e-10, 1e-3, true)?;
        self.range("switch.epsilon_r", s.epsilon_r, 1.0, 1e4, true)?;
        self.range("switch.epsilon_0", s.epsilon_0, 1e-12, 1e-10, true)?;
        self.range("switch.film_thickness", s.film_thickness, 1e-10, 1e-3, true)?;
        match (s.impact_energy, s.k_s) {
            (Some(e), None) => {
                self.range("switch.impact_energy", e, 1e-9, 100.0, true)?;
                if let Some(v) = s.voltage {
                    return Err(self.fail(
                        "switch.voltage",
                        v,
                        "absent when impact_energy is given (U = V_PI)",
                    ));
                }
            }
            (None, Some(k)) => {
                self.range("switch.k_s", k, 0.0, 1e20, false)?;
                if let Some(v) = s.voltage {
                    self.range("switch.voltage", v, 0.0, 1e5, false)?;
                }
            }
            (Some(e), Some(_)) => {
                return Err(self.fail(
                    "switch.impact_energy",
                    e,
                    "given alone, or replaced by k_s (not both)",
                ))
            }
            (None, None) => {
                return Err(self.fail(
                    "switch.impact_energy",
                    "missing",
                    "given, or k_s given instead",
                ))
            }
        }
        Ok(())
    }
}

/// Parses TOML text into a scene type, naming `file` in errors.
pub fn parse<T: for<'de> Deserialize<'de>>(file: &str, text: &str) -> Result<T, SceneError> {
    if text.trim().is_empty() {
        return Err(SceneError::Parse {
            file: file.into(),
            message: "empty scene file".into(),
        });
    }
    toml::from_str(text).map_err(|e| SceneError::Parse {
        file: file.into(),
        message: e.to_string().trim_end().to_string(),
    })
}

/// Reads a scene file (or the embedded default when `path` is None).
pub fn load<T: for<'de> Deserialize<'de>>(
    path: Option<&std::path::Path>,
    default: &str,
) -> Result<(String, T), SceneError> {
    match path {
        None => Ok(("<default scene>".into(), parse("<default scene>", default)?)),
        Some(p) => {
            let name = p.display().to_string();
            let bytes = std::fs::read(p).map_err(|e| SceneError::Read {
                file: name.clone(),
                message: e.to_string(),
            })?;
            let text = String::from_utf8(bytes).map_err(|_| SceneError::Parse {
                file: name.clone(),
                message: "not UTF-8 text".into(),
            })?;
            Ok((name.clone(), parse(&name, &text)?))
        }
    }
}

impl AsperityScene {
    pub fn validate(&self, file: &str) -> Result<(), SceneError> {
        let c = Checker { file };
        c.contact(&self.contact)?;
        if self.delta_max.is_empty() {
            return Err(c.fail("delta_max", "[]", "a non-empty list"));
        }
        for (i, &d) in self.delta_max.iter().enumerate() {
            c.range(
                &format!("delta_max[{i}]"),
                d,
                0.0,
                1e3 * self.contact.radius,
                false,
            )?;
        }
        c.count("points", self.points, 2, 100_000)
    }
}

impl SurfaceScene {
    pub fn validate(&self, file: &str) -> Result<(), SceneError> {
        let c = Checker { file };
        c.contact(&self.contact)?;
        c.surface(&self.surface)?;
        let lim = 20.0 * self.surface.sigma_s;
        if let Some(d) = self.d_start {
            c.range("d_start", d, -lim, lim, true)?;
        }
        if let Some(d) = self.unload_from {
            c.range("unload_from", d, -lim, lim, true)?;
        }
        c.count("points", self.points, 2, 100_000)
    }
}

impl SwitchScene {
    pub fn validate(&self, file: &str) -> Result<(), SceneError> {
        let c = Checker { file };
        c.contact(&self.contact)?;
        c.surface(&self.surface)?;
        c.switch(&self.switch)?;
        c.count("cycles", self.cycles, 1, 1000)?;
        c.range(
            "accommodation_tolerance",
            self.accommodation_tolerance,
            0.0,
            0.1,
            false,
        )?;
        c.count("points", self.points, 0, 100_000)
    }
}
