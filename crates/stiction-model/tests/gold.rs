//! Issue 43: gold inside the model. The `adhesion_coupled` plasticity law on switches:
//! its weak-adhesion limit on the paper's Ru switch, the validity that follows the law, and
//! the law in every kind of run.

use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::model_form::Forms;
use stiction_model::scene::Scene;
use stiction_model::spec::SwitchSpec;
use stiction_model::switch::SwitchModel;
use stiction_model::Silent;

fn spec(settings: &[(&str, &str)]) -> SwitchSpec {
    let mut s = Scene::paper(Kind::Switch);
    for (k, v) in [
        ("accuracy", "\"fast\""),
        ("points", "0"),
        ("elastic_comparison", "false"),
        ("contact_state", "\"none\""),
    ]
    .iter()
    .chain(settings)
    {
        s.set_text(k, v).unwrap();
    }
    SwitchSpec::new(&s, &LawRegistry::builtin()).unwrap()
}

const GOLD: &[(&str, &str)] = &[
    ("contact.youngs_modulus", "79e9"),
    ("contact.poisson_ratio", "0.42"),
    ("contact.yield_stress", "0.25e9"),
    ("contact.radius", "2e-6"),
    ("contact.work_of_adhesion", "0.3"),
    ("contact.z0", "0.2e-9"),
    ("contact.yield_modulus", "\"composite\""),
    ("contact.reload", "\"bounded\""),
    ("surface.sigma_s", "5e-9"),
    ("surface.asperity_density", "5e12"),
    ("switch.film_thickness", "0.5e-6"),
    ("switch.contact_area_fraction", "0.2"),
    ("switch.dimple_height", "1e-6"),
    ("switch.impact_energy", "1e-3"),
    ("cycles", "3"),
];

/// The model-form check tries `adhesion_coupled` where adhesion alone yields a virgin
/// asperity (the uncoupled laws' assumption fails there), and leaves it out, with the
/// reason, where it does not (the paper's Ru switch: its 8 combinations stay 8).
#[test]
fn the_model_form_check_tries_the_coupled_law_where_adhesion_yields() {
    let paper = Forms::of(&spec(&[]), &LawRegistry::builtin());
    assert_eq!(paper.forms.len(), 8);
    assert!(paper
        .excluded
        .iter()
        .any(|e| e.value == "adhesion_coupled" && e.reason.contains("adhesion does not yield")));
    let mut gold: Vec<(&str, &str)> = GOLD.to_vec();
    gold.push(("contact.plasticity_law", "\"etsion_kadin\""));
    let forms = Forms::of(&spec(&gold), &LawRegistry::builtin());
    assert_eq!(forms.forms.len(), 12);
    assert!(forms
        .forms
        .iter()
        .any(|f| f.plasticity == "adhesion_coupled"));
}

fn switch(settings: &[(&str, &str)]) -> stiction_model::switch::SwitchResult {
    let mut s = Scene::paper(Kind::Switch);
    for (k, v) in [
        ("accuracy", "\"fast\""),
        ("points", "0"),
        ("elastic_comparison", "false"),
        ("contact_state", "\"none\""),
    ]
    .iter()
    .chain(settings)
    {
        s.set_text(k, v).unwrap();
    }
    let spec = SwitchSpec::new(&s, &LawRegistry::builtin()).unwrap();
    SwitchModel::build(&spec).unwrap().run(&Silent).unwrap()
}

/// The limit: the paper's Ru switch with w = 1e-3 J/m^2 under `adhesion_coupled`
/// is within 2e-3 of `etsion_kadin` in every cycle's pull-out (and end of impact).
#[test]
fn weak_adhesion_on_the_paper_switch_is_etsion_kadin() {
    let run = |law: &str| {
        switch(&[
            ("contact.work_of_adhesion", "1e-3"),
            ("contact.plasticity_law", &format!("\"{law}\"")),
            ("cycles", "4"),
        ])
    };
    let (ek, coupled) = (run("etsion_kadin"), run("adhesion_coupled"));
    assert_eq!(coupled.laws.plasticity, "adhesion_coupled");
    for (a, b) in ek.cycles.iter().zip(&coupled.cycles) {
        assert!(
            (a.pull_out_pressure - b.pull_out_pressure).abs() <= 2e-3 * a.pull_out_pressure,
            "cycle {}: {} vs {}",
            a.cycle,
            a.pull_out_pressure,
            b.pull_out_pressure
        );
        assert!(
            (a.d_e - b.d_e).abs() <= 2e-3 * a.d_e.abs(),
            "cycle {}",
            a.cycle
        );
    }
}

/// A dimpled gold switch (E 79 GPa, S_Y 0.25 GPa, w 0.3 J/m^2): adhesion alone yields its
/// asperities. Under a law that assumes the uncoupling that is a breach of validity; under
/// `adhesion_coupled` it is a note, and the verdict is inside the model. The coupled law
/// flattens more (adhesion adds to the core's interference), so it pulls harder.
#[test]
fn a_gold_switch_answers_inside_the_model_under_the_coupled_law() {
    let gold = |law: &str| {
        let plasticity = format!("\"{law}\"");
        let mut settings: Vec<(&str, &str)> = GOLD.to_vec();
        settings.push(("contact.plasticity_law", &plasticity));
        switch(&settings)
    };
    let code = "adhesion_yields_asperity";
    let ek = gold("etsion_kadin");
    assert!(!ek.validity.holds);
    assert!(
        ek.validity.reasons.iter().any(|r| r.contains("adhesion")),
        "{:?}",
        ek.validity
    );
    assert!(ek
        .warnings
        .iter()
        .any(|w| w.code == code && w.breaks_validity));
    let coupled = gold("adhesion_coupled");
    assert!(coupled.validity.holds, "{:?}", coupled.validity);
    let w = coupled.warnings.iter().find(|w| w.code == code).unwrap();
    assert!(!w.breaks_validity && w.message.contains("adhesion_coupled"));
    for (a, b) in ek.cycles.iter().zip(&coupled.cycles) {
        assert!(
            b.pull_out_pressure > a.pull_out_pressure,
            "cycle {}",
            a.cycle
        );
    }
    // the pull-out stays below the interface's strength w/z0 (1.5 GPa)
    assert!(coupled.largest_pull_out < 0.3 / 0.2e-9);
}

/// The law is registered like the others: named in the scene, echoed, with its parameter.
#[test]
fn the_law_is_registered_with_its_base() {
    let r = LawRegistry::builtin();
    let e = r.plasticity("adhesion_coupled").unwrap();
    assert!(e.credible());
    assert_eq!(e.params()[0].name, "base");
    let ke = switch(&[
        ("contact.plasticity_law", "\"adhesion_coupled\""),
        ("cycles", "1"),
    ]);
    let mut s = Scene::paper(Kind::Switch);
    s.set_text("contact.plasticity_law", "\"adhesion_coupled\"")
        .unwrap();
    s.remove("contact.effective_radius");
    s.set_text("contact.plasticity", "{ base = \"kogut_etsion\" }")
        .unwrap();
    for (k, v) in [
        ("accuracy", "\"fast\""),
        ("points", "0"),
        ("elastic_comparison", "false"),
        ("cycles", "1"),
        ("contact_state", "\"none\""),
    ] {
        s.set_text(k, v).unwrap();
    }
    let spec = SwitchSpec::new(&s, &LawRegistry::builtin()).unwrap();
    let with_ke = SwitchModel::build(&spec).unwrap().run(&Silent).unwrap();
    assert_eq!(
        with_ke.scene["contact"]["plasticity"]["base"],
        "kogut_etsion"
    );
    assert!(with_ke.cycles[0].pull_out_pressure != ke.cycles[0].pull_out_pressure);
    s.set_text("contact.plasticity", "{ base = \"elastic\" }")
        .unwrap();
    let e = SwitchSpec::new(&s, &LawRegistry::builtin())
        .unwrap_err()
        .to_string();
    assert!(e.contains("base") && e.contains("elastic"), "{e}");
}
