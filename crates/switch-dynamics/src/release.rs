//! The opening: the voltage removed, the spring pulls the plate off the contact, or the
//! contact holds it.

use crate::motion::Plate;
use crate::ode::{self, End, Threshold};
use crate::table::PressureTable;
use crate::DynamicsError;
use contact_core::{Path, SurfaceLaw};

/// What the release did.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Release {
    /// The contact let go: the plate passed the reach of the retraction.
    pub opens: bool,
    /// The time from the release to the separation (s), when it opens.
    pub opening_time: Option<f64>,
    /// The separation where the upward motion stopped in contact (m), when it sticks.
    pub held_at: Option<f64>,
}

/// Releases the plate resting at separation `d` on the retraction from `from` (the deepest
/// separation of the history): at t = 0 the voltage is removed, the plate starts at rest,
/// and the spring (K_s y), the gas and the contact act. It opens when it passes the reach
/// of the retraction; it sticks when its upward motion stops in contact (a turning point:
/// the contact's tension held the spring's pull, and nothing it does afterwards can give it
/// more energy than it had).
pub fn release<S: SurfaceLaw>(
    surface: &S,
    history: &S::History,
    d: f64,
    from: f64,
    plate: &Plate,
    tolerance: f64,
) -> Result<Release, DynamicsError> {
    let plate = plate.validated()?;
    let s = plate.travel();
    let m = plate.areal_mass;
    let phi = plate.contact_area_fraction;
    let t0 = plate.natural_time();
    let sigma = surface.length_scales(history)?.roughness;
    // the speed the spring alone would give over one roughness scale
    let vel = sigma / t0;
    let tau = t0;
    let path = Path::Retract { from };
    let out = surface.reach(history, path)?;
    let floor = plate.k_s * s / phi;
    let table = PressureTable::new(
        surface,
        history.clone(),
        path,
        from,
        out,
        2.0 * sigma,
        tolerance,
        floor,
    );
    let rhs = |_t: f64, z: &[f64], dz: &mut [f64]| -> Result<(), DynamicsError> {
        let dd = z[0] * sigma;
        let v = z[1] * vel;
        let y = s - dd;
        let x = plate.switch.d0() - y;
        let p = table.pressure(dd)?;
        let force = -plate.k_s * y - plate.damping(x) * v - phi * p;
        dz[0] = -z[1];
        dz[1] = force * tau / (m * vel);
        Ok(())
    };
    let limit = 1e3;
    let end = ode::run(
        "release",
        rhs,
        &[
            Threshold {
                component: 1,
                level: 0.0,
                rising: true,
            },
            Threshold {
                component: 0,
                level: out / sigma,
                rising: true,
            },
        ],
        &[d / sigma, 0.0],
        limit,
        tolerance,
        &mut |_| {},
        // a contact that holds an overdamped plate: it creeps into the equilibrium of the
        // spring and the contact's tension without turning
        &|z: &[f64]| {
            let dd = z[0] * sigma;
            let v = z[1] * vel;
            let y = s - dd;
            let x = plate.switch.d0() - y;
            let step = 1e-3 * sigma;
            let (Ok(p), Ok(p_above)) = (table.pressure(dd), table.pressure(dd + step)) else {
                return false;
            };
            let force = -plate.k_s * y - phi * p;
            let kappa = plate.k_s + phi * ((p_above - p) / step).abs();
            plate.at_rest(x, v, force, kappa, tolerance * sigma)
        },
        &|| surface.check_cancelled(),
    )?;
    match end {
        End::Crossed { t, which: 1, .. } => Ok(Release {
            opens: true,
            opening_time: Some(t * tau),
            held_at: None,
        }),
        End::Crossed { y, .. } | End::Settled { y, .. } => Ok(Release {
            opens: false,
            opening_time: None,
            held_at: Some(y[0] * sigma),
        }),
        End::Timeout { .. } => Err(DynamicsError::Timeout {
            phase: "release",
            limit: limit * t0,
            what: "neither an opening nor a hold",
        }),
    }
}
