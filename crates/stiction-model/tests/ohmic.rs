//! The ohmic switch (issue: contact area, spots and contact resistance), verified against
//! closed forms and invariants:
//!
//! * a Greenwood-Williamson surface of Hertzian asperities against the closed forms of
//!   its integrals (Greenwood & Williamson 1966): with t = d/sigma and
//!   F_n(t) = integral_t^inf (s - t)^n phi(s) ds,
//!   A_r/A_n = pi N R sigma F_1(t), n = N F_0(t), mean a = sqrt(R sigma) F_1/2(t) / F_0(t),
//!   and the conductance per area N integral g(a(s)) phi(s) ds with a = sqrt(R sigma (s-t)),
//!   each F computed here independently (Simpson in v with s = t + v^2, which removes the
//!   square root at the lower end);
//! * the hold balance: the contact pressure at the rest equals the hold pressure; with no
//!   hold voltage the switch rests shut exactly when it sticks (the spring alone against
//!   the pull-out); a hold pressing harder than the impact rests deeper and says so;
//! * the resistance: 1 / (G/A_n x phi x electrode_area).

use stiction_model::contact_core::{Path, SurfaceLaw};
use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::ohmic::Conduction;
use stiction_model::scene::Scene;
use stiction_model::spec::{SurfaceSpec, SwitchSpec};
use stiction_model::switch::{rough_surface, SwitchModel, SwitchResult};
use stiction_model::{Accuracy, Silent};

/// F_n(t) = integral_t^inf (s - t)^n phi(s) ds = integral_0^V 2 v^(2n+1) phi(t + v^2) dv.
fn f_n(n: f64, t: f64) -> f64 {
    let upper = (12.0f64 - t.min(0.0)).max(1.0).sqrt() + 1.0;
    let m = 40_000;
    let h = upper / m as f64;
    let phi = |s: f64| (-0.5 * s * s).exp() / (2.0 * std::f64::consts::PI).sqrt();
    let g = |v: f64| 2.0 * v.powf(2.0 * n + 1.0) * phi(t + v * v);
    let mut sum = g(0.0) + g(upper);
    for i in 1..m {
        sum += if i % 2 == 1 { 4.0 } else { 2.0 } * g(i as f64 * h);
    }
    sum * h / 3.0
}

/// The same kind of integral with any function of the spot radius.
fn spot_integral(t: f64, r_sigma: f64, g_of_a: &dyn Fn(f64) -> f64) -> f64 {
    let upper = (12.0f64 - t.min(0.0)).max(1.0).sqrt() + 1.0;
    let m = 40_000;
    let h = upper / m as f64;
    let phi = |s: f64| (-0.5 * s * s).exp() / (2.0 * std::f64::consts::PI).sqrt();
    let g = |v: f64| 2.0 * v * g_of_a((r_sigma * v * v).sqrt()) * phi(t + v * v);
    let mut sum = g(0.0) + g(upper);
    for i in 1..m {
        sum += if i % 2 == 1 { 4.0 } else { 2.0 } * g(i as f64 * h);
    }
    sum * h / 3.0
}

#[test]
fn hertzian_surface_meets_the_gw_closed_forms() {
    let mut scene = Scene::paper(Kind::Surface);
    scene.set_text("contact.adhesion_law", "hertz").unwrap();
    scene.set_text("contact.plasticity_law", "elastic").unwrap();
    let spec = SurfaceSpec::new(&scene, &LawRegistry::builtin()).unwrap();
    let gw = rough_surface(
        spec.contact(),
        spec.roughness(),
        Accuracy::Accurate,
        0.0,
        false,
    )
    .unwrap();
    let (sigma, n, r) = (
        spec.roughness().sigma_s(),
        spec.roughness().asperity_density(),
        spec.contact().radius(),
    );
    let c = Conduction::new(2.2e-8, 37.7e-9).unwrap();
    let g = move |a: f64| c.spot_conductance(a);
    for t in [-1.0, 0.0, 1.5, 3.0] {
        let d = t * sigma;
        let spots = gw
            .contact_spots(d, &gw.virgin(), Path::Approach, Some(&g))
            .unwrap();
        let area = std::f64::consts::PI * n * r * sigma * f_n(1.0, t);
        let count = n * f_n(0.0, t);
        let mean_a = (r * sigma).sqrt() * f_n(0.5, t) / f_n(0.0, t);
        let conductance = n * spot_integral(t, r * sigma, &|a| if a > 0.0 { g(a) } else { 0.0 });
        for (what, got, want) in [
            ("A_r/A_n", spots.real_contact_fraction, area),
            ("spot density", spots.spot_density, count),
            ("mean spot radius", spots.mean_spot_radius, mean_a),
            (
                "conductance per area",
                spots.conductance_per_area.unwrap(),
                conductance,
            ),
        ] {
            assert!(
                (got / want - 1.0).abs() < 1e-6,
                "t = {t}: {what} {got:e} vs closed form {want:e}"
            );
        }
        assert!(spots.relative_error < 1e-6);
    }
}

fn switch_scene(edits: &[(&str, &str)]) -> Scene {
    let mut s = Scene::paper(Kind::Switch);
    s.set_text("accuracy", "balanced").unwrap();
    s.set_text("points", "0").unwrap();
    s.set_text("cycles", "4").unwrap();
    s.set_text("elastic_comparison", "false").unwrap();
    for (k, v) in edits {
        s.set_text(k, v).unwrap();
    }
    s
}

fn run(scene: &Scene) -> (SwitchSpec, SwitchResult) {
    let spec = SwitchSpec::new(scene, &LawRegistry::builtin()).unwrap();
    let r = SwitchModel::build(&spec).unwrap().run(&Silent).unwrap();
    (spec, r)
}

#[test]
fn the_hold_balances_and_the_resistance_is_the_spots_in_parallel() {
    let (spec, r) = run(&switch_scene(&[]));
    assert_eq!(
        r.hold_voltage, r.voltage,
        "default hold: the actuation voltage"
    );
    let g = spec.switch();
    let gap = g.t_d() / g.epsilon_r();
    let p_es = 0.5 * g.epsilon_0() * r.voltage * r.voltage / (gap * gap);
    let want = (p_es - r.restoring_pressure) / g.contact_area_fraction();
    assert!((r.hold_pressure / want - 1.0).abs() < 1e-12);
    let conduction = spec.contact().conduction().unwrap();
    for c in &r.cycles {
        assert_eq!(c.hold_status, "rests");
        let h = c.hold.as_ref().unwrap();
        // on the unloading branch, above d_e, where the contact pushes with the hold
        assert!(h.separation > c.d_e);
        assert!(
            (h.contact_pressure / r.hold_pressure - 1.0).abs() < 1e-6,
            "cycle {}: {} vs {}",
            c.cycle,
            h.contact_pressure,
            r.hold_pressure
        );
        // fewer, smaller spots than at the end of impact
        let e = c.end_of_impact.as_ref().unwrap();
        assert_eq!(e.separation, c.d_e);
        assert!(h.real_contact_fraction < e.real_contact_fraction);
        assert!(h.contact_resistance.unwrap() > e.contact_resistance.unwrap());
        let area = g.contact_area_fraction() * g.electrode_area().unwrap();
        let spots = h.spots.unwrap();
        assert!((spots / (h.spot_density * area) - 1.0).abs() < 1e-12);
        // the spots of the mean radius in parallel: the Wexler resistance is decreasing
        // and convex in a, so by Jensen 1/R_W(mean a) >= mean of 1/R_W(a) is not given;
        // a loose sanity bound (same order) only
        let one = conduction.spot_resistance(h.mean_spot_radius) / spots;
        let ratio = h.contact_resistance.unwrap() / one;
        assert!(ratio > 0.1 && ratio < 10.0, "R / R(mean spot) = {ratio}");
        let with = h.contact_resistance_with_interaction.unwrap();
        assert!(
            (with - h.contact_resistance.unwrap() - conduction.interaction_resistance(area)).abs()
                < 1e-12 * with
        );
    }
}

#[test]
fn without_a_hold_voltage_the_switch_rests_shut_exactly_when_it_sticks() {
    // a sticking switch (the paper's) and a free one (composite eq 1, stiff spring)
    for (name, edits, sticks) in [
        ("paper", vec![("switch.hold_voltage", "0")], true),
        (
            "free",
            vec![
                ("switch.hold_voltage", "0"),
                ("contact.yield_modulus", "composite"),
                ("switch.impact_energy", "2.0"),
            ],
            false,
        ),
    ] {
        let scene = switch_scene(&edits.iter().map(|(a, b)| (*a, *b)).collect::<Vec<_>>());
        let (_, r) = run(&scene);
        assert_eq!(r.stiction, sticks, "{name}: ratio {}", r.pull_out_ratio);
        assert!(r.hold_pressure < 0.0, "{name}: only the spring acts");
        for c in &r.cycles {
            if c.sticks {
                assert_eq!(c.hold_status, "rests", "{name} cycle {}", c.cycle);
                let h = c.hold.as_ref().unwrap();
                // held by adhesion: a tensile contact pressure equal to the spring's pull
                assert!((h.contact_pressure / r.hold_pressure - 1.0).abs() < 1e-6);
            } else {
                assert_eq!(c.hold_status, "opens", "{name} cycle {}", c.cycle);
                assert!(c.hold.is_none());
            }
        }
    }
}

#[test]
fn a_hold_pressing_harder_than_the_impact_rests_deeper_and_says_so() {
    let (_, r) = run(&switch_scene(&[("switch.hold_voltage", "400")]));
    let c = &r.cycles[0];
    assert_eq!(c.hold_status, "deeper_than_impact");
    let h = c.hold.as_ref().unwrap();
    assert!(h.separation < c.d_e);
    assert!((h.contact_pressure / r.hold_pressure - 1.0).abs() < 1e-6);
    assert!(r
        .warnings
        .iter()
        .any(|w| w.code == "hold_deeper_than_impact"));
}

#[test]
fn contact_state_none_computes_nothing_and_last_cycle_only_the_last() {
    let (_, none) = run(&switch_scene(&[("contact_state", "none")]));
    assert!(none
        .cycles
        .iter()
        .all(|c| c.hold.is_none() && c.end_of_impact.is_none() && c.hold_status == "not_computed"));
    let (_, last) = run(&switch_scene(&[("contact_state", "last_cycle")]));
    let (_, every) = run(&switch_scene(&[]));
    let n = last.cycles.len();
    assert!(last.cycles[..n - 1].iter().all(|c| c.hold.is_none()));
    let (a, b) = (
        last.cycles[n - 1].hold.as_ref().unwrap(),
        every.cycles[n - 1].hold.as_ref().unwrap(),
    );
    assert_eq!(a.contact_resistance, b.contact_resistance);
    // the verdict does not depend on it
    assert_eq!(none.pull_out_ratio, every.pull_out_ratio);
}

#[test]
fn no_conduction_no_resistance_and_the_keys_say_what_is_missing() {
    let mut s = switch_scene(&[]);
    s.remove("contact.resistivity");
    s.remove("contact.mean_free_path");
    let (_, r) = run(&s);
    let h = r.cycles[0].hold.as_ref().unwrap();
    assert!(h.contact_resistance.is_none() && h.real_contact_fraction > 0.0);
    // resistivity without a mean free path names the missing key
    let mut s = switch_scene(&[]);
    s.remove("contact.mean_free_path");
    let e = SwitchSpec::new(&s, &LawRegistry::builtin())
        .unwrap_err()
        .to_string();
    assert!(e.contains("contact.mean_free_path"), "{e}");
    // two holds
    let s = switch_scene(&[("switch.hold_voltage", "30"), ("switch.hold_force", "1e-4")]);
    let e = SwitchSpec::new(&s, &LawRegistry::builtin())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("switch.hold_force") && e.contains("hold_voltage"),
        "{e}"
    );
}

#[test]
fn a_hold_force_is_a_pressure_over_the_contact_area() {
    let (spec, r) = run(&switch_scene(&[("switch.hold_force", "2e-3")]));
    let g = spec.switch();
    let want = 2e-3 / (g.contact_area_fraction() * g.electrode_area().unwrap());
    assert!((r.hold_pressure / want - 1.0).abs() < 1e-12);
    let h = r.cycles[0].hold.as_ref().unwrap();
    assert!((h.contact_pressure / want - 1.0).abs() < 1e-6);
}

/// `design threshold --require contact_resistance<LIMIT`: the requirement's crossing lies
/// between the scan points where it flips, and the window (free of stiction, closing, and
/// below the resistance) agrees point by point with independent design-point runs.
#[test]
fn the_design_window_holds_point_by_point() {
    use stiction_model::design::{self, Evaluator};
    let registry = LawRegistry::builtin();
    let mut s = Scene::paper(Kind::Switch);
    s.remove("switch.impact_energy");
    s.set_text("switch.k_s", "3e11").unwrap();
    s.set_text("switch.voltage", "300").unwrap();
    s.set_text("contact.yield_modulus", "composite").unwrap();
    let limit = 4e-6;
    let require = format!("contact_resistance<{limit}");
    let t = design::threshold_with(
        &s,
        &registry,
        "switch.voltage",
        100.0,
        500.0,
        Some(Accuracy::Fast),
        Some(&require),
        &stiction_model::Silent,
    )
    .unwrap();
    let req = t.threshold.requirement.as_ref().unwrap();
    assert_eq!(req.crossings.len(), 1, "{req:?}");
    let rc = &req.crossings[0];
    assert_eq!(
        rc.met_side.word(),
        "above",
        "more voltage, more hold, less resistance"
    );
    let stiction = t.threshold.critical_value.unwrap();
    assert_eq!(t.threshold.free_side.word(), "below");
    assert_eq!(req.window.len(), 1);
    let w = req.window[0];
    assert!((w[0] - rc.value).abs() <= rc.uncertainty, "{w:?} vs {rc:?}");
    assert!(
        (w[1] - stiction).abs() <= t.threshold.uncertainty.unwrap(),
        "{w:?}"
    );
    // independent runs of the design points, inside and outside the window
    let base = design::design_scene(&s, Some(Accuracy::Fast)).unwrap();
    let ev = Evaluator::new(base, &registry);
    let r = design::Requirement::parse(&require).unwrap();
    for v in [
        200.0,
        0.97 * w[0],
        1.03 * w[0],
        0.5 * (w[0] + w[1]),
        0.97 * w[1],
        1.03 * w[1],
        480.0,
    ] {
        let inside = v > w[0] && v < w[1];
        let p = ev.point(&[("switch.voltage", v)]).unwrap();
        assert_eq!(r.in_window(&p), inside, "at {v} V: {p:?}");
        if p.closes {
            let resistance = p.contact_resistance.unwrap();
            assert_eq!(
                resistance < limit,
                v > rc.value,
                "at {v} V: R = {resistance}"
            );
        }
    }
}

/// The requirement is checked against the scene before any point runs.
#[test]
fn a_requirement_the_scene_cannot_compute_is_refused_by_name() {
    use stiction_model::design;
    let registry = LawRegistry::builtin();
    let mut s = Scene::paper(Kind::Switch);
    s.remove("switch.electrode_area");
    let e = design::threshold_with(
        &s,
        &registry,
        "switch.impact_energy",
        0.1,
        1.0,
        Some(Accuracy::Fast),
        Some("contact_resistance<1"),
        &stiction_model::Silent,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("require") && e.contains("switch.electrode_area"),
        "{e}"
    );
    let e = design::threshold_with(
        &Scene::paper(Kind::Switch),
        &registry,
        "switch.impact_energy",
        0.1,
        1.0,
        None,
        Some("resistance<1"),
        &stiction_model::Silent,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("unknown quantity"), "{e}");
}

/// A soft Pt-Au film (E = 90 GPa, S_Y = 320 MPa) with eq 12 as printed: after a few
/// cycles the impacts stop short of the deepest one and every later cycle repeats the one
/// before it. Its contact states are solved once and shared (`contact_states`); the shared
/// state must be the one a run solving that cycle alone (`last_cycle`) finds, to the bit.
#[test]
fn a_repeated_cycle_shares_the_contact_state_solved_for_it_alone() {
    let soft = |state: &str| {
        let mut s = switch_scene(&[
            ("accuracy", "fast"),
            ("cycles", "12"),
            ("contact_state", state),
            ("contact.youngs_modulus", "90e9"),
            ("contact.poisson_ratio", "0.42"),
            ("contact.yield_stress", "320e6"),
            ("contact.radius", "2e-6"),
            ("contact.work_of_adhesion", "0.08"),
            ("contact.z0", "0.2e-9"),
            ("contact.yield_modulus", "composite"),
            ("surface.sigma_s", "2.2e-8"),
            ("surface.asperity_density", "3e12"),
            ("switch.film_thickness", "0.6e-6"),
            ("switch.contact_area_fraction", "0.02"),
        ]);
        s.set_text("until_accommodated", "false").unwrap();
        // the spring given, the impact energy derived from it
        s.remove("switch.impact_energy");
        s.set_text("switch.k_s", "2e9").unwrap();
        run(&s).1
    };
    let every = soft("every_cycle");
    let last = soft("last_cycle");
    let n = every.cycles.len();
    assert_eq!(n, 12);
    // the scene does what the test needs: its last cycle repeats the one before
    let (a, b) = (&every.cycles[n - 2], &every.cycles[n - 1]);
    assert!(
        !b.deepened && a.d_e.to_bits() == b.d_e.to_bits(),
        "{} {}",
        a.d_e,
        b.d_e
    );
    let json = |c: &stiction_model::switch::CycleResult| {
        serde_json::to_string(&(&c.hold, c.hold_status, &c.end_of_impact)).unwrap()
    };
    assert!(every.cycles.iter().all(|c| c.hold_status != "not_computed"));
    assert_eq!(json(&every.cycles[n - 1]), json(&last.cycles[n - 1]));
    assert_eq!(json(&every.cycles[n - 2]), json(&every.cycles[n - 1]));
}

/// A hold the surface cannot bear (1e5 V on the paper's switch: some 1e17 Pa per contact
/// area, beyond any pressure of the surface down to its deepest separation) leaves the hold
/// state absent with a warning, never the run: the cycles, the pull-out and the verdict are
/// those of the run without contact states (../shared/repro/2026-11-24 D13, which lost them).
#[test]
fn a_hold_the_surface_cannot_bear_is_a_warning_and_the_cycles_are_kept() {
    let (_, held) = run(&switch_scene(&[("switch.hold_voltage", "1e5")]));
    let (_, none) = run(&switch_scene(&[
        ("switch.hold_voltage", "1e5"),
        ("contact_state", "none"),
    ]));
    assert_eq!(held.cycles.len(), none.cycles.len());
    for (a, b) in held.cycles.iter().zip(&none.cycles) {
        assert_eq!(a.d_e.to_bits(), b.d_e.to_bits());
        assert_eq!(a.pull_out_pressure.to_bits(), b.pull_out_pressure.to_bits());
        assert_eq!(a.sticks, b.sticks);
        assert_eq!(a.hold_status, "not_computable", "cycle {}", a.cycle);
        assert!(a.hold.is_none());
    }
    assert_eq!(held.stiction, none.stiction);
    assert_eq!(held.first_sticking_cycle, none.first_sticking_cycle);
    assert!(
        held.warnings
            .iter()
            .any(|w| w.code == "side_quantity_not_computed"
                && w.message.contains("the rest under the hold of cycle 1")),
        "{:?}",
        held.warnings
    );
    // absent values are null in JSON, never a number made up
    let v = serde_json::to_value(&held).unwrap();
    assert!(v["cycles"][0]["hold"].is_null());
    assert_eq!(v["cycles"][0]["hold_status"], "not_computable");
}
