//! The SI adhesion laws. Each holds the material constants and takes the radius per
//! call, because the elasto-plastic asperity changes its radius with interference.

use crate::error::{check_positive, MkError};
use crate::md::MdCurve;
use crate::scales::Scales;
use contact_core::numeric::brent;
use contact_core::{AdhesionLaw, Jumps, LawError, Path};
use std::f64::consts::PI;

fn finite(field: &'static str, v: f64) -> Result<f64, MkError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(MkError::Invalid {
            field,
            value: v,
            allowed: "finite",
        })
    }
}

/// Hertz: F = K sqrt(R) delta^(3/2) for delta > 0, zero otherwise (K = 4/3 E*).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    k: f64,
}

impl Hertz {
    /// `k` = 4/3 E* (Pa).
    pub fn new(k: f64) -> Result<Self, MkError> {
        Ok(Self {
            k: check_positive("k", k)?,
        })
    }
}

impl AdhesionLaw for Hertz {
    fn force(&self, radius: f64, delta: f64, _path: Path) -> Result<f64, LawError> {
        check_positive("radius", radius)?;
        finite("delta", delta)?;
        Ok(if delta > 0.0 {
            self.k * radius.sqrt() * delta * delta.sqrt()
        } else {
            0.0
        })
    }
    fn jumps(&self, _radius: f64) -> Result<Jumps, LawError> {
        Ok(Jumps {
            jump_in: 0.0,
            jump_out: 0.0,
        })
    }
}

/// Derjaguin-Muller-Toporov with a Dugdale interaction of range z0, the lambda -> 0 limit
/// of Maugis-Kim: in contact F = K sqrt(R) delta^(3/2) - 2 pi w R; out of contact the
/// Dugdale stress sigma0 = w/z0 acts where the rigid gap is below z0, so
/// F = -2 pi w R (1 + delta/z0) for -z0 < delta < 0 and 0 below. No hysteresis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dmt {
    k: f64,
    w: f64,
    z0: f64,
}

impl Dmt {
    /// `k` = 4/3 E* (Pa), work of adhesion `w` (J/m^2), range `z0` (m).
    pub fn new(k: f64, w: f64, z0: f64) -> Result<Self, MkError> {
        Ok(Self {
            k: check_positive("k", k)?,
            w: check_positive("work_of_adhesion", w)?,
            z0: check_positive("z0", z0)?,
        })
    }
}

impl AdhesionLaw for Dmt {
    fn force(&self, radius: f64, delta: f64, _path: Path) -> Result<f64, LawError> {
        check_positive("radius", radius)?;
        finite("delta", delta)?;
        let adh = 2.0 * PI * self.w * radius;
        Ok(if delta >= 0.0 {
            self.k * radius.sqrt() * delta * delta.sqrt() - adh
        } else if delta > -self.z0 {
            -adh * (1.0 + delta / self.z0)
        } else {
            0.0
        })
    }
    fn jumps(&self, _radius: f64) -> Result<Jumps, LawError> {
        Ok(Jumps {
            jump_in: -self.z0,
            jump_out: -self.z0,
        })
    }
    /// The Hertz term starts at delta = 0.
    fn kinks(&self, _radius: f64) -> Result<Vec<f64>, LawError> {
        Ok(vec![0.0])
    }
}

/// Johnson-Kendall-Roberts, the lambda -> infinity limit. Nondimensionally (eq 7)
/// Fbar = A^3 - sqrt(6) A^(3/2), Delta = A^2 - (2/3) sqrt(6 A); stable for
/// A >= 6^(-1/3) (Delta_t = -3 6^(-2/3), Fbar_t = -5/6), jump-in at Delta = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jkr {
    k: f64,
    w: f64,
}

impl Jkr {
    /// `k` = 4/3 E* (Pa), work of adhesion `w` (J/m^2).
    pub fn new(k: f64, w: f64) -> Result<Self, MkError> {
        Ok(Self {
            k: check_positive("k", k)?,
            w: check_positive("work_of_adhesion", w)?,
        })
    }

    /// Turning-point interference Delta_t = -3 6^(-2/3).
    pub fn turning_delta() -> f64 {
        -3.0 * 6f64.powf(-2.0 / 3.0)
    }

    /// Nondimensional force on the stable branch at Delta >= Delta_t.
    pub fn stable_force(delta: f64) -> Result<f64, MkError> {
        let dt = Self::turning_delta();
        if delta < dt {
            return Err(MkError::BelowTurningPoint { delta, turning: dt });
        }
        // y = sqrt(A) >= y_t solves y^4 - (2/3) sqrt(6) y - Delta = 0, increasing for y >= y_t.
        let c = 2.0 / 3.0 * 6f64.sqrt();
        let y_t = 6f64.powf(-1.0 / 6.0);
        let g = |y: f64| y * y * y * y - c * y - delta;
        let mut y_hi = 2.0 * (1.0 + c.cbrt() + delta.abs().powf(0.25));
        while g(y_hi) < 0.0 {
            y_hi *= 2.0;
        }
        let y = if g(y_t) >= 0.0 {
            y_t
        } else {
            brent("JKR Delta(A) = Delta", g, y_t, y_hi, 1e-15, 0.0, 200)?
        };
        let a = y * y;
        Ok(a * a * a - 6f64.sqrt() * a * y)
    }

    /// Nondimensional force on a path (see [`MdCurve::force`] for the path rule).
    pub fn force_nd(delta: f64, path: Path) -> Result<f64, MkError> {
        if delta.is_nan() {
            return Err(MkError::Invalid {
                field: "delta",
                value: delta,
                allowed: "a number",
            });
        }
        if delta >= 0.0 {
            return Self::stable_force(delta);
        }
        match path {
            Path::Retract { from } if from >= 0.0 && delta >= Self::turning_delta() => {
                Self::stable_force(delta)
            }
            _ => Ok(0.0),
        }
    }
}

impl AdhesionLaw for Jkr {
    fn force(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
        let sc = Scales::new(self.k, self.w, radius)?;
        finite("delta", delta)?;
        let path = nd_path(path, sc.interference);
        Ok(Self::force_nd(delta / sc.interference, path)? * sc.force)
    }
    fn jumps(&self, radius: f64) -> Result<Jumps, LawError> {
        let sc = Scales::new(self.k, self.w, radius)?;
        Ok(Jumps {
            jump_in: 0.0,
            jump_out: Self::turning_delta() * sc.interference,
        })
    }
}

fn nd_path(path: Path, scale: f64) -> Path {
    match path {
        Path::Approach => Path::Approach,
        Path::Retract { from } => Path::Retract { from: from / scale },
    }
}

/// Maugis-Dugdale with the Kim extension (paper eqs 6-11) as an SI law: lambda is
/// recomputed from the radius of each call, lambda = 2 sigma0 (R/(pi w K^2))^(1/3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaugisKim {
    k: f64,
    w: f64,
    z0: f64,
}

impl MaugisKim {
    /// `k` = 4/3 E* (Pa), work of adhesion `w` (J/m^2), Dugdale range `z0` (m);
    /// sigma0 = w/z0.
    pub fn new(k: f64, w: f64, z0: f64) -> Result<Self, MkError> {
        Ok(Self {
            k: check_positive("k", k)?,
            w: check_positive("work_of_adhesion", w)?,
            z0: check_positive("z0", z0)?,
        })
    }

    /// The transition parameter for a sphere of `radius` (m).
    pub fn lambda(&self, radius: f64) -> f64 {
        Scales::lambda(self.k, self.w, self.z0, radius)
    }

    /// Scales of eq 7 for a sphere of `radius` (m).
    pub fn scales(&self, radius: f64) -> Result<Scales, MkError> {
        Scales::new(self.k, self.w, radius)
    }

    /// The nondimensional curve of a sphere of `radius` (m).
    pub fn curve(&self, radius: f64) -> Result<MdCurve, MkError> {
        check_positive("radius", radius)?;
        MdCurve::new(self.lambda(radius))
    }
}

impl AdhesionLaw for MaugisKim {
    fn force(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
        finite("delta", delta)?;
        let sc = self.scales(radius)?;
        let curve = MdCurve::new(self.lambda(radius))?;
        Ok(curve.force(delta / sc.interference, nd_path(path, sc.interference))? * sc.force)
    }
    fn jumps(&self, radius: f64) -> Result<Jumps, LawError> {
        let sc = self.scales(radius)?;
        let curve = MdCurve::new(self.lambda(radius))?;
        Ok(Jumps {
            jump_in: curve.jump_in_delta() * sc.interference,
            jump_out: curve.turning_point()?.delta * sc.interference,
        })
    }
    /// -z0: the rigid gap at the centre equals the Dugdale range (no turning point needed).
    fn jump_in(&self, _radius: f64) -> Result<f64, LawError> {
        Ok(-self.z0)
    }
    /// For lambda <= lambda_c the stable branch passes the junction of the non-contact
    /// and contact branches, where the curvature of F(delta) changes; NaN above lambda_c
    /// (the stable branch ends at the turning point first), so the list keeps its length.
    fn kinks(&self, radius: f64) -> Result<Vec<f64>, LawError> {
        let sc = self.scales(radius)?;
        let curve = MdCurve::new(self.lambda(radius))?;
        Ok(vec![if curve.lambda() <= crate::LAMBDA_CRITICAL {
            curve.junction().delta * sc.interference
        } else {
            f64::NAN
        }])
    }
}
