//! Yield onset of a contact pair, shared by the plasticity laws of this crate: eq 1 for
//! each body that can yield, and the rule that the body yielding first governs.

use crate::error::PlasticError;
use crate::etsion_kadin::YieldModulus;
use contact_core::{positive, Material, Pair, YieldingBody};
use std::f64::consts::PI;

/// The onset of yield of a pair: delta_CP, the onset coefficient used, and the governing
/// body with its material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Onset {
    /// delta_CP (m).
    pub delta_cp: f64,
    /// The coefficient C of delta_CP = R (pi C S_Y / (2 E_1))^2 for the governing body.
    pub coefficient: f64,
    /// Which body yields first.
    pub body: YieldingBody,
    /// Its material.
    pub material: Material,
}

/// delta_CP = R (pi C(nu) S_Y / (2 E_1))^2 (eq 1) for each body of `pair` that can yield,
/// with E_1 = E* or the body's own E (`modulus`) and the coefficient `coefficient(nu)`;
/// the body with the smaller delta_CP (the one that yields first) governs.
pub(crate) fn governing(
    pair: &Pair,
    modulus: YieldModulus,
    coefficient: impl Fn(f64) -> f64,
) -> Result<Onset, PlasticError> {
    let onset = |m: &Material| -> Option<(f64, f64)> {
        let s_y = m.yield_stress();
        if !s_y.is_finite() {
            return None;
        }
        let c = coefficient(m.poisson_ratio());
        let e = match modulus {
            YieldModulus::Composite => pair.e_star(),
            YieldModulus::AsPrinted => m.youngs_modulus(),
        };
        let root = PI * c * s_y / (2.0 * e);
        Some((pair.radius() * root * root, c))
    };
    let first = onset(pair.asperity()).map(|o| (o, YieldingBody::Asperity, *pair.asperity()));
    let second = pair
        .counter()
        .and_then(|m| onset(m).map(|o| (o, YieldingBody::Counter, *m)));
    let ((delta_cp, c), body, material) = match (first, second) {
        (Some(a), Some(b)) => {
            if b.0 .0 < a.0 .0 {
                b
            } else {
                a
            }
        }
        (Some(a), None) => a,
        (None, Some(b)) => b,
        (None, None) => return Err(PlasticError::NeverYields),
    };
    positive("delta_cp", delta_cp)?;
    Ok(Onset {
        delta_cp,
        coefficient: c,
        body,
        material,
    })
}
