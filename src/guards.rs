//! Physics guards: where a result should not be trusted as it stands, a [`Warning`] says
//! so with numbers (docs/theory.md section 8).

use crate::error::Error;
use crate::model::Asperity;
use crate::render::{self, Warning};
use crate::scene::Contact;
use asperity_plastic::FIT_RANGE_MAX;
use contact_core::numeric::{brent, Tolerance};
use contact_core::{AsperityHistory, AsperityModel, Path};

/// Tabor's constraint factor: the hardness of a plastically indented surface is about
/// 2.8 S_Y (Tabor 1951). A nominal pressure above it cannot be carried by separate
/// asperity contacts.
pub const HARDNESS_FACTOR: f64 = 2.8;

/// Share of the load beyond the fits' range above which `beyond_fit_range` is raised.
pub const FIT_SHARE_LIMIT: f64 = 0.01;

/// The interference (m) of a virgin elastic asperity in stable adhesive contact under
/// zero external load: the root of F(delta) on the retraction branch (0 for Hertz).
pub fn zero_load_interference(elastic: &Asperity) -> Result<f64, Error> {
    let hist = AsperityHistory::VIRGIN;
    let f = |d: f64| {
        elastic.force(
            d,
            hist,
            Path::Retract {
                from: d.max(0.0) + 1.0,
            },
        )
    };
    if f(0.0)? >= 0.0 {
        return Ok(0.0);
    }
    let mut hi = 1e-12f64.max(elastic.radius() * 1e-9);
    while f(hi)? < 0.0 {
        hi *= 2.0;
        if hi > elastic.radius() {
            return Ok(elastic.radius());
        }
    }
    brent(
        "zero-load interference",
        |d| Ok::<_, Error>(elastic.force(d, hist, Path::Retract { from: hi })?),
        0.0,
        hi,
        Tolerance::relative(1e-10),
    )
}

/// `adhesion_yields_asperity`: adhesion alone presses a virgin asperity beyond delta_CP
/// (the paper's caveat for gold: plastic deformation is then not uncoupled from adhesion).
pub fn adhesion_yields(
    contact: &Contact,
    plastic: &Asperity,
    elastic: &Asperity,
) -> Result<Option<Warning>, Error> {
    let dcp = plastic.delta_cp();
    if !dcp.is_finite() {
        return Ok(None);
    }
    let d0 = zero_load_interference(elastic)?;
    // the body that yields first governs delta_CP: name its E and S_Y
    let counter_yields = matches!(
        crate::model::plasticity(contact, false)?,
        crate::model::AnyPlasticity::EtsionKadin(l)
            if l.yielding_body() == asperity_plastic::YieldingBody::Counter
    );
    let (body, e, s_y) = match (
        counter_yields,
        contact.counter_youngs_modulus,
        contact.counter_yield_stress,
    ) {
        (true, Some(e), Some(s_y)) => ("counter-surface", e, s_y),
        _ => ("asperity", contact.youngs_modulus, contact.yield_stress),
    };
    Ok((d0 > dcp).then(|| Warning {
        code: "adhesion_yields_asperity",
        message: format!(
            "adhesion alone presses an asperity to {} at zero load, beyond its yield onset delta_CP = {} ({body} yields first: E = {}, S_Y = {}; w = {} J/m^2): the model assumes plasticity uncoupled from adhesion, which does not hold here (the paper's caveat for gold)",
            render::si(d0, "m", 3),
            render::si(dcp, "m", 3),
            render::pressure(e),
            render::pressure(s_y),
            crate::scene::num(contact.work_of_adhesion),
        ),
    }))
}

/// `beyond_fit_range` for single asperities: the largest delta_max/delta_CP asked.
pub fn asperity_beyond_fit(dcp: f64, delta_max: &[f64]) -> Option<Warning> {
    let worst = delta_max.iter().fold(0.0f64, |m, &d| m.max(d / dcp));
    (worst > FIT_RANGE_MAX).then(|| Warning {
        code: "beyond_fit_range",
        message: format!(
            "delta_max/delta_CP reaches {worst:.1}, beyond the range of the Etsion-Kadin fits (1 to {FIT_RANGE_MAX}): eqs 4, 5 and 12 are extrapolated"
        ),
    })
}

/// `beyond_fit_range` for a rough surface: the share of the load carried by asperities
/// past delta_max/delta_CP = 110.
pub fn surface_beyond_fit(share: f64, at: f64) -> Option<Warning> {
    (share > FIT_SHARE_LIMIT).then(|| Warning {
        code: "beyond_fit_range",
        message: format!(
            "{:.1} % of the load at d = {} is carried by asperities loaded beyond delta_max/delta_CP = {FIT_RANGE_MAX}, where the Etsion-Kadin fits are extrapolated",
            100.0 * share,
            render::si(at, "m", 4)
        ),
    })
}

/// `pressure_above_hardness`: a nominal contact pressure above the hardness (the real
/// contact area would exceed the nominal one), or a pull-out above the Dugdale stress
/// (more than the theoretical strength of the interface over the whole area).
pub fn pressure_above_hardness(contact: &Contact, compressive: f64, pull_out: f64) -> Vec<Warning> {
    let mut out = Vec::new();
    let s_y = contact
        .yield_stress
        .min(contact.counter_yield_stress.unwrap_or(f64::INFINITY));
    let hardness = HARDNESS_FACTOR * s_y;
    if compressive > hardness {
        out.push(Warning {
            code: "pressure_above_hardness",
            message: format!(
                "the nominal contact pressure {} exceeds the hardness {HARDNESS_FACTOR} S_Y = {}: the asperities cannot carry it as separate contacts (the Greenwood-Williamson picture no longer holds)",
                render::pressure(compressive),
                render::pressure(hardness)
            ),
        });
    }
    let sigma0 = contact.work_of_adhesion / contact.z0;
    if pull_out > sigma0 {
        out.push(Warning {
            code: "pressure_above_hardness",
            message: format!(
                "the pull-out pressure {} exceeds the Dugdale stress w/z0 = {}, the strength of the interface over the whole nominal area: separate asperity contacts cannot pull that hard",
                render::pressure(pull_out),
                render::pressure(sigma0)
            ),
        });
    }
    out
}
