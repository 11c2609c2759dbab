//! A validated spec is read-only; a changed setting goes through validation again: the
//! `with_*` methods re-apply every rule and the curve budget, keep the law registry the
//! spec was validated against, and the echo states the setting the new spec runs with.

use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene;
use stiction_model::spec::{AsperitySpec, ContactStates, Spec, SurfaceSpec, SwitchSpec};
use stiction_model::switch::SwitchModel;
use stiction_model::{Accuracy, ModelError, Silent};

fn paper_switch() -> SwitchSpec {
    SwitchSpec::new(&Scene::paper(Kind::Switch), &LawRegistry::builtin()).unwrap()
}

#[test]
fn the_echo_states_the_accuracy_actually_run() -> Result<(), ModelError> {
    let spec = paper_switch();
    assert_eq!(spec.common().accuracy(), Accuracy::Accurate);
    for mode in [Accuracy::Fast, Accuracy::Balanced, Accuracy::Reference] {
        let changed = spec.with_accuracy(mode)?;
        assert_eq!(changed.common().accuracy(), mode);
        assert_eq!(changed.common().echo()["accuracy"], mode.as_str());
        // the scene it carries says so too: validated again, it is the same spec
        let again = SwitchSpec::new(changed.common().scene(), &LawRegistry::builtin())?;
        assert_eq!(again.common().echo(), changed.common().echo());
        // the original is untouched
        assert_eq!(spec.common().accuracy(), Accuracy::Accurate);
        assert_eq!(spec.common().echo()["accuracy"], "accurate");
    }
    // a run of the changed spec runs the mode its echo states: as the mode given in the
    // scene itself
    let mut scene = Scene::paper(Kind::Switch);
    scene.set_text("accuracy", "fast")?;
    scene.set_number("points", 0.0)?;
    scene.set_number("cycles", 2.0)?;
    let given = SwitchSpec::new(&scene, &LawRegistry::builtin())?;
    let changed = spec.with_values(&[
        ("points", stiction_model::spec::count_value(0)),
        ("cycles", stiction_model::spec::count_value(2)),
    ])?;
    let changed = changed.with_accuracy(Accuracy::Fast)?;
    assert_eq!(changed.common().echo(), given.common().echo());
    let a = SwitchModel::build(&given)?.run(&Silent)?;
    let b = SwitchModel::build(&changed)?.run(&Silent)?;
    assert_eq!(
        serde_json::to_string(&a.cycles).unwrap(),
        serde_json::to_string(&b.cycles).unwrap()
    );
    Ok(())
}

#[test]
fn a_changed_setting_is_validated_again() -> Result<(), ModelError> {
    let spec = paper_switch();
    // the curve budget: points x cycles within MAX_CURVE_POINTS
    let e = spec.with_points(2_000_000).unwrap_err();
    assert!(e.to_string().contains("points"), "{e}");
    let e = spec.with_cycles(0).unwrap_err();
    assert!(e.to_string().contains("cycles"), "{e}");
    let e = spec
        .with_value("accuracy", toml::Value::String("quick".into()))
        .unwrap_err();
    assert!(e.to_string().contains("accuracy"), "{e}");
    // several keys at once are validated once, together
    let s = spec.with_values(&[
        ("cycles", stiction_model::spec::count_value(20)),
        ("until_accommodated", toml::Value::Boolean(true)),
    ])?;
    assert_eq!((s.cycles(), s.until_accommodated()), (20, true));
    assert_eq!(s.common().echo()["cycles"], 20);
    assert_eq!(s.common().echo()["until_accommodated"], true);
    let s = spec.with_contact_states(ContactStates::None)?;
    assert_eq!(s.contact_states(), ContactStates::None);
    assert_eq!(s.common().echo()["contact_state"], "none");
    Ok(())
}

#[test]
fn every_kind_changes_through_its_constructor() -> Result<(), ModelError> {
    let registry = LawRegistry::builtin();
    let a = AsperitySpec::new(&Scene::paper(Kind::Asperity), &registry)?;
    let a = a.with_accuracy(Accuracy::Fast)?.with_points(50)?;
    assert_eq!(
        (a.common().accuracy(), a.common().points()),
        (Accuracy::Fast, 50)
    );
    assert_eq!(a.common().echo()["points"], 50);
    let s = SurfaceSpec::new(&Scene::paper(Kind::Surface), &registry)?;
    let s = s.with_accuracy(Accuracy::Balanced)?;
    assert_eq!(s.common().echo()["accuracy"], "balanced");
    let spec = Spec::new(&Scene::paper(Kind::Switch), &registry)?;
    let spec = spec.with_accuracy(Accuracy::Fast)?;
    assert_eq!(spec.common().accuracy(), Accuracy::Fast);
    assert_eq!(spec.common().echo()["accuracy"], "fast");
    Ok(())
}
