//! The SI adhesion laws. Each holds the material constants and takes the radius per
//! call, because the elasto-plastic asperity changes its radius with interference.

use crate::error::MkError;
use crate::md::MdCurve;
use crate::scales::Scales;
use contact_core::numeric::{brent_from, expand_bracket, Expansion, Sample, Tolerance};
use contact_core::{finite, positive, AdhesionLaw, CoreError, Jumps, LawError, Pair, Path};
use std::f64::consts::PI;

/// The constants of a Dugdale adhesive interface between two elastic bodies, SI units:
/// the argument of [`MaugisKim::new`] and [`Dmt::new`] (named fields, so that w and z0
/// cannot be swapped silently).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DugdaleParams {
    /// Maugis' K = 4/3 E* (Pa, eq 6).
    pub k: f64,
    /// Work of adhesion w (J/m^2).
    pub work_of_adhesion: f64,
    /// Range of the Dugdale interaction z0 (m); sigma0 = w/z0.
    pub z0: f64,
}

impl DugdaleParams {
    /// The constants for a [`Pair`] (K from its composite modulus).
    pub fn for_pair(pair: &Pair, work_of_adhesion: f64, z0: f64) -> Self {
        Self {
            k: pair.k(),
            work_of_adhesion,
            z0,
        }
    }

    fn validated(self) -> Result<Self, MkError> {
        positive("k", self.k)?;
        positive("work_of_adhesion", self.work_of_adhesion)?;
        positive("z0", self.z0)?;
        Ok(self)
    }
}

/// The constants of a JKR interface: the argument of [`Jkr::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JkrParams {
    /// Maugis' K = 4/3 E* (Pa, eq 6).
    pub k: f64,
    /// Work of adhesion w (J/m^2).
    pub work_of_adhesion: f64,
}

/// Hertz: F = K sqrt(R) delta^(3/2) for delta > 0, zero otherwise (K = 4/3 E*).
///
/// ```
/// use contact_core::{AdhesionLaw, Path};
/// let hertz = maugis_kim::Hertz::new(1e11)?;
/// let f = hertz.force(4e-6, 1e-9, Path::Approach)?;
/// assert!((f - 1e11 * 2e-3 * 1e-9f64.powf(1.5)).abs() < 1e-18);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    k: f64,
}

impl Hertz {
    /// `k` = 4/3 E* (Pa).
    pub fn new(k: f64) -> Result<Self, MkError> {
        Ok(Self {
            k: positive("k", k)?,
        })
    }
}

impl AdhesionLaw for Hertz {
    fn force(&self, radius: f64, delta: f64, _path: Path) -> Result<f64, LawError> {
        positive("radius", radius)?;
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
    /// No adhesion: never tensile.
    fn max_tension(&self, _radius: f64) -> Option<f64> {
        Some(0.0)
    }
}

/// Derjaguin-Muller-Toporov with a Dugdale interaction of range z0, the lambda -> 0 limit
/// of Maugis-Kim: in contact F = K sqrt(R) delta^(3/2) - 2 pi w R; out of contact the
/// Dugdale stress sigma0 = w/z0 acts where the rigid gap is below z0, so
/// F = -2 pi w R (1 + delta/z0) for -z0 < delta < 0 and 0 below. No hysteresis.
///
/// ```
/// use contact_core::{AdhesionLaw, Path};
/// use maugis_kim::{Dmt, DugdaleParams};
/// let dmt = Dmt::new(DugdaleParams { k: 1e11, work_of_adhesion: 1.0, z0: 0.2e-9 })?;
/// // in touch (delta = 0) the pull is the DMT pull-off, 2 pi w R
/// let f = dmt.force(1e-6, 0.0, Path::Approach)?;
/// assert!((f + 2.0 * std::f64::consts::PI * 1e-6).abs() < 1e-18);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dmt {
    p: DugdaleParams,
}

impl Dmt {
    /// The law of a Dugdale interface.
    pub fn new(params: DugdaleParams) -> Result<Self, MkError> {
        Ok(Self {
            p: params.validated()?,
        })
    }
}

impl AdhesionLaw for Dmt {
    fn force(&self, radius: f64, delta: f64, _path: Path) -> Result<f64, LawError> {
        positive("radius", radius)?;
        finite("delta", delta)?;
        let adh = 2.0 * PI * self.p.work_of_adhesion * radius;
        Ok(if delta >= 0.0 {
            self.p.k * radius.sqrt() * delta * delta.sqrt() - adh
        } else if delta > -self.p.z0 {
            -adh * (1.0 + delta / self.p.z0)
        } else {
            0.0
        })
    }
    fn jumps(&self, _radius: f64) -> Result<Jumps, LawError> {
        Ok(Jumps {
            jump_in: -self.p.z0,
            jump_out: -self.p.z0,
        })
    }
    /// The Hertz term starts at delta = 0.
    fn kinks(&self, _radius: f64) -> Result<Vec<Option<f64>>, LawError> {
        Ok(vec![Some(0.0)])
    }
    /// 2 pi w R: the whole Dugdale pull, reached at delta = 0.
    fn max_tension(&self, radius: f64) -> Option<f64> {
        Some(TENSION_MARGIN * 2.0 * PI * self.p.work_of_adhesion * radius)
    }
}

/// Relative headroom of the tension bounds ([`AdhesionLaw::max_tension`]) over their
/// analytic values: rounding, and the interpolation table's error (at most
/// [`crate::INTERPOLATION_ERROR`] of max(|Fbar|, 1)), stay far below it.
const TENSION_MARGIN: f64 = 1.0 + 1e-6;

/// Johnson-Kendall-Roberts, the lambda -> infinity limit. Nondimensionally (eq 7)
/// Fbar = A^3 - sqrt(6) A^(3/2), Delta = A^2 - (2/3) sqrt(6 A); stable for
/// A >= 6^(-1/3) (Delta_t = -3 6^(-2/3), Fbar_t = -5/6), jump-in at Delta = 0.
///
/// ```
/// use maugis_kim::Jkr;
/// // displacement-control pull-off at the turning point: -5/6 pi w R
/// let f = Jkr::stable_force(Jkr::turning_delta())?;
/// assert!((f + 5.0 / 6.0).abs() < 1e-12);
/// # Ok::<(), maugis_kim::MkError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jkr {
    p: JkrParams,
    /// The radius-free factors of eq 7's scales: with q = R^(1/3), interference = i q and
    /// radius scale = r q^2 (one cube root per call, as for [`MaugisKim`]).
    i: f64,
    r: f64,
}

/// (2/3) sqrt(6): Delta = A^2 - JKR_C sqrt(A) on the JKR curve.
const JKR_C: f64 = 1.632_993_161_855_452;
/// JKR_C^(1/3), the root y = sqrt(A) at Delta = 0.
const JKR_C_CBRT: f64 = 1.177_591_843_000_481;
/// 6^(-1/6), y = sqrt(A) at the turning point, where dDelta/dy = 0.
const JKR_Y_T: f64 = 0.741_836_375_590_402_3;

impl Jkr {
    /// The law of a JKR interface.
    pub fn new(params: JkrParams) -> Result<Self, MkError> {
        let (k, w) = (
            positive("k", params.k)?,
            positive("work_of_adhesion", params.work_of_adhesion)?,
        );
        Ok(Self {
            p: params,
            i: (PI * PI * w * w / (k * k)).cbrt(),
            r: (PI * w / k).cbrt(),
        })
    }

    /// The scales of eq 7 for a sphere of `radius` (m), with one cube root.
    fn scales(&self, radius: f64) -> Result<Scales, MkError> {
        positive("radius", radius)?;
        let q = cbrt_positive(radius);
        Ok(Scales {
            interference: self.i * q,
            radius: self.r * q * q,
            force: PI * self.p.work_of_adhesion * radius,
        })
    }

    /// Turning-point interference Delta_t = -3 6^(-2/3).
    pub fn turning_delta() -> f64 {
        -3.0 * 6f64.powf(-2.0 / 3.0)
    }

    /// Nondimensional force on the stable branch at Delta >= Delta_t.
    pub fn stable_force(delta: f64) -> Result<f64, MkError> {
        Ok(Self::stable_point(delta)?.1)
    }

    /// Nondimensional contact radius A and force on the stable branch at Delta >= Delta_t.
    ///
    /// y = sqrt(A) >= y_t solves g(y) = y^4 - (2/3) sqrt(6) y - Delta = 0. g is convex and
    /// increasing for y >= y_t, so Newton's method started above the root descends onto it
    /// monotonically; it starts at Delta^(1/4) + ((2/3) sqrt 6)^(1/3), above the root
    /// because (a + b)^4 >= a^4 + b^3 (a + b). Near the turning point, where g has a double
    /// root, the descent slows to halving steps; after 200 the bracketed solve takes over.
    pub fn stable_point(delta: f64) -> Result<(f64, f64), MkError> {
        finite("delta", delta)?;
        let dt = Self::turning_delta();
        if delta < dt {
            return Err(MkError::BelowTurningPoint { delta, turning: dt });
        }
        let y = match Self::newton_y(delta) {
            Some(y) => y,
            None => Self::bracketed_y(delta)?,
        };
        let a = y * y;
        Ok((a, a * a * a - 6f64.sqrt() * a * y))
    }

    /// The root y >= y_t of y^4 - c y - Delta by Newton's method from above; None if it
    /// has not settled in 200 steps.
    fn newton_y(delta: f64) -> Option<f64> {
        let g = |y: f64| {
            let y2 = y * y;
            (y2 * y2 - JKR_C * y - delta, 4.0 * y2 * y - JKR_C)
        };
        if g(JKR_Y_T).0 >= 0.0 {
            // Delta at the turning point to rounding
            return Some(JKR_Y_T);
        }
        let mut y = delta.max(0.0).sqrt().sqrt() + JKR_C_CBRT;
        for _ in 0..200 {
            let (gy, dg) = g(y);
            if gy <= 0.0 {
                // on the root to rounding (from above, g only reaches 0 there)
                return Some(y);
            }
            let next = y - gy / dg;
            if !(next > JKR_Y_T) {
                // cannot happen above the root of a convex g; the bracketed solve decides
                return None;
            }
            if next >= y {
                // the step is below rounding
                return Some(y);
            }
            y = next;
        }
        None
    }

    /// The same root by a bracket search and Brent's method (the fallback of
    /// [`Jkr::newton_y`], and the independent solve its test compares with).
    #[doc(hidden)]
    pub fn bracketed_y(delta: f64) -> Result<f64, MkError> {
        let c = JKR_C;
        let y_t = JKR_Y_T;
        let g = |y: f64| y * y * y * y - c * y - delta;
        let start = Sample { x: y_t, f: g(y_t) };
        Ok(if start.f >= 0.0 {
            y_t
        } else {
            let ok = |y: f64| Ok::<_, CoreError>(g(y));
            let first = 2.0 * (1.0 + c.cbrt() + delta.abs().powf(0.25));
            let (lo, hi) = expand_bracket(
                "JKR Delta(A) = Delta",
                ok,
                start,
                first,
                Expansion::Geometric(2.0),
                f64::MAX,
            )?
            .ok_or(MkError::Unresolvable { delta })?;
            brent_from(
                "JKR Delta(A) = Delta",
                ok,
                lo,
                hi,
                Tolerance::relative(1e-15).with_max_iter(200),
            )?
        })
    }

    /// Nondimensional force on a path (see [`MdCurve::force`] for the path rule).
    pub fn force_nd(delta: f64, path: Path) -> Result<f64, MkError> {
        if delta.is_nan() {
            return Err(CoreError::Invalid {
                field: "delta",
                value: delta,
                allowed: "a number",
            }
            .into());
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
        let sc = self.scales(radius)?;
        finite("delta", delta)?;
        let path = nd_path(path, sc.interference);
        Ok(Self::force_nd(delta / sc.interference, path)? * sc.force)
    }
    fn jumps(&self, radius: f64) -> Result<Jumps, LawError> {
        let sc = self.scales(radius)?;
        Ok(Jumps {
            jump_in: 0.0,
            jump_out: Self::turning_delta() * sc.interference,
        })
    }
    /// The load-controlled pull-off 3/2 pi w R: Fbar = A^3 - sqrt(6) A^(3/2) is least
    /// where A^(3/2) = sqrt(6)/2, Fbar = -3/2.
    fn max_tension(&self, radius: f64) -> Option<f64> {
        self.scales(radius)
            .ok()
            .map(|sc| TENSION_MARGIN * 1.5 * sc.force)
    }
    /// The JKR contact radius a = A (pi w R^2 / K)^(1/3), A = y^2 of the stable branch;
    /// 0 when detached.
    fn contact_radius(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
        let sc = self.scales(radius)?;
        finite("delta", delta)?;
        let d = delta / sc.interference;
        let attached = d >= 0.0
            || matches!(nd_path(path, sc.interference), Path::Retract { from } if from >= 0.0 && d >= Self::turning_delta());
        Ok(if attached {
            Self::stable_point(d)?.0 * sc.radius
        } else {
            0.0
        })
    }
}

fn nd_path(path: Path, scale: f64) -> Path {
    match path {
        Path::Approach => Path::Approach,
        Path::Retract { from } => Path::Retract { from: from / scale },
    }
}

/// Cube root of a positive x to within two ulps: a first guess from the exponent bits
/// (about 3 %) refined by two Halley steps, y <- y (y^3 + 2x)/(2y^3 + x), each of which
/// cubes the relative error, and a last Newton step. A third of the cost of the library's cube root, which was 4 %
/// of a switch run (one per asperity evaluation; docs/performance.md). Subnormal, zero,
/// infinite or NaN arguments take the library's.
pub(crate) fn cbrt_positive(x: f64) -> f64 {
    if !(x.is_normal() && x > 0.0) {
        return x.cbrt();
    }
    let mut y = f64::from_bits(x.to_bits() / 3 + 0x2A9F_7893_782D_A1CE);
    for _ in 0..2 {
        let y3 = y * y * y;
        y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
    }
    // a last Newton step
    let y2 = y * y;
    y - (y2 * y - x) / (3.0 * y2)
}

/// Maugis-Dugdale with the Kim extension (paper eqs 6-11) as an SI law: lambda is
/// recomputed from the radius of each call, lambda = 2 sigma0 (R/(pi w K^2))^(1/3).
///
/// ```
/// use contact_core::{paper, AdhesionLaw, Material, Pair, Path};
/// use maugis_kim::{DugdaleParams, MaugisKim};
/// // a Ru asperity of Table 1 on a rigid flat: lambda = 1.80
/// let pair = Pair::new(Material::new(paper::RU)?, None, paper::RADIUS)?;
/// let mk = MaugisKim::new(DugdaleParams::for_pair(&pair, paper::WORK_OF_ADHESION, paper::Z0))?;
/// assert!((mk.lambda(paper::RADIUS) - 1.80).abs() < 5e-3);
/// // retracting from 1 nm, the asperity still pulls at zero interference
/// let f = mk.force(paper::RADIUS, 0.0, Path::Retract { from: 1e-9 })?;
/// assert!(f < 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaugisKim {
    p: DugdaleParams,
    /// The radius-free factors of eq 7's scales and of lambda: with q = R^(1/3),
    /// interference = i q, radius scale = r q^2, lambda = l q (one cube root per call).
    i: f64,
    r: f64,
    l: f64,
    /// The force above the junction from the interpolation table ([`Self::interpolated`]).
    table: bool,
}

impl MaugisKim {
    /// The law of a Dugdale interface.
    pub fn new(params: DugdaleParams) -> Result<Self, MkError> {
        let p = params.validated()?;
        let (k, w) = (p.k, p.work_of_adhesion);
        Ok(Self {
            i: (PI * PI * w * w / (k * k)).cbrt(),
            r: (PI * w / k).cbrt(),
            l: 2.0 * (w / p.z0) * (1.0 / (PI * w * k * k)).cbrt(),
            p,
            table: false,
        })
    }

    /// The same law with its force on the contact branch above the junction interpolated
    /// from a table instead of solved, within [`crate::INTERPOLATION_ERROR`] of
    /// max(|F|, pi w R) (the solve everywhere else, and for the contact radius): a lookup
    /// costs about 440 instructions with its two logarithms against about 1300 for the
    /// solve (callgrind, the paper's switch), plus the tiles a run solves once. The
    /// turning point (where a retracting sphere jumps out: the jump-out of
    /// [`AdhesionLaw::jumps`] and the end of the retracting force) is read from a table in
    /// ln lambda too, within 1e-12 of max(|Delta_t|, 1). What a rough surface uses in fast
    /// mode.
    ///
    /// ```
    /// use contact_core::{AdhesionLaw, Path};
    /// use maugis_kim::{DugdaleParams, MaugisKim, INTERPOLATION_ERROR};
    /// let exact = MaugisKim::new(DugdaleParams { k: 1e11, work_of_adhesion: 1.0, z0: 0.4e-9 })?;
    /// let table = exact.interpolated();
    /// let (r, delta) = (1e-6, 2e-9);
    /// let scale = std::f64::consts::PI * 1.0 * r; // pi w R
    /// let (a, b) = (exact.force(r, delta, Path::Approach)?, table.force(r, delta, Path::Approach)?);
    /// assert!((a - b).abs() <= INTERPOLATION_ERROR * a.abs().max(scale));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn interpolated(self) -> Self {
        Self {
            table: true,
            ..self
        }
    }

    /// The scales and the curve of a sphere of `radius` (m) at once.
    fn sphere(&self, radius: f64) -> Result<(Scales, MdCurve), MkError> {
        positive("radius", radius)?;
        let q = cbrt_positive(radius);
        let scales = Scales {
            interference: self.i * q,
            radius: self.r * q * q,
            force: PI * self.p.work_of_adhesion * radius,
        };
        Ok((scales, MdCurve::new(self.l * q)?))
    }

    /// The transition parameter for a sphere of `radius` (m).
    pub fn lambda(&self, radius: f64) -> f64 {
        Scales::lambda(self.p.k, self.p.work_of_adhesion, self.p.z0, radius)
    }

    /// Scales of eq 7 for a sphere of `radius` (m).
    pub fn scales(&self, radius: f64) -> Result<Scales, MkError> {
        Scales::new(self.p.k, self.p.work_of_adhesion, radius)
    }

    /// The nondimensional curve of a sphere of `radius` (m).
    pub fn curve(&self, radius: f64) -> Result<MdCurve, MkError> {
        positive("radius", radius)?;
        MdCurve::new(self.lambda(radius))
    }
}

impl AdhesionLaw for MaugisKim {
    fn force(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
        finite("delta", delta)?;
        let (sc, curve) = self.sphere(radius)?;
        let (d, path) = (delta / sc.interference, nd_path(path, sc.interference));
        let f = if self.table {
            curve.force_interpolated(d, path)?
        } else {
            curve.force(d, path)?
        };
        Ok(f * sc.force)
    }
    /// The interpolated law ([`MaugisKim::interpolated`]) where its error bound is within
    /// `rel_force`.
    fn within(&self, rel_force: f64) -> Option<std::sync::Arc<dyn AdhesionLaw + Send + Sync>> {
        (crate::INTERPOLATION_ERROR.max(crate::table::TURNING_ERROR) <= rel_force)
            .then(|| std::sync::Arc::new(self.interpolated()) as _)
    }
    fn jumps(&self, radius: f64) -> Result<Jumps, LawError> {
        let (sc, curve) = self.sphere(radius)?;
        let turning = if self.table {
            curve.turning_delta_interpolated()?
        } else {
            curve.turning_point()?.delta
        };
        Ok(Jumps {
            jump_in: curve.jump_in_delta() * sc.interference,
            jump_out: turning * sc.interference,
        })
    }
    /// -z0: the rigid gap at the centre equals the Dugdale range (no turning point needed).
    fn jump_in(&self, _radius: f64) -> Result<f64, LawError> {
        Ok(-self.p.z0)
    }
    /// 2 pi w R, the DMT limit of the load-controlled pull-off, which falls to 3/2 pi w R
    /// as lambda grows: the least force of the stable branch (and of the non-contact
    /// branch, whose Dugdale pull is at most the DMT one) over every lambda
    /// (test `no_force_is_more_tensile_than_the_bound`).
    fn max_tension(&self, radius: f64) -> Option<f64> {
        Some(TENSION_MARGIN * 2.0 * PI * self.p.work_of_adhesion * radius)
    }
    /// The Maugis-Dugdale contact radius a = A (pi w R^2 / K)^(1/3) of the stable point
    /// (eqs 7-9); 0 detached and on the non-contact branch.
    fn contact_radius(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
        finite("delta", delta)?;
        let (sc, curve) = self.sphere(radius)?;
        Ok(
            curve.contact_radius(delta / sc.interference, nd_path(path, sc.interference))?
                * sc.radius,
        )
    }
    /// For lambda <= lambda_c the stable branch passes the junction of the non-contact
    /// and contact branches, where the curvature of F(delta) changes; absent above
    /// lambda_c (the stable branch ends at the turning point first).
    fn kinks(&self, radius: f64) -> Result<Vec<Option<f64>>, LawError> {
        let (sc, curve) = self.sphere(radius)?;
        Ok(vec![(curve.lambda() <= crate::LAMBDA_CRITICAL)
            .then(|| curve.junction().delta * sc.interference)])
    }
}

#[cfg(test)]
mod tests {
    use super::{cbrt_positive, Jkr, JKR_C, JKR_C_CBRT, JKR_Y_T};

    /// The JKR constants are what they stand for, to an ulp or two.
    #[test]
    fn jkr_constants_are_their_formulas() {
        let ulps = |a: f64, b: f64| (a - b).abs() / (f64::EPSILON * b);
        assert!(ulps(JKR_C, 2.0 / 3.0 * 6f64.sqrt()) <= 1.0);
        assert!(ulps(JKR_C_CBRT, JKR_C.cbrt()) <= 1.0);
        assert!(ulps(JKR_Y_T, 6f64.powf(-1.0 / 6.0)) <= 2.0);
        // dDelta/dy = 4 y^3 - c vanishes at the turning point
        assert!((4.0 * JKR_Y_T.powi(3) - JKR_C).abs() <= 4.0 * f64::EPSILON);
    }

    /// Newton's descent finds the root of y^4 - c y - Delta that the bracketed Brent solve
    /// finds, over Delta from the turning point to 1e15: the same y to 1e-14 where the root
    /// is simple, and a residual at rounding next to the turning point (a double root,
    /// where y itself is only defined to about sqrt(eps)). At Delta = 0 the root is
    /// c^(1/3) (hand-derived: y^3 = c).
    #[test]
    fn jkr_newton_descent_matches_the_bracketed_solve() {
        let dt = Jkr::turning_delta();
        let mut deltas: Vec<f64> = (1..=16).map(|k| dt + 10f64.powi(-k)).collect();
        deltas.extend([dt, 0.0, -0.5, 1.0]);
        let mut x = 1e-12;
        while x < 1e15 {
            deltas.push(x);
            if -x > dt {
                deltas.push(-x);
            }
            x *= 1.37;
        }
        for &d in &deltas {
            let y = Jkr::newton_y(d).expect("the descent settles");
            let b = Jkr::bracketed_y(d).unwrap();
            assert!(y >= JKR_Y_T, "Delta {d}: y {y}");
            let scale = y.powi(4) + JKR_C * y + d.abs();
            let residual = (y.powi(4) - JKR_C * y - d).abs();
            assert!(
                residual <= 8.0 * f64::EPSILON * scale,
                "Delta {d}: residual {residual:e}"
            );
            if d - dt > 1e-3 {
                assert!((y - b).abs() <= 1e-14 * b, "Delta {d}: {y} vs {b}");
            }
        }
        let y0 = Jkr::newton_y(0.0).unwrap();
        assert!((y0 - JKR_C_CBRT).abs() <= 2.0 * f64::EPSILON * y0);
        assert!(Jkr::stable_point(f64::NAN).is_err());
        assert!(Jkr::stable_point(f64::INFINITY).is_err());
    }

    /// Within two ulps of the library's cube root over every binade a radius can take and
    /// far beyond (1e-300 to 1e300), and exact on perfect cubes of small integers.
    #[test]
    fn fast_cube_root_is_within_two_ulps() {
        let mut x = 1e-300_f64;
        let mut worst = 0.0_f64;
        while x < 1e300 {
            for k in 0..7 {
                let v = x * (1.0 + 0.137 * k as f64);
                let (ours, lib) = (cbrt_positive(v), v.cbrt());
                let ulp = f64::from_bits(lib.to_bits() + 1) - lib;
                worst = worst.max((ours - lib).abs() / ulp);
            }
            x *= 1.73;
        }
        assert!(worst <= 2.0, "worst {worst} ulp");
        for n in 1..=50 {
            let c = (n * n * n) as f64;
            assert!((cbrt_positive(c) - n as f64).abs() <= 2.0 * f64::EPSILON * n as f64);
        }
        assert_eq!(cbrt_positive(0.0), 0.0);
        assert!(cbrt_positive(f64::NAN).is_nan());
    }

    /// The tension bounds hold: no force of a law, on approach or on retraction from
    /// anywhere, pulls harder than `max_tension` (Maugis-Kim exact and from its table over
    /// lambda from 0.01 to 1e4; JKR; DMT), and the Maugis-Kim bound is tight in the DMT
    /// limit (the load-controlled pull-off approaches 2 pi w R as lambda falls).
    #[test]
    fn no_force_is_more_tensile_than_the_bound() {
        use super::{Dmt, DugdaleParams, JkrParams, MaugisKim};
        use contact_core::{AdhesionLaw, Path};
        let p = DugdaleParams {
            k: 1e11,
            work_of_adhesion: 1.0,
            z0: 0.2e-9,
        };
        let mk = MaugisKim::new(p).unwrap();
        let laws: Vec<(&str, Box<dyn AdhesionLaw>)> = vec![
            ("maugis_kim", Box::new(mk)),
            ("maugis_kim table", Box::new(mk.interpolated())),
            ("dmt", Box::new(Dmt::new(p).unwrap())),
            (
                "jkr",
                Box::new(
                    Jkr::new(JkrParams {
                        k: 1e11,
                        work_of_adhesion: 1.0,
                    })
                    .unwrap(),
                ),
            ),
        ];
        let mut tightest = 0.0_f64;
        for (name, law) in &laws {
            // radii with lambda from about 0.01 to 1e4 (lambda ~ R^(1/3))
            for i in 0..=40 {
                let lambda = 10f64.powf(-2.0 + 6.0 * i as f64 / 40.0);
                let radius = (lambda / mk.lambda(1.0)).powi(3);
                let bound = law.max_tension(radius).unwrap();
                let scale = mk.scales(radius).unwrap().interference;
                let j = law.jumps(radius).unwrap();
                let mut least = f64::INFINITY;
                for from in [j.jump_in, 0.0, 0.5 * scale, 3.0 * scale, 30.0 * scale] {
                    for k in 0..=400 {
                        let d = j.jump_out.min(j.jump_in) - 0.5 * scale
                            + (from - j.jump_out.min(j.jump_in) + scale) * k as f64 / 400.0;
                        for path in [Path::Approach, Path::Retract { from }] {
                            if matches!(path, Path::Retract { from }
                                if d > from)
                            {
                                continue;
                            }
                            least = least.min(law.force(radius, d, path).unwrap());
                        }
                    }
                }
                assert!(
                    -least <= bound,
                    "{name}: lambda {lambda}: force {least} beyond the bound {bound}"
                );
                if *name == "maugis_kim" {
                    tightest = tightest.max(-least / bound);
                }
            }
        }
        // at lambda = 0.01 the pull-off is within a few percent of the DMT 2 pi w R
        assert!(tightest > 0.95, "tightest {tightest}");
    }
}
