//! Every scene key in one place: its unit, its domain, its default, what it means, and
//! which scenes take it. Validation ([`crate::spec`]), the defaults a missing key takes,
//! the echo of a resolved scene, `stiction scene --print` (checked by a test), the design
//! commands' `section.key` fields and the domain table of `docs/validation.md` (checked by
//! a test) all read this table; nothing else states a domain or a default.

use std::fmt::Write as _;

/// Which scene files a key belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum Kind {
    /// One asperity loaded and unloaded (`stiction asperity`).
    Asperity,
    /// The rough surface (`stiction surface`, and `stiction law` on a surface).
    Surface,
    /// The micro-switch (`stiction switch`, `design`, `law`).
    Switch,
}

impl Kind {
    /// Every kind.
    pub const ALL: [Kind; 3] = [Kind::Asperity, Kind::Surface, Kind::Switch];

    /// The name scenes and messages use: `asperity`, `surface`, `switch`.
    pub fn as_str(self) -> &'static str {
        match self {
            Kind::Asperity => "asperity",
            Kind::Surface => "surface",
            Kind::Switch => "switch",
        }
    }
}

impl std::fmt::Display for Kind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

const ALL: &[Kind] = &[Kind::Asperity, Kind::Surface, Kind::Switch];
const ROUGH: &[Kind] = &[Kind::Surface, Kind::Switch];
const SWITCH: &[Kind] = &[Kind::Switch];
const SURFACE: &[Kind] = &[Kind::Surface];
const ASPERITY: &[Kind] = &[Kind::Asperity];

/// The values a key accepts.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Domain {
    /// A finite number between lo and hi, each end included unless marked open.
    Range {
        /// Lower bound.
        lo: f64,
        /// Upper bound.
        hi: f64,
        /// Whether lo itself is excluded.
        open_below: bool,
        /// Whether hi itself is excluded.
        open_above: bool,
    },
    /// A number in [lo, inf], infinity included (a yield stress: never yields).
    RangeOrInfinite {
        /// Lower bound.
        lo: f64,
    },
    /// An integer in [lo, hi].
    Count {
        /// Lower bound.
        lo: usize,
        /// Upper bound.
        hi: usize,
    },
    /// One of these words.
    Choice(&'static [&'static str]),
    /// A law name, looked up in the law registry (its names are listed in messages).
    Law,
    /// true or false.
    Flag,
    /// Free text.
    Text,
    /// Exactly three numbers, each finite and of magnitude at most [`TRIPLE_LIMIT`]
    /// (validated further by the law they parametrise).
    Triple,
    /// A non-empty list of interferences in (0, 1e3 radius] (asperity `delta_max`).
    Interferences,
    /// A table of a law's own parameters (checked against the law's parameter list).
    LawTable,
    /// A non-empty list of words of these choices (a model-form pin).
    ChoiceList(&'static [&'static str]),
    /// A non-empty list of registered law names (a model-form pin).
    LawList,
}

impl Domain {
    /// A closed range [lo, hi].
    pub const fn range(lo: f64, hi: f64) -> Self {
        Domain::Range {
            lo,
            hi,
            open_below: false,
            open_above: false,
        }
    }

    /// A range (lo, hi].
    pub const fn above(lo: f64, hi: f64) -> Self {
        Domain::Range {
            lo,
            hi,
            open_below: true,
            open_above: false,
        }
    }

    /// The domain in words, as error messages and the docs print it.
    pub fn describe(&self) -> String {
        match *self {
            Domain::Range {
                lo,
                hi,
                open_below,
                open_above,
            } => format!(
                "finite and in {}{}, {}{}",
                if open_below { "(" } else { "[" },
                num(lo),
                num(hi),
                if open_above { ")" } else { "]" }
            ),
            Domain::RangeOrInfinite { lo } => format!("in [{}, inf]", num(lo)),
            Domain::Count { lo, hi } => format!("an integer in [{lo}, {hi}]"),
            Domain::Choice(words) => format!("one of {}", words.join(", ")),
            Domain::Law => "the name of a registered law".into(),
            Domain::Flag => "true or false".into(),
            Domain::Text => "text".into(),
            Domain::Triple => format!(
                "three numbers, each finite and in [{}, {}]",
                num(-TRIPLE_LIMIT),
                num(TRIPLE_LIMIT)
            ),
            Domain::Interferences => "a non-empty list of values in (0, 1e3 radius]".into(),
            Domain::LawTable => "a table of the named law's parameters".into(),
            Domain::ChoiceList(words) => format!("a non-empty list of {}", words.join(", ")),
            Domain::LawList => "a non-empty list of registered law names".into(),
        }
    }

    /// Whether a number lies in a numeric domain (always false for the others).
    pub fn contains(&self, v: f64) -> bool {
        match *self {
            Domain::Range {
                lo,
                hi,
                open_below,
                open_above,
            } => {
                v.is_finite()
                    && (if open_below { v > lo } else { v >= lo })
                    && (if open_above { v < hi } else { v <= hi })
            }
            Domain::RangeOrInfinite { lo } => !v.is_nan() && v >= lo,
            Domain::Count { lo, hi } => v.fract() == 0.0 && v >= lo as f64 && v <= hi as f64,
            _ => false,
        }
    }

    /// Whether the key holds one number a design sweep may vary.
    pub fn is_numeric(&self) -> bool {
        matches!(
            self,
            Domain::Range { .. } | Domain::RangeOrInfinite { .. } | Domain::Count { .. }
        )
    }

    /// The ends of a numeric domain (inf for an unbounded one), for tests and tools.
    pub fn bounds(&self) -> Option<(f64, f64)> {
        match *self {
            Domain::Range { lo, hi, .. } => Some((lo, hi)),
            Domain::RangeOrInfinite { lo } => Some((lo, f64::INFINITY)),
            Domain::Count { lo, hi } => Some((lo as f64, hi as f64)),
            _ => None,
        }
    }
}

/// What a key takes when a scene leaves it out.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Default {
    /// Required: a scene must give it.
    Required,
    /// Optional, and its absence means something of its own (the help says what).
    Absent,
    /// Required when another key has a given value (the condition, as a scene writes it).
    RequiredWhen(&'static str),
    /// This number (SI).
    Number(f64),
    /// This count.
    Count(usize),
    /// This word.
    Word(&'static str),
    /// This flag.
    Flag(bool),
    /// These three numbers.
    Triple([f64; 3]),
    /// The value of another key of the same scene.
    Key(&'static str),
}

impl Default {
    /// The default as a scene would write it (None for `Required` and `Absent`).
    pub fn as_written(&self) -> Option<String> {
        match *self {
            Default::Required | Default::Absent | Default::RequiredWhen(_) => None,
            Default::Number(v) => Some(toml_number(v)),
            Default::Count(n) => Some(n.to_string()),
            Default::Word(w) => Some(format!("\"{w}\"")),
            Default::Flag(b) => Some(b.to_string()),
            Default::Triple(t) => Some(format!(
                "[{}, {}, {}]",
                toml_number(t[0]),
                toml_number(t[1]),
                toml_number(t[2])
            )),
            Default::Key(k) => Some(k.to_string()),
        }
    }
}

/// One scene key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Key {
    /// `section.key` (or `key` at the top level).
    pub key: &'static str,
    /// SI unit ("-" for a pure number, "" for words).
    pub unit: &'static str,
    /// What it accepts.
    pub domain: Domain,
    /// What it takes when left out.
    pub default: Default,
    /// What it means.
    pub help: &'static str,
    /// Which scenes take it.
    pub scenes: &'static [Kind],
}

impl Key {
    /// The last part of the key (`youngs_modulus` of `contact.youngs_modulus`).
    pub fn leaf(&self) -> &'static str {
        self.key.rsplit('.').next().unwrap_or(self.key)
    }

    /// Whether a scene of `kind` takes this key.
    pub fn in_kind(&self, kind: Kind) -> bool {
        self.scenes.contains(&kind)
    }
}

const POISSON: Domain = Domain::Range {
    lo: 0.0,
    hi: 0.5,
    open_below: false,
    open_above: true,
};

/// The largest magnitude of a number of a [`Domain::Triple`] (a law's fitted constants,
/// such as eq 13's, of order 0.1 to 10): beyond it a constant is no fit of an asperity, and
/// the law's radii and forces would overflow on the way (a constant of 1e308) instead of
/// refusing the key that gave it.
pub const TRIPLE_LIMIT: f64 = 1e6;

/// The readings of eq 1.
pub const YIELD_MODULI: &[&str] = &["as_printed", "composite"];
/// The reload rules of an asperity pressed beyond yield.
pub const RELOADS: &[&str] = &["as_printed", "bounded"];
/// The counter-surfaces.
pub const COUNTERS: &[&str] = &["rigid", "same", "material"];
/// The accuracy modes.
pub const ACCURACIES: &[&str] = &["accurate", "balanced", "fast", "reference"];
/// When the contact state of a switch is computed.
pub const CONTACT_STATES: &[&str] = &["every_cycle", "last_cycle", "none"];
/// Whether a run is checked against the other published model forms (docs/theory.md
/// section 12).
pub const MODEL_FORMS: &[&str] = &["single", "check"];
/// The scene kinds, as the optional `kind` key names them.
pub const KINDS: &[&str] = &["asperity", "surface", "switch"];
/// The routes of a measured surface's GW parameters (`surface.topography_route`).
pub const TOPOGRAPHY_ROUTES: &[&str] = &["summits", "spectral"];
/// The forms removed from a measured surface first (`surface.topography_detrend`).
pub const TOPOGRAPHY_DETRENDS: &[&str] = &[
    "mean", "plane", "poly:2", "poly:3", "poly:4", "poly:5", "poly:6",
];
/// What a measured surface's undefined points get (`surface.topography_undefined`).
pub const TOPOGRAPHY_UNDEFINED: &[&str] = &["refuse", "fill"];
/// Height units of a height-map file that states none (`surface.topography_height_unit`).
pub const LENGTH_UNITS: &[&str] = &["m", "mm", "um", "nm", "pm", "angstrom"];
/// The height-map formats (`surface.topography_file_format`; `topography::Format::name`).
pub const TOPOGRAPHY_FORMATS: &[&str] = &[
    "text",
    "xyz",
    "npy",
    "gsf",
    "gwy",
    "x3p",
    "nanoscope",
    "opd",
    "metropro",
    "sur",
    "plu",
    "vk4",
    "sdf",
];

/// Every key of every scene.
#[rustfmt::skip]
pub const KEYS: &[Key] = &[
    Key { key: "kind", unit: "", domain: Domain::Choice(KINDS), default: Default::Absent, help: "the scene's kind (default: inferred, delta_max for asperity, [switch] for switch, else surface)", scenes: ALL },
    Key { key: "title", unit: "", domain: Domain::Text, default: Default::Absent, help: "title of plots and tables (default: the scene file's name)", scenes: ALL },
    Key { key: "contact.youngs_modulus", unit: "Pa", domain: Domain::range(1e6, 1e13), default: Default::Required, help: "Young's modulus E of the asperity-carrying film", scenes: ALL },
    Key { key: "contact.poisson_ratio", unit: "-", domain: POISSON, default: Default::Required, help: "Poisson ratio nu", scenes: ALL },
    Key { key: "contact.yield_stress", unit: "Pa", domain: Domain::RangeOrInfinite { lo: 1e3 }, default: Default::Required, help: "yield stress S_Y (inf: never yields, with plasticity_law = \"elastic\")", scenes: ALL },
    Key { key: "contact.radius", unit: "m", domain: Domain::range(1e-9, 1e-2), default: Default::Required, help: "asperity tip radius R (the equivalent radius of eq 6 for two rough surfaces)", scenes: ALL },
    Key { key: "contact.work_of_adhesion", unit: "J/m^2", domain: Domain::range(1e-6, 100.0), default: Default::Required, help: "work of adhesion w", scenes: ALL },
    Key { key: "contact.z0", unit: "m", domain: Domain::range(1e-12, 1e-6), default: Default::Required, help: "Dugdale range z0 (sigma0 = w/z0)", scenes: ALL },
    Key { key: "contact.counter", unit: "", domain: Domain::Choice(COUNTERS), default: Default::Required, help: "counter-surface: rigid, same (the same film), or material (give the counter_* keys)", scenes: ALL },
    Key { key: "contact.counter_youngs_modulus", unit: "Pa", domain: Domain::range(1e6, 1e13), default: Default::RequiredWhen("counter = \"material\""), help: "counter-surface E, required with counter = \"material\"", scenes: ALL },
    Key { key: "contact.counter_poisson_ratio", unit: "-", domain: POISSON, default: Default::RequiredWhen("counter = \"material\""), help: "counter-surface nu, required with counter = \"material\"", scenes: ALL },
    Key { key: "contact.counter_yield_stress", unit: "Pa", domain: Domain::RangeOrInfinite { lo: 1e3 }, default: Default::Number(f64::INFINITY), help: "counter-surface S_Y, with counter = \"material\"; the body that yields first (smaller delta_CP) governs plasticity", scenes: ALL },
    Key { key: "contact.resistivity", unit: "ohm m", domain: Domain::range(1e-9, 1e-3), default: Default::Absent, help: "resistivity rho of the films, for the contact resistance (absent: none computed); Au 2.2e-8, Ru 7.1e-8 (bulk, 295 K; thin films run higher)", scenes: SWITCH },
    Key { key: "contact.mean_free_path", unit: "m", domain: Domain::range(1e-11, 1e-6), default: Default::RequiredWhen("resistivity"), help: "electron mean free path lambda of the films (Sharvin-Holm interpolation; needed with resistivity); Au 37.7e-9, Ru 6.6e-9 (Gall 2016)", scenes: SWITCH },
    Key { key: "contact.adhesion_law", unit: "", domain: Domain::Law, default: Default::Word("maugis_kim"), help: "adhesion law of one asperity (built in: maugis_kim, jkr, dmt, hertz); its own parameters in [contact.adhesion]", scenes: ALL },
    Key { key: "contact.plasticity_law", unit: "", domain: Domain::Law, default: Default::Word("etsion_kadin"), help: "plasticity law of one asperity (built in: etsion_kadin, kogut_etsion, adhesion_coupled, elastic); its own parameters in [contact.plasticity]", scenes: ALL },
    Key { key: "contact.yield_modulus", unit: "", domain: Domain::Choice(YIELD_MODULI), default: Default::Required, help: "the modulus of eq 1 (required): \"as_printed\" uses the film's E as the paper prints it (its scenes); \"composite\" uses the pair's E* (Kogut-Etsion), as the fits' sources define the yield onset (recommended for new scenes, theory 12.3). About 100x on the paper switch's pull-out; model_form = \"check\" shows whether it decides the verdict", scenes: ALL },
    Key { key: "contact.reload", unit: "", domain: Domain::Choice(RELOADS), default: Default::Word("as_printed"), help: "reload and unload of a yielded asperity: \"as_printed\" follows eq 12 as the paper prints it (stiffer than virgin loading beyond about 16 delta_CP, theory 2.5); \"bounded\" caps the force at the virgin loading force at the same interference (recommended for new scenes, soft films above all)", scenes: ALL },
    Key { key: "contact.adhesion", unit: "", domain: Domain::LawTable, default: Default::Absent, help: "parameters of the adhesion law, if it takes any (the built-in laws take none: w and z0 above)", scenes: ALL },
    Key { key: "contact.plasticity", unit: "", domain: Domain::LawTable, default: Default::Absent, help: "parameters of the plasticity law (etsion_kadin: c1, c2 of eq 13, also accepted as [contact.effective_radius])", scenes: ALL },
    Key { key: "contact.effective_radius", unit: "", domain: Domain::LawTable, default: Default::Absent, help: "the paper's name for the [contact.plasticity] table of etsion_kadin (c1, c2 of eq 13); with another plasticity law it is checked and not used, so that a scene switches laws by one key", scenes: ALL },
    Key { key: "delta_max", unit: "m", domain: Domain::Interferences, default: Default::Required, help: "maximum interferences, each loaded and unloaded", scenes: ASPERITY },
    Key { key: "points", unit: "-", domain: Domain::Count { lo: 0, hi: 100_000 }, default: Default::Count(200), help: "points per written curve (0: no curves; asperity and surface need at least 2); searches never depend on it", scenes: ALL },
    Key { key: "accuracy", unit: "", domain: Domain::Choice(ACCURACIES), default: Default::Word("accurate"), help: "error targets, see docs/performance.md", scenes: ALL },
    Key { key: "surface.sigma_s", unit: "m", domain: Domain::range(1e-11, 1e-6), default: Default::Required, help: "standard deviation of asperity heights sigma_s (equivalent surface)", scenes: ROUGH },
    Key { key: "surface.asperity_density", unit: "1/m^2", domain: Domain::range(1e9, 1e17), default: Default::Required, help: "asperities per unit area N (1e13 = 10 per um^2)", scenes: ROUGH },
    Key { key: "surface.topography", unit: "", domain: Domain::Text, default: Default::Absent, help: "a measured height-map file (any format `stiction topography` reads; a relative path is relative to the scene file's folder) whose GW parameters set surface.sigma_s, surface.asperity_density and, unless the scene gives it, contact.radius; a key the scene gives wins, with a note naming both values (docs/topography.md section 11)", scenes: ROUGH },
    Key { key: "surface.topography_route", unit: "", domain: Domain::Choice(TOPOGRAPHY_ROUTES), default: Default::Word("summits"), help: "which analysis of the map gives the parameters: summits (the grid's local maxima) or spectral (McCool's formulas on the moments); a map without summits gives the spectral route's", scenes: ROUGH },
    Key { key: "surface.topography_cutoff", unit: "m", domain: Domain::range(0.0, 1.0), default: Default::Absent, help: "short-wavelength cutoff: the map is low-pass filtered at this wavelength (Gaussian, ISO 16610-61) before the analysis, at most half the scan (absent: 4 sqrt(R sigma_s), four contact-spot radii, when the scene gives contact.radius, else 0; 0: the map as sampled)", scenes: ROUGH },
    Key { key: "surface.topography_detrend", unit: "", domain: Domain::Choice(TOPOGRAPHY_DETRENDS), default: Default::Word("plane"), help: "the form removed from the map first: its mean, its mean plane, or a polynomial of degree 2 to 6", scenes: ROUGH },
    Key { key: "surface.topography_spacing", unit: "m", domain: Domain::range(1e-12, 1.0), default: Default::Absent, help: "grid spacing of a map file that gives none (text, npy); overrides the file's (absent: the file's)", scenes: ROUGH },
    Key { key: "surface.topography_height_unit", unit: "", domain: Domain::Choice(LENGTH_UNITS), default: Default::Absent, help: "unit of the heights of a map file that states none (absent: the file's)", scenes: ROUGH },
    Key { key: "surface.topography_undefined", unit: "", domain: Domain::Choice(TOPOGRAPHY_UNDEFINED), default: Default::Word("refuse"), help: "the map's undefined points (instrument markers, NaN): refuse the map, or fill them by harmonic interpolation", scenes: ROUGH },
    Key { key: "surface.topography_channel", unit: "", domain: Domain::Text, default: Default::Absent, help: "the channel of a file with several, by name or 0-based index (absent: the first height channel)", scenes: ROUGH },
    Key { key: "surface.topography_file_format", unit: "", domain: Domain::Choice(TOPOGRAPHY_FORMATS), default: Default::Absent, help: "the map file's format (absent: from its first bytes, else its extension)", scenes: ROUGH },
    Key { key: "d_start", unit: "m", domain: Domain::range(-2e-5, 2e-5), default: Default::Absent, help: "smallest separation of the loading curve (default: unload_from, else 0); also within 20 sigma_s of the mean plane", scenes: SURFACE },
    Key { key: "unload_from", unit: "m", domain: Domain::range(-2e-5, 2e-5), default: Default::Absent, help: "load to this separation and unload from it (absent: loading only); also within 20 sigma_s of the mean plane", scenes: SURFACE },
    Key { key: "cycles", unit: "-", domain: Domain::Count { lo: 1, hi: 1000 }, default: Default::Count(10), help: "impact cycles (the cap with until_accommodated)", scenes: SWITCH },
    Key { key: "until_accommodated", unit: "", domain: Domain::Flag, default: Default::Flag(false), help: "stop once accommodated", scenes: SWITCH },
    Key { key: "accommodation_tolerance", unit: "-", domain: Domain::above(0.0, 0.1), default: Default::Number(1e-3), help: "relative change of pull-out (and of d_e in sigma_s) below which the next cycle counts as accommodated", scenes: SWITCH },
    Key { key: "contact_state", unit: "", domain: Domain::Choice(CONTACT_STATES), default: Default::Word("every_cycle"), help: "when the contact state (rest under the hold voltage, real contact area, spots, contact resistance) is computed: every_cycle, last_cycle (design points) or none", scenes: SWITCH },
    Key { key: "model_form", unit: "", domain: Domain::Choice(MODEL_FORMS), default: Default::Word("single"), help: "single: the scene's own modelling choices; check: the run is repeated under every combination of the credible published forms (plasticity law, eq-1 reading, reload rule, adhesion law by the Tabor parameter) and the report says whether any changes the verdict (theory 12)", scenes: SWITCH },
    Key { key: "model_form_plasticity", unit: "", domain: Domain::LawList, default: Default::Absent, help: "pins the plasticity laws a model-form check tries (default: the scene's and every registered plastic law)", scenes: SWITCH },
    Key { key: "model_form_yield_modulus", unit: "", domain: Domain::ChoiceList(YIELD_MODULI), default: Default::Absent, help: "pins the eq-1 readings a model-form check tries (default: both)", scenes: SWITCH },
    Key { key: "model_form_reload", unit: "", domain: Domain::ChoiceList(RELOADS), default: Default::Absent, help: "pins the reload rules a model-form check tries (default: both)", scenes: SWITCH },
    Key { key: "model_form_adhesion", unit: "", domain: Domain::LawList, default: Default::Absent, help: "pins the adhesion laws a model-form check tries (default: the scene's, maugis_kim, jkr where lambda >= 5, dmt where lambda <= 0.1)", scenes: SWITCH },
    Key { key: "elastic_comparison", unit: "", domain: Domain::Flag, default: Default::Flag(true), help: "also run the surface with elastic asperities (one cycle)", scenes: SWITCH },
    Key { key: "switch.d0", unit: "m", domain: Domain::range(1e-9, 1e-3), default: Default::Required, help: "initial air gap d0", scenes: SWITCH },
    Key { key: "switch.dimple_height", unit: "m", domain: Domain::range(0.0, 1e-3), default: Default::Number(0.0), help: "air gap at which the contact (dimples or a bump, area fraction contact_area_fraction) touches, below d0: the electrode travels d0 - dimple_height, the electrostatic gap at contact is dimple_height + t_d/epsilon_r, the spring pulls back with K_s (d0 - dimple_height) (default 0: the electrode lands on the dielectric, as in the paper)", scenes: SWITCH },
    Key { key: "switch.t_d", unit: "m", domain: Domain::range(1e-10, 1e-3), default: Default::Required, help: "dielectric thickness t_d", scenes: SWITCH },
    Key { key: "switch.epsilon_r", unit: "-", domain: Domain::range(1.0, 1e4), default: Default::Required, help: "relative permittivity of the dielectric", scenes: SWITCH },
    Key { key: "switch.epsilon_0", unit: "F/m", domain: Domain::range(1e-12, 1e-10), default: Default::Number(8.854e-12), help: "vacuum permittivity", scenes: SWITCH },
    Key { key: "switch.film_thickness", unit: "m", domain: Domain::range(1e-10, 1e-3), default: Default::Required, help: "film thickness t_s of eq 17", scenes: SWITCH },
    Key { key: "switch.film_youngs_modulus", unit: "Pa", domain: Domain::range(1e6, 1e13), default: Default::Key("contact.youngs_modulus"), help: "Young's modulus of the film in eq 17 (default: the contact material's)", scenes: SWITCH },
    Key { key: "switch.impact_energy", unit: "J/m^2", domain: Domain::range(1e-9, 100.0), default: Default::RequiredWhen("neither k_s nor spring_constant"), help: "drive A: impact energy E_I per electrode area; K_s is derived so that release at U = V_PI gives it", scenes: SWITCH },
    Key { key: "switch.k_s", unit: "Pa/m", domain: Domain::above(0.0, 1e20), default: Default::Absent, help: "drive B: spring stiffness per unit area K_s (instead of impact_energy); E_I is derived", scenes: SWITCH },
    Key { key: "switch.voltage", unit: "V", domain: Domain::above(0.0, 1e5), default: Default::Absent, help: "with k_s: the step voltage U (default V_PI); below the dynamic pull-in the switch does not close", scenes: SWITCH },
    Key { key: "switch.spring_constant", unit: "N/m", domain: Domain::above(0.0, 1e6), default: Default::Absent, help: "drive B as a spring constant: K_s = spring_constant / electrode_area (instead of k_s; give electrode_area)", scenes: SWITCH },
    Key { key: "switch.electrode_area", unit: "m^2", domain: Domain::range(1e-14, 1e-2), default: Default::Absent, help: "area of the movable electrode (needed with spring_constant, and for forces and contact resistances)", scenes: SWITCH },
    Key { key: "switch.hold_voltage", unit: "V", domain: Domain::range(0.0, 1e5), default: Default::Absent, help: "voltage that holds the switch shut after each impact (default: the actuation voltage U); the rest separation balances its electrostatic pressure minus the spring", scenes: SWITCH },
    Key { key: "switch.hold_force", unit: "N", domain: Domain::above(0.0, 10.0), default: Default::Absent, help: "force holding the closed switch on its contacts (instead of hold_voltage; needs electrode_area): for a dimpled switch whose electrode stays apart, e.g. from an FE model; the hold pressure per contact area is hold_force / (phi electrode_area)", scenes: SWITCH },
    Key { key: "switch.contact_area_fraction", unit: "-", domain: Domain::above(0.0, 1.0), default: Default::Number(1.0), help: "fraction phi of the electrode area that meets the substrate (contact dimples): it absorbs E_I/phi per contact area and adheres on phi of the area", scenes: SWITCH },
    Key { key: "dynamics.areal_mass", unit: "kg/m^2", domain: Domain::above(0.0, 1e3), default: Default::Absent, help: "mass of the movable electrode per unit area (a [dynamics] section integrates the switch in time: the impact energy becomes a result; one of areal_mass and resonance_frequency)", scenes: SWITCH },
    Key { key: "dynamics.resonance_frequency", unit: "Hz", domain: Domain::above(0.0, 1e10), default: Default::Absent, help: "the electrode's mechanical resonance f0 instead of areal_mass: m'' = K_s / (2 pi f0)^2", scenes: SWITCH },
    Key { key: "dynamics.gas_pressure", unit: "Pa", domain: Domain::range(0.0, 1e7), default: Default::Number(0.0), help: "pressure of the gas under the plate (0: vacuum, no squeeze film); needs switch.dimple_height > 0 (theory 13.2)", scenes: SWITCH },
    Key { key: "dynamics.gas_viscosity", unit: "Pa s", domain: Domain::range(1e-7, 1e-2), default: Default::Number(1.85e-5), help: "dynamic viscosity of the gas (default: air at 300 K)", scenes: SWITCH },
    Key { key: "dynamics.gas_mean_free_path", unit: "m", domain: Domain::range(1e-10, 1e-5), default: Default::Number(68e-9), help: "mean free path of the gas at 101325 Pa (default: air, 68 nm), scaled by 101325/gas_pressure (Veijola's rarefaction)", scenes: SWITCH },
    Key { key: "dynamics.plate_width", unit: "m", domain: Domain::range(1e-7, 1.0), default: Default::Absent, help: "width W of the plate over the squeeze film (default: the side of a square of switch.electrode_area)", scenes: SWITCH },
    Key { key: "dynamics.plate_length", unit: "m", domain: Domain::range(1e-7, 1.0), default: Default::Absent, help: "length L of the plate (default: plate_width)", scenes: SWITCH },
    Key { key: "dynamics.max_bounces", unit: "-", domain: Domain::Count { lo: 0, hi: 10000 }, default: Default::Count(50), help: "bounces allowed per closure before the run is refused (bounces that never decay)", scenes: SWITCH },
];

/// The key `key`, if any scene has it.
pub fn key(key: &str) -> Option<&'static Key> {
    KEYS.iter().find(|f| f.key == key)
}

/// The keys of one kind of scene, in table order.
pub fn of(kind: Kind) -> impl Iterator<Item = &'static Key> {
    KEYS.iter().filter(move |f| f.scenes.contains(&kind))
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

/// A number as a TOML file would write it: `1.0` for whole numbers below a million,
/// scientific notation otherwise (`1e-3`, `8.854e-12`), `inf` for infinity.
pub fn toml_number(v: f64) -> String {
    if v.is_finite() && v.fract() == 0.0 && v.abs() < 1e6 {
        format!("{v:.1}")
    } else {
        num(v)
    }
}

/// The scene-key table of `docs/validation.md`, generated from [`KEYS`]: key, unit,
/// domain, default, scenes. A test checks the document against it; `cargo xtask docs`
/// rewrites it.
pub fn markdown_table() -> String {
    let mut s =
        String::from("| key | unit | accepts | default | scenes |\n|---|---|---|---|---|\n");
    for f in KEYS {
        let scenes: Vec<&str> = f.scenes.iter().map(|k| k.as_str()).collect();
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} |",
            f.key,
            f.unit,
            f.domain.describe(),
            match f.default {
                Default::RequiredWhen(c) => format!("required with `{c}`"),
                d => d.as_written().map_or("-".to_string(), |d| format!("`{d}`")),
            },
            scenes.join(", ")
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_is_unique_and_in_some_scene() {
        for (i, k) in KEYS.iter().enumerate() {
            assert!(!k.scenes.is_empty(), "{}", k.key);
            assert!(
                KEYS[i + 1..].iter().all(|o| o.key != k.key),
                "{} twice",
                k.key
            );
        }
    }

    #[test]
    fn every_default_lies_in_its_domain() {
        for k in KEYS {
            match (k.default, k.domain) {
                (Default::Number(v), d) => assert!(d.contains(v), "{}: {v}", k.key),
                (Default::Count(n), d) => assert!(d.contains(n as f64), "{}: {n}", k.key),
                (Default::Word(w), Domain::Choice(words)) => {
                    assert!(words.contains(&w), "{}: {w}", k.key)
                }
                (Default::Word(_), Domain::Law) => {}
                (Default::Word(w), d) => panic!("{}: word {w} for {d:?}", k.key),
                (Default::Flag(_), d) => assert_eq!(d, Domain::Flag, "{}", k.key),
                (Default::Triple(t), d) => {
                    assert_eq!(d, Domain::Triple, "{}", k.key);
                    assert!(t.iter().all(|x| x.is_finite()));
                }
                (Default::Key(other), d) => {
                    let o = key(other).expect("default key exists");
                    assert_eq!(
                        o.domain, d,
                        "{} defaults to {other} of another domain",
                        k.key
                    );
                }
                (Default::Required | Default::Absent | Default::RequiredWhen(_), _) => {}
            }
        }
    }

    #[test]
    fn numbers_are_written_as_people_write_them() {
        assert_eq!(toml_number(1.0), "1.0");
        assert_eq!(toml_number(1e-3), "1e-3");
        assert_eq!(toml_number(8.854e-12), "8.854e-12");
        assert_eq!(toml_number(f64::INFINITY), "inf");
        assert_eq!(num(-410e9), "-4.1e11");
    }
}
