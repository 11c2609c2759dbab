//! Issue 44 item 1: `switch.dimple_height`, the air gap at which the contact (dimples or a
//! bump) touches. The electrode travels d0 - h, the gap at contact is h + t_d/eps_r, the
//! spring pulls back with K_s (d0 - h): every output that uses them (drive B's derived E_I,
//! the pull-in voltages, the restoring pressure, the hold) takes it into account.

use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene;
use stiction_model::spec::SwitchSpec;
use stiction_model::switch::{electrostatics, SwitchModel};
use stiction_model::Silent;

/// The dimpled switch: a 20 N/m spring on a (100 um)^2 electrode at its static
/// pull-in voltage, dimples on 1 % of the area, the paper's films and gap, fast.
fn dimpled(h: f64) -> SwitchSpec {
    let mut s = Scene::paper(Kind::Switch);
    s.remove("switch.impact_energy");
    for (k, v) in [
        ("switch.spring_constant", "20.0"),
        ("switch.contact_area_fraction", "0.01"),
        ("switch.dimple_height", &format!("{h:e}")),
        ("accuracy", "\"fast\""),
        ("points", "0"),
        ("elastic_comparison", "false"),
        ("cycles", "3"),
    ] {
        s.set_text(k, v).unwrap();
    }
    SwitchSpec::new(&s, &LawRegistry::builtin()).unwrap()
}

#[test]
fn the_drive_and_the_hold_end_at_the_dimple_gap() {
    let eps0: f64 = 8.854e-12;
    let (d0, t_d, eps_r): (f64, f64, f64) = (2e-6, 0.15e-6, 7.6);
    let k_s: f64 = 20.0 / 1e-8;
    let g = d0 + t_d / eps_r;
    for h in [0.0, 0.3e-6, 1.0e-6] {
        let spec = dimpled(h);
        let (_, es) = electrostatics(&spec).unwrap();
        // V_PI depends on the gap at rest alone; E_I is the net work over the travel d0 - h
        let v = (8.0 * k_s * g.powi(3) / (27.0 * eps0)).sqrt();
        assert!((es.voltage / v - 1.0).abs() < 1e-12);
        let s = d0 - h;
        let e = 0.5 * eps0 * v * v * (1.0 / (h + t_d / eps_r) - 1.0 / g) - 0.5 * k_s * s * s;
        assert!(
            (es.impact_energy / e - 1.0).abs() < 1e-12,
            "h = {h}: {}",
            es.impact_energy
        );
        assert!((es.restoring_pressure / (k_s * s) - 1.0).abs() < 1e-12);
        // the hold at U: eps0 U^2/(2 (h + t_d/eps_r)^2) - K_s (d0 - h), over phi
        let model = SwitchModel::build(&spec).unwrap();
        let hold = (0.5 * eps0 * v * v / (h + t_d / eps_r).powi(2) - k_s * s) / 0.01;
        assert!((model.hold_pressure() / hold - 1.0).abs() < 1e-12);
    }
    // the case: landing on the dielectric the dimples absorb 30x the energy they do
    // at a 0.3 um air gap, and the real contact area is impossible there
    let flat = SwitchModel::build(&dimpled(0.0))
        .unwrap()
        .run(&Silent)
        .unwrap();
    let on_dimples = SwitchModel::build(&dimpled(0.3e-6))
        .unwrap()
        .run(&Silent)
        .unwrap();
    assert!(flat.impact_energy > 30.0 * on_dimples.impact_energy);
    assert!(!flat.validity.holds);
    assert!(on_dimples.validity.holds, "{:?}", on_dimples.validity);
    assert_eq!(on_dimples.scene["switch"]["dimple_height"], 0.3e-6);
}

#[test]
fn a_dimple_that_never_touches_is_refused_by_name() {
    let mut s = Scene::paper(Kind::Switch);
    s.set_text("switch.dimple_height", "2e-6").unwrap();
    let e = SwitchSpec::new(&s, &LawRegistry::builtin())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("switch.dimple_height") && e.contains("below d0"),
        "{e}"
    );
    s.set_text("switch.dimple_height", "-1e-9").unwrap();
    assert!(SwitchSpec::new(&s, &LawRegistry::builtin()).is_err());
}
