//! Squeeze-film damping of a rigid rectangular plate moving normal to a fixed plane.

use crate::DynamicsError;

/// The pressure at which `mean_free_path` is given (Pa): 1 atm.
pub const REFERENCE_PRESSURE: f64 = 101_325.0;

/// Coefficients of Veijola, Kuisma, Lahdenperä & Ryhänen (1995)'s effective viscosity,
/// mu_eff = mu / (1 + 9.638 Kn^1.159): the fit to the Fukui-Kaneko Poiseuille flow rate
/// over Kn in [0, 880].
pub const VEIJOLA_A: f64 = 9.638;
/// The exponent of [`VEIJOLA_A`]'s fit.
pub const VEIJOLA_B: f64 = 1.159;

/// Squeeze-film damping of a W x L plate over a gas film (Reynolds' equation,
/// isothermal, incompressible: the squeeze number sigma = 12 mu_eff W^2 omega/(p x^2) small,
/// ambient pressure at the four edges, no holes):
///
/// ```text
///   c''(x) = beta(W/L) mu_eff(x) W^2 / x^3        (Pa s/m per unit plate area),
///   beta(r) = 1 - (192 r / pi^5) sum_{n odd} tanh(n pi / (2 r)) / n^5,   r = W/L <= 1
/// ```
///
/// (Griffin, Richardson & Yamanami 1966; Blech 1983: beta = 0.4217 for a square, 1 for a
/// long strip), with the rarefied gas's effective viscosity of Veijola et al. (1995),
/// mu_eff = mu / (1 + 9.638 Kn^1.159), Kn = lambda(p)/x, lambda(p) = lambda_0 p_0 / p.
///
/// Limits (docs/theory.md 13.2): the incompressible form holds while the squeeze number is
/// small (it overestimates the damping of a fast plate at a small gap, where the film also
/// springs back); the plate is rigid and parallel; edge effects (Veijola's elongation) and
/// perforations are left out.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct SqueezeFilm {
    width: f64,
    length: f64,
    viscosity: f64,
    mean_free_path: f64,
    pressure: f64,
}

impl SqueezeFilm {
    /// A plate `width` x `length` (m) over a gas of `viscosity` (Pa s) whose mean free path
    /// at [`REFERENCE_PRESSURE`] is `mean_free_path` (m), at `pressure` (Pa, > 0).
    pub fn new(
        width: f64,
        length: f64,
        viscosity: f64,
        mean_free_path: f64,
        pressure: f64,
    ) -> Result<Self, DynamicsError> {
        for (field, v) in [
            ("plate_width", width),
            ("plate_length", length),
            ("gas_viscosity", viscosity),
            ("gas_mean_free_path", mean_free_path),
            ("gas_pressure", pressure),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(DynamicsError::Invalid {
                    field,
                    value: v,
                    allowed: "finite and > 0",
                });
            }
        }
        Ok(Self {
            width: width.min(length),
            length: width.max(length),
            viscosity,
            mean_free_path,
            pressure,
        })
    }

    /// beta(W/L) of the plate (its shorter side over its longer).
    pub fn geometry_factor(&self) -> f64 {
        geometry_factor(self.width / self.length)
    }

    /// The gas's mean free path at its pressure (m): lambda_0 p_0 / p.
    pub fn mean_free_path(&self) -> f64 {
        self.mean_free_path * REFERENCE_PRESSURE / self.pressure
    }

    /// Veijola's effective viscosity (Pa s) at gap `x` (m).
    pub fn effective_viscosity(&self, x: f64) -> f64 {
        let kn = self.mean_free_path() / x;
        self.viscosity / (1.0 + VEIJOLA_A * kn.powf(VEIJOLA_B))
    }

    /// c''(x) (Pa s/m per unit plate area) at gap `x` (m).
    pub fn coefficient(&self, x: f64) -> f64 {
        self.geometry_factor() * self.effective_viscosity(x) * self.width * self.width / (x * x * x)
    }
}

/// beta(r) of a rectangular plate, r = W/L in (0, 1] (the series to n = 199: its terms
/// fall as n^-5, the remainder is below 1e-12).
pub fn geometry_factor(r: f64) -> f64 {
    let r = r.clamp(f64::MIN_POSITIVE, 1.0);
    let pi = std::f64::consts::PI;
    let sum: f64 = (1..200)
        .step_by(2)
        .map(|n| {
            let n = n as f64;
            (n * pi / (2.0 * r)).tanh() / n.powi(5)
        })
        .sum();
    1.0 - 192.0 * r / pi.powi(5) * sum
}
