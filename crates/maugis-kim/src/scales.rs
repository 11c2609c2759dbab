use crate::error::MkError;
use contact_core::positive;
use std::f64::consts::PI;

/// The scales of eq 7 for one sphere: SI = nondimensional x scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// Interference scale (m): delta = Delta * interference = Delta (pi^2 w^2 R / K^2)^(1/3).
    pub interference: f64,
    /// Radius scale (m): a = A * radius = A (pi w R^2 / K)^(1/3).
    pub radius: f64,
    /// Force scale (N): F = Fbar * pi w R.
    pub force: f64,
}

impl Scales {
    /// Scales for modulus `k` = 4/3 E* (Pa), work of adhesion `w` (J/m^2), radius `r` (m).
    pub fn new(k: f64, w: f64, r: f64) -> Result<Self, MkError> {
        positive("k", k)?;
        positive("work_of_adhesion", w)?;
        positive("radius", r)?;
        Ok(Self {
            interference: (PI * PI * w * w * r / (k * k)).cbrt(),
            radius: (PI * w * r * r / k).cbrt(),
            force: PI * w * r,
        })
    }

    /// Maugis' transition parameter lambda = 2 sigma0 (R/(pi w K^2))^(1/3) (eq 6) with
    /// sigma0 = w/z0.
    pub fn lambda(k: f64, w: f64, z0: f64, r: f64) -> f64 {
        2.0 * (w / z0) * (r / (PI * w * k * k)).cbrt()
    }
}
