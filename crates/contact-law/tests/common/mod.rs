//! Shared fixtures: the analytic toy law tabulated once per test process.
#![allow(dead_code)]

use contact_law::tabulate::{tabulate, Tabulation};
use contact_law::toy::ToyLaw;
use contact_law::ContactLaw;
use std::sync::OnceLock;

/// Histories tabulated: 0.5 to 5 sigma.
pub const LO: f64 = 1.5e-9;
/// Shallowest tabulated history.
pub const HI: f64 = 15e-9;

/// The toy law with default parameters (sigma = 3 nm, P0 = 1 GPa).
pub fn toy() -> ToyLaw {
    ToyLaw::default()
}

/// The toy law tabulated with the default options.
pub fn law() -> &'static ContactLaw {
    static LAW: OnceLock<ContactLaw> = OnceLock::new();
    LAW.get_or_init(|| tabulate(&toy(), &Tabulation::adaptive(LO, HI)).unwrap())
}

/// A 64-bit LCG for reproducible test points (independent of the tabulator's seed).
pub struct Lcg(pub u64);

impl Lcg {
    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The format's error metric.
pub fn rel(interp: f64, direct: f64, pull_out: f64) -> f64 {
    (interp - direct).abs() / (direct.abs() + pull_out.abs())
}
