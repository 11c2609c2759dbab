//! Validated scenes: every value checked once, against the key registry
//! ([`crate::keys::KEYS`]) and the law registry ([`crate::laws::LawRegistry`]), the rules
//! between keys applied, the laws built. A spec holds typed values only: what a model
//! needs, with no `Option` that validation has already decided.
//!
//! ```
//! use stiction_model::{keys::Kind, laws::LawRegistry, scene::Scene, spec::SwitchSpec};
//! let spec = SwitchSpec::new(&Scene::paper(Kind::Switch), &LawRegistry::builtin())?;
//! assert_eq!(spec.cycles(), 10);
//! assert_eq!(spec.contact().plasticity().name(), "etsion_kadin");
//! # Ok::<(), stiction_model::ModelError>(())
//! ```
//!
//! A spec is read-only once validated: its fields are private to this crate and read
//! through getters of the same names. A setting is changed by validating the scene again,
//! directly (edit the [`Scene`], call [`SwitchSpec::new`]) or through the `with_*` methods
//! ([`SwitchSpec::with_accuracy`], [`SwitchSpec::with_values`], ...), so that every rule
//! and the curve budget ([`MAX_CURVE_POINTS`]) hold and the echo states what runs:
//!
//! ```
//! use stiction_model::{keys::Kind, laws::LawRegistry, scene::Scene, spec::SwitchSpec};
//! use stiction_model::Accuracy;
//! let spec = SwitchSpec::new(&Scene::paper(Kind::Switch), &LawRegistry::builtin())?;
//! let fast = spec.with_accuracy(Accuracy::Fast)?;
//! assert_eq!(fast.common().accuracy(), Accuracy::Fast);
//! assert_eq!(fast.common().echo()["accuracy"], "fast");
//! // the curve budget holds for a changed setting as for a scene's own
//! assert!(spec.with_points(2_000_000).is_err());
//! # Ok::<(), stiction_model::ModelError>(())
//! ```
//!
//! A field cannot be assigned from outside the crate:
//!
//! ```compile_fail
//! use stiction_model::{keys::Kind, laws::LawRegistry, scene::Scene, spec::SwitchSpec};
//! use stiction_model::Accuracy;
//! let mut spec = SwitchSpec::new(&Scene::paper(Kind::Switch), &LawRegistry::builtin()).unwrap();
//! spec.common.accuracy = Accuracy::Fast; // error[E0616]: field `common` is private
//! ```
//!
//! ```compile_fail
//! use stiction_model::{keys::Kind, laws::LawRegistry, scene::Scene, spec::SwitchSpec};
//! let mut spec = SwitchSpec::new(&Scene::paper(Kind::Switch), &LawRegistry::builtin()).unwrap();
//! spec.cycles = 20; // error[E0616]: field `cycles` is private
//! ```

use crate::accuracy::Accuracy;
use crate::error::{ModelError, SceneError};
use crate::keys::{self, num, Default, Domain, Key, Kind};
use crate::laws::{
    self, DynAdhesion, DynPlasticity, LawContext, LawParams, LawRegistry, Param, ParamValue,
};
use crate::scene::Scene;
use asperity_plastic::{Elastic, ElastoPlasticAsperity, PlasticError};
pub use asperity_plastic::{Reload, YieldModulus};
use contact_core::{Categorized, Category, Material, MaterialProps, Pair};
use std::collections::BTreeSet;
use std::sync::Arc;

/// The most curve points a run may write (points x cycles of a switch, 2 x points x cases
/// of an asperity): about 1 GB of output.
pub const MAX_CURVE_POINTS: f64 = 1e7;

/// The counter-surface of a contact.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Counter {
    /// A rigid flat.
    Rigid,
    /// The same film (two identical surfaces).
    Same,
    /// Another material.
    Material {
        /// Its E (Pa).
        youngs_modulus: f64,
        /// Its nu.
        poisson_ratio: f64,
        /// Its S_Y (Pa; infinite: never yields).
        yield_stress: f64,
    },
}

impl Counter {
    /// The scene spelling.
    pub fn as_str(&self) -> &'static str {
        match self {
            Counter::Rigid => "rigid",
            Counter::Same => "same",
            Counter::Material { .. } => "material",
        }
    }
}

/// A law chosen by name, with its parameters and the law built from them.
#[derive(Clone)]
pub struct Chosen<L> {
    /// The registered name.
    pub(crate) name: String,
    /// Its validated parameters.
    pub(crate) params: LawParams,
    /// The law.
    pub(crate) law: L,
}

impl<L> std::fmt::Debug for Chosen<L> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Chosen")
            .field("name", &self.name)
            .field("params", &self.params)
            .finish()
    }
}

/// The asperity every model uses: any registered plasticity law with any registered
/// adhesion law.
pub type Asperity = ElastoPlasticAsperity<DynPlasticity, DynAdhesion>;
/// The rough surface every model uses.
pub type RoughSurface = gw_surface::GreenwoodWilliamson<Asperity>;

/// The contact section: the pair, its constants, the modelling choices and the laws.
#[derive(Debug, Clone)]
pub struct ContactSpec {
    /// E of the asperity-carrying film (Pa).
    pub(crate) youngs_modulus: f64,
    /// Its nu.
    pub(crate) poisson_ratio: f64,
    /// Its S_Y (Pa; infinite: never yields).
    pub(crate) yield_stress: f64,
    /// Asperity tip radius R (m).
    pub(crate) radius: f64,
    /// Work of adhesion w (J/m^2).
    pub(crate) work_of_adhesion: f64,
    /// Dugdale range z0 (m).
    pub(crate) z0: f64,
    /// The counter-surface.
    pub(crate) counter: Counter,
    /// The reading of eq 1.
    pub(crate) yield_modulus: YieldModulus,
    /// The reload rule.
    pub(crate) reload: Reload,
    /// The films' conduction (resistivity, mean free path), if given.
    pub(crate) conduction: Option<crate::ohmic::Conduction>,
    /// The adhesion law.
    pub(crate) adhesion: Chosen<DynAdhesion>,
    /// The plasticity law.
    pub(crate) plasticity: Chosen<DynPlasticity>,
    /// The pair (E*, K, the radius), built once.
    pub(crate) pair: Pair,
}

impl ContactSpec {
    /// The asperity of the scene's laws (with its reload rule).
    pub fn asperity(&self) -> Asperity {
        self.asperity_with(self.adhesion.law.clone())
    }

    /// [`Self::asperity`] with another form of the adhesion law (its cheaper form within
    /// a mode's force tolerance, `AdhesionLaw::within`).
    pub fn asperity_with(&self, adhesion: DynAdhesion) -> Asperity {
        ElastoPlasticAsperity::new(self.plasticity.law.clone(), adhesion).with_reload(self.reload)
    }

    /// The same asperity with a plasticity law that never yields (the elastic comparison).
    pub fn elastic_asperity(&self) -> Asperity {
        self.elastic_asperity_with(self.adhesion.law.clone())
    }

    /// [`Self::elastic_asperity`] with another form of the adhesion law.
    pub fn elastic_asperity_with(&self, adhesion: DynAdhesion) -> Asperity {
        let elastic: DynPlasticity =
            Arc::new(Elastic::new(self.radius).expect("a validated radius is positive"));
        ElastoPlasticAsperity::new(elastic, adhesion)
    }

    /// The smaller yield stress of the two bodies (Pa; infinite if neither yields).
    pub fn weakest_yield_stress(&self) -> f64 {
        match self.counter {
            Counter::Material { yield_stress, .. } => self.yield_stress.min(yield_stress),
            _ => self.yield_stress,
        }
    }

    /// Dugdale stress sigma0 = w/z0 (Pa): the strength of the interface.
    pub fn dugdale_stress(&self) -> f64 {
        self.work_of_adhesion / self.z0
    }

    /// Maugis' transition parameter lambda at the initial radius (eq 6).
    pub fn lambda(&self) -> f64 {
        maugis_kim::Scales::lambda(self.pair.k(), self.work_of_adhesion, self.z0, self.radius)
    }
}

/// The roughness of the equivalent surface (eq 14).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughnessSpec {
    /// sigma_s (m).
    pub(crate) sigma_s: f64,
    /// N (1/m^2).
    pub(crate) asperity_density: f64,
}

/// How the switch is driven: which of E_I, K_s, U the scene gives.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Drive {
    /// E_I given (J/m^2); K_s derived so that release at U = V_PI gives it.
    ImpactEnergy(f64),
    /// K_s given (Pa/m) with the step voltage U (V; None: V_PI); E_I derived.
    Spring {
        /// K_s (Pa/m).
        k_s: f64,
        /// U (V), if given.
        voltage: Option<f64>,
    },
}

/// Table 2 and the drive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwitchGeometrySpec {
    /// Initial gap d0 (m).
    pub(crate) d0: f64,
    /// The air gap at which the contact (dimples or a bump) touches (m; 0: the electrode
    /// lands on the dielectric).
    pub(crate) dimple_height: f64,
    /// Dielectric thickness t_d (m).
    pub(crate) t_d: f64,
    /// Relative permittivity.
    pub(crate) epsilon_r: f64,
    /// Vacuum permittivity (F/m).
    pub(crate) epsilon_0: f64,
    /// Film thickness t_s of eq 17 (m).
    pub(crate) film_thickness: f64,
    /// Film modulus of eq 17 (Pa).
    pub(crate) film_youngs_modulus: f64,
    /// The drive.
    pub(crate) drive: Drive,
    /// Fraction phi of the electrode in contact.
    pub(crate) contact_area_fraction: f64,
    /// The electrode's area (m^2), if given (needed for forces and resistances).
    pub(crate) electrode_area: Option<f64>,
    /// The spring constant (N/m), if the drive was given that way (K_s = k / area).
    pub(crate) spring_constant: Option<f64>,
    /// The voltage holding the switch shut (V), if given (default: the actuation voltage).
    pub(crate) hold_voltage: Option<f64>,
    /// The force holding the switch shut on its contacts (N), if given instead.
    pub(crate) hold_force: Option<f64>,
}

/// When a switch run computes the contact state (rest, area, spots, resistance).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ContactStates {
    /// After every cycle.
    EveryCycle,
    /// After the last cycle only (design points).
    LastCycle,
    /// Never.
    None,
}

impl ContactStates {
    /// The scene word: `every_cycle`, `last_cycle` or `none`.
    pub fn as_str(self) -> &'static str {
        match self {
            ContactStates::EveryCycle => "every_cycle",
            ContactStates::LastCycle => "last_cycle",
            ContactStates::None => "none",
        }
    }
}

/// What every validated scene carries: its source, title and accuracy mode.
#[derive(Debug, Clone)]
pub struct Common {
    /// The scene it was made from (for echoes and design variations).
    pub(crate) scene: Scene,
    /// The title of plots and tables.
    pub(crate) title: String,
    /// Accuracy mode.
    pub(crate) accuracy: Accuracy,
    /// Points per written curve.
    pub(crate) points: usize,
    /// Every key with the value it resolved to (defaults filled), for echoes.
    pub(crate) resolved: toml::Table,
    /// Notes of the validation for the front ends to show with a run's warnings (a key
    /// the scene gives overriding the value its `surface.topography` gives:
    /// [`crate::topography::TOPOGRAPHY_VALUE_OVERRIDDEN`]).
    pub(crate) notes: Vec<crate::guards::Warning>,
    /// The law registry the scene was validated against, to validate it again when a
    /// setting changes (the `with_*` methods of the specs).
    pub(crate) registry: Arc<LawRegistry>,
}

impl Common {
    /// The resolved scene as JSON (non-finite numbers as their names, `"inf"`).
    pub fn echo(&self) -> serde_json::Value {
        toml_to_json(&toml::Value::Table(self.resolved.clone()))
    }
}

/// A validated asperity scene.
#[derive(Debug, Clone)]
pub struct AsperitySpec {
    /// Source, title, accuracy, points.
    pub(crate) common: Common,
    /// The contact.
    pub(crate) contact: ContactSpec,
    /// The maximum interferences (m).
    pub(crate) delta_max: Vec<f64>,
}

/// A validated surface scene.
#[derive(Debug, Clone)]
pub struct SurfaceSpec {
    /// Source, title, accuracy, points.
    pub(crate) common: Common,
    /// The contact.
    pub(crate) contact: ContactSpec,
    /// The roughness.
    pub(crate) roughness: RoughnessSpec,
    /// Smallest separation of the loading curve (m), if given.
    pub(crate) d_start: Option<f64>,
    /// Load to this separation and unload (m), if given.
    pub(crate) unload_from: Option<f64>,
}

/// A validated switch scene.
#[derive(Debug, Clone)]
pub struct SwitchSpec {
    /// Source, title, accuracy, points.
    pub(crate) common: Common,
    /// The contact.
    pub(crate) contact: ContactSpec,
    /// The roughness.
    pub(crate) roughness: RoughnessSpec,
    /// The switch.
    pub(crate) switch: SwitchGeometrySpec,
    /// Cycles (the cap with `until_accommodated`).
    pub(crate) cycles: usize,
    /// Stop once accommodated.
    pub(crate) until_accommodated: bool,
    /// Accommodation tolerance.
    pub(crate) accommodation_tolerance: f64,
    /// Run the elastic comparison.
    pub(crate) elastic_comparison: bool,
    /// When the contact state is computed.
    pub(crate) contact_states: ContactStates,
    /// The model-form check (`model_form` and its pins).
    pub(crate) model_form: crate::model_form::ModelFormSpec,
    /// The switch in time (`[dynamics]`), if the scene asks for it.
    pub(crate) dynamics: Option<DynamicsSpec>,
}

/// The `[dynamics]` section: the electrode's mass and the gas under it (theory 13).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicsSpec {
    /// m'' (kg/m^2), if given.
    pub(crate) areal_mass: Option<f64>,
    /// f0 (Hz), if given instead.
    pub(crate) resonance_frequency: Option<f64>,
    /// The gas film, when gas_pressure > 0.
    pub(crate) gas: Option<GasSpec>,
    /// Bounces allowed per closure.
    pub(crate) max_bounces: usize,
}

impl DynamicsSpec {
    /// m'' (kg/m^2) for a spring K_s (Pa/m): given, or K_s/(2 pi f0)^2.
    #[must_use]
    pub fn areal_mass_for(&self, k_s: f64) -> f64 {
        match (self.areal_mass, self.resonance_frequency) {
            (Some(m), _) => m,
            (None, Some(f)) => k_s / (2.0 * std::f64::consts::PI * f).powi(2),
            (None, None) => f64::NAN,
        }
    }
}

/// The gas under the plate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GasSpec {
    /// Pressure (Pa).
    pub(crate) pressure: f64,
    /// Viscosity (Pa s).
    pub(crate) viscosity: f64,
    /// Mean free path at 101325 Pa (m).
    pub(crate) mean_free_path: f64,
    /// Plate width (m).
    pub(crate) width: f64,
    /// Plate length (m).
    pub(crate) length: f64,
}

// The fields of the validated specs are `pub(crate)`: outside this crate a spec is read
// through these getters and changed only by validating a scene again (`SwitchSpec::new`,
// or the `with_*` methods, which do), so the curve budget and the echo always hold.

impl<L> Chosen<L> {
    /// The registered name.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Its validated parameters.
    #[must_use]
    pub fn params(&self) -> &LawParams {
        &self.params
    }

    /// The law.
    #[must_use]
    pub fn law(&self) -> &L {
        &self.law
    }
}

impl ContactSpec {
    /// E of the asperity-carrying film (Pa).
    #[must_use]
    pub fn youngs_modulus(&self) -> f64 {
        self.youngs_modulus
    }

    /// Its nu.
    #[must_use]
    pub fn poisson_ratio(&self) -> f64 {
        self.poisson_ratio
    }

    /// Its S_Y (Pa; infinite: never yields).
    #[must_use]
    pub fn yield_stress(&self) -> f64 {
        self.yield_stress
    }

    /// Asperity tip radius R (m).
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Work of adhesion w (J/m^2).
    #[must_use]
    pub fn work_of_adhesion(&self) -> f64 {
        self.work_of_adhesion
    }

    /// Dugdale range z0 (m).
    #[must_use]
    pub fn z0(&self) -> f64 {
        self.z0
    }

    /// The counter-surface.
    #[must_use]
    pub fn counter(&self) -> Counter {
        self.counter
    }

    /// The reading of eq 1.
    #[must_use]
    pub fn yield_modulus(&self) -> YieldModulus {
        self.yield_modulus
    }

    /// The reload rule.
    #[must_use]
    pub fn reload(&self) -> Reload {
        self.reload
    }

    /// The films' conduction (resistivity, mean free path), if given.
    #[must_use]
    pub fn conduction(&self) -> Option<crate::ohmic::Conduction> {
        self.conduction
    }

    /// The adhesion law.
    #[must_use]
    pub fn adhesion(&self) -> &Chosen<DynAdhesion> {
        &self.adhesion
    }

    /// The plasticity law.
    #[must_use]
    pub fn plasticity(&self) -> &Chosen<DynPlasticity> {
        &self.plasticity
    }

    /// The pair (E*, K, the radius), built once.
    #[must_use]
    pub fn pair(&self) -> Pair {
        self.pair
    }
}

impl RoughnessSpec {
    /// sigma_s (m).
    #[must_use]
    pub fn sigma_s(&self) -> f64 {
        self.sigma_s
    }

    /// N (1/m^2).
    #[must_use]
    pub fn asperity_density(&self) -> f64 {
        self.asperity_density
    }
}

impl SwitchGeometrySpec {
    /// Initial gap d0 (m).
    #[must_use]
    pub fn d0(&self) -> f64 {
        self.d0
    }

    /// The air gap at which the contact (dimples or a bump) touches (m; 0: the electrode
    /// lands on the dielectric).
    #[must_use]
    pub fn dimple_height(&self) -> f64 {
        self.dimple_height
    }

    /// Dielectric thickness t_d (m).
    #[must_use]
    pub fn t_d(&self) -> f64 {
        self.t_d
    }

    /// Relative permittivity.
    #[must_use]
    pub fn epsilon_r(&self) -> f64 {
        self.epsilon_r
    }

    /// Vacuum permittivity (F/m).
    #[must_use]
    pub fn epsilon_0(&self) -> f64 {
        self.epsilon_0
    }

    /// Film thickness t_s of eq 17 (m).
    #[must_use]
    pub fn film_thickness(&self) -> f64 {
        self.film_thickness
    }

    /// Film modulus of eq 17 (Pa).
    #[must_use]
    pub fn film_youngs_modulus(&self) -> f64 {
        self.film_youngs_modulus
    }

    /// The drive.
    #[must_use]
    pub fn drive(&self) -> Drive {
        self.drive
    }

    /// Fraction phi of the electrode in contact.
    #[must_use]
    pub fn contact_area_fraction(&self) -> f64 {
        self.contact_area_fraction
    }

    /// The electrode's area (m^2), if given (needed for forces and resistances).
    #[must_use]
    pub fn electrode_area(&self) -> Option<f64> {
        self.electrode_area
    }

    /// The spring constant (N/m), if the drive was given that way (K_s = k / area).
    #[must_use]
    pub fn spring_constant(&self) -> Option<f64> {
        self.spring_constant
    }

    /// The voltage holding the switch shut (V), if given (default: the actuation voltage).
    #[must_use]
    pub fn hold_voltage(&self) -> Option<f64> {
        self.hold_voltage
    }

    /// The force holding the switch shut on its contacts (N), if given instead.
    #[must_use]
    pub fn hold_force(&self) -> Option<f64> {
        self.hold_force
    }
}

impl Common {
    /// The scene it was made from (for echoes and design variations).
    #[must_use]
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The title of plots and tables.
    #[must_use]
    pub fn title(&self) -> &str {
        &self.title
    }

    /// Accuracy mode.
    #[must_use]
    pub fn accuracy(&self) -> Accuracy {
        self.accuracy
    }

    /// Points per written curve.
    #[must_use]
    pub fn points(&self) -> usize {
        self.points
    }

    /// Every key with the value it resolved to (defaults filled), for echoes.
    #[must_use]
    pub fn resolved(&self) -> &toml::Table {
        &self.resolved
    }

    /// Notes of the validation for the front ends to show with a run's warnings (a key
    /// the scene gives overriding the value its `surface.topography` gives:
    /// [`crate::topography::TOPOGRAPHY_VALUE_OVERRIDDEN`]).
    #[must_use]
    pub fn notes(&self) -> &[crate::guards::Warning] {
        &self.notes
    }
}

/// The getters every kind of spec shares (`common()`, `contact()`), and `roughness()` for
/// the kinds with a rough surface.
macro_rules! shared_getters {
    () => {
        /// Source, title, accuracy, points.
        #[must_use]
        pub fn common(&self) -> &Common {
            &self.common
        }

        /// The contact.
        #[must_use]
        pub fn contact(&self) -> &ContactSpec {
            &self.contact
        }
    };
    (rough) => {
        shared_getters!();

        /// The roughness.
        #[must_use]
        pub fn roughness(&self) -> RoughnessSpec {
            self.roughness
        }
    };
}

impl AsperitySpec {
    shared_getters!();

    /// The maximum interferences (m).
    #[must_use]
    pub fn delta_max(&self) -> &[f64] {
        &self.delta_max
    }
}

impl SurfaceSpec {
    shared_getters!(rough);

    /// Smallest separation of the loading curve (m), if given.
    #[must_use]
    pub fn d_start(&self) -> Option<f64> {
        self.d_start
    }

    /// Load to this separation and unload (m), if given.
    #[must_use]
    pub fn unload_from(&self) -> Option<f64> {
        self.unload_from
    }
}

impl SwitchSpec {
    shared_getters!(rough);

    /// The switch.
    #[must_use]
    pub fn switch(&self) -> &SwitchGeometrySpec {
        &self.switch
    }

    /// Cycles (the cap with `until_accommodated`).
    #[must_use]
    pub fn cycles(&self) -> usize {
        self.cycles
    }

    /// Stop once accommodated.
    #[must_use]
    pub fn until_accommodated(&self) -> bool {
        self.until_accommodated
    }

    /// Accommodation tolerance.
    #[must_use]
    pub fn accommodation_tolerance(&self) -> f64 {
        self.accommodation_tolerance
    }

    /// Run the elastic comparison.
    #[must_use]
    pub fn elastic_comparison(&self) -> bool {
        self.elastic_comparison
    }

    /// When the contact state is computed.
    #[must_use]
    pub fn contact_states(&self) -> ContactStates {
        self.contact_states
    }

    /// The model-form check (`model_form` and its pins).
    #[must_use]
    pub fn model_form(&self) -> &crate::model_form::ModelFormSpec {
        &self.model_form
    }

    /// The switch in time (`[dynamics]`), if the scene asks for it.
    #[must_use]
    pub fn dynamics(&self) -> Option<DynamicsSpec> {
        self.dynamics
    }
}

impl DynamicsSpec {
    /// m'' (kg/m^2), if given.
    #[must_use]
    pub fn areal_mass(&self) -> Option<f64> {
        self.areal_mass
    }

    /// f0 (Hz), if given instead.
    #[must_use]
    pub fn resonance_frequency(&self) -> Option<f64> {
        self.resonance_frequency
    }

    /// The gas film, when gas_pressure > 0.
    #[must_use]
    pub fn gas(&self) -> Option<GasSpec> {
        self.gas
    }

    /// Bounces allowed per closure.
    #[must_use]
    pub fn max_bounces(&self) -> usize {
        self.max_bounces
    }
}

impl GasSpec {
    /// Pressure (Pa).
    #[must_use]
    pub fn pressure(&self) -> f64 {
        self.pressure
    }

    /// Viscosity (Pa s).
    #[must_use]
    pub fn viscosity(&self) -> f64 {
        self.viscosity
    }

    /// Mean free path at 101325 Pa (m).
    #[must_use]
    pub fn mean_free_path(&self) -> f64 {
        self.mean_free_path
    }

    /// Plate width (m).
    #[must_use]
    pub fn width(&self) -> f64 {
        self.width
    }

    /// Plate length (m).
    #[must_use]
    pub fn length(&self) -> f64 {
        self.length
    }
}

/// Any validated scene.
// a spec is built once a run and moved rarely: the switch's size is no cost worth a box
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum Spec {
    /// One asperity.
    Asperity(AsperitySpec),
    /// The rough surface.
    Surface(SurfaceSpec),
    /// The switch.
    Switch(SwitchSpec),
}

impl Spec {
    /// Validates `scene` as the kind it says or implies ([`Scene::kind`]).
    pub fn new(scene: &Scene, registry: &LawRegistry) -> Result<Self, ModelError> {
        Ok(match scene.kind()? {
            Kind::Asperity => Spec::Asperity(AsperitySpec::new(scene, registry)?),
            Kind::Surface => Spec::Surface(SurfaceSpec::new(scene, registry)?),
            Kind::Switch => Spec::Switch(SwitchSpec::new(scene, registry)?),
        })
    }

    /// Source, title, accuracy, points.
    pub fn common(&self) -> &Common {
        match self {
            Spec::Asperity(s) => &s.common,
            Spec::Surface(s) => &s.common,
            Spec::Switch(s) => &s.common,
        }
    }

    /// The contact section.
    pub fn contact(&self) -> &ContactSpec {
        match self {
            Spec::Asperity(s) => &s.contact,
            Spec::Surface(s) => &s.contact,
            Spec::Switch(s) => &s.contact,
        }
    }
}

/// A spec changed the one way a spec changes: its scene edited and validated again.
macro_rules! revalidated {
    ($spec:ty) => {
        impl $spec {
            /// This spec's scene with each `(key, value)` set (as [`Scene::set`] sets it),
            /// validated again against the law registry it was validated against: every
            /// rule and the curve budget checked anew, and the echo ([`Common::echo`])
            /// stating the values the new spec runs with. The one way to change a setting
            /// of a validated spec; several keys at once are validated once.
            pub fn with_values(&self, values: &[(&str, toml::Value)]) -> Result<Self, ModelError> {
                let mut scene = self.common.scene.clone();
                for (key, value) in values {
                    scene.set(key, value.clone())?;
                }
                Self::new(&scene, &self.common.registry)
            }

            /// This spec with `key` set to `value`, validated again ([`Self::with_values`]).
            pub fn with_value(&self, key: &str, value: toml::Value) -> Result<Self, ModelError> {
                self.with_values(&[(key, value)])
            }

            /// This spec run in accuracy mode `accuracy`, validated again
            /// ([`Self::with_values`]): its echo states the mode.
            pub fn with_accuracy(&self, accuracy: Accuracy) -> Result<Self, ModelError> {
                self.with_value("accuracy", accuracy_value(accuracy))
            }

            /// This spec writing `points` points per curve, validated again against the
            /// curve budget ([`MAX_CURVE_POINTS`]).
            pub fn with_points(&self, points: usize) -> Result<Self, ModelError> {
                self.with_value("points", count_value(points))
            }
        }
    };
}

revalidated!(AsperitySpec);
revalidated!(SurfaceSpec);
revalidated!(SwitchSpec);

/// The scene value of an accuracy mode (`accuracy = "fast"`).
pub fn accuracy_value(accuracy: Accuracy) -> toml::Value {
    toml::Value::String(accuracy.as_str().into())
}

/// The scene value of a count (`cycles = 20`; beyond `i64::MAX`: the largest, which
/// validation refuses).
pub fn count_value(n: usize) -> toml::Value {
    toml::Value::Integer(i64::try_from(n).unwrap_or(i64::MAX))
}

impl SwitchSpec {
    /// This spec run for `cycles` cycles, validated again ([`Self::with_values`]).
    pub fn with_cycles(&self, cycles: usize) -> Result<Self, ModelError> {
        self.with_value("cycles", count_value(cycles))
    }

    /// This spec computing the contact state `states`, validated again
    /// ([`Self::with_values`]).
    pub fn with_contact_states(&self, states: ContactStates) -> Result<Self, ModelError> {
        self.with_value("contact_state", toml::Value::String(states.as_str().into()))
    }
}

impl Spec {
    /// This spec with each `(key, value)` set, validated again (as the kind's
    /// `with_values`, e.g. [`SwitchSpec::with_values`]).
    pub fn with_values(&self, values: &[(&str, toml::Value)]) -> Result<Self, ModelError> {
        Ok(match self {
            Spec::Asperity(s) => Spec::Asperity(s.with_values(values)?),
            Spec::Surface(s) => Spec::Surface(s.with_values(values)?),
            Spec::Switch(s) => Spec::Switch(s.with_values(values)?),
        })
    }

    /// This spec run in accuracy mode `accuracy`, validated again: its echo states the
    /// mode.
    pub fn with_accuracy(&self, accuracy: Accuracy) -> Result<Self, ModelError> {
        self.with_values(&[("accuracy", accuracy_value(accuracy))])
    }
}

impl Common {
    /// The law registry the scene was validated against (a copy, shared by the specs
    /// made from it), which the `with_*` methods validate a changed scene against.
    #[must_use]
    pub fn registry(&self) -> &LawRegistry {
        &self.registry
    }
}

impl AsperitySpec {
    /// Validates an asperity scene.
    pub fn new(scene: &Scene, registry: &LawRegistry) -> Result<Self, ModelError> {
        let mut r = Reader::new(scene, Kind::Asperity);
        let contact = r.contact(registry)?;
        let key = "delta_max";
        let delta_max = match r.take(key) {
            None => return Err(r.missing(key).into()),
            Some(toml::Value::Array(a)) if !a.is_empty() => {
                let mut out = Vec::with_capacity(a.len());
                for (i, v) in a.iter().enumerate() {
                    let d = as_number(v).unwrap_or(f64::NAN);
                    if !delta_max_within(d, contact.radius) {
                        return Err(r
                            .fail(
                                &format!("{key}[{i}]"),
                                show(v),
                                delta_max_domain(contact.radius),
                            )
                            .into());
                    }
                    out.push(d);
                }
                out
            }
            Some(v) => return Err(r.fail(key, show(&v), "a non-empty list of numbers").into()),
        };
        r.record(
            key,
            toml::Value::Array(delta_max.iter().map(|&d| toml::Value::Float(d)).collect()),
        );
        let common = r.common(2)?;
        // every case writes a loading and an unloading curve, held whole for rendering
        let curve_points = 2.0 * common.points as f64 * delta_max.len() as f64;
        if curve_points > MAX_CURVE_POINTS {
            return Err(r
                .fail(
                    "delta_max",
                    format!("a list of {} interferences", delta_max.len()),
                    format!(
                        "at most {} cases with points = {}: 2 x points x cases = {} curve points exceeds {}",
                        num((MAX_CURVE_POINTS / (2.0 * common.points as f64)).floor()),
                        common.points,
                        num(curve_points),
                        num(MAX_CURVE_POINTS)
                    ),
                )
                .into());
        }
        r.finish()?;
        Ok(Self {
            common: common.with_resolved(r.resolved, registry),
            contact,
            delta_max,
        })
    }
}

impl SurfaceSpec {
    /// Validates a surface scene.
    pub fn new(scene: &Scene, registry: &LawRegistry) -> Result<Self, ModelError> {
        let mut r = Reader::new(scene, Kind::Surface);
        r.topography()?;
        let contact = r.contact(registry)?;
        let roughness = r.roughness()?;
        let lim = 20.0 * roughness.sigma_s;
        let mut ends = [None, None];
        for (i, key) in ["d_start", "unload_from"].into_iter().enumerate() {
            if let Some(d) = r.opt_number(key)? {
                // within 20 sigma_s up to the rounding of the product
                if d.abs() > lim * (1.0 + 4.0 * f64::EPSILON) {
                    return Err(r
                        .fail(
                            key,
                            format!("{} m", num(d)),
                            format!(
                                "finite and within 20 sigma_s = {} m of the mean plane",
                                num(lim)
                            ),
                        )
                        .into());
                }
                ends[i] = Some(d);
            }
        }
        let common = r.common(2)?;
        r.finish()?;
        Ok(Self {
            common: common.with_resolved(r.resolved, registry),
            contact,
            roughness,
            d_start: ends[0],
            unload_from: ends[1],
        })
    }
}

impl SwitchSpec {
    /// Validates a switch scene.
    pub fn new(scene: &Scene, registry: &LawRegistry) -> Result<Self, ModelError> {
        let mut r = Reader::new(scene, Kind::Switch);
        r.topography()?;
        let contact = r.contact(registry)?;
        let roughness = r.roughness()?;
        let switch = r.switch(contact.youngs_modulus)?;
        let cycles = r.count("cycles")?;
        let until_accommodated = r.flag("until_accommodated")?;
        let accommodation_tolerance = r.number("accommodation_tolerance")?;
        let elastic_comparison = r.flag("elastic_comparison")?;
        let contact_states = match r.required_word("contact_state")?.as_str() {
            "last_cycle" => ContactStates::LastCycle,
            "none" => ContactStates::None,
            _ => ContactStates::EveryCycle,
        };
        let model_form = r.model_form(registry)?;
        let dynamics = r.dynamics(&switch)?;
        let common = r.common(0)?;
        // every cycle writes its curves and the whole result is held for rendering: bound
        // it up front rather than fail on memory after the computation
        let curve_points = common.points as f64 * cycles as f64;
        if curve_points > MAX_CURVE_POINTS {
            return Err(r
                .fail(
                    "points",
                    common.points.to_string(),
                    format!(
                        "at most {} with cycles = {}: points x cycles = {} curve points exceeds {} (about 1 GB of output); lower points or cycles (points = 0 keeps the pull-out and writes no curves)",
                        num((MAX_CURVE_POINTS / cycles as f64).floor()),
                        cycles,
                        num(curve_points),
                        num(MAX_CURVE_POINTS)
                    ),
                )
                .into());
        }
        r.finish()?;
        Ok(Self {
            common: common.with_resolved(r.resolved, registry),
            contact,
            roughness,
            switch,
            cycles,
            until_accommodated,
            accommodation_tolerance,
            elastic_comparison,
            contact_states,
            model_form,
            dynamics,
        })
    }
}

impl Common {
    fn with_resolved(mut self, resolved: toml::Table, registry: &LawRegistry) -> Self {
        self.resolved = resolved;
        self.registry = Arc::new(registry.clone());
        self
    }
}

/// Reads a scene's keys against the registries, recording the value each resolved to.
struct Reader<'a> {
    scene: &'a Scene,
    kind: Kind,
    used: BTreeSet<String>,
    resolved: toml::Table,
    /// Values of keys the scene leaves out, derived from its `surface.topography`.
    derived: Vec<(&'static str, f64)>,
    /// Notes for the front ends (`Common::notes`).
    notes: Vec<crate::guards::Warning>,
}

/// The keys of a scene's `surface.topography` analysis, besides the file itself.
const TOPOGRAPHY_OPTIONS: [&str; 8] = [
    "surface.topography_route",
    "surface.topography_cutoff",
    "surface.topography_detrend",
    "surface.topography_spacing",
    "surface.topography_height_unit",
    "surface.topography_undefined",
    "surface.topography_channel",
    "surface.topography_file_format",
];

/// The keys a scene's `surface.topography` sets, unless the scene gives them.
const TOPOGRAPHY_SETS: [&str; 3] = [
    "surface.sigma_s",
    "surface.asperity_density",
    "contact.radius",
];

/// The notes of a surface or switch scene's `surface.topography` (a key the scene gives
/// overriding the map's value, [`crate::topography::TOPOGRAPHY_VALUE_OVERRIDDEN`]), as
/// the spec's [`Common::notes`] holds them: for a front end to show before the spec is
/// made. Empty for other scenes and for a scene whose topography is refused (the spec
/// says why).
pub fn topography_notes(scene: &Scene) -> Vec<crate::guards::Warning> {
    match scene.kind() {
        Ok(kind @ (Kind::Surface | Kind::Switch)) => {
            let mut r = Reader::new(scene, kind);
            match r.topography() {
                Ok(()) => r.notes,
                Err(_) => Vec::new(),
            }
        }
        _ => Vec::new(),
    }
}

/// The deepest maximum interference of an asperity, in tip radii: `delta_max` lies in
/// (0, 1e3 R], in an asperity scene and in every front end's argument of that name.
pub const DELTA_MAX_RADII: f64 = 1e3;

fn delta_max_within(delta_max: f64, radius: f64) -> bool {
    delta_max.is_finite() && delta_max > 0.0 && delta_max <= DELTA_MAX_RADII * radius
}

fn delta_max_domain(radius: f64) -> String {
    format!(
        "finite and in (0, {}] (1e3 radius)",
        num(DELTA_MAX_RADII * radius)
    )
}

/// Checks a maximum interference `delta_max` (m) of an asperity of tip radius `radius`
/// (m) against the domain of the asperity scene's `delta_max`: finite and in
/// (0, 1e3 radius]. The one check of every front end that takes a `delta_max` as an
/// argument (the Python `Asperity`): an argument error named `name` otherwise.
pub fn check_delta_max(name: &str, delta_max: f64, radius: f64) -> Result<(), ModelError> {
    if delta_max_within(delta_max, radius) {
        Ok(())
    } else {
        Err(ModelError::argument(
            name,
            num(delta_max),
            delta_max_domain(radius),
        ))
    }
}

fn as_number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(f) => Some(*f),
        toml::Value::Integer(i) => Some(*i as f64),
        toml::Value::String(s) if s == "inf" => Some(f64::INFINITY),
        _ => None,
    }
}

/// A value as messages show it: numbers in scientific notation, strings quoted, long
/// values cut.
fn show(v: &toml::Value) -> String {
    let s = match v {
        toml::Value::Float(f) => num(*f),
        toml::Value::Integer(i) => i.to_string(),
        other => other.to_string(),
    };
    if s.len() > 80 {
        let cut: String = s.chars().take(60).collect();
        format!("{cut}... ({} characters)", s.len())
    } else {
        s
    }
}

impl<'a> Reader<'a> {
    fn new(scene: &'a Scene, kind: Kind) -> Self {
        Self {
            scene,
            kind,
            used: BTreeSet::new(),
            resolved: toml::Table::new(),
            derived: Vec::new(),
            notes: Vec::new(),
        }
    }

    fn file(&self) -> String {
        self.scene.file().to_string()
    }

    /// The file that gave `key` (of a merged scene: the last to give it).
    fn file_of(&self, key: &str) -> String {
        self.scene
            .file_of(key.split('[').next().unwrap_or(key))
            .to_string()
    }

    fn line(&self, key: &str) -> String {
        self.scene
            .line_of(key)
            .map_or(String::new(), |l| format!(" (line {l})"))
    }

    fn fail(&self, key: &str, value: impl Into<String>, allowed: impl Into<String>) -> SceneError {
        SceneError::Field {
            file: self.file_of(key),
            key: key.to_string(),
            value: value.into(),
            line: self.line(key),
            allowed: allowed.into(),
        }
    }

    fn missing(&self, key: &str) -> SceneError {
        // a required key misspelled: the key as written is what to fix
        if let Some(typo) = self.misspelling_of(key) {
            return SceneError::Unknown {
                file: self.file_of(&typo),
                line: self.line(&typo),
                kind: self.kind.to_string(),
                hint: format!(": did you mean `{key}`?"),
                key: typo,
            };
        }
        // a key or section no scene of this kind takes (a misspelt section such as
        // [switchx], a value where a section belongs) explains the missing key better than
        // the missing key does: it is reported first
        if let Err(unknown) = self.check_table(self.scene.tree(), "", true) {
            return unknown;
        }
        let k = keys::key(key);
        SceneError::Missing {
            file: self.file(),
            key: key.into(),
            explanation: match k {
                Some(k) if k.unit.is_empty() || k.unit == "-" => {
                    format!("required: {}", k.help)
                }
                Some(k) => format!("required: {} ({})", k.help, k.unit),
                None => "required".into(),
            },
        }
    }

    /// A key of the scene in `key`'s section that no scene of this kind takes and that
    /// reads like `key` (as [`Self::finish`] suggests), if any.
    fn misspelling_of(&self, key: &str) -> Option<String> {
        let (section, table) = match key.rsplit_once('.') {
            Some((section, _)) => (section, self.scene.get(section)?.as_table()?),
            None => ("", self.scene.tree()),
        };
        table
            .keys()
            .map(|k| match section {
                "" => k.clone(),
                s => format!("{s}.{k}"),
            })
            .filter(|k| !keys::of(self.kind).any(|f| f.key == k))
            .map(|k| (strsim::jaro_winkler(&k, key), k))
            .filter(|(s, _)| *s > 0.85)
            .max_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, k)| k)
    }

    fn registry_key(&self, key: &str) -> &'static Key {
        keys::key(key)
            .filter(|k| k.in_kind(self.kind))
            .unwrap_or_else(|| panic!("{key} is not a key of a {} scene", self.kind))
    }

    /// The value of `key`, marking it read.
    fn take(&mut self, key: &str) -> Option<toml::Value> {
        self.used.insert(key.to_string());
        self.scene.get(key).cloned()
    }

    /// Records the value `key` resolved to.
    fn record(&mut self, key: &str, v: toml::Value) {
        let parts: Vec<&str> = key.split('.').collect();
        let mut node = &mut self.resolved;
        for part in &parts[..parts.len() - 1] {
            let e = node
                .entry(part.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            node = match e {
                toml::Value::Table(t) => t,
                _ => return,
            };
        }
        node.insert(parts[parts.len() - 1].to_string(), v);
    }

    /// A number of the registry: given, or its default; in its domain.
    fn number(&mut self, key: &str) -> Result<f64, SceneError> {
        match self.opt_number(key)? {
            Some(v) => Ok(v),
            None => Err(self.missing(key)),
        }
    }

    /// A number that may be absent (None when absent without a default).
    fn opt_number(&mut self, key: &str) -> Result<Option<f64>, SceneError> {
        let k = self.registry_key(key);
        let v = match self.take(key) {
            Some(v) => match as_number(&v) {
                Some(x) => x,
                None => {
                    return Err(self.fail(
                        key,
                        show(&v),
                        format!("a number, {}", k.domain.describe()),
                    ))
                }
            },
            // left out: the value its `surface.topography` gives, else the default
            None => match (self.derived.iter().find(|(d, _)| *d == key), k.default) {
                (Some(&(_, x)), _) => x,
                (None, Default::Number(x)) => x,
                (None, Default::Key(other)) => match self.scene.get(other).and_then(as_number) {
                    Some(x) => x,
                    None => return Ok(None),
                },
                _ => return Ok(None),
            },
        };
        if !k.domain.contains(v) {
            return Err(self.fail(key, num(v), k.domain.describe()));
        }
        self.record(key, toml::Value::Float(v));
        Ok(Some(v))
    }

    /// A count of the registry.
    fn count(&mut self, key: &str) -> Result<usize, SceneError> {
        let k = self.registry_key(key);
        let v = match self.take(key) {
            Some(toml::Value::Integer(i)) => i as f64,
            Some(v) => return Err(self.fail(key, show(&v), k.domain.describe())),
            None => match k.default {
                Default::Count(n) => n as f64,
                _ => return Err(self.missing(key)),
            },
        };
        if !k.domain.contains(v) {
            return Err(self.fail(key, format!("{v}"), k.domain.describe()));
        }
        self.record(key, toml::Value::Integer(v as i64));
        Ok(v as usize)
    }

    /// A flag of the registry.
    fn flag(&mut self, key: &str) -> Result<bool, SceneError> {
        let k = self.registry_key(key);
        let b = match self.take(key) {
            Some(toml::Value::Boolean(b)) => b,
            Some(v) => return Err(self.fail(key, show(&v), "true or false")),
            None => match k.default {
                Default::Flag(b) => b,
                _ => return Err(self.missing(key)),
            },
        };
        self.record(key, toml::Value::Boolean(b));
        Ok(b)
    }

    /// A word of the registry: one of its choices (or a law name, checked by the caller).
    fn word(&mut self, key: &str) -> Result<Option<String>, SceneError> {
        let k = self.registry_key(key);
        let w = match self.take(key) {
            Some(toml::Value::String(s)) => s,
            Some(v) => return Err(self.fail(key, show(&v), k.domain.describe())),
            None => match k.default {
                Default::Word(w) => w.to_string(),
                _ => return Ok(None),
            },
        };
        if let Domain::Choice(words) = k.domain {
            if !words.contains(&w.as_str()) {
                return Err(self.fail(key, format!("\"{w}\""), k.domain.describe()));
            }
        }
        self.record(key, toml::Value::String(w.clone()));
        Ok(Some(w))
    }

    /// A list of words of the registry (a [`Domain::ChoiceList`] checked here, a
    /// [`Domain::LawList`] against `laws`), absent as None.
    fn word_list(&mut self, key: &str, laws: &[&str]) -> Result<Option<Vec<String>>, SceneError> {
        let k = self.registry_key(key);
        let Some(v) = self.take(key) else {
            return Ok(None);
        };
        let words: Option<Vec<String>> = match &v {
            toml::Value::Array(a) if !a.is_empty() => {
                a.iter().map(|x| x.as_str().map(str::to_string)).collect()
            }
            _ => None,
        };
        let Some(words) = words else {
            return Err(self.fail(key, show(&v), k.domain.describe()));
        };
        let allowed: Vec<&str> = match k.domain {
            Domain::ChoiceList(w) => w.to_vec(),
            _ => laws.to_vec(),
        };
        for w in &words {
            if !allowed.contains(&w.as_str()) {
                return Err(self.fail(
                    key,
                    format!("\"{w}\""),
                    format!("{}: one of {}", k.domain.describe(), allowed.join(", ")),
                ));
            }
        }
        self.record(
            key,
            toml::Value::Array(
                words
                    .iter()
                    .map(|w| toml::Value::String(w.clone()))
                    .collect(),
            ),
        );
        Ok(Some(words))
    }

    /// `model_form` and its pins.
    fn model_form(
        &mut self,
        registry: &LawRegistry,
    ) -> Result<crate::model_form::ModelFormSpec, SceneError> {
        use crate::model_form::Choice;
        let check = self.required_word("model_form")? == "check";
        let mut pins = Vec::new();
        for c in Choice::ALL {
            let laws = match c {
                Choice::Plasticity => registry.plasticity_names(),
                Choice::Adhesion => registry.adhesion_names(),
                _ => Vec::new(),
            };
            if let Some(words) = self.word_list(c.pin_key(), &laws)? {
                pins.push((c, words));
            }
        }
        Ok(crate::model_form::ModelFormSpec { check, pins })
    }

    fn required_word(&mut self, key: &str) -> Result<String, SceneError> {
        match self.word(key)? {
            Some(w) => Ok(w),
            None => Err(self.missing(key)),
        }
    }

    /// The title, accuracy and points (at least `min_points` when not zero).
    fn common(&mut self, min_points: usize) -> Result<Common, SceneError> {
        let title = match self.take("title") {
            Some(toml::Value::String(s)) => Some(s),
            Some(v) => return Err(self.fail("title", show(&v), "text")),
            None => None,
        };
        if let Some(t) = &title {
            self.record("title", toml::Value::String(t.clone()));
        }
        if let Some(v) = self.take("kind") {
            if v.as_str() != Some(self.kind.as_str()) {
                return Err(self.fail(
                    "kind",
                    show(&v),
                    format!("\"{}\" for this command", self.kind),
                ));
            }
        }
        self.record("kind", toml::Value::String(self.kind.as_str().into()));
        let accuracy = self.required_word("accuracy")?;
        let accuracy = Accuracy::from_name(&accuracy).expect("a registry choice");
        let points = self.count("points")?;
        if min_points > 0 && points < min_points {
            return Err(self.fail(
                "points",
                points.to_string(),
                format!("at least {min_points} for the {} curves", self.kind),
            ));
        }
        Ok(Common {
            scene: self.scene.clone(),
            title: title.unwrap_or_else(|| self.scene.file().to_string()),
            accuracy,
            points,
            resolved: toml::Table::new(),
            notes: self.notes.clone(),
            registry: Arc::default(),
        })
    }

    /// `surface.topography`: the height map read and analysed with the scene's options
    /// (`surface.topography_*`), its GW parameters set as the values of the keys the scene
    /// leaves out ([`TOPOGRAPHY_SETS`]) and noted where the scene gives another; the file,
    /// the route taken and the cutoff recorded for the echo. Options without the file are
    /// refused. Errors name the key and the scene file that gave it.
    fn topography(&mut self) -> Result<(), SceneError> {
        let key = "surface.topography";
        let Some(v) = self.take(key) else {
            for option in TOPOGRAPHY_OPTIONS {
                if let Some(v) = self.scene.get(option).cloned() {
                    // a value outside the option's domain is refused as such first
                    self.topography_option(option)?;
                    return Err(self.fail(
                        option,
                        show(&v),
                        "given with surface.topography, the height-map file it is an option of (the scene gives none)",
                    ));
                }
            }
            return Ok(());
        };
        let written = match &v {
            toml::Value::String(p) if !p.trim().is_empty() => p.clone(),
            _ => {
                return Err(self.fail(
                    key,
                    show(&v),
                    "the path of a height-map file (text; a relative path is relative to the scene file's folder)",
                ))
            }
        };
        let path = match self.scene.dir_of(key) {
            Some(dir) if std::path::Path::new(&written).is_relative() => dir.join(&written),
            _ => std::path::PathBuf::from(&written),
        };
        let mut request = crate::topography::TopographyRequest::default();
        let mut options = std::collections::BTreeMap::new();
        for option in TOPOGRAPHY_OPTIONS {
            if let Some(v) = self.topography_option(option)? {
                options.insert(option, v);
            }
        }
        let word = |o: &str| match options.get(o) {
            Some(toml::Value::String(w)) => Some(w.clone()),
            _ => None,
        };
        let number = |o: &str| match options.get(o) {
            Some(toml::Value::Float(x)) => Some(*x),
            _ => None,
        };
        request.route = word("surface.topography_route");
        request.detrend = word("surface.topography_detrend");
        request.undefined = word("surface.topography_undefined");
        request.height_unit = word("surface.topography_height_unit");
        request.file_format = word("surface.topography_file_format");
        request.channel = word("surface.topography_channel");
        request.spacing = number("surface.topography_spacing");
        request.cutoff = number("surface.topography_cutoff");
        let given_radius = self.scene.get("contact.radius").and_then(as_number);
        if request.cutoff.is_none() {
            request.contact_radius = given_radius.filter(|r| r.is_finite() && *r > 0.0);
        }
        let surface = crate::topography::scene_surface(&path, &request).map_err(|e| match e {
            ModelError::Option { name, message }
                if name == "cutoff" || name == "contact_radius" =>
            {
                let option = "surface.topography_cutoff";
                let value = match request.cutoff {
                    Some(c) => num(c),
                    None => format!(
                        "absent, 4 sqrt(R sigma_s) with contact.radius = R = {}",
                        given_radius.map_or("?".into(), num)
                    ),
                };
                self.fail(option, value, crate::topography::as_scene_keys(&message))
            }
            e => self.fail(
                key,
                format!("\"{written}\""),
                format!(
                    "a height map that can be read and analysed: {}",
                    crate::topography::as_scene_keys(&e.to_string())
                ),
            ),
        })?;
        self.record(key, toml::Value::String(path.display().to_string()));
        let route = match surface.route {
            crate::topography::Route::Spectral => "spectral",
            crate::topography::Route::Summits => "summits",
        };
        self.record(
            "surface.topography_route",
            toml::Value::String(route.into()),
        );
        // the cutoff the map was analysed at (0: as sampled), so the echo runs as it ran
        self.record(
            "surface.topography_cutoff",
            toml::Value::Float(surface.cutoff.wavelength.unwrap_or(0.0)),
        );
        let file = path.display().to_string();
        let band = match (surface.cutoff.wavelength, surface.cutoff.applied) {
            (Some(w), true) => format!("wavelengths above the cutoff {w:.4e} m"),
            _ => "the map as sampled".to_string(),
        };
        for (k, v) in [
            (TOPOGRAPHY_SETS[0], surface.gw.sigma_s),
            (TOPOGRAPHY_SETS[1], surface.gw.asperity_density),
            (TOPOGRAPHY_SETS[2], surface.gw.radius),
        ] {
            let unit = keys::key(k).map_or("", |f| f.unit);
            match self.scene.get(k).and_then(as_number) {
                Some(given) => {
                    if (given - v).abs() > 1e-9 * v.abs() {
                        self.notes.push(crate::guards::Warning::note(
                            crate::topography::TOPOGRAPHY_VALUE_OVERRIDDEN,
                            format!(
                                "{k} = {} {unit} given by {} wins over {v:.4e} {unit} from {file} ({route} route, {band})",
                                num(given),
                                self.file_of(k),
                            ),
                        ));
                    }
                }
                None if self.scene.get(k).is_some() => {} // not a number: its own error
                None => {
                    let domain = self.registry_key(k).domain;
                    if !domain.contains(v) {
                        return Err(self.fail(
                            key,
                            format!("\"{written}\""),
                            format!(
                                "a map whose {k} lies in the key's domain ({}): {file} gives {v:.4e} {unit} ({route} route, {band}); give {k} in the scene, or choose another band (surface.topography_cutoff)",
                                domain.describe(),
                            ),
                        ));
                    }
                    self.derived.push((k, v));
                }
            }
        }
        Ok(())
    }

    /// One option of `surface.topography`, checked against its domain and recorded (the
    /// choices' defaults too); None when absent without a default. The channel is a name
    /// or a 0-based index (an integer), given back as text.
    fn topography_option(&mut self, key: &str) -> Result<Option<toml::Value>, SceneError> {
        let k = self.registry_key(key);
        Ok(match k.domain {
            Domain::Choice(_) => self.word(key)?.map(toml::Value::String),
            Domain::Range { .. } => self.opt_number(key)?.map(toml::Value::Float),
            _ => match self.take(key) {
                None => None,
                Some(toml::Value::String(c)) if !c.trim().is_empty() => {
                    self.record(key, toml::Value::String(c.clone()));
                    Some(toml::Value::String(c))
                }
                Some(toml::Value::Integer(i)) if i >= 0 => {
                    self.record(key, toml::Value::Integer(i));
                    Some(toml::Value::String(i.to_string()))
                }
                Some(v) => {
                    return Err(self.fail(
                        key,
                        show(&v),
                        "a channel's name (text) or its 0-based index (an integer >= 0)",
                    ))
                }
            },
        })
    }

    fn roughness(&mut self) -> Result<RoughnessSpec, SceneError> {
        Ok(RoughnessSpec {
            sigma_s: self.number("surface.sigma_s")?,
            asperity_density: self.number("surface.asperity_density")?,
        })
    }

    /// The `[dynamics]` section, if the scene has one (its keys are read only then, so a
    /// quasi-static scene's echo stays as it was).
    fn dynamics(
        &mut self,
        switch: &SwitchGeometrySpec,
    ) -> Result<Option<DynamicsSpec>, SceneError> {
        if self.scene.get("dynamics").is_none() {
            return Ok(None);
        }
        if let Drive::ImpactEnergy(e) = switch.drive {
            return Err(self.fail(
                "switch.impact_energy",
                num(e),
                "absent with a [dynamics] section: the impact energy is what the integration finds; give k_s (or spring_constant with electrode_area) and the voltage",
            ));
        }
        let areal_mass = self.opt_number("dynamics.areal_mass")?;
        let resonance_frequency = self.opt_number("dynamics.resonance_frequency")?;
        match (areal_mass, resonance_frequency) {
            (Some(_), Some(f)) => {
                return Err(self.fail(
                    "dynamics.resonance_frequency",
                    num(f),
                    "absent when areal_mass is given (the same mass twice): give one of the two",
                ))
            }
            (None, None) => {
                return Err(SceneError::Missing {
                    file: self.file(),
                    key: "dynamics.areal_mass".into(),
                    explanation: "a [dynamics] section needs the electrode's mass: areal_mass (kg/m^2) or resonance_frequency (Hz)".into(),
                })
            }
            _ => {}
        }
        let pressure = self.number("dynamics.gas_pressure")?;
        let viscosity = self.number("dynamics.gas_viscosity")?;
        let mean_free_path = self.number("dynamics.gas_mean_free_path")?;
        let width = self.opt_number("dynamics.plate_width")?;
        let length = self.opt_number("dynamics.plate_length")?;
        let max_bounces = self.count("dynamics.max_bounces")?;
        let gas = if pressure > 0.0 {
            if switch.dimple_height <= 0.0 {
                return Err(self.fail(
                    "dynamics.gas_pressure",
                    format!("{} Pa", num(pressure)),
                    "0 (vacuum) when switch.dimple_height = 0: a flat plate landing on the dielectric squeezes the gas out through a gap closing as x^-3 (x^-1.84 with rarefaction): under Reynolds' squeeze film it never closes in finite time; give the dimples' height (theory 13.2)",
                ));
            }
            let width = match (width, switch.electrode_area) {
                (Some(w), _) => w,
                (None, Some(a)) => a.sqrt(),
                (None, None) => {
                    return Err(SceneError::Missing {
                        file: self.file(),
                        key: "dynamics.plate_width".into(),
                        explanation: "the squeeze film needs the plate's size: plate_width (and plate_length), or switch.electrode_area for a square plate".into(),
                    })
                }
            };
            Some(GasSpec {
                pressure,
                viscosity,
                mean_free_path,
                width,
                length: length.unwrap_or(width),
            })
        } else {
            None
        };
        Ok(Some(DynamicsSpec {
            areal_mass,
            resonance_frequency,
            gas,
            max_bounces,
        }))
    }

    fn switch(&mut self, film_modulus: f64) -> Result<SwitchGeometrySpec, SceneError> {
        let d0 = self.number("switch.d0")?;
        let dimple_height = self.number("switch.dimple_height")?;
        if !(dimple_height < d0) {
            return Err(self.fail(
                "switch.dimple_height",
                num(dimple_height),
                format!(
                    "below d0 = {} m: the contact (dimples or a bump) must touch before the electrode meets the dielectric",
                    num(d0)
                ),
            ));
        }
        let t_d = self.number("switch.t_d")?;
        let epsilon_r = self.number("switch.epsilon_r")?;
        let epsilon_0 = self.number("switch.epsilon_0")?;
        let film_thickness = self.number("switch.film_thickness")?;
        let film_youngs_modulus = self
            .opt_number("switch.film_youngs_modulus")?
            .unwrap_or(film_modulus);
        let contact_area_fraction = self.number("switch.contact_area_fraction")?;
        let hold_voltage = self.opt_number("switch.hold_voltage")?;
        let hold_force = self.opt_number("switch.hold_force")?;
        let energy = self.opt_number("switch.impact_energy")?;
        let mut k_s = self.opt_number("switch.k_s")?;
        let voltage = self.opt_number("switch.voltage")?;
        let electrode_area = self.opt_number("switch.electrode_area")?;
        let spring_constant = self.opt_number("switch.spring_constant")?;
        if let Some(k) = spring_constant {
            // drive B in a spring constant (N/m) over the electrode area (m^2)
            let Some(area) = electrode_area else {
                return Err(SceneError::Missing {
                    file: self.file(),
                    key: "switch.electrode_area".into(),
                    explanation: format!(
                        "spring_constant = {} N/m is a force per length: give the electrode area (m^2) it acts on, K_s = spring_constant / electrode_area",
                        num(k)
                    ),
                });
            };
            if let Some(ks) = k_s {
                return Err(self.fail(
                    "switch.spring_constant",
                    num(k),
                    format!(
                        "absent when k_s = {} Pa/m is given (the same spring twice): give one of the two",
                        num(ks)
                    ),
                ));
            }
            let per_area = k / area;
            let domain = keys::key("switch.k_s").map(|f| f.domain);
            if !domain.is_some_and(|d| d.contains(per_area)) {
                return Err(self.fail(
                    "switch.spring_constant",
                    format!(
                        "{} N/m (K_s = spring_constant / electrode_area = {} Pa/m)",
                        num(k),
                        num(per_area)
                    ),
                    format!(
                        "such that K_s lies in the domain of switch.k_s: {}",
                        domain.map(|d| d.describe()).unwrap_or_default()
                    ),
                ));
            }
            k_s = Some(per_area);
        }
        let drive = match (energy, k_s) {
            (Some(e), None) => {
                if let Some(v) = voltage {
                    return Err(self.fail(
                        "switch.voltage",
                        num(v),
                        "absent when impact_energy is given (K_s is derived at U = V_PI; give k_s and voltage instead of impact_energy to set the voltage)",
                    ));
                }
                Drive::ImpactEnergy(e)
            }
            (None, Some(k)) => Drive::Spring { k_s: k, voltage },
            (Some(e), Some(_)) => {
                return Err(self.fail(
                    "switch.impact_energy",
                    num(e),
                    "given alone (K_s derived at U = V_PI), or replaced by k_s (or spring_constant with electrode_area) with an optional voltage (E_I derived), not both",
                ))
            }
            (None, None) => {
                return Err(SceneError::Missing {
                    file: self.file(),
                    key: "switch.impact_energy".into(),
                    explanation: "give impact_energy (J/m^2; K_s is derived so that release at U = V_PI gives it), or k_s (Pa/m), or spring_constant (N/m) with electrode_area (m^2), with an optional voltage (V, default V_PI; E_I is derived)".into(),
                })
            }
        };
        if let Some(f) = hold_force {
            if let Some(u) = hold_voltage {
                return Err(self.fail(
                    "switch.hold_force",
                    num(f),
                    format!(
                        "absent when hold_voltage = {} V is given (two holds): give one of the two",
                        num(u)
                    ),
                ));
            }
            if electrode_area.is_none() {
                return Err(SceneError::Missing {
                    file: self.file(),
                    key: "switch.electrode_area".into(),
                    explanation: format!(
                        "hold_force = {} N needs the area it acts on: the hold pressure per contact area is hold_force / (contact_area_fraction x electrode_area)",
                        num(f)
                    ),
                });
            }
        }
        Ok(SwitchGeometrySpec {
            d0,
            dimple_height,
            t_d,
            epsilon_r,
            epsilon_0,
            film_thickness,
            film_youngs_modulus,
            drive,
            contact_area_fraction,
            electrode_area,
            spring_constant,
            hold_voltage,
            hold_force,
        })
    }

    fn contact(&mut self, registry: &LawRegistry) -> Result<ContactSpec, ModelError> {
        let youngs_modulus = self.number("contact.youngs_modulus")?;
        let poisson_ratio = self.number("contact.poisson_ratio")?;
        let yield_stress = self.number("contact.yield_stress")?;
        let radius = self.number("contact.radius")?;
        let work_of_adhesion = self.number("contact.work_of_adhesion")?;
        let z0 = self.number("contact.z0")?;
        let counter = match self.required_word("contact.counter")?.as_str() {
            "material" => {
                let mut given = [0.0; 2];
                for (i, key) in [
                    "contact.counter_youngs_modulus",
                    "contact.counter_poisson_ratio",
                ]
                .into_iter()
                .enumerate()
                {
                    given[i] = match self.opt_number(key)? {
                        Some(v) => v,
                        None => {
                            return Err(self
                                .fail(key, "missing", "given when counter = \"material\"")
                                .into())
                        }
                    };
                }
                Counter::Material {
                    youngs_modulus: given[0],
                    poisson_ratio: given[1],
                    yield_stress: self.number("contact.counter_yield_stress")?,
                }
            }
            word => {
                for key in [
                    "contact.counter_youngs_modulus",
                    "contact.counter_poisson_ratio",
                    "contact.counter_yield_stress",
                ] {
                    if let Some(v) = self.take(key) {
                        return Err(self
                            .fail(key, show(&v), "absent unless counter = \"material\"")
                            .into());
                    }
                }
                if word == "rigid" {
                    Counter::Rigid
                } else {
                    Counter::Same
                }
            }
        };
        let yield_modulus = match self.word("contact.yield_modulus")?.as_deref() {
            Some("composite") => YieldModulus::Composite,
            Some(_) => YieldModulus::AsPrinted,
            None => {
                return Err(SceneError::Missing {
                    file: self.file(),
                    key: "contact.yield_modulus".into(),
                    explanation: "the modulus of the yield onset, eq 1, moves the paper switch's pull-out by about 100x, so a scene must say which it uses: \"as_printed\" (E of the film, as the paper prints eq 1; its scenes use this and it reproduces Fig 4's changing curves) or \"composite\" (E* of the pair, the Kogut-Etsion convention that makes eq 3 the Hertz force at delta_CP); see docs/theory.md section 2.1".into(),
                }
                .into())
            }
        };
        // the films' conduction: keys of switch scenes only (the contact resistance)
        let resistivity = if self.kind == Kind::Switch {
            self.opt_number("contact.resistivity")?
        } else {
            None
        };
        let conduction = match resistivity {
            Some(rho) => {
                let lambda = self
                    .opt_number("contact.mean_free_path")?
                    .ok_or_else(|| SceneError::Missing {
                        file: self.file(),
                        key: "contact.mean_free_path".into(),
                        explanation: format!(
                            "resistivity = {} ohm m is given: the contact resistance needs the films' electron mean free path too (m; Au 37.7e-9, Ru 6.6e-9)",
                            num(rho)
                        ),
                    })?;
                Some(crate::ohmic::Conduction {
                    resistivity: rho,
                    mean_free_path: lambda,
                })
            }
            None => {
                // a mean free path alone is checked and echoed, and computes nothing (a
                // scene that comments out its resistivity turns the resistance off)
                if self.kind == Kind::Switch {
                    self.opt_number("contact.mean_free_path")?;
                }
                None
            }
        };
        let reload = match self.required_word("contact.reload")?.as_str() {
            "bounded" => Reload::Bounded,
            _ => Reload::AsPrinted,
        };
        let film = Material::new(MaterialProps {
            youngs_modulus,
            poisson_ratio,
            yield_stress,
        })?;
        let pair = laws::pair_of(film, &counter, radius)?;
        // the adhesion law
        let name = self.required_word("contact.adhesion_law")?;
        let entry = registry.adhesion(&name).ok_or_else(|| {
            self.fail(
                "contact.adhesion_law",
                format!("\"{name}\""),
                format!(
                    "one of the registered adhesion laws: {}",
                    registry.adhesion_names().join(", ")
                ),
            )
        })?;
        let params = self.law_params("contact.adhesion", None, &name, entry.params())?;
        let law = entry
            .build(&LawContext {
                pair: &pair,
                work_of_adhesion,
                z0,
                yield_modulus,
                params: &params,
                adhesion: None,
            })
            .map_err(|e| self.law_error("contact.adhesion", "contact.adhesion_law", &name, e))?;
        let adhesion = Chosen { name, params, law };
        // the plasticity law
        let name = self.required_word("contact.plasticity_law")?;
        let entry = registry.plasticity(&name).ok_or_else(|| {
            self.fail(
                "contact.plasticity_law",
                format!("\"{name}\""),
                format!(
                    "one of the registered plasticity laws: {}",
                    registry.plasticity_names().join(", ")
                ),
            )
        })?;
        // [contact.effective_radius] is the paper's name for etsion_kadin's constants: with
        // that law it is its table; with another it is checked as etsion_kadin's and left
        // unused, so that a scene switches laws by one key
        let paper_table = self.scene.get("contact.effective_radius").is_some();
        let table = if paper_table && name == "etsion_kadin" {
            if self.scene.get("contact.plasticity").is_some() {
                return Err(self
                    .fail(
                        "contact.effective_radius",
                        "a table",
                        "absent when [contact.plasticity] is given (it is the paper's name for the same table)",
                    )
                    .into());
            }
            "contact.effective_radius"
        } else {
            if paper_table {
                let ek = "etsion_kadin";
                let params = crate::laws::ETSION_KADIN_PARAMS;
                let fit = self.law_params("contact.effective_radius", None, ek, params)?;
                asperity_plastic::EffectiveRadiusFit::new(
                    fit.triple("c1").unwrap_or_default(),
                    fit.triple("c2").unwrap_or_default(),
                )
                .map_err(|e| {
                    self.law_error(
                        "contact.effective_radius",
                        "contact.plasticity_law",
                        ek,
                        e.into(),
                    )
                })?;
            }
            "contact.plasticity"
        };
        let params = self.law_params(table, None, &name, entry.params())?;
        let law = entry
            .build(&LawContext {
                pair: &pair,
                work_of_adhesion,
                z0,
                yield_modulus,
                params: &params,
                adhesion: Some(&adhesion.law),
            })
            .map_err(|e| match e {
            contact_core::LawError::Law { ref source, .. }
                if matches!(
                    source.downcast_ref::<PlasticError>(),
                    Some(PlasticError::NeverYields)
                ) =>
            {
                self.fail(
                    "contact.yield_stress",
                    num(yield_stress),
                    format!("finite with plasticity_law = \"{name}\" (use \"elastic\" for no yield)"),
                )
                .into()
            }
            e => self.law_error(table, "contact.plasticity_law", &name, e),
        })?;
        let plasticity = Chosen { name, params, law };
        Ok(ContactSpec {
            youngs_modulus,
            poisson_ratio,
            yield_stress,
            radius,
            work_of_adhesion,
            z0,
            counter,
            yield_modulus,
            reload,
            conduction,
            adhesion,
            plasticity,
            pair,
        })
    }

    /// The error of a law's constructor: a parameter it refuses (named by the law's own
    /// field when it says which) is a scene error of its table; anything else names the
    /// law.
    fn law_error(
        &self,
        table: &str,
        name_key: &str,
        law: &str,
        e: contact_core::LawError,
    ) -> ModelError {
        if let Some(PlasticError::Core(contact_core::CoreError::Invalid {
            field: "delta_cp",
            value,
            ..
        })) = e.downcast_ref::<PlasticError>()
        {
            let s_y = self.scene.get("contact.yield_stress").and_then(as_number);
            return self
                .fail(
                    "contact.yield_stress",
                    s_y.map_or("?".into(), num),
                    format!(
                        "small enough that the yield onset of eq 1, delta_CP = R (pi C_v S_Y / 2E)^2, stays finite (it is {} here); a body that never yields is yield_stress = inf with plasticity_law = \"elastic\"",
                        num(*value)
                    ),
                )
                .into();
        }
        if let Some(PlasticError::Fit {
            field,
            value,
            allowed,
        }) = e.downcast_ref::<PlasticError>()
        {
            return self
                .fail(&format!("{table}.{field}"), num(*value), *allowed)
                .into();
        }
        if e.category() == Category::Input {
            return self
                .fail(
                    name_key,
                    format!("\"{law}\""),
                    format!("a law its parameters allow: {e}"),
                )
                .into();
        }
        ModelError::Law(e)
    }

    /// The parameters of law `law` from table `table` (recorded under `echo_as`, default
    /// `table`), each checked against the law's list.
    fn law_params(
        &mut self,
        table: &str,
        echo_as: Option<&str>,
        law: &str,
        params: &[Param],
    ) -> Result<LawParams, SceneError> {
        self.used.insert(table.to_string());
        let given = match self.scene.get(table) {
            None => toml::Table::new(),
            Some(toml::Value::Table(t)) => t.clone(),
            Some(v) => return Err(self.fail(table, show(v), "a table of the law's parameters")),
        };
        for name in given.keys() {
            if !params.iter().any(|p| p.name == name) {
                let known: Vec<&str> = params.iter().map(|p| p.name).collect();
                return Err(SceneError::Unknown {
                    file: self.file(),
                    key: format!("{table}.{name}"),
                    line: self.line(&format!("{table}.{name}")),
                    kind: self.kind.to_string(),
                    hint: if known.is_empty() {
                        format!(": the law `{law}` takes no parameters")
                    } else {
                        format!(": the law `{law}` takes {}", known.join(", "))
                    },
                });
            }
        }
        let mut values = std::collections::BTreeMap::new();
        let mut echo = toml::Table::new();
        for p in params {
            let key = format!("{table}.{}", p.name);
            let value = match given.get(p.name) {
                Some(v) => self.param_value(&key, p, v)?,
                None => match p.default {
                    Default::Number(x) => ParamValue::Number(x),
                    Default::Count(n) => ParamValue::Count(n),
                    Default::Triple(t) => ParamValue::Triple(t),
                    Default::Word(w) => ParamValue::Word(w.into()),
                    Default::Flag(b) => ParamValue::Flag(b),
                    Default::Required => {
                        return Err(SceneError::Missing {
                            file: self.file(),
                            key,
                            explanation: format!(
                                "required by the law `{law}`: {} ({})",
                                p.help, p.unit
                            ),
                        })
                    }
                    Default::Absent | Default::Key(_) | Default::RequiredWhen(_) => continue,
                },
            };
            echo.insert(p.name.to_string(), param_to_toml(&value));
            values.insert(p.name.to_string(), value);
        }
        if !echo.is_empty() {
            self.record(echo_as.unwrap_or(table), toml::Value::Table(echo));
        }
        Ok(LawParams::from_values(values))
    }

    fn param_value(&self, key: &str, p: &Param, v: &toml::Value) -> Result<ParamValue, SceneError> {
        let bad = || self.fail(key, show(v), p.domain.describe());
        Ok(match p.domain {
            Domain::Triple => match v {
                toml::Value::Array(a) if a.len() == 3 => {
                    let mut t = [0.0; 3];
                    for (i, x) in a.iter().enumerate() {
                        let n = as_number(x).ok_or_else(bad)?;
                        // the number at fault named by its place (`c1[0]`), as a law names it
                        if !(n.is_finite() && n.abs() <= keys::TRIPLE_LIMIT) {
                            return Err(self.fail(
                                &format!("{key}[{i}]"),
                                num(n),
                                p.domain.describe(),
                            ));
                        }
                        t[i] = n;
                    }
                    ParamValue::Triple(t)
                }
                _ => return Err(bad()),
            },
            Domain::Count { .. } => match v {
                toml::Value::Integer(i) if p.domain.contains(*i as f64) => {
                    ParamValue::Count(*i as usize)
                }
                _ => return Err(bad()),
            },
            Domain::Range { .. } | Domain::RangeOrInfinite { .. } => {
                let x = as_number(v).ok_or_else(bad)?;
                if !p.domain.contains(x) {
                    return Err(self.fail(key, num(x), p.domain.describe()));
                }
                ParamValue::Number(x)
            }
            Domain::Choice(words) => match v {
                toml::Value::String(s) if words.contains(&s.as_str()) => {
                    ParamValue::Word(s.clone())
                }
                _ => return Err(bad()),
            },
            Domain::Flag => match v {
                toml::Value::Boolean(b) => ParamValue::Flag(*b),
                _ => return Err(bad()),
            },
            _ => return Err(bad()),
        })
    }

    /// Refuses any key of the scene that this kind does not take.
    fn finish(&self) -> Result<(), SceneError> {
        self.check_table(self.scene.tree(), "", false)
    }

    /// Refuses a key of `t` (at `prefix`) that no scene of this kind takes; `early`: while
    /// the scene is still being read, so a key this kind takes (read or not yet) and the
    /// law-parameter tables (which their laws check) pass.
    fn check_table(&self, t: &toml::Table, prefix: &str, early: bool) -> Result<(), SceneError> {
        for (k, v) in t {
            let key = if prefix.is_empty() {
                k.clone()
            } else {
                format!("{prefix}.{k}")
            };
            let known_now = early
                && (keys::of(self.kind).any(|f| f.key == key)
                    || [
                        "contact.adhesion",
                        "contact.plasticity",
                        "contact.effective_radius",
                    ]
                    .contains(&key.as_str()));
            if self.used.contains(&key) || known_now {
                continue;
            }
            let is_section =
                v.is_table() && keys::of(self.kind).any(|f| f.key.starts_with(&format!("{key}.")));
            if is_section {
                self.check_table(v.as_table().expect("a table"), &key, early)?;
                continue;
            }
            let known: Vec<&str> = keys::of(self.kind).map(|f| f.key).collect();
            let close = known
                .iter()
                .map(|c| (strsim::jaro_winkler(c, &key), *c))
                .filter(|(s, _)| *s > 0.85)
                .max_by(|a, b| a.0.total_cmp(&b.0));
            let hint = match close {
                Some((_, c)) => format!(": did you mean `{c}`?"),
                None => {
                    let in_section: Vec<&str> = known
                        .iter()
                        .filter(|c| {
                            c.rsplit_once('.')
                                .map_or(prefix.is_empty(), |(s, _)| s == prefix)
                        })
                        .copied()
                        .collect();
                    format!(
                        " (the keys {}: {})",
                        if prefix.is_empty() {
                            "at the top".to_string()
                        } else {
                            format!("of [{prefix}]")
                        },
                        in_section.join(", ")
                    )
                }
            };
            return Err(SceneError::Unknown {
                file: self.file_of(&key),
                key: key.clone(),
                line: self.line(&key),
                kind: self.kind.to_string(),
                hint,
            });
        }
        Ok(())
    }
}

fn param_to_toml(v: &ParamValue) -> toml::Value {
    match v {
        ParamValue::Number(x) => toml::Value::Float(*x),
        ParamValue::Count(n) => toml::Value::Integer(*n as i64),
        ParamValue::Triple(t) => {
            toml::Value::Array(t.iter().map(|&x| toml::Value::Float(x)).collect())
        }
        ParamValue::Word(w) => toml::Value::String(w.clone()),
        ParamValue::Flag(b) => toml::Value::Boolean(*b),
    }
}

/// A TOML value as JSON: non-finite numbers as their names (`"inf"`), never null.
pub fn toml_to_json(v: &toml::Value) -> serde_json::Value {
    use serde_json::Value as J;
    match v {
        toml::Value::String(s) => J::String(s.clone()),
        toml::Value::Integer(i) => J::from(*i),
        toml::Value::Float(f) => {
            if f.is_finite() {
                J::from(*f)
            } else {
                J::String(num(*f))
            }
        }
        toml::Value::Boolean(b) => J::Bool(*b),
        toml::Value::Datetime(d) => J::String(d.to_string()),
        toml::Value::Array(a) => J::Array(a.iter().map(toml_to_json).collect()),
        toml::Value::Table(t) => J::Object(
            t.iter()
                .map(|(k, v)| (k.clone(), toml_to_json(v)))
                .collect(),
        ),
    }
}
