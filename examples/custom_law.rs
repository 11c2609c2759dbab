//! A user-defined adhesion law plugged into the elasto-plastic asperity without touching
//! any crate: a DMT law whose attraction decays linearly over its own cohesive range
//! `range` (instead of the Dugdale z0 of `maugis_kim::Dmt`).
//!
//! Run with `cargo run --example custom_law`.

use stiction::asperity_plastic::{ElastoPlasticAsperity, EtsionKadin, YieldModulus};
use stiction::contact_core::{
    AdhesionLaw, AsperityHistory, AsperityModel, Jumps, LawError, Material, Pair, Path,
};

/// DMT in contact, F = K sqrt(R) delta^(3/2) - 2 pi w R; out of contact the attraction
/// falls linearly to zero at delta = -range. No hysteresis.
#[derive(Debug, Clone, Copy)]
pub struct LinearRangeDmt {
    pub k: f64,
    pub work_of_adhesion: f64,
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

    fn kinks(&self, _radius: f64) -> Result<Vec<f64>, LawError> {
        Ok(vec![0.0])
    }
}

/// The Ru asperity of Table 1 on a rigid flat with the custom law.
pub fn ru_asperity(range: f64) -> ElastoPlasticAsperity<EtsionKadin, LinearRangeDmt> {
    let ru = Material::new(410e9, 0.3, 3.42e9).expect("Table 1 is valid");
    let pair = Pair::new(ru, None, 4e-6).expect("Table 1 is valid");
    let plastic = EtsionKadin::new(&pair, YieldModulus::Composite).expect("Ru yields");
    let law = LinearRangeDmt {
        k: pair.k(),
        work_of_adhesion: 1.0,
        range,
    };
    ElastoPlasticAsperity::new(plastic, law)
}

/// Most tensile force on unloading from `delta_max` (N), scanned on 2000 points and on
/// the law's kinks (a DMT force is most tensile exactly at its kink, delta = delta_res).
pub fn pull_off(asperity: &impl AsperityModel, delta_max: f64) -> Result<f64, LawError> {
    let hist = AsperityHistory { delta_max };
    let out = asperity.jumps(hist)?.jump_out;
    let path = Path::Retract { from: delta_max };
    let mut min: f64 = 0.0;
    for i in 0..=2000 {
        let d = out + (delta_max - out) * i as f64 / 2000.0;
        min = min.min(asperity.force(d, hist, path)?);
    }
    for k in asperity.kinks(hist)? {
        min = min.min(asperity.force(k, hist, path)?);
    }
    Ok(min)
}

#[allow(dead_code)]
fn main() -> Result<(), LawError> {
    let asperity = ru_asperity(1e-9);
    println!("delta_max [nm]  pull-off [uN]");
    for dmax in [17e-9, 34e-9, 51e-9] {
        println!(
            "{:>14.1} {:>14.3}",
            dmax * 1e9,
            pull_off(&asperity, dmax)? * 1e6
        );
    }
    Ok(())
}
