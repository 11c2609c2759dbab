//! The law registry: adhesion and plasticity laws looked up by the name a scene gives,
//! each with its own parameter list.
//!
//! A scene names its laws (`contact.adhesion_law`, `contact.plasticity_law`) and gives
//! their parameters in `[contact.adhesion]` and `[contact.plasticity]`. A law is an entry
//! of a [`LawRegistry`]: a name, a summary, its parameters (unit, domain, default, meaning:
//! the same vocabulary as the scene keys) and a constructor from the validated contact
//! section. The built-in laws register themselves exactly as a user's law does
//! ([`LawRegistry::builtin`]); a program built on this library adds its own with
//! [`LawRegistry::register_adhesion`] or [`LawRegistry::register_plasticity`] and passes the
//! registry to spec construction, and every command runs with it.
//!
//! ```
//! use stiction_model::laws::{LawRegistry, PlasticityEntry};
//! use stiction_model::asperity_plastic::Elastic;
//! let mut registry = LawRegistry::builtin();
//! // a law that never yields, under a name of one's own
//! registry.register_plasticity(PlasticityEntry::new(
//!     "rigid_plastic_free",
//!     "never yields (an example)",
//!     vec![],
//!     |ctx| Ok(std::sync::Arc::new(Elastic::new(ctx.pair.radius())?)),
//! ))?;
//! assert!(registry.plasticity("rigid_plastic_free").is_some());
//! # Ok::<(), stiction_model::ModelError>(())
//! ```

use crate::error::ModelError;
use crate::keys::{Default, Domain};
use crate::spec::Counter;
use asperity_plastic::{
    AdhesionCoupled, EffectiveRadiusFit, Elastic, EtsionKadin, KogutEtsion, YieldModulus,
};
use contact_core::{AdhesionLaw, LawError, Pair, PlasticityLaw};
use maugis_kim::{Dmt, DugdaleParams, Hertz, Jkr, JkrParams, MaugisKim};
use std::collections::BTreeMap;
use std::sync::Arc;

/// An adhesion law as the model holds it.
pub type DynAdhesion = Arc<dyn AdhesionLaw + Send + Sync>;
/// A plasticity law as the model holds it.
pub type DynPlasticity = Arc<dyn PlasticityLaw + Send + Sync>;

/// One parameter of a law: its name inside the law's table, unit, domain, default and
/// meaning.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Param {
    /// The name in `[contact.adhesion]` or `[contact.plasticity]`.
    pub name: &'static str,
    /// SI unit ("-" for a pure number).
    pub unit: &'static str,
    /// What it accepts (numbers, a triple, a choice, a flag).
    pub domain: Domain,
    /// What it takes when left out.
    pub default: Default,
    /// What it means.
    pub help: &'static str,
}

/// A validated value of a law parameter.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ParamValue {
    /// A number (SI).
    Number(f64),
    /// A count.
    Count(usize),
    /// Three numbers.
    Triple([f64; 3]),
    /// A word of a choice.
    Word(String),
    /// A flag.
    Flag(bool),
}

/// The validated parameters of one law, by name.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LawParams {
    values: BTreeMap<String, ParamValue>,
}

impl LawParams {
    /// Parameters from name-value pairs (validated by the caller).
    pub fn from_values(values: BTreeMap<String, ParamValue>) -> Self {
        Self { values }
    }

    /// All values.
    pub fn values(&self) -> &BTreeMap<String, ParamValue> {
        &self.values
    }

    /// A number parameter (its default if the law declares one and the scene left it out).
    pub fn number(&self, name: &str) -> Option<f64> {
        match self.values.get(name) {
            Some(ParamValue::Number(v)) => Some(*v),
            Some(ParamValue::Count(n)) => Some(*n as f64),
            _ => None,
        }
    }

    /// A triple parameter.
    pub fn triple(&self, name: &str) -> Option<[f64; 3]> {
        match self.values.get(name) {
            Some(ParamValue::Triple(t)) => Some(*t),
            _ => None,
        }
    }

    /// A word parameter.
    pub fn word(&self, name: &str) -> Option<&str> {
        match self.values.get(name) {
            Some(ParamValue::Word(w)) => Some(w),
            _ => None,
        }
    }

    /// A flag parameter.
    pub fn flag(&self, name: &str) -> Option<bool> {
        match self.values.get(name) {
            Some(ParamValue::Flag(b)) => Some(*b),
            _ => None,
        }
    }
}

/// What a law's constructor sees: the contact pair built from the scene (both bodies, E*,
/// the radius), the scene's contact constants and the law's own parameters.
#[derive(Clone, Copy)]
pub struct LawContext<'a> {
    /// The pair: moduli, Poisson ratios, yield stresses, E*, K and the asperity radius.
    pub pair: &'a Pair,
    /// Work of adhesion w (J/m^2).
    pub work_of_adhesion: f64,
    /// Dugdale range z0 (m).
    pub z0: f64,
    /// The reading of eq 1.
    pub yield_modulus: YieldModulus,
    /// The law's parameters, validated against its list.
    pub params: &'a LawParams,
    /// The scene's adhesion law, when a plasticity law is built (None while the adhesion
    /// law itself is): a law whose plastic state the adhesive contact drives reads it.
    pub adhesion: Option<&'a DynAdhesion>,
}

impl std::fmt::Debug for LawContext<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LawContext")
            .field("pair", self.pair)
            .field("work_of_adhesion", &self.work_of_adhesion)
            .field("z0", &self.z0)
            .field("yield_modulus", &self.yield_modulus)
            .field("params", self.params)
            .field("adhesion", &self.adhesion.map(|_| "an adhesion law"))
            .finish()
    }
}

type AdhesionBuild = dyn Fn(&LawContext) -> Result<DynAdhesion, LawError> + Send + Sync;
type PlasticityBuild = dyn Fn(&LawContext) -> Result<DynPlasticity, LawError> + Send + Sync;

/// A registered adhesion law.
#[derive(Clone)]
pub struct AdhesionEntry {
    name: String,
    summary: String,
    params: Vec<Param>,
    build: Arc<AdhesionBuild>,
    credible: bool,
    where_adhesion_yields: bool,
}

/// A registered plasticity law.
#[derive(Clone)]
pub struct PlasticityEntry {
    name: String,
    summary: String,
    params: Vec<Param>,
    build: Arc<PlasticityBuild>,
    credible: bool,
    where_adhesion_yields: bool,
}

macro_rules! entry_common {
    ($entry:ident, $law:ty) => {
        impl $entry {
            /// An entry: the name scenes give, a one-line summary, the parameters of its
            /// table and its constructor.
            pub fn new(
                name: impl Into<String>,
                summary: impl Into<String>,
                params: Vec<Param>,
                build: impl Fn(&LawContext) -> Result<$law, LawError> + Send + Sync + 'static,
            ) -> Self {
                Self {
                    name: name.into(),
                    summary: summary.into(),
                    params,
                    build: Arc::new(build),
                    credible: true,
                    where_adhesion_yields: false,
                }
            }

            /// The entry marked as no credible alternative form for a model-form check
            /// (a plasticity law that never yields); entries are credible by default.
            pub fn not_credible(mut self) -> Self {
                self.credible = false;
                self
            }

            /// The entry marked as a credible alternative form only where adhesion alone
            /// yields a virgin asperity (`adhesion_yields_asperity`): a law for the regime
            /// where the uncoupled laws' assumption fails.
            pub fn credible_where_adhesion_yields(mut self) -> Self {
                self.where_adhesion_yields = true;
                self
            }

            /// Whether a model-form check tries this law as an alternative
            /// ([`crate::model_form`]); see also [`Self::only_where_adhesion_yields`].
            pub fn credible(&self) -> bool {
                self.credible
            }

            /// Whether the law is an alternative only where adhesion alone yields a virgin
            /// asperity.
            pub fn only_where_adhesion_yields(&self) -> bool {
                self.where_adhesion_yields
            }

            /// The name scenes give.
            pub fn name(&self) -> &str {
                &self.name
            }

            /// One line on what it is (with its reference).
            pub fn summary(&self) -> &str {
                &self.summary
            }

            /// Its parameters.
            pub fn params(&self) -> &[Param] {
                &self.params
            }

            /// Builds the law.
            pub fn build(&self, ctx: &LawContext) -> Result<$law, LawError> {
                (self.build)(ctx)
            }
        }

        impl std::fmt::Debug for $entry {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.debug_struct(stringify!($entry))
                    .field("name", &self.name)
                    .field("params", &self.params)
                    .finish()
            }
        }
    };
}

entry_common!(AdhesionEntry, DynAdhesion);
entry_common!(PlasticityEntry, DynPlasticity);

/// Adhesion and plasticity laws by name.
#[derive(Debug, Clone, Default)]
pub struct LawRegistry {
    adhesion: Vec<AdhesionEntry>,
    plasticity: Vec<PlasticityEntry>,
}

fn check_name(kind: &str, name: &str, taken: bool) -> Result<(), ModelError> {
    if name.is_empty() || !name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_') {
        return Err(ModelError::Registry(format!(
            "{kind} law name `{name}` must be non-empty ASCII letters, digits and _"
        )));
    }
    if taken {
        return Err(ModelError::Registry(format!(
            "{kind} law `{name}` is registered already"
        )));
    }
    Ok(())
}

impl LawRegistry {
    /// A registry without laws.
    pub fn empty() -> Self {
        Self::default()
    }

    /// The built-in laws: adhesion `maugis_kim`, `jkr`, `dmt`, `hertz`; plasticity
    /// `etsion_kadin`, `kogut_etsion`, `adhesion_coupled`, `elastic`.
    pub fn builtin() -> Self {
        let mut r = Self::empty();
        for e in builtin_adhesion() {
            r.register_adhesion(e).expect("built-in names are distinct");
        }
        for e in builtin_plasticity() {
            r.register_plasticity(e)
                .expect("built-in names are distinct");
        }
        r
    }

    /// Adds an adhesion law; its name must be new.
    pub fn register_adhesion(&mut self, entry: AdhesionEntry) -> Result<(), ModelError> {
        check_name(
            "adhesion",
            &entry.name,
            self.adhesion(&entry.name).is_some(),
        )?;
        self.adhesion.push(entry);
        Ok(())
    }

    /// Adds a plasticity law; its name must be new.
    pub fn register_plasticity(&mut self, entry: PlasticityEntry) -> Result<(), ModelError> {
        check_name(
            "plasticity",
            &entry.name,
            self.plasticity(&entry.name).is_some(),
        )?;
        self.plasticity.push(entry);
        Ok(())
    }

    /// The adhesion law `name`.
    pub fn adhesion(&self, name: &str) -> Option<&AdhesionEntry> {
        self.adhesion.iter().find(|e| e.name == name)
    }

    /// The plasticity law `name`.
    pub fn plasticity(&self, name: &str) -> Option<&PlasticityEntry> {
        self.plasticity.iter().find(|e| e.name == name)
    }

    /// The adhesion laws, in registration order.
    pub fn adhesion_laws(&self) -> &[AdhesionEntry] {
        &self.adhesion
    }

    /// The plasticity laws, in registration order.
    pub fn plasticity_laws(&self) -> &[PlasticityEntry] {
        &self.plasticity
    }

    /// The names of the adhesion laws.
    pub fn adhesion_names(&self) -> Vec<&str> {
        self.adhesion.iter().map(|e| e.name.as_str()).collect()
    }

    /// The names of the plasticity laws.
    pub fn plasticity_names(&self) -> Vec<&str> {
        self.plasticity.iter().map(|e| e.name.as_str()).collect()
    }
}

/// The Dugdale parameters of a context (w, z0 on the pair's K).
fn dugdale(ctx: &LawContext) -> DugdaleParams {
    DugdaleParams::for_pair(ctx.pair, ctx.work_of_adhesion, ctx.z0)
}

fn builtin_adhesion() -> Vec<AdhesionEntry> {
    vec![
        AdhesionEntry::new(
            "maugis_kim",
            "Maugis-Dugdale with the Kim extension out of contact (paper eqs 6-11; Maugis 1992, Kim, McMeeking & Johnson 1998)",
            vec![],
            |ctx| Ok(Arc::new(MaugisKim::new(dugdale(ctx))?)),
        ),
        AdhesionEntry::new(
            "jkr",
            "Johnson-Kendall-Roberts (1971): the Maugis-Dugdale limit lambda -> infinity",
            vec![],
            |ctx| {
                Ok(Arc::new(Jkr::new(JkrParams {
                    k: ctx.pair.k(),
                    work_of_adhesion: ctx.work_of_adhesion,
                })?))
            },
        ),
        AdhesionEntry::new(
            "dmt",
            "Derjaguin-Muller-Toporov (1975) with a Dugdale range z0: the limit lambda -> 0",
            vec![],
            |ctx| Ok(Arc::new(Dmt::new(dugdale(ctx))?)),
        ),
        AdhesionEntry::new(
            "hertz",
            "Hertz (1882): elastic contact without adhesion",
            vec![],
            |ctx| Ok(Arc::new(Hertz::new(ctx.pair.k())?)),
        ),
    ]
}

/// The parameters of `etsion_kadin`: the constants of eq 13.
pub const ETSION_KADIN_PARAMS: &[Param] = &[
    Param {
        name: "c1",
        unit: "-",
        domain: Domain::Triple,
        default: Default::Triple(EffectiveRadiusFit::PAPER.c1),
        help: "eq 13: c1 = a1 + a2 exp(-a3 delta_max/delta_CP)",
    },
    Param {
        name: "c2",
        unit: "-",
        domain: Domain::Triple,
        default: Default::Triple(EffectiveRadiusFit::PAPER.c2),
        help: "eq 13: c2 = b1/(1 + (delta_max/(b2 delta_CP))^2) - b3",
    },
];

/// The parameters of `adhesion_coupled`: the uncoupled law whose fits it drives.
pub const ADHESION_COUPLED_PARAMS: &[Param] = &[
    Param {
        name: "base",
        unit: "-",
        domain: Domain::Choice(&["etsion_kadin", "kogut_etsion"]),
        default: Default::Word("etsion_kadin"),
        help: "the uncoupled law whose state (eqs 4-5, 12) is read at the Hertz interference of the adhesive contact",
    },
    Param {
        name: "c1",
        unit: "-",
        domain: Domain::Triple,
        default: Default::Triple(EffectiveRadiusFit::PAPER.c1),
        help: "eq 13's c1 of the etsion_kadin base (as etsion_kadin's; `stiction calibrate` fits it)",
    },
    Param {
        name: "c2",
        unit: "-",
        domain: Domain::Triple,
        default: Default::Triple(EffectiveRadiusFit::PAPER.c2),
        help: "eq 13's c2 of the etsion_kadin base",
    },
];

fn builtin_plasticity() -> Vec<PlasticityEntry> {
    vec![
        PlasticityEntry::new(
            "etsion_kadin",
            "the paper's fits: yield onset eq 1 (Kogut-Etsion/Brizmer), residual height and radius eqs 4-5 (Kadin, Kligerman & Etsion 2006; Etsion, Kligerman & Kadin 2005), effective radius eqs 12-13",
            ETSION_KADIN_PARAMS.to_vec(),
            |ctx| {
                let fit = EffectiveRadiusFit::new(
                    ctx.params.triple("c1").unwrap_or(EffectiveRadiusFit::PAPER.c1),
                    ctx.params.triple("c2").unwrap_or(EffectiveRadiusFit::PAPER.c2),
                )?;
                Ok(Arc::new(
                    EtsionKadin::new(ctx.pair, ctx.yield_modulus)?.with_fit(fit),
                ))
            },
        ),
        PlasticityEntry::new(
            "kogut_etsion",
            "Kogut & Etsion (2002) loading with Etsion, Kligerman & Kadin (2005) unloading, radius-based through E* (docs/theory.md 2.7)",
            vec![],
            |ctx| Ok(Arc::new(KogutEtsion::new(ctx.pair, ctx.yield_modulus)?)),
        ),
        PlasticityEntry::new(
            "adhesion_coupled",
            "the state of etsion_kadin (or kogut_etsion) driven by the Hertz interference a^2/R of the adhesive contact, not the geometric interference alone: adhesion itself yields the asperity (Maugis & Pollock 1984; docs/theory.md 2.8)",
            ADHESION_COUPLED_PARAMS.to_vec(),
            |ctx| {
                let adhesion = ctx.adhesion.cloned().ok_or_else(|| {
                    LawError::from(contact_core::CoreError::Invalid {
                        field: "adhesion law",
                        value: f64::NAN,
                        allowed: "the scene's adhesion law (adhesion_coupled reads its contact radius)",
                    })
                })?;
                let base: DynPlasticity = match ctx.params.word("base") {
                    Some("kogut_etsion") => Arc::new(KogutEtsion::new(ctx.pair, ctx.yield_modulus)?),
                    _ => {
                        let fit = EffectiveRadiusFit::new(
                            ctx.params.triple("c1").unwrap_or(EffectiveRadiusFit::PAPER.c1),
                            ctx.params.triple("c2").unwrap_or(EffectiveRadiusFit::PAPER.c2),
                        )?;
                        Arc::new(EtsionKadin::new(ctx.pair, ctx.yield_modulus)?.with_fit(fit))
                    }
                };
                Ok(Arc::new(AdhesionCoupled::new(base, adhesion)?))
            },
        )
        .credible_where_adhesion_yields(),
        PlasticityEntry::new(
            "elastic",
            "never yields: the asperity keeps its radius and height",
            vec![],
            |ctx| Ok(Arc::new(Elastic::new(ctx.pair.radius())?)),
        )
        .not_credible(),
    ]
}

/// The pair of a contact section: the film against a rigid flat, itself, or another
/// material.
pub fn pair_of(
    film: contact_core::Material,
    counter: &Counter,
    radius: f64,
) -> Result<Pair, ModelError> {
    let counter = match *counter {
        Counter::Rigid => None,
        Counter::Same => Some(film),
        Counter::Material {
            youngs_modulus,
            poisson_ratio,
            yield_stress,
        } => Some(contact_core::Material::new(contact_core::MaterialProps {
            youngs_modulus,
            poisson_ratio,
            yield_stress,
        })?),
    };
    Ok(Pair::new(film, counter, radius)?)
}
