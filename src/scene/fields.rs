//! Every scene key in one place: its unit, its domain, what it means, and which scenes take
//! it. Validation, `scene --print`, the design commands' `section.key` fields and the
//! domain table of `docs/validation.md` (checked by a test) all read this table.

/// Which scene files a key belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// `stiction asperity`.
    Asperity,
    /// `stiction surface`.
    Surface,
    /// `stiction switch` (and the design and law commands, which read switch scenes).
    Switch,
}

const ALL: &[Kind] = &[Kind::Asperity, Kind::Surface, Kind::Switch];
const ROUGH: &[Kind] = &[Kind::Surface, Kind::Switch];
const SWITCH: &[Kind] = &[Kind::Switch];
const SURFACE: &[Kind] = &[Kind::Surface];
const ASPERITY: &[Kind] = &[Kind::Asperity];

/// The values a key accepts.
#[derive(Debug, Clone, Copy, PartialEq)]
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
    /// A number in [lo, hi], where hi may be infinite (yield stress).
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
    /// true or false.
    Flag,
    /// Free text.
    Text,
    /// Three finite numbers (validated by the law they parametrise).
    Triple,
    /// A list of numbers in (0, hi * radius] (asperity `delta_max`).
    Interferences,
}

impl Domain {
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
                super::num(lo),
                super::num(hi),
                if open_above { ")" } else { "]" }
            ),
            Domain::RangeOrInfinite { lo } => format!("in [{}, inf]", super::num(lo)),
            Domain::Count { lo, hi } => format!("an integer in [{lo}, {hi}]"),
            Domain::Choice(words) => format!("one of {}", words.join(", ")),
            Domain::Flag => "true or false".into(),
            Domain::Text => "text".into(),
            Domain::Triple => "three finite numbers".into(),
            Domain::Interferences => "a non-empty list of values in (0, 1e3 radius]".into(),
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
}

/// One scene key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Field {
    /// `section.key` (or `key` at the top level).
    pub key: &'static str,
    /// SI unit ("-" for a pure number, "" for words).
    pub unit: &'static str,
    /// What it accepts.
    pub domain: Domain,
    /// The default when the key may be left out (as written in a scene), or None when
    /// required or when absence has a meaning of its own (then `help` says which).
    pub default: Option<&'static str>,
    /// What it means.
    pub help: &'static str,
    /// Which scenes take it.
    pub scenes: &'static [Kind],
}

const fn range(lo: f64, hi: f64) -> Domain {
    Domain::Range {
        lo,
        hi,
        open_below: false,
        open_above: false,
    }
}

const fn above(lo: f64, hi: f64) -> Domain {
    Domain::Range {
        lo,
        hi,
        open_below: true,
        open_above: false,
    }
}

const POISSON: Domain = Domain::Range {
    lo: 0.0,
    hi: 0.5,
    open_below: false,
    open_above: true,
};

/// The adhesion laws a scene may name.
pub const ADHESION_LAWS: &[&str] = &["maugis_kim", "jkr", "dmt", "hertz"];
/// The plasticity laws.
pub const PLASTICITY_LAWS: &[&str] = &["etsion_kadin", "elastic"];
/// The readings of eq 1.
pub const YIELD_MODULI: &[&str] = &["as_printed", "composite"];
/// The counter-surfaces.
pub const COUNTERS: &[&str] = &["rigid", "same", "material"];
/// The accuracy modes.
pub const ACCURACIES: &[&str] = &["accurate", "balanced", "fast", "reference"];

/// Every key of every scene.
#[rustfmt::skip]
pub const FIELDS: &[Field] = &[
    Field { key: "title", unit: "", domain: Domain::Text, default: None, help: "title of plots and tables (default: the scene file's name)", scenes: ALL },
    Field { key: "contact.youngs_modulus", unit: "Pa", domain: range(1e6, 1e13), default: None, help: "Young's modulus E of the asperity-carrying film", scenes: ALL },
    Field { key: "contact.poisson_ratio", unit: "-", domain: POISSON, default: None, help: "Poisson ratio nu", scenes: ALL },
    Field { key: "contact.yield_stress", unit: "Pa", domain: Domain::RangeOrInfinite { lo: 1e3 }, default: None, help: "yield stress S_Y (inf: never yields, with plasticity_law = \"elastic\")", scenes: ALL },
    Field { key: "contact.radius", unit: "m", domain: range(1e-9, 1e-2), default: None, help: "asperity tip radius R (the equivalent radius of eq 6 for two rough surfaces)", scenes: ALL },
    Field { key: "contact.work_of_adhesion", unit: "J/m^2", domain: range(1e-6, 100.0), default: None, help: "work of adhesion w", scenes: ALL },
    Field { key: "contact.z0", unit: "m", domain: range(1e-12, 1e-6), default: None, help: "Dugdale range z0 (sigma0 = w/z0)", scenes: ALL },
    Field { key: "contact.counter", unit: "", domain: Domain::Choice(COUNTERS), default: None, help: "counter-surface: rigid, same (the same film), or material (give the counter_* keys)", scenes: ALL },
    Field { key: "contact.counter_youngs_modulus", unit: "Pa", domain: range(1e6, 1e13), default: None, help: "counter-surface E, with counter = \"material\"", scenes: ALL },
    Field { key: "contact.counter_poisson_ratio", unit: "-", domain: POISSON, default: None, help: "counter-surface nu, with counter = \"material\"", scenes: ALL },
    Field { key: "contact.counter_yield_stress", unit: "Pa", domain: Domain::RangeOrInfinite { lo: 1e3 }, default: Some("inf"), help: "counter-surface S_Y, with counter = \"material\"; the body that yields first (smaller delta_CP) governs plasticity", scenes: ALL },
    Field { key: "contact.adhesion_law", unit: "", domain: Domain::Choice(ADHESION_LAWS), default: Some("\"maugis_kim\""), help: "adhesion law of one asperity", scenes: ALL },
    Field { key: "contact.plasticity_law", unit: "", domain: Domain::Choice(PLASTICITY_LAWS), default: Some("\"etsion_kadin\""), help: "plasticity law of one asperity", scenes: ALL },
    Field { key: "contact.yield_modulus", unit: "", domain: Domain::Choice(YIELD_MODULI), default: None, help: "the modulus of eq 1 (required): \"as_printed\" uses the film's E as the paper prints it (its scenes); \"composite\" uses the pair's E* (Kogut-Etsion). About 100x on the paper switch's pull-out", scenes: ALL },
    Field { key: "contact.effective_radius.c1", unit: "-", domain: Domain::Triple, default: Some("[0.22, 0.6242, 0.092]"), help: "eq 13: c1 = a1 + a2 exp(-a3 delta_max/delta_CP)", scenes: ALL },
    Field { key: "contact.effective_radius.c2", unit: "-", domain: Domain::Triple, default: Some("[10.0, 10.0, 5.0]"), help: "eq 13: c2 = b1/(1 + (delta_max/(b2 delta_CP))^2) - b3", scenes: ALL },
    Field { key: "delta_max", unit: "m", domain: Domain::Interferences, default: None, help: "maximum interferences, each loaded and unloaded", scenes: ASPERITY },
    Field { key: "points", unit: "-", domain: Domain::Count { lo: 0, hi: 100_000 }, default: Some("200"), help: "points per written curve (0: no curves; asperity and surface need at least 2); searches never depend on it", scenes: ALL },
    Field { key: "accuracy", unit: "", domain: Domain::Choice(ACCURACIES), default: Some("\"accurate\""), help: "error targets, see docs/performance.md", scenes: ALL },
    Field { key: "surface.sigma_s", unit: "m", domain: range(1e-11, 1e-6), default: None, help: "standard deviation of asperity heights sigma_s (equivalent surface)", scenes: ROUGH },
    Field { key: "surface.asperity_density", unit: "1/m^2", domain: range(1e9, 1e17), default: None, help: "asperities per unit area N (1e13 = 10 per um^2)", scenes: ROUGH },
    Field { key: "d_start", unit: "m", domain: range(-1e-6, 1e-6), default: None, help: "smallest separation of the loading curve (default: unload_from, else 0); within 20 sigma_s", scenes: SURFACE },
    Field { key: "unload_from", unit: "m", domain: range(-1e-6, 1e-6), default: None, help: "load to this separation and unload from it (absent: loading only); within 20 sigma_s", scenes: SURFACE },
    Field { key: "cycles", unit: "-", domain: Domain::Count { lo: 1, hi: 1000 }, default: Some("10"), help: "impact cycles (the cap with until_accommodated)", scenes: SWITCH },
    Field { key: "until_accommodated", unit: "", domain: Domain::Flag, default: Some("false"), help: "stop once accommodated", scenes: SWITCH },
    Field { key: "accommodation_tolerance", unit: "-", domain: above(0.0, 0.1), default: Some("1e-3"), help: "relative change of pull-out (and of d_e in sigma_s) below which the next cycle counts as accommodated", scenes: SWITCH },
    Field { key: "elastic_comparison", unit: "", domain: Domain::Flag, default: Some("true"), help: "also run the surface with elastic asperities (one cycle)", scenes: SWITCH },
    Field { key: "switch.d0", unit: "m", domain: range(1e-9, 1e-3), default: None, help: "initial air gap d0", scenes: SWITCH },
    Field { key: "switch.t_d", unit: "m", domain: range(1e-10, 1e-3), default: None, help: "dielectric thickness t_d", scenes: SWITCH },
    Field { key: "switch.epsilon_r", unit: "-", domain: range(1.0, 1e4), default: None, help: "relative permittivity of the dielectric", scenes: SWITCH },
    Field { key: "switch.epsilon_0", unit: "F/m", domain: range(1e-12, 1e-10), default: Some("8.854e-12"), help: "vacuum permittivity", scenes: SWITCH },
    Field { key: "switch.film_thickness", unit: "m", domain: range(1e-10, 1e-3), default: None, help: "film thickness t_s of eq 17", scenes: SWITCH },
    Field { key: "switch.film_youngs_modulus", unit: "Pa", domain: range(1e6, 1e13), default: Some("contact.youngs_modulus"), help: "Young's modulus of the film in eq 17 (default: the contact material's)", scenes: SWITCH },
    Field { key: "switch.impact_energy", unit: "J/m^2", domain: range(1e-9, 100.0), default: None, help: "drive A: impact energy E_I per electrode area; K_s is derived so that release at U = V_PI gives it", scenes: SWITCH },
    Field { key: "switch.k_s", unit: "Pa/m", domain: above(0.0, 1e20), default: None, help: "drive B: spring stiffness per unit area K_s (instead of impact_energy); E_I is derived", scenes: SWITCH },
    Field { key: "switch.voltage", unit: "V", domain: above(0.0, 1e5), default: None, help: "with k_s: the step voltage U (default V_PI); below the dynamic pull-in the switch does not close", scenes: SWITCH },
    Field { key: "switch.contact_area_fraction", unit: "-", domain: above(0.0, 1.0), default: Some("1.0"), help: "fraction phi of the electrode area that meets the substrate (contact dimples): it absorbs E_I/phi per contact area and adheres on phi of the area", scenes: SWITCH },
];

/// The field of `key`, if any scene has it.
pub fn field(key: &str) -> Option<&'static Field> {
    FIELDS.iter().find(|f| f.key == key)
}

/// A clap value parser for an option that replaces the count field `key`: an integer in
/// the field's domain, with the domain in the message otherwise (`--cycles -1`: "must be
/// an integer in [1, 1000]", not a parse error about digits).
pub fn count_option(key: &'static str) -> impl Fn(&str) -> Result<usize, String> + Clone {
    move |text: &str| {
        let f = field(key).unwrap_or_else(|| panic!("{key} is not in fields::FIELDS"));
        let Domain::Count { lo, hi } = f.domain else {
            panic!("{key} is not a count")
        };
        match text.trim().parse::<i128>() {
            Ok(v) if v >= lo as i128 && v <= hi as i128 => Ok(v as usize),
            _ => Err(format!("must be {}", f.domain.describe())),
        }
    }
}

/// The keys of one kind of scene, in table order.
pub fn of(kind: Kind) -> impl Iterator<Item = &'static Field> {
    FIELDS.iter().filter(move |f| f.scenes.contains(&kind))
}

/// The scene-field table of `docs/validation.md` (section 6), generated from [`FIELDS`]:
/// key, unit, domain, default, scenes. `tests/domains.rs` checks the document against it;
/// `cargo xtask docs` rewrites it.
pub fn markdown_table() -> String {
    let mut s =
        String::from("| key | unit | accepts | default | scenes |\n|---|---|---|---|---|\n");
    for f in FIELDS {
        let scenes: Vec<&str> = f
            .scenes
            .iter()
            .map(|k| match k {
                Kind::Asperity => "asperity",
                Kind::Surface => "surface",
                Kind::Switch => "switch",
            })
            .collect();
        let unit = if f.unit.is_empty() { "" } else { f.unit };
        s += &format!(
            "| `{}` | {} | {} | {} | {} |\n",
            f.key,
            unit,
            f.domain.describe(),
            f.default.map_or("-".to_string(), |d| format!("`{d}`")),
            scenes.join(", ")
        );
    }
    s
}
