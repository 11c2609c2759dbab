//! Physics guards: where a result should not be trusted as it stands, a [`Warning`] says so
//! with numbers (`docs/theory.md` section 8). One code per check. The checks that say the
//! model does not hold at all make the result's [`Validity`] fail, and every verdict says
//! so. The guards ask the laws for what they need (which body yields, the range of their
//! fits), never for their type.

use crate::error::ModelError;
use crate::spec::{Asperity, ContactSpec, Counter};
use contact_core::numeric::{brent_from, expand_bracket, Expansion, Sample, Tolerance};
use contact_core::{AsperityHistory, AsperityModel, Path, PlasticityLaw, YieldingBody};
use serde::Serialize;

/// Tabor's constraint factor: the hardness of a plastically indented surface is about
/// 2.8 S_Y (Tabor 1951). A nominal pressure above it cannot be carried by separate
/// asperity contacts.
pub const HARDNESS_FACTOR: f64 = 2.8;

/// Share of the load beyond the fits' range above which `beyond_fit_range` is raised.
pub const FIT_SHARE_LIMIT: f64 = 0.01;

/// Share of the load beyond the fits' range above which the model is outside its validity
/// (most of the load rests on extrapolated fits).
pub const FIT_SHARE_INVALID: f64 = 0.5;

/// The codes of the checks.
pub mod code {
    /// Adhesion alone yields a virgin asperity (plasticity not uncoupled from adhesion).
    pub const ADHESION_YIELDS: &str = "adhesion_yields_asperity";
    /// Part of the load (or an asperity case) lies beyond the plasticity fits' range.
    pub const BEYOND_FIT_RANGE: &str = "beyond_fit_range";
    /// A nominal compressive pressure above the hardness 2.8 S_Y.
    pub const ABOVE_HARDNESS: &str = "pressure_above_hardness";
    /// A pull-out pressure above the interface's strength w/z0.
    pub const ABOVE_STRENGTH: &str = "pull_out_above_interface_strength";
    /// An impact that stopped shallower than an earlier one.
    pub const NON_DEEPENING: &str = "non_deepening_impact";
    /// The hold voltage presses the contact deeper than the impact did.
    pub const HOLD_DEEPER_THAN_IMPACT: &str = "hold_deeper_than_impact";
    /// A real contact fraction at which the asperities' spots merge.
    pub const DENSE_CONTACT_SPOTS: &str = "dense_contact_spots";
    /// A value derived for a scene (a topography's GW parameters) outside the domain the
    /// scene key accepts: left out of the fragment written.
    pub const OUTSIDE_SCENE_DOMAIN: &str = "outside_scene_domain";
    /// A quantity derived beside the cycles (a contact state, the hold's rest, the elastic
    /// comparison, a guard's check) that could not be computed: absent from the result,
    /// the cycles and the verdict kept.
    pub const NOT_COMPUTED: &str = "side_quantity_not_computed";
    /// A cycle's reported error estimate (d_e or pull-out) above the accuracy mode's
    /// target: the result is what the mode could do, not what it promises.
    pub const ESTIMATE_ABOVE_TARGET: &str = "estimate_above_target";
    /// In time, the electrode stopped short of the contact (the gas and the spring) although
    /// the vacuum drive would close: the switch does not close.
    pub const DOES_NOT_CLOSE: &str = "does_not_close";
    /// Every code above.
    pub const ALL: [&str; 11] = [
        ADHESION_YIELDS,
        BEYOND_FIT_RANGE,
        ABOVE_HARDNESS,
        ABOVE_STRENGTH,
        NON_DEEPENING,
        HOLD_DEEPER_THAN_IMPACT,
        DENSE_CONTACT_SPOTS,
        OUTSIDE_SCENE_DOMAIN,
        NOT_COMPUTED,
        ESTIMATE_ABOVE_TARGET,
        DOES_NOT_CLOSE,
    ];
}

/// A physics guard raised by a run: the model is used where it leaves its ground.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Warning {
    /// Stable identifier (see [`code`]).
    pub code: &'static str,
    /// What happened and what it means, with numbers.
    pub message: String,
    /// Whether it puts the result outside the model's validity.
    #[serde(skip)]
    pub breaks_validity: bool,
}

impl Warning {
    /// A warning that leaves the model valid.
    pub fn note(code: &'static str, message: String) -> Self {
        Self {
            code,
            message,
            breaks_validity: false,
        }
    }

    /// A warning that puts the result outside the model's validity.
    pub fn invalid(code: &'static str, message: String) -> Self {
        Self {
            code,
            message,
            breaks_validity: true,
        }
    }
}

/// Whether the model holds for a result, and if not, which checks say so.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Default)]
pub struct Validity {
    /// True when no check puts the result outside the model's validity.
    pub holds: bool,
    /// The codes of the checks that do (each once).
    pub reasons: Vec<&'static str>,
}

impl Validity {
    /// The validity of a result with these warnings.
    pub fn of(warnings: &[Warning]) -> Self {
        let mut reasons: Vec<&'static str> = Vec::new();
        for w in warnings.iter().filter(|w| w.breaks_validity) {
            if !reasons.contains(&w.code) {
                reasons.push(w.code);
            }
        }
        Self {
            holds: reasons.is_empty(),
            reasons,
        }
    }

    /// "outside the model's validity: adhesion yields the asperity, ..." (empty when it
    /// holds).
    pub fn words(&self) -> String {
        if self.holds {
            return String::new();
        }
        let parts: Vec<&str> = self
            .reasons
            .iter()
            .map(|c| match *c {
                code::ADHESION_YIELDS => "adhesion alone yields the asperities",
                code::BEYOND_FIT_RANGE => "most of the load rests on extrapolated plasticity fits",
                code::ABOVE_HARDNESS => "the nominal pressure exceeds the hardness",
                code::ABOVE_STRENGTH => "the pull-out exceeds the interface's strength w/z0",
                code::DENSE_CONTACT_SPOTS => {
                    "the contact spots are so dense that they merge (GW asperities are independent)"
                }
                code::NON_DEEPENING => "an impact stopped shallower than an earlier one",
                code::HOLD_DEEPER_THAN_IMPACT => "the hold presses deeper than the impact",
                code::OUTSIDE_SCENE_DOMAIN => "a derived value lies outside its scene key's domain",
                code::NOT_COMPUTED => "a quantity beside the cycles could not be computed",
                code::DOES_NOT_CLOSE => "the electrode stops short of the contact in time",
                code::ESTIMATE_ABOVE_TARGET => {
                    "an error estimate exceeds the accuracy mode's target"
                }
                other => other,
            })
            .collect();
        format!("outside the model's validity: {}", parts.join("; "))
    }
}

/// `estimate_above_target`: the first cycle whose d_e estimate (m) exceeds the mode's
/// target times `sigma_s`, or whose pull-out estimate exceeds its target times the larger
/// of the pull-out and the floor (Pa); each cycle is (number, d_e error, pull-out, its
/// error). Where a mode cannot reach its target the run says so instead of returning a
/// number its estimate disowns (issue 41).
pub fn estimates_within_targets(
    targets: crate::accuracy::Targets,
    sigma_s: f64,
    floor: f64,
    cycles: impl IntoIterator<Item = (usize, f64, f64, f64)>,
) -> Option<Warning> {
    let d_e_target = targets.d_e_tolerance_sigma * sigma_s;
    cycles.into_iter().find_map(|(cycle, d_e_error, pull, pull_error)| {
        let pull_target = targets.pull_out_tolerance * pull.abs().max(floor);
        (d_e_error > d_e_target || pull_error > pull_target).then(|| {
            Warning::note(
                code::ESTIMATE_ABOVE_TARGET,
                format!(
                    "cycle {cycle}: the error estimates ({d_e_error:.3e} m on d_e, {pull_error:.3e} Pa on the pull-out) exceed the {} mode's targets ({d_e_target:.3e} m, {pull_target:.3e} Pa); a tighter mode gives the result to its targets",
                    targets.mode
                ),
            )
        })
    })
}

/// The interference (m) of a virgin elastic asperity in stable adhesive contact under
/// zero external load: the root of F(delta) on the retraction branch (0 for Hertz; the
/// radius when none is found within it).
pub fn zero_load_interference(elastic: &Asperity) -> Result<f64, ModelError> {
    let hist = AsperityHistory::VIRGIN;
    let f = |d: f64| {
        Ok::<_, ModelError>(elastic.force(
            d,
            hist,
            Path::Retract {
                from: d.max(0.0) + 1.0,
            },
        )?)
    };
    let f0 = f(0.0)?;
    if f0 >= 0.0 {
        return Ok(0.0);
    }
    let first = 1e-12f64.max(elastic.radius() * 1e-9);
    let Some((lo, hi)) = expand_bracket(
        "zero-load interference",
        f,
        Sample { x: 0.0, f: f0 },
        first,
        Expansion::Geometric(2.0),
        elastic.radius(),
    )?
    else {
        return Ok(elastic.radius());
    };
    let top = hi.x;
    brent_from(
        "zero-load interference",
        |d| Ok::<_, ModelError>(elastic.force(d, hist, Path::Retract { from: top })?),
        lo,
        hi,
        Tolerance::relative(1e-10),
    )
}

/// `adhesion_yields_asperity`: adhesion alone presses a virgin asperity beyond delta_CP
/// (the paper's caveat for gold: plastic deformation is then not uncoupled from adhesion).
/// A validity breach for a plasticity law that assumes the uncoupling; a note for one whose
/// state the adhesive contact drives ([`contact_core::PlasticityLaw::couples_adhesion`]).
pub fn adhesion_yields(contact: &ContactSpec) -> Result<Option<Warning>, ModelError> {
    let plastic = contact.asperity();
    let dcp = plastic.delta_cp();
    if !dcp.is_finite() {
        return Ok(None);
    }
    let d0 = zero_load_interference(&contact.elastic_asperity())?;
    if d0 <= dcp {
        return Ok(None);
    }
    // the body that yields first governs delta_CP: name its E and S_Y
    let (body, e, s_y) = match (plastic.yielding_body(), contact.counter) {
        (
            Some(YieldingBody::Counter),
            Counter::Material {
                youngs_modulus,
                yield_stress,
                ..
            },
        ) => ("counter-surface", youngs_modulus, yield_stress),
        _ => ("asperity", contact.youngs_modulus, contact.yield_stress),
    };
    let what = format!(
        "adhesion alone presses an asperity to {} at zero load, beyond its yield onset delta_CP = {} ({body} yields first: E = {}, S_Y = {}; w = {} J/m^2)",
        si(d0, "m", 3),
        si(dcp, "m", 3),
        si(e, "Pa", 4),
        si(s_y, "Pa", 4),
        crate::keys::num(contact.work_of_adhesion),
    );
    // a breach only for a law that assumes plasticity uncoupled from adhesion
    if contact.plasticity.law.couples_adhesion() {
        return Ok(Some(Warning::note(
            code::ADHESION_YIELDS,
            format!(
                "{what}: plasticity_law = \"{}\" drives the plastic state by the adhesive contact, so this is inside its model",
                contact.plasticity.name
            ),
        )));
    }
    Ok(Some(Warning::invalid(
        code::ADHESION_YIELDS,
        format!(
            "{what}: the model assumes plasticity uncoupled from adhesion, which does not hold here (the paper's caveat for gold; plasticity_law = \"adhesion_coupled\" does not assume it)"
        ),
    )))
}

/// The upper end of the plasticity law's fitted omega range, if it has one.
pub fn fit_range_max(contact: &ContactSpec) -> Option<f64> {
    contact.asperity().fit_range().map(|r| r.1)
}

/// `beyond_fit_range` for single asperities: the largest delta_max/delta_CP asked, beyond
/// the plasticity law's fitted range (a warning; the model's validity fails when every case
/// is beyond it).
pub fn asperity_beyond_fit(contact: &ContactSpec, delta_max: &[f64]) -> Option<Warning> {
    let hi = fit_range_max(contact)?;
    let dcp = contact.asperity().delta_cp();
    // the fits are read at the Hertz interference (delta_max itself for a law uncoupled
    // from adhesion)
    let law = &contact.plasticity.law;
    let omegas: Vec<f64> = delta_max
        .iter()
        .map(|&d| {
            let st = law.state(d);
            (d + st.adhesive_displacement) / dcp
        })
        .collect();
    let worst = omegas.iter().fold(0.0f64, |m, &w| m.max(w));
    let beyond = omegas.iter().filter(|&&w| w > hi).count();
    (worst > hi).then(|| {
        let message = format!(
            "delta_max/delta_CP reaches {worst:.1}, beyond the range of the {} fits (1 to {hi}): the law is extrapolated there",
            contact.plasticity.name
        );
        if beyond == omegas.len() {
            Warning::invalid(code::BEYOND_FIT_RANGE, message)
        } else {
            Warning::note(code::BEYOND_FIT_RANGE, message)
        }
    })
}

/// `beyond_fit_range` for a rough surface: the share of the load at `at` carried by
/// asperities past the fits' range (a warning above 1 %, outside the validity above 50 %).
pub fn surface_beyond_fit(contact: &ContactSpec, share: f64, at: f64) -> Option<Warning> {
    let hi = fit_range_max(contact)?;
    (share > FIT_SHARE_LIMIT).then(|| {
        let message = format!(
            "{:.1} % of the load at d = {} is carried by asperities loaded beyond delta_max/delta_CP = {hi}, where the {} fits are extrapolated",
            100.0 * share,
            si(at, "m", 4),
            contact.plasticity.name
        );
        if share > FIT_SHARE_INVALID {
            Warning::invalid(code::BEYOND_FIT_RANGE, message)
        } else {
            Warning::note(code::BEYOND_FIT_RANGE, message)
        }
    })
}

/// `pressure_above_hardness`: a nominal contact pressure above the hardness (the real
/// contact area would exceed the nominal one), and `pull_out_above_interface_strength`: a
/// pull-out above the Dugdale stress (more than the theoretical strength of the interface
/// over the whole area).
pub fn pressures(contact: &ContactSpec, compressive: f64, pull_out: f64) -> Vec<Warning> {
    let mut out = Vec::new();
    let hardness = HARDNESS_FACTOR * contact.weakest_yield_stress();
    if compressive > hardness {
        out.push(Warning::invalid(
            code::ABOVE_HARDNESS,
            format!(
                "the nominal contact pressure {} exceeds the hardness {HARDNESS_FACTOR} S_Y = {}: the asperities cannot carry it as separate contacts (the Greenwood-Williamson picture no longer holds)",
                si(compressive, "Pa", 4),
                si(hardness, "Pa", 4)
            ),
        ));
    }
    let sigma0 = contact.dugdale_stress();
    if pull_out > sigma0 {
        out.push(Warning::invalid(
            code::ABOVE_STRENGTH,
            format!(
                "the pull-out pressure {} exceeds the Dugdale stress w/z0 = {}, the strength of the interface over the whole nominal area: separate asperity contacts cannot pull that hard",
                si(pull_out, "Pa", 4),
                si(sigma0, "Pa", 4)
            ),
        ));
    }
    out
}

/// `value` in `unit` with the SI prefix that keeps 1 to 3 digits before the point and
/// `digits` significant digits (never "0.000000" for a non-zero value).
pub fn si(value: f64, unit: &str, digits: usize) -> String {
    if value == 0.0 {
        return format!("0 {unit}");
    }
    if !value.is_finite() {
        return format!("{value} {unit}");
    }
    const PREFIXES: [(f64, &str); 9] = [
        (1e12, "T"),
        (1e9, "G"),
        (1e6, "M"),
        (1e3, "k"),
        (1.0, ""),
        (1e-3, "m"),
        (1e-6, "u"),
        (1e-9, "n"),
        (1e-12, "p"),
    ];
    let a = value.abs();
    if !(1e-12..1e15).contains(&a) {
        return format!("{value:.*e} {unit}", digits.saturating_sub(1));
    }
    let (scale, prefix) = PREFIXES
        .iter()
        .copied()
        .find(|(s, _)| a >= *s)
        .unwrap_or((1e-12, "p"));
    let x = value / scale;
    if x.abs() >= 1e3 || x.abs() < 1e-3 {
        return format!("{value:.*e} {unit}", digits.saturating_sub(1));
    }
    let int_digits = (x.abs().log10().floor() as i64 + 1).max(1) as usize;
    let decimals = digits.saturating_sub(int_digits);
    format!("{x:.decimals$} {prefix}{unit}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validity_lists_each_breaking_code_once() {
        let w = vec![
            Warning::invalid(code::ABOVE_HARDNESS, "a".into()),
            Warning::note(code::BEYOND_FIT_RANGE, "b".into()),
            Warning::invalid(code::ABOVE_HARDNESS, "c".into()),
            Warning::invalid(code::ABOVE_STRENGTH, "d".into()),
        ];
        let v = Validity::of(&w);
        assert!(!v.holds);
        assert_eq!(v.reasons, vec![code::ABOVE_HARDNESS, code::ABOVE_STRENGTH]);
        assert!(v.words().starts_with("outside the model's validity: "));
        assert!(Validity::of(&w[1..2]).holds);
        // every code the guards raise reads as words, never as the code itself
        for c in code::ALL {
            let words = Validity::of(&[Warning::invalid(c, "x".into())]).words();
            assert!(!words.contains(c), "{words}");
        }
    }

    #[test]
    fn numbers_take_the_prefix_that_fits() {
        assert_eq!(si(16_880.37, "Pa", 4), "16.88 kPa");
        assert_eq!(si(7.78e-9, "m", 3), "7.78 nm");
        assert_eq!(si(1e-20, "Pa", 3), "1.00e-20 Pa");
    }
}
