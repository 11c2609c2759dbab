//! Seeded random switch scenes over the documented domains (docs/validation.md section 6),
//! for measuring the accuracy modes where users go rather than at the paper's point.
//!
//! * [`Domain::Mems`]: plausible MEMS contacts: metal films (E 50-600 GPa, S_Y 0.2-5 GPa),
//!   asperity radii 0.5-20 um, w 0.05-2.5 J/m^2, z0 0.1-0.5 nm, sigma_s 0.5-30 nm,
//!   0.1-100 asperities per um^2, gaps 0.5-5 um, impact energies 1e-3-2 J/m^2.
//! * [`Domain::Wide`]: every scene key over the range a scene file accepts, log-uniform.
//! * [`Domain::Soft`]: soft films such as gold (E 50-100 GPa, S_Y 0.1-0.5 GPa, Poisson
//!   0.35-0.44; every plastic law, both eq-1 readings and reload rules; a counter-surface
//!   of the same film, rigid, or another soft film), the rest as MEMS contacts: the films
//!   that flatten most from cycle to cycle, where the reload tables carry each later cycle.
//!
//! Every built-in adhesion law, every plasticity law, both readings of eq 1, both reload
//! rules and all three counter-surfaces are drawn. A small SplitMix64 generator keeps the
//! scenes identical on every machine (the draws of the laws added later come after the
//! others, so earlier scenes keep their numbers).

use crate::scene::Scene;
use toml::Value;

/// Which documented domain to draw from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Domain {
    /// Plausible MEMS switch contacts.
    Mems,
    /// The whole range a scene file accepts.
    Wide,
    /// Soft films (gold-like), otherwise MEMS contacts.
    Soft,
}

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny, well-mixed, seedable generator.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// Log-uniform in [lo, hi).
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }
    /// One of `items`.
    pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[(self.next_u64() % items.len() as u64) as usize]
    }
}

/// A random switch scene (validate it before use: a rare draw, for instance a drive that
/// cannot reach the impact-energy domain, is refused like any scene). `file` names it.
pub fn switch_scene(rng: &mut Rng, domain: Domain, file: &str) -> Scene {
    let adhesion = rng.pick(&["maugis_kim", "maugis_kim", "jkr", "dmt", "hertz"]);
    let mut plasticity = rng.pick(&["etsion_kadin", "etsion_kadin", "etsion_kadin", "elastic"]);
    let yield_modulus = rng.pick(&["as_printed", "composite"]);
    let counter = rng.pick(&["same", "rigid", "material"]);
    let mut t = toml::Table::new();
    let mut contact = toml::Table::new();
    let mut surface = toml::Table::new();
    let mut switch = toml::Table::new();
    let f = Value::Float;
    let material = counter == "material";
    match domain {
        Domain::Mems | Domain::Soft => {
            contact.insert("youngs_modulus".into(), f(rng.log_uniform(50e9, 600e9)));
            contact.insert("poisson_ratio".into(), f(rng.uniform(0.2, 0.42)));
            contact.insert("yield_stress".into(), f(rng.log_uniform(0.2e9, 5e9)));
            contact.insert("radius".into(), f(rng.log_uniform(0.5e-6, 20e-6)));
            contact.insert("work_of_adhesion".into(), f(rng.log_uniform(0.05, 2.5)));
            contact.insert("z0".into(), f(rng.log_uniform(0.1e-9, 0.5e-9)));
            if material {
                contact.insert(
                    "counter_youngs_modulus".into(),
                    f(rng.log_uniform(50e9, 600e9)),
                );
                contact.insert("counter_poisson_ratio".into(), f(rng.uniform(0.2, 0.42)));
                contact.insert(
                    "counter_yield_stress".into(),
                    f(rng.log_uniform(0.2e9, 5e9)),
                );
            }
            surface.insert("sigma_s".into(), f(rng.log_uniform(0.5e-9, 30e-9)));
            surface.insert("asperity_density".into(), f(rng.log_uniform(1e11, 1e14)));
            switch.insert("d0".into(), f(rng.log_uniform(0.5e-6, 5e-6)));
            switch.insert("t_d".into(), f(rng.log_uniform(20e-9, 1e-6)));
            switch.insert("epsilon_r".into(), f(rng.uniform(3.0, 12.0)));
            switch.insert("film_thickness".into(), f(rng.log_uniform(20e-9, 2e-6)));
            switch.insert("impact_energy".into(), f(rng.log_uniform(1e-3, 2.0)));
            let phi = if rng.unit() < 0.25 {
                rng.uniform(0.05, 1.0)
            } else {
                1.0
            };
            switch.insert("contact_area_fraction".into(), f(phi));
        }
        Domain::Wide => {
            contact.insert("youngs_modulus".into(), f(rng.log_uniform(1e6, 1e13)));
            contact.insert("poisson_ratio".into(), f(rng.uniform(0.0, 0.49)));
            contact.insert("yield_stress".into(), f(rng.log_uniform(1e3, 1e11)));
            contact.insert("radius".into(), f(rng.log_uniform(1e-8, 1e-3)));
            contact.insert("work_of_adhesion".into(), f(rng.log_uniform(1e-6, 100.0)));
            contact.insert("z0".into(), f(rng.log_uniform(1e-11, 1e-7)));
            if material {
                contact.insert(
                    "counter_youngs_modulus".into(),
                    f(rng.log_uniform(1e6, 1e13)),
                );
                contact.insert("counter_poisson_ratio".into(), f(rng.uniform(0.0, 0.49)));
                contact.insert("counter_yield_stress".into(), f(rng.log_uniform(1e3, 1e11)));
            }
            surface.insert("sigma_s".into(), f(rng.log_uniform(1e-11, 1e-6)));
            surface.insert("asperity_density".into(), f(rng.log_uniform(1e9, 1e17)));
            switch.insert("d0".into(), f(rng.log_uniform(1e-8, 1e-3)));
            switch.insert("t_d".into(), f(rng.log_uniform(1e-10, 1e-4)));
            switch.insert("epsilon_r".into(), f(rng.log_uniform(1.0, 1e4)));
            switch.insert("film_thickness".into(), f(rng.log_uniform(1e-10, 1e-3)));
            switch.insert("impact_energy".into(), f(rng.log_uniform(1e-9, 100.0)));
            let phi = if rng.unit() < 0.25 {
                rng.log_uniform(1e-3, 1.0)
            } else {
                1.0
            };
            switch.insert("contact_area_fraction".into(), f(phi));
        }
    }
    // the laws added after the first measurements: drawn last
    if plasticity == "etsion_kadin" && rng.unit() < 1.0 / 3.0 {
        plasticity = "kogut_etsion";
    }
    if domain == Domain::Soft {
        // the film's own numbers, drawn after the others so that the MEMS draws keep theirs
        contact.insert("youngs_modulus".into(), f(rng.log_uniform(50e9, 100e9)));
        contact.insert("poisson_ratio".into(), f(rng.uniform(0.35, 0.44)));
        contact.insert("yield_stress".into(), f(rng.log_uniform(0.1e9, 0.5e9)));
        if material {
            contact.insert(
                "counter_youngs_modulus".into(),
                f(rng.log_uniform(50e9, 100e9)),
            );
            contact.insert("counter_poisson_ratio".into(), f(rng.uniform(0.35, 0.44)));
            contact.insert(
                "counter_yield_stress".into(),
                f(rng.log_uniform(0.1e9, 0.5e9)),
            );
        }
        // every plastic law (a soft film's point is its plasticity)
        plasticity = rng.pick(&["etsion_kadin", "kogut_etsion"]);
    }
    let reload = rng.pick(&["as_printed", "bounded"]);
    // adhesion_coupled (issue 43) on a share of the plastic scenes, chosen from the bits of
    // the scene's own yield stress rather than a new draw, so that every scene drawn before
    // it was added keeps its numbers: a quarter of the MEMS and wide scenes, half the soft
    // films (the law's point), on the law that was drawn as its base
    if plasticity != "elastic" {
        let bits = contact
            .get("yield_stress")
            .and_then(Value::as_float)
            .map_or(0, |v| v.to_bits() >> 20);
        let share = if domain == Domain::Soft { 2 } else { 4 };
        if bits.is_multiple_of(share) {
            let mut table = toml::Table::new();
            table.insert("base".into(), Value::String(plasticity.into()));
            contact.insert("plasticity".into(), Value::Table(table));
            plasticity = "adhesion_coupled";
        }
    }
    let s = |w: &str| Value::String(w.into());
    contact.insert("counter".into(), s(counter));
    contact.insert("adhesion_law".into(), s(adhesion));
    contact.insert("plasticity_law".into(), s(plasticity));
    contact.insert("yield_modulus".into(), s(yield_modulus));
    contact.insert("reload".into(), s(reload));
    t.insert("cycles".into(), Value::Integer(4));
    t.insert("until_accommodated".into(), Value::Boolean(false));
    t.insert("elastic_comparison".into(), Value::Boolean(false));
    t.insert("points".into(), Value::Integer(0));
    t.insert("accuracy".into(), s("accurate"));
    t.insert("contact".into(), Value::Table(contact));
    t.insert("surface".into(), Value::Table(surface));
    t.insert("switch".into(), Value::Table(switch));
    Scene::from_tree(file, t)
}

/// The scene as TOML text (to reproduce a flagged scene from a file).
pub fn to_toml(scene: &Scene) -> String {
    toml::to_string(scene.tree()).unwrap_or_default()
}
