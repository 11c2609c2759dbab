//! Seeded random switch scenes over the documented domains (docs/validation.md section 6),
//! for measuring the accuracy modes where users go rather than at the paper's point.
//!
//! * [`Domain::Mems`]: plausible MEMS contacts: metal films (E 50-600 GPa, S_Y 0.2-5 GPa),
//!   asperity radii 0.5-20 um, w 0.05-2.5 J/m^2, z0 0.1-0.5 nm, sigma_s 0.5-30 nm,
//!   0.1-100 asperities per um^2, gaps 0.5-5 um, impact energies 1e-3-2 J/m^2.
//! * [`Domain::Wide`]: every scene key over the range a scene file accepts, log-uniform.
//!
//! Every adhesion law, both plasticity laws, both readings of eq 1 and all three
//! counter-surfaces are drawn. A small SplitMix64 generator keeps the project free of a
//! random-number dependency and the scenes identical on every machine.

use crate::accuracy::Accuracy;
use crate::scene::{
    AdhesionKind, Contact, CounterKind, EffectiveRadius, PlasticityKind, Surface, SwitchGeometry,
    SwitchScene,
};
use asperity_plastic::YieldModulus;

/// Which documented domain to draw from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Domain {
    /// Plausible MEMS switch contacts.
    Mems,
    /// The whole range a scene file accepts.
    Wide,
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

/// A random valid switch scene (validate it before use: a rare draw, for instance a drive
/// that cannot reach the impact-energy domain, is refused like any scene).
pub fn switch_scene(rng: &mut Rng, domain: Domain) -> SwitchScene {
    let adhesion = rng.pick(&[
        AdhesionKind::MaugisKim,
        AdhesionKind::MaugisKim,
        AdhesionKind::Jkr,
        AdhesionKind::Dmt,
        AdhesionKind::Hertz,
    ]);
    let plasticity = rng.pick(&[
        PlasticityKind::EtsionKadin,
        PlasticityKind::EtsionKadin,
        PlasticityKind::EtsionKadin,
        PlasticityKind::Elastic,
    ]);
    let yield_modulus = rng.pick(&[YieldModulus::AsPrinted, YieldModulus::Composite]);
    let counter = rng.pick(&[CounterKind::Same, CounterKind::Rigid, CounterKind::Material]);
    let (contact, surface, switch) = match domain {
        Domain::Mems => {
            let e = rng.log_uniform(50e9, 600e9);
            let nu = rng.uniform(0.2, 0.42);
            let sy = rng.log_uniform(0.2e9, 5e9);
            let contact = Contact {
                youngs_modulus: e,
                poisson_ratio: nu,
                yield_stress: sy,
                radius: rng.log_uniform(0.5e-6, 20e-6),
                work_of_adhesion: rng.log_uniform(0.05, 2.5),
                z0: rng.log_uniform(0.1e-9, 0.5e-9),
                counter,
                counter_youngs_modulus: (counter == CounterKind::Material)
                    .then(|| rng.log_uniform(50e9, 600e9)),
                counter_poisson_ratio: (counter == CounterKind::Material)
                    .then(|| rng.uniform(0.2, 0.42)),
                counter_yield_stress: (counter == CounterKind::Material)
                    .then(|| rng.log_uniform(0.2e9, 5e9)),
                adhesion_law: adhesion,
                plasticity_law: plasticity,
                yield_modulus: Some(yield_modulus),
                effective_radius: EffectiveRadius::default(),
            };
            let surface = Surface {
                sigma_s: rng.log_uniform(0.5e-9, 30e-9),
                asperity_density: rng.log_uniform(1e11, 1e14),
            };
            let switch = SwitchGeometry {
                d0: rng.log_uniform(0.5e-6, 5e-6),
                t_d: rng.log_uniform(20e-9, 1e-6),
                epsilon_r: rng.uniform(3.0, 12.0),
                epsilon_0: switch_1d::EPSILON_0,
                film_thickness: rng.log_uniform(20e-9, 2e-6),
                film_youngs_modulus: None,
                impact_energy: Some(rng.log_uniform(1e-3, 2.0)),
                k_s: None,
                voltage: None,
                contact_area_fraction: if rng.unit() < 0.25 {
                    rng.uniform(0.05, 1.0)
                } else {
                    1.0
                },
            };
            (contact, surface, switch)
        }
        Domain::Wide => {
            let contact = Contact {
                youngs_modulus: rng.log_uniform(1e6, 1e13),
                poisson_ratio: rng.uniform(0.0, 0.49),
                yield_stress: rng.log_uniform(1e3, 1e11),
                radius: rng.log_uniform(1e-8, 1e-3),
                work_of_adhesion: rng.log_uniform(1e-6, 100.0),
                z0: rng.log_uniform(1e-11, 1e-7),
                counter,
                counter_youngs_modulus: (counter == CounterKind::Material)
                    .then(|| rng.log_uniform(1e6, 1e13)),
                counter_poisson_ratio: (counter == CounterKind::Material)
                    .then(|| rng.uniform(0.0, 0.49)),
                counter_yield_stress: (counter == CounterKind::Material)
                    .then(|| rng.log_uniform(1e3, 1e11)),
                adhesion_law: adhesion,
                plasticity_law: plasticity,
                yield_modulus: Some(yield_modulus),
                effective_radius: EffectiveRadius::default(),
            };
            let surface = Surface {
                sigma_s: rng.log_uniform(1e-11, 1e-6),
                asperity_density: rng.log_uniform(1e9, 1e17),
            };
            let switch = SwitchGeometry {
                d0: rng.log_uniform(1e-8, 1e-3),
                t_d: rng.log_uniform(1e-10, 1e-4),
                epsilon_r: rng.log_uniform(1.0, 1e4),
                epsilon_0: switch_1d::EPSILON_0,
                film_thickness: rng.log_uniform(1e-10, 1e-3),
                film_youngs_modulus: None,
                impact_energy: Some(rng.log_uniform(1e-9, 100.0)),
                k_s: None,
                voltage: None,
                contact_area_fraction: if rng.unit() < 0.25 {
                    rng.log_uniform(1e-3, 1.0)
                } else {
                    1.0
                },
            };
            (contact, surface, switch)
        }
    };
    SwitchScene {
        title: None,
        contact,
        surface,
        switch,
        cycles: 4,
        until_accommodated: false,
        accommodation_tolerance: 1e-3,
        elastic_comparison: false,
        points: 0,
        accuracy: Accuracy::Accurate,
    }
}
