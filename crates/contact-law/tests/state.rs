//! The one-number history state machine: virgin start, deepening, reversals both ways,
//! the range, invalid input, and the stateless evaluation.

mod common;

use common::{law, toy, HI, LO};
use contact_law::{LawError, Path, State};
use proptest::prelude::*;

#[test]
fn a_fresh_state_follows_the_virgin_envelope_and_deepens() {
    let law = law();
    let mut s = State::VIRGIN;
    assert!(s.is_virgin());
    for d in [3e-8, 1.8e-8, 1.2e-8, 6e-9, 3e-9, 2e-9] {
        let (p, t) = law.pressure(d, &mut s).unwrap();
        assert_eq!((p, t), law.virgin_pressure(d).unwrap());
        assert_eq!((s.d_min, s.path, s.last_d), (d, Path::Approach, d));
        assert_eq!(s.d_turn, f64::INFINITY);
    }
    // far above the reach the pressure is exactly zero
    let mut s = State::VIRGIN;
    assert_eq!(law.pressure(3e-8, &mut s).unwrap(), (0.0, 0.0));
    // the virgin envelope is close to the toy
    let t = toy();
    let mut s = State::VIRGIN;
    let (p, _) = law.pressure(2e-9, &mut s).unwrap();
    assert!((p - t.virgin(2e-9)).abs() < 1e-4 * t.virgin(2e-9).abs());
}

#[test]
fn reversals_switch_the_path_both_ways_at_fixed_history() {
    let law = law();
    let mut s = State::VIRGIN;
    law.pressure(6e-9, &mut s).unwrap();
    law.pressure(3e-9, &mut s).unwrap();
    // approach -> retract
    let (p, t) = law.pressure(3.3e-9, &mut s).unwrap();
    assert_eq!((s.d_min, s.path, s.d_turn), (3e-9, Path::Retract, 3e-9));
    assert_eq!(
        (p, t),
        law.branch_pressure(3.3e-9, 3e-9, Path::Retract).unwrap()
    );
    law.pressure(4e-9, &mut s).unwrap();
    assert_eq!(s.path, Path::Retract);
    // an equal separation is no reversal
    law.pressure(4e-9, &mut s).unwrap();
    assert_eq!(s.path, Path::Retract);
    // retract -> approach above d_min: the reload branch of the same history
    let (p, _) = law.pressure(3.5e-9, &mut s).unwrap();
    assert_eq!((s.d_min, s.path, s.d_turn), (3e-9, Path::Approach, 4e-9));
    assert_eq!(
        p,
        law.branch_pressure(3.5e-9, 3e-9, Path::Approach).unwrap().0
    );
    // approach again past d_min: the history deepens and the envelope applies
    let (p, _) = law.pressure(2.5e-9, &mut s).unwrap();
    assert_eq!(
        (s.d_min, s.path, s.d_turn),
        (2.5e-9, Path::Approach, f64::INFINITY)
    );
    assert_eq!(p, law.virgin_pressure(2.5e-9).unwrap().0);
    // from retract straight below d_min: deepening too
    law.pressure(2.8e-9, &mut s).unwrap();
    assert_eq!(s.path, Path::Retract);
    law.pressure(2.0e-9, &mut s).unwrap();
    assert_eq!((s.d_min, s.path), (2.0e-9, Path::Approach));
}

#[test]
fn the_pressure_is_continuous_through_a_reversal_at_d_min() {
    let law = law();
    let mut s = State::VIRGIN;
    let (pv, _) = law.pressure(3.123e-9, &mut s).unwrap();
    // the retract branch drops by about p_V/(0.02 sigma) per metre: 1e-19 m is 1e-9 of p_V
    let (pr, _) = law.pressure(3.123e-9 + 1e-19, &mut s).unwrap();
    assert_eq!(s.path, Path::Retract);
    assert!((pr - pv).abs() < 1e-8 * pv.abs(), "{pv:e} {pr:e}");
    // exactly at d_min the branch value is the envelope's
    assert_eq!(
        law.branch_pressure(3.123e-9, 3.123e-9, Path::Retract)
            .unwrap()
            .0,
        pv
    );
}

#[test]
fn history_exactness_flags_partial_reloads_and_retractions() {
    let law = law();
    let mut s = State::VIRGIN;
    assert!(law.is_history_exact(&s));
    law.pressure(3e-9, &mut s).unwrap();
    assert!(law.is_history_exact(&s));
    law.pressure(4e-9, &mut s).unwrap(); // retraction from d_min: exact
    assert!(law.is_history_exact(&s));
    law.pressure(3.5e-9, &mut s).unwrap(); // re-approach after a partial retraction
    assert!(!law.is_history_exact(&s));
    law.pressure(3.8e-9, &mut s).unwrap(); // retraction after a partial reload
    assert!(!law.is_history_exact(&s));
    assert!(s.d_turn > s.d_min);
    law.pressure(2e-8, &mut s).unwrap(); // beyond every jump-out
    law.pressure(5e-9, &mut s).unwrap(); // a reload from far: exact again
    assert!(law.is_history_exact(&s));
}

#[test]
fn queries_below_the_tabulated_histories_are_errors_that_leave_the_state() {
    let law = law();
    let mut s = State::VIRGIN;
    law.pressure(2e-9, &mut s).unwrap();
    let before = s;
    let e = law.pressure(1e-9, &mut s).unwrap_err();
    assert!(matches!(e, LawError::OutOfRange(_)));
    let m = e.to_string();
    assert!(
        m.contains("1e-9") && m.contains("1.5e-9") && m.contains("1.5e-8"),
        "{m}"
    );
    assert_eq!(s, before);
    assert!(matches!(
        law.evaluate(2e-9, 1e-9, Path::Retract),
        Err(LawError::OutOfRange(_))
    ));
    assert!(matches!(
        law.evaluate(1e-9, 2e-9, Path::Retract),
        Err(LawError::OutOfRange(_))
    ));
    // the deepest tabulated history itself is in range
    assert!(law.evaluate(LO, f64::INFINITY, Path::Approach).is_ok());
    assert!(law.evaluate(LO + 1e-10, LO, Path::Retract).is_ok());
}

#[test]
fn non_finite_input_and_corrupt_states_are_errors() {
    let law = law();
    let mut s = State::VIRGIN;
    law.pressure(3e-9, &mut s).unwrap();
    let before = s;
    for d in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert!(matches!(
            law.pressure(d, &mut s),
            Err(LawError::Invalid { .. })
        ));
        assert_eq!(s, before);
        assert!(law.evaluate(d, 3e-9, Path::Approach).is_err());
    }
    for bad in [
        State {
            d_min: f64::NAN,
            ..before
        },
        State {
            d_min: f64::NEG_INFINITY,
            ..before
        },
        State {
            last_d: f64::NAN,
            ..before
        },
        State {
            d_turn: f64::NAN,
            ..before
        },
    ] {
        let mut b = bad;
        assert!(
            matches!(law.pressure(3e-9, &mut b), Err(LawError::Invalid { .. })),
            "{bad:?}"
        );
    }
    assert!(law.evaluate(3e-9, f64::NAN, Path::Approach).is_err());
    assert!(law.branch_pressure(2e-9, 3e-9, Path::Approach).is_err());
}

#[test]
fn above_the_last_branch_the_law_fades_to_zero_at_the_virgin_reach() {
    let law = law();
    let top = law.virgin().reach();
    let d_min = 0.5 * (HI + top);
    let p = law
        .branch_pressure(d_min + 1e-10, d_min, Path::Retract)
        .unwrap()
        .0;
    let p_hi = law
        .branch_pressure(HI + 1e-10, HI, Path::Retract)
        .unwrap()
        .0;
    assert!(p.abs() < p_hi.abs());
    assert_eq!(
        law.branch_pressure(top + 1e-9, top, Path::Retract).unwrap(),
        (0.0, 0.0)
    );
    assert_eq!(
        law.evaluate(top + 2e-9, top + 1e-9, Path::Approach)
            .unwrap()
            .pressure,
        0.0
    );
}

#[derive(Debug, Clone, Copy)]
enum Step {
    Move(f64),
    Reset,
}

fn steps() -> impl Strategy<Value = Vec<Step>> {
    prop::collection::vec(
        prop_oneof![9 => (1.5e-9f64..2.5e-8).prop_map(Step::Move), 1 => Just(Step::Reset)],
        1..60,
    )
}

proptest! {
    /// For any sequence of separations: d_min is the running minimum, the path follows the
    /// last move, and the stateful value is the stateless value of the state before the
    /// call with the path after it.
    #[test]
    fn the_state_machine_matches_its_definition(seq in steps()) {
        let law = law();
        let mut s = State::VIRGIN;
        let mut running_min = f64::INFINITY;
        let mut last = f64::INFINITY;
        for step in seq {
            let d = match step {
                Step::Reset => { s = State::VIRGIN; running_min = f64::INFINITY; last = f64::INFINITY; continue; }
                Step::Move(d) => d,
            };
            let before = s;
            let (p, t) = law.pressure(d, &mut s).unwrap();
            running_min = running_min.min(d);
            prop_assert_eq!(s.d_min, running_min);
            prop_assert_eq!(s.last_d, d);
            if d < before.d_min {
                prop_assert_eq!(s.path, Path::Approach);
            } else if d > last {
                prop_assert_eq!(s.path, Path::Retract);
            } else if d < last {
                prop_assert_eq!(s.path, Path::Approach);
            } else {
                prop_assert_eq!(s.path, before.path);
            }
            let e = law.evaluate(d, before.d_min, s.path).unwrap();
            prop_assert_eq!((e.pressure, e.tangent, e.d_min), (p, t, s.d_min));
            prop_assert!(p.is_finite() && t.is_finite());
            last = d;
        }
    }
}
