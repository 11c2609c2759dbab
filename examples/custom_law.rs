//! A user-defined adhesion law plugged into the elasto-plastic asperity and the rough
//! surface without touching any crate: a DMT law whose attraction decays linearly over its
//! own cohesive range `range` (instead of the Dugdale z0 of `maugis_kim::Dmt`).
//!
//! The law declares no kinks (it has one, at delta = 0): declaring them is an optional
//! speed-up; the surface's error control finds its way around them anyway.
//!
//! Run with `cargo run --example custom_law`.

use stiction::asperity_plastic::{ElastoPlasticAsperity, EtsionKadin, YieldModulus};
use stiction::contact_core::{paper, AdhesionLaw, Jumps, LawError, Material, Pair, Path};

/// DMT in contact, F = K sqrt(R) delta^(3/2) - 2 pi w R; out of contact the attraction
/// falls linearly to zero at delta = -range. No hysteresis.
#[derive(Debug, Clone, Copy)]
pub struct LinearRangeDmt {
    /// K = 4/3 E* (Pa).
    pub k: f64,
    /// Work of adhesion w (J/m^2).
    pub work_of_adhesion: f64,
    /// Range of the attraction (m).
    pub range: f64,
}

impl AdhesionLaw for LinearRangeDmt {
    fn force(&self, radius: f64, delta: f64, _path: Path) -> Result<f64, LawError> {
        let adhesion = 2.0 * std::f64::consts::PI * self.work_of_adhesion * radius;
        Ok(if delta >= 0.0 {
            self.k * radius.sqrt() * delta.powf(1.5) - adhesion
        } else if delta > -self.range {
            -adhesion * (1.0 + delta / self.range)
        } else {
            0.0
        })
    }

    fn jumps(&self, _radius: f64) -> Result<Jumps, LawError> {
        Ok(Jumps {
            jump_in: -self.range,
            jump_out: -self.range,
        })
    }
}

/// The Ru asperity of Table 1 on a rigid flat with the custom law (eq 1 as printed).
pub fn ru_asperity(range: f64) -> ElastoPlasticAsperity<EtsionKadin, LinearRangeDmt> {
    let ru = Material::new(paper::RU).expect("Table 1 is valid");
    let pair = Pair::new(ru, None, paper::RADIUS).expect("Table 1 is valid");
    let plastic = EtsionKadin::new(&pair, YieldModulus::AsPrinted).expect("Ru yields");
    let law = LinearRangeDmt {
        k: pair.k(),
        work_of_adhesion: paper::WORK_OF_ADHESION,
        range,
    };
    ElastoPlasticAsperity::new(plastic, law)
}

#[allow(dead_code)]
fn main() -> Result<(), LawError> {
    let asperity = ru_asperity(1e-9);
    println!("delta_max [nm]  pull-off [uN]");
    for dmax in paper::FIG2_DELTA_MAX {
        println!(
            "{:>14.1} {:>14.3}",
            dmax * 1e9,
            asperity.pull_off(dmax)?.force * 1e6
        );
    }
    Ok(())
}
