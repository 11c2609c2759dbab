//! Scenes: TOML files in SI units that say what to model and what to compute.
//!
//! Every key, its unit and its domain live in [`fields::FIELDS`]; unknown keys are
//! rejected; an error names the file, the key, the value (in scientific notation) and the
//! allowed range. Files larger than [`MAX_SCENE_BYTES`] are refused before they are read
//! whole.

pub mod fields;

pub use crate::accuracy::Accuracy;
use asperity_plastic::YieldModulus;
use fields::{Domain, Kind};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::io::Read;

/// Scene files are at most this large (1 MiB): a scene is a few dozen lines.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// A scene error: a file that could not be read or parsed, or a value out of its domain.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file cannot be opened or read.
    #[error("{file}: cannot read: {source}")]
    Read {
        /// The file.
        file: String,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// The file is larger than [`MAX_SCENE_BYTES`].
    #[error("{file}: larger than {limit} bytes: not a scene file")]
    TooLarge {
        /// The file.
        file: String,
        /// The limit.
        limit: u64,
    },
    /// The file is not UTF-8 text.
    #[error("{file}: not UTF-8 text")]
    NotText {
        /// The file.
        file: String,
    },
    /// The file is empty.
    #[error("{file}: empty scene file")]
    Empty {
        /// The file.
        file: String,
    },
    /// TOML syntax, an unknown or missing key, a value of the wrong type.
    #[error("{file}: {message}")]
    Parse {
        /// The file.
        file: String,
        /// The TOML parser's message.
        message: String,
    },
    /// A value outside its domain.
    #[error("{file}: invalid `{key}` = {value}: must be {allowed}")]
    Field {
        /// The file.
        file: String,
        /// The key (`section.key`).
        key: String,
        /// The value as written (numbers in scientific notation).
        value: String,
        /// The domain or rule.
        allowed: String,
    },
    /// A required key that needs explaining.
    #[error("{file}: missing `{key}`: {explanation}")]
    Missing {
        /// The file.
        file: String,
        /// The key.
        key: String,
        /// What to give and why.
        explanation: String,
    },
}

/// A number as messages print it: scientific notation, shortest round-trip digits (5e-1,
/// 1e13), so every message reads the same way whatever the magnitude.
pub fn num(v: f64) -> String {
    if v.is_nan() {
        "NaN".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{v:e}")
    }
}

/// Which adhesion law the asperities follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AdhesionKind {
    /// Hertz, no adhesion.
    Hertz,
    /// DMT with a Dugdale range.
    Dmt,
    /// JKR.
    Jkr,
    /// Maugis-Dugdale with the Kim extension.
    MaugisKim,
}

/// Which plasticity law the asperities follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PlasticityKind {
    /// Etsion-Kadin fits (eqs 1-5, 12-13).
    EtsionKadin,
    /// Never yields.
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
    /// Another material: `counter_youngs_modulus`, `counter_poisson_ratio`,
    /// `counter_yield_stress`.
    Material,
}

/// The constants of eq 13.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EffectiveRadius {
    /// [a1, a2, a3] of c1 = a1 + a2 exp(-a3 omega).
    #[serde(default = "paper_c1")]
    pub c1: [f64; 3],
    /// [b1, b2, b3] of c2 = b1/(1 + (omega/b2)^2) - b3.
    #[serde(default = "paper_c2")]
    pub c2: [f64; 3],
}

fn paper_c1() -> [f64; 3] {
    asperity_plastic::EffectiveRadiusFit::PAPER.c1
}
fn paper_c2() -> [f64; 3] {
    asperity_plastic::EffectiveRadiusFit::PAPER.c2
}

impl Default for EffectiveRadius {
    fn default() -> Self {
        Self {
            c1: paper_c1(),
            c2: paper_c2(),
        }
    }
}

/// The contact pair and its laws (shared by every scene kind). Units and domains:
/// [`fields::FIELDS`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct Contact {
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    #[serde(serialize_with = "crate::render::number_or_name")]
    pub yield_stress: f64,
    pub radius: f64,
    pub work_of_adhesion: f64,
    pub z0: f64,
    pub counter: CounterKind,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub counter_youngs_modulus: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub counter_poisson_ratio: Option<f64>,
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        serialize_with = "crate::render::some_number_or_name"
    )]
    pub counter_yield_stress: Option<f64>,
    #[serde(default = "default_adhesion")]
    pub adhesion_law: AdhesionKind,
    #[serde(default = "default_plasticity")]
    pub plasticity_law: PlasticityKind,
    /// Required; an Option only so that its absence gets an explanation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yield_modulus: Option<YieldModulus>,
    #[serde(default)]
    pub effective_radius: EffectiveRadius,
}

fn default_adhesion() -> AdhesionKind {
    AdhesionKind::MaugisKim
}
fn default_plasticity() -> PlasticityKind {
    PlasticityKind::EtsionKadin
}

impl Contact {
    /// The eq-1 reading (validated scenes always have one).
    pub fn yield_modulus(&self) -> YieldModulus {
        self.yield_modulus.unwrap_or(YieldModulus::AsPrinted)
    }
}

/// `stiction asperity`: one asperity loaded to each delta_max and unloaded.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct AsperityScene {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub title: Option<String>,
    pub contact: Contact,
    pub delta_max: Vec<f64>,
    #[serde(default = "default_points")]
    pub points: usize,
    #[serde(default)]
    pub accuracy: Accuracy,
}

/// Roughness of the equivalent surface against a smooth flat.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct Surface {
    pub sigma_s: f64,
    pub asperity_density: f64,
}

/// `stiction surface`: the Greenwood-Williamson surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct SurfaceScene {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub title: Option<String>,
    pub contact: Contact,
    pub surface: Surface,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub d_start: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unload_from: Option<f64>,
    #[serde(default = "default_points")]
    pub points: usize,
    #[serde(default)]
    pub accuracy: Accuracy,
}

/// `stiction switch`: the micro-switch of Table 2, cycle by cycle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct SwitchScene {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub title: Option<String>,
    pub contact: Contact,
    pub surface: Surface,
    pub switch: SwitchGeometry,
    #[serde(default = "default_cycles")]
    pub cycles: usize,
    #[serde(default)]
    pub until_accommodated: bool,
    #[serde(default = "default_accommodation")]
    pub accommodation_tolerance: f64,
    #[serde(default = "default_true")]
    pub elastic_comparison: bool,
    #[serde(default = "default_points")]
    pub points: usize,
    #[serde(default)]
    pub accuracy: Accuracy,
}

/// Table 2 and the drive of the impact.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct SwitchGeometry {
    pub d0: f64,
    pub t_d: f64,
    pub epsilon_r: f64,
    #[serde(default = "default_eps0")]
    pub epsilon_0: f64,
    pub film_thickness: f64,
    /// Resolved to the contact material's E when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub film_youngs_modulus: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impact_energy: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub k_s: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub voltage: Option<f64>,
    #[serde(default = "default_phi")]
    pub contact_area_fraction: f64,
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
fn default_phi() -> f64 {
    1.0
}

/// The paper's Fig 2 scene, embedded.
pub const DEFAULT_ASPERITY: &str = include_str!("../../scenes/asperity.toml");
/// The paper's rough-surface scene, embedded.
pub const DEFAULT_SURFACE: &str = include_str!("../../scenes/surface.toml");
/// The paper's micro-switch scene (Fig 4), embedded: the main job.
pub const DEFAULT_SWITCH: &str = include_str!("../../scenes/switch.toml");

/// A scene kind: its file format, its default, its checks.
pub trait Scene: Serialize + DeserializeOwned + Clone {
    /// Which keys it takes.
    const KIND: Kind;
    /// The embedded paper scene.
    const DEFAULT: &'static str;
    /// Checks every value against [`fields::FIELDS`] and the rules between keys, and fills
    /// in resolved defaults; `file` names the source in messages.
    fn validate(&mut self, file: &str) -> Result<(), SceneError>;
    /// The scene's title, if it gives one.
    fn title(&self) -> Option<&str>;
    /// The accuracy mode.
    fn accuracy(&self) -> Accuracy;
}

/// A scene read from a file or the embedded default.
#[derive(Debug, Clone)]
pub struct Loaded<S> {
    /// The file's name in messages (`<default scene>` for the embedded one).
    pub file: String,
    /// The scene, parsed (validate it after applying command-line overrides).
    pub scene: S,
    /// Whether this is the embedded paper scene.
    pub is_paper: bool,
}

impl<S: Scene> Loaded<S> {
    /// The title of plots and tables: the scene's, else the file name.
    pub fn title(&self) -> String {
        self.scene
            .title()
            .map(str::to_string)
            .unwrap_or_else(|| self.file.clone())
    }
}

/// Parses TOML text into a scene, naming `file` in errors.
pub fn parse<S: Scene>(file: &str, text: &str) -> Result<S, SceneError> {
    if text.trim().is_empty() {
        return Err(SceneError::Empty { file: file.into() });
    }
    toml::from_str(text).map_err(|e| SceneError::Parse {
        file: file.into(),
        message: e.to_string().trim_end().to_string(),
    })
}

/// Reads a scene file (or the embedded default when `path` is None), refusing files
/// larger than [`MAX_SCENE_BYTES`] before reading them whole.
pub fn load<S: Scene>(path: Option<&std::path::Path>) -> Result<Loaded<S>, SceneError> {
    let Some(p) = path else {
        return Ok(Loaded {
            file: "<default scene>".into(),
            scene: parse("<default scene>", S::DEFAULT)?,
            is_paper: true,
        });
    };
    let file = p.display().to_string();
    let read = |source| SceneError::Read {
        file: file.clone(),
        source,
    };
    let f = std::fs::File::open(p).map_err(read)?;
    // a bounded read: /dev/zero and other endless sources stop at the limit
    let mut bytes = Vec::new();
    f.take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(read)?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(SceneError::TooLarge {
            file,
            limit: MAX_SCENE_BYTES,
        });
    }
    let text = String::from_utf8(bytes).map_err(|_| SceneError::NotText { file: file.clone() })?;
    Ok(Loaded {
        scene: parse(&file, &text)?,
        file,
        is_paper: false,
    })
}

/// The checks, naming the file.
pub struct Checker<'a> {
    file: &'a str,
}

impl<'a> Checker<'a> {
    /// Checks for `file`.
    pub fn new(file: &'a str) -> Self {
        Self { file }
    }

    /// A field error.
    pub fn fail(
        &self,
        key: &str,
        value: impl Into<String>,
        allowed: impl Into<String>,
    ) -> SceneError {
        SceneError::Field {
            file: self.file.to_string(),
            key: key.to_string(),
            value: value.into(),
            allowed: allowed.into(),
        }
    }

    /// `v` in the domain of `key` from [`fields::FIELDS`].
    pub fn value(&self, key: &str, v: f64) -> Result<f64, SceneError> {
        let f = fields::field(key).unwrap_or_else(|| panic!("{key} is not in fields::FIELDS"));
        if f.domain.contains(v) {
            Ok(v)
        } else {
            Err(self.fail(key, num(v), f.domain.describe()))
        }
    }

    /// An integer in the domain of `key`.
    pub fn count(&self, key: &str, v: usize) -> Result<usize, SceneError> {
        let f = fields::field(key).unwrap_or_else(|| panic!("{key} is not in fields::FIELDS"));
        match f.domain {
            Domain::Count { lo, hi } if (lo..=hi).contains(&v) => Ok(v),
            d => Err(self.fail(key, v.to_string(), d.describe())),
        }
    }

    /// Checks the contact section.
    pub fn contact(&self, c: &Contact) -> Result<(), SceneError> {
        self.value("contact.youngs_modulus", c.youngs_modulus)?;
        self.value("contact.poisson_ratio", c.poisson_ratio)?;
        self.value("contact.yield_stress", c.yield_stress)?;
        self.value("contact.radius", c.radius)?;
        self.value("contact.work_of_adhesion", c.work_of_adhesion)?;
        self.value("contact.z0", c.z0)?;
        let counter_keys = [
            ("contact.counter_youngs_modulus", c.counter_youngs_modulus),
            ("contact.counter_poisson_ratio", c.counter_poisson_ratio),
            ("contact.counter_yield_stress", c.counter_yield_stress),
        ];
        match c.counter {
            CounterKind::Material => {
                for (key, v) in &counter_keys[..2] {
                    let v = v.ok_or_else(|| {
                        self.fail(key, "missing", "given when counter = \"material\"")
                    })?;
                    self.value(key, v)?;
                }
                if let Some(v) = c.counter_yield_stress {
                    self.value("contact.counter_yield_stress", v)?;
                }
            }
            _ => {
                for (key, v) in counter_keys {
                    if let Some(v) = v {
                        return Err(self.fail(key, num(v), "absent unless counter = \"material\""));
                    }
                }
            }
        }
        if c.yield_modulus.is_none() {
            return Err(SceneError::Missing {
                file: self.file.to_string(),
                key: "contact.yield_modulus".into(),
                explanation: "the modulus of the yield onset, eq 1, moves the paper switch's pull-out by about 100x, so a scene must say which it uses: \"as_printed\" (E of the film, as the paper prints eq 1; its scenes use this and it reproduces Fig 4's changing curves) or \"composite\" (E* of the pair, the Kogut-Etsion convention that makes eq 3 the Hertz force at delta_CP); see docs/theory.md section 2.1".into(),
            });
        }
        if c.plasticity_law == PlasticityKind::EtsionKadin
            && !c.yield_stress.is_finite()
            && !c.counter_yield_stress.is_some_and(f64::is_finite)
        {
            return Err(self.fail(
                "contact.yield_stress",
                num(c.yield_stress),
                "finite with plasticity_law = \"etsion_kadin\" (use \"elastic\" for no yield)",
            ));
        }
        let fit =
            asperity_plastic::EffectiveRadiusFit::new(c.effective_radius.c1, c.effective_radius.c2);
        if let Err(asperity_plastic::PlasticError::Fit {
            field,
            value,
            allowed,
        }) = fit
        {
            let key = format!("contact.effective_radius.{field}");
            return Err(self.fail(&key, num(value), allowed));
        }
        Ok(())
    }

    /// Checks the surface section.
    pub fn surface(&self, s: &Surface) -> Result<(), SceneError> {
        self.value("surface.sigma_s", s.sigma_s)?;
        self.value("surface.asperity_density", s.asperity_density)?;
        Ok(())
    }

    /// Checks the switch section and its drive.
    pub fn switch(&self, s: &SwitchGeometry) -> Result<(), SceneError> {
        self.value("switch.d0", s.d0)?;
        self.value("switch.t_d", s.t_d)?;
        self.value("switch.epsilon_r", s.epsilon_r)?;
        self.value("switch.epsilon_0", s.epsilon_0)?;
        self.value("switch.film_thickness", s.film_thickness)?;
        if let Some(e) = s.film_youngs_modulus {
            self.value("switch.film_youngs_modulus", e)?;
        }
        self.value("switch.contact_area_fraction", s.contact_area_fraction)?;
        match (s.impact_energy, s.k_s) {
            (Some(e), None) => {
                self.value("switch.impact_energy", e)?;
                if let Some(v) = s.voltage {
                    return Err(self.fail(
                        "switch.voltage",
                        num(v),
                        "absent when impact_energy is given (K_s is derived at U = V_PI; give k_s and voltage instead of impact_energy to set the voltage)",
                    ));
                }
            }
            (None, Some(k)) => {
                self.value("switch.k_s", k)?;
                if let Some(v) = s.voltage {
                    self.value("switch.voltage", v)?;
                }
            }
            (Some(e), Some(_)) => {
                return Err(self.fail(
                    "switch.impact_energy",
                    num(e),
                    "given alone (K_s derived at U = V_PI), or replaced by k_s with an optional voltage (E_I derived), not both",
                ))
            }
            (None, None) => {
                return Err(SceneError::Missing {
                    file: self.file.to_string(),
                    key: "switch.impact_energy".into(),
                    explanation: "give impact_energy (J/m^2; K_s is derived so that release at U = V_PI gives it), or k_s (Pa/m) with an optional voltage (V, default V_PI; E_I is derived)".into(),
                })
            }
        }
        Ok(())
    }
}

impl Scene for AsperityScene {
    const KIND: Kind = Kind::Asperity;
    const DEFAULT: &'static str = DEFAULT_ASPERITY;
    fn validate(&mut self, file: &str) -> Result<(), SceneError> {
        let c = Checker::new(file);
        c.contact(&self.contact)?;
        if self.delta_max.is_empty() {
            return Err(c.fail("delta_max", "[]", "a non-empty list"));
        }
        let hi = 1e3 * self.contact.radius;
        for (i, &d) in self.delta_max.iter().enumerate() {
            if !(d.is_finite() && d > 0.0 && d <= hi) {
                return Err(c.fail(
                    &format!("delta_max[{i}]"),
                    num(d),
                    format!("finite and in (0, {}] (1e3 radius)", num(hi)),
                ));
            }
        }
        c.count("points", self.points)?;
        if self.points < 2 {
            return Err(c.fail(
                "points",
                self.points.to_string(),
                "at least 2 for the asperity curves",
            ));
        }
        Ok(())
    }
    fn title(&self) -> Option<&str> {
        self.title.as_deref()
    }
    fn accuracy(&self) -> Accuracy {
        self.accuracy
    }
}

impl Scene for SurfaceScene {
    const KIND: Kind = Kind::Surface;
    const DEFAULT: &'static str = DEFAULT_SURFACE;
    fn validate(&mut self, file: &str) -> Result<(), SceneError> {
        let c = Checker::new(file);
        c.contact(&self.contact)?;
        c.surface(&self.surface)?;
        let lim = 20.0 * self.surface.sigma_s;
        for (key, v) in [("d_start", self.d_start), ("unload_from", self.unload_from)] {
            if let Some(d) = v {
                if !(d.is_finite() && d.abs() <= lim) {
                    return Err(c.fail(
                        key,
                        format!("{} m", num(d)),
                        format!(
                            "finite and within 20 sigma_s = {} m of the mean plane",
                            num(lim)
                        ),
                    ));
                }
            }
        }
        c.count("points", self.points)?;
        if self.points < 2 {
            return Err(c.fail(
                "points",
                self.points.to_string(),
                "at least 2 for the surface curves",
            ));
        }
        Ok(())
    }
    fn title(&self) -> Option<&str> {
        self.title.as_deref()
    }
    fn accuracy(&self) -> Accuracy {
        self.accuracy
    }
}

impl Scene for SwitchScene {
    const KIND: Kind = Kind::Switch;
    const DEFAULT: &'static str = DEFAULT_SWITCH;
    fn validate(&mut self, file: &str) -> Result<(), SceneError> {
        let c = Checker::new(file);
        c.contact(&self.contact)?;
        c.surface(&self.surface)?;
        c.switch(&self.switch)?;
        c.count("cycles", self.cycles)?;
        c.value("accommodation_tolerance", self.accommodation_tolerance)?;
        c.count("points", self.points)?;
        // every cycle writes its curves and the whole report is held for rendering: bound
        // it up front rather than fail on memory after the computation
        let curve_points = self.points as f64 * self.cycles as f64;
        if curve_points > MAX_CURVE_POINTS {
            return Err(c.fail(
                "points",
                self.points.to_string(),
                format!(
                    "at most {} with cycles = {}: points x cycles = {} curve points exceeds {} (about 1 GB of output); lower points or cycles (points = 0 keeps the pull-out and writes no curves)",
                    num((MAX_CURVE_POINTS / self.cycles as f64).floor()),
                    self.cycles,
                    num(curve_points),
                    num(MAX_CURVE_POINTS)
                ),
            ));
        }
        self.switch
            .film_youngs_modulus
            .get_or_insert(self.contact.youngs_modulus);
        Ok(())
    }
    fn title(&self) -> Option<&str> {
        self.title.as_deref()
    }
    fn accuracy(&self) -> Accuracy {
        self.accuracy
    }
}

/// The most curve points (points x cycles) a switch run may write.
pub const MAX_CURVE_POINTS: f64 = 1e7;

/// A scene with `key` (`section.key`, a numeric key of [`fields::FIELDS`]) set to `value`:
/// the TOML tree is edited and read back, so every check of the scene applies.
pub fn with_field<S: Scene>(scene: &S, key: &str, value: f64) -> Result<S, SceneError> {
    let mut tree = toml::Value::try_from(scene).map_err(|e| SceneError::Parse {
        file: "<scene>".into(),
        message: e.to_string(),
    })?;
    let mut node = &mut tree;
    let parts: Vec<&str> = key.split('.').collect();
    for part in &parts[..parts.len() - 1] {
        node = node
            .as_table_mut()
            .and_then(|t| t.get_mut(*part))
            .ok_or_else(|| SceneError::Parse {
                file: "<scene>".into(),
                message: format!("no section `{part}` for `{key}`"),
            })?;
    }
    let last = parts[parts.len() - 1];
    let table = node.as_table_mut().ok_or_else(|| SceneError::Parse {
        file: "<scene>".into(),
        message: format!("`{key}` is not in a section"),
    })?;
    let v = match fields::field(key).map(|f| f.domain) {
        Some(Domain::Count { .. }) => {
            if value.fract() != 0.0 || value < 0.0 || value > i64::MAX as f64 {
                return Err(SceneError::Field {
                    file: "<scene>".into(),
                    key: key.into(),
                    value: num(value),
                    allowed: "an integer".into(),
                });
            }
            toml::Value::Integer(value as i64)
        }
        _ => toml::Value::Float(value),
    };
    table.insert(last.to_string(), v);
    let text = toml::to_string(&tree).map_err(|e| SceneError::Parse {
        file: "<scene>".into(),
        message: e.to_string(),
    })?;
    parse("<scene>", &text)
}
