//! Shared fixtures: Ru of Table 1 on a rigid flat with Maugis-Kim, and FE-like curves made
//! by the model itself with constants other than the paper's.
#![allow(dead_code)]

use asperity_plastic::{EffectiveRadiusFit, EtsionKadin, YieldModulus};
use calibrate::{Calibrator, Constant, FeData, SynthSpec};
use contact_core::{paper, Material, Pair};
use maugis_kim::{DugdaleParams, MaugisKim};

/// The truth of the synthetic "finite-element" data.
pub fn truth() -> EffectiveRadiusFit {
    EffectiveRadiusFit::new([0.3, 0.5, 0.12], [8.0, 12.0, 4.0]).unwrap()
}

/// Ru of Table 1 on a rigid flat, Maugis-Kim adhesion (w, z0 of Table 1).
pub fn ru(modulus: YieldModulus) -> Calibrator<MaugisKim> {
    let pair = Pair::new(Material::new(paper::RU).unwrap(), None, paper::RADIUS).unwrap();
    Calibrator::new(
        EtsionKadin::new(&pair, modulus).unwrap(),
        MaugisKim::new(DugdaleParams::for_pair(
            &pair,
            paper::WORK_OF_ADHESION,
            paper::Z0,
        ))
        .unwrap(),
    )
}

/// Runs at `omegas` delta_CP, `n` points per branch (0 unloading points: loading only).
pub fn spec(
    cal: &Calibrator<MaugisKim>,
    omegas: &[f64],
    n_load: usize,
    n_unload: usize,
    noise: f64,
    seed: u64,
) -> SynthSpec {
    SynthSpec {
        delta_max: omegas.iter().map(|w| w * cal.delta_cp()).collect(),
        loading_points: n_load,
        unloading_points: n_unload,
        noise,
        seed,
    }
}

/// The four runs of the main tests: omega 5, 10, 20, 40, 25 points per branch.
pub const OMEGAS: [f64; 4] = [5.0, 10.0, 20.0, 40.0];

/// Worst per-curve RMS of (model at `fit`) - (reference forces), relative to the curve's
/// peak.
pub fn worst_relative_rms(
    cal: &Calibrator<MaugisKim>,
    fit: EffectiveRadiusFit,
    reference: &FeData,
) -> f64 {
    let pred = cal.predict(fit, reference).unwrap();
    reference
        .curves()
        .iter()
        .zip(&pred)
        .map(|(c, p)| {
            let ss: f64 = c
                .points
                .iter()
                .zip(p)
                .map(|(a, f)| (a.force - f).powi(2))
                .sum();
            (ss / p.len() as f64).sqrt() / c.peak_force()
        })
        .fold(0.0, f64::max)
}

/// Value of a constant.
pub fn value(fit: &EffectiveRadiusFit, c: Constant) -> f64 {
    c.get(fit)
}
