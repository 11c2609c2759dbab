//! Property tests over the whole range: lambda in [1e-3, 1e3], |Delta| up to 1e3.

use contact_core::Path;
use maugis_kim::{Branch, MdCurve};
use proptest::prelude::*;

fn lambda() -> impl Strategy<Value = f64> {
    (-3.0f64..3.0).prop_map(|e| 10f64.powf(e))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn stable_points_are_finite_and_solve_the_requested_interference(l in lambda(), t in 0.0f64..1.0) {
        let c = MdCurve::new(l).unwrap();
        let dt = c.turning_point().unwrap().delta;
        // from the turning point to 1e3, denser near Delta_t
        let delta = dt + (1e3 - dt) * t.powi(4);
        let p = c.stable_point(delta).unwrap();
        prop_assert!(p.force.is_finite() && p.a.is_finite() && p.c.is_finite());
        prop_assert!(p.a >= 0.0 && p.c >= p.a);
        prop_assert!((p.delta - delta).abs() <= 1e-12 * delta.abs().max(1.0), "{} vs {}", p.delta, delta);
        prop_assert!(p.stable);
    }

    #[test]
    fn stable_branch_is_continuous(l in lambda(), t in 0.0f64..1.0) {
        let c = MdCurve::new(l).unwrap();
        let dt = c.turning_point().unwrap().delta;
        let delta = dt + (50.0 - dt) * t;
        let h = 1e-7 * (1.0 + delta.abs());
        let f0 = c.stable_point(delta).unwrap().force;
        let f1 = c.stable_point(delta + h).unwrap().force;
        // at worst a square-root singularity at Delta_t: |dF| <= C sqrt(h)
        prop_assert!((f1 - f0).abs() <= 1e-2 * (1.0 + f0.abs()), "F({delta}) = {f0}, F(+{h}) = {f1}");
    }

    #[test]
    fn interference_increases_along_the_stable_branch(l in lambda()) {
        let c = MdCurve::new(l).unwrap();
        let pts = c.curve(300, 20.0).unwrap();
        let stable: Vec<_> = pts.iter().filter(|p| p.stable).collect();
        prop_assert!(stable.len() > 10);
        for w in stable.windows(2) {
            prop_assert!(w[1].delta > w[0].delta, "{:?} then {:?}", w[0], w[1]);
        }
        // and the unstable part lies before it along the curve
        let first_stable = pts.iter().position(|p| p.stable).unwrap();
        prop_assert!(pts[first_stable..].iter().all(|p| p.stable));
    }

    #[test]
    fn path_rule_never_gives_a_force_outside_contact(l in lambda(), d in -1e3f64..1e3) {
        let c = MdCurve::new(l).unwrap();
        let approach = c.force(d, Path::Approach).unwrap();
        prop_assert!(approach.is_finite());
        if d < c.jump_in_delta() {
            prop_assert_eq!(approach, 0.0);
        }
        let retract = c.force(d, Path::Retract { from: 1e3 }).unwrap();
        prop_assert!(retract.is_finite());
        if d < c.turning_point().unwrap().delta {
            prop_assert_eq!(retract, 0.0);
        }
        if d >= c.jump_in_delta() {
            prop_assert_eq!(approach, retract);
        }
    }

    #[test]
    fn pull_offs_lie_between_the_jkr_and_dmt_limits(l in lambda()) {
        let c = MdCurve::new(l).unwrap();
        let lc = c.pull_off_load_control().unwrap();
        let dc = c.pull_off_displacement_control().unwrap();
        prop_assert!(lc.force >= -2.0 - 1e-9 && lc.force <= -1.5 + 1e-3, "{}", lc.force);
        prop_assert!(dc.force >= lc.force - 1e-12);
        prop_assert!(lc.stable);
        if lc.branch == Branch::NonContact {
            prop_assert!(l <= maugis_kim::LAMBDA_CRITICAL);
        }
    }
}
