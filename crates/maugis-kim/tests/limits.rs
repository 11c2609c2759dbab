//! Analytic limits and invariants of the Maugis-Kim curve.

use contact_core::{paper, AdhesionLaw, Material, Pair, Path};
use maugis_kim::{Branch, Dmt, DugdaleParams, Jkr, MaugisKim, MdCurve, LAMBDA_CRITICAL};
use std::f64::consts::PI;

/// K = 4/3 E* of the Ru sphere of Table 1 on a rigid flat.
fn ru_on_rigid_k() -> f64 {
    Pair::new(Material::new(paper::RU).unwrap(), None, paper::RADIUS)
        .unwrap()
        .k()
}

/// Residuals of eqs 8-10 for a contact point, each relative to the size of its terms.
fn residuals(lambda: f64, p: &maugis_kim::MdPoint) -> (f64, f64, f64) {
    // s from the point itself: m = c/a rounded to a double cannot resolve small s.
    let (a, s) = (p.a, p.s);
    let m = (1.0 + s * s).sqrt();
    let t = s.atan();
    // Each bracket of eq 8 cancels to O(s^3) and O(s^2) at small s: the residual is
    // measured against the magnitudes of the terms summed, the scale of rounding.
    let t1 = lambda * a * a / 2.0 * (s + (m * m - 2.0) * t);
    let t1_mag = lambda * a * a / 2.0 * (s + (m * m - 2.0).abs() * t);
    let t2 = 4.0 * lambda * lambda * a / 3.0 * (s * t - m + 1.0);
    let t2_mag = 4.0 * lambda * lambda * a / 3.0 * (s * t + m + 1.0);
    let r8 = (t1 + t2 - 1.0).abs() / (t1_mag + t2_mag + 1.0);
    let d9 = a * a - 4.0 * lambda * a / 3.0 * s;
    let r9 = (d9 - p.delta).abs() / (a * a + (4.0 * lambda * a / 3.0 * s).abs());
    let f10 = a * a * a - lambda * a * a * (s + m * m * t);
    let r10 = (f10 - p.force).abs() / (a * a * a + (lambda * a * a * (s + m * m * t)).abs());
    (r8, r9, r10)
}

#[test]
fn critical_lambda_satisfies_its_defining_equation() {
    let l = LAMBDA_CRITICAL;
    assert!((16.0 / 9.0 * (1.0 - 1.0 / PI) * l.powi(3) - 1.0).abs() < 1e-15);
}

#[test]
fn branches_join_continuously_at_the_junction() {
    for lambda in [1e-3, 0.1, 0.5, 0.93, 0.95, 2.0, 10.0, 1e3] {
        let c = MdCurve::new(lambda).unwrap();
        let j = c.junction();
        assert!((j.delta + 4.0 * lambda / 3.0 * j.c).abs() <= 1e-13 * j.delta.abs());
        // the contact branch tends to the junction as s -> infinity
        let far = c.contact_point(1e7);
        assert!(
            (far.delta - j.delta).abs() <= 1e-9 * (1.0 + j.delta.abs()),
            "lambda {lambda}: {} vs {}",
            far.delta,
            j.delta
        );
        assert!((far.force - j.force).abs() <= 1e-9 * (1.0 + j.force.abs()));
        assert!((far.c - j.c).abs() <= 1e-9 * j.c);
        assert!(far.a < 1e-6 * j.c);
    }
}

#[test]
fn turning_point_moves_to_contact_branch_at_critical_lambda() {
    let below = MdCurve::new(LAMBDA_CRITICAL * (1.0 - 1e-3)).unwrap();
    let above = MdCurve::new(LAMBDA_CRITICAL * (1.0 + 1e-3)).unwrap();
    assert_eq!(below.turning_point().unwrap().branch, Branch::NonContact);
    assert_eq!(above.turning_point().unwrap().branch, Branch::Contact);
    // and the turning point is continuous through lambda_c
    let tb = below.turning_point().unwrap();
    let ta = above.turning_point().unwrap();
    assert!((tb.delta - ta.delta).abs() < 1e-2, "{tb:?} {ta:?}");
    assert!((tb.force - ta.force).abs() < 1e-2, "{tb:?} {ta:?}");
}

#[test]
fn turning_point_is_the_minimum_interference_along_the_curve() {
    for lambda in [1e-3, 0.3, 0.9, 1.0, 3.0, 30.0, 1e3] {
        let c = MdCurve::new(lambda).unwrap();
        let t = c.turning_point().unwrap();
        for p in c.curve(400, 5.0).unwrap() {
            assert!(
                p.delta >= t.delta - 1e-12 * t.delta.abs(),
                "lambda {lambda}: {p:?} below {t:?}"
            );
        }
    }
}

#[test]
fn pull_off_tends_to_dmt_at_small_lambda() {
    let c = MdCurve::new(1e-3).unwrap();
    let lc = c.pull_off_load_control().unwrap().force;
    assert!((lc + 2.0).abs() < 5e-3, "{lc}");
    let c = MdCurve::new(1e-5).unwrap();
    assert!((c.pull_off_load_control().unwrap().force + 2.0).abs() < 1e-4);
}

#[test]
fn pull_off_tends_to_jkr_at_large_lambda() {
    let c = MdCurve::new(1e3).unwrap();
    let lc = c.pull_off_load_control().unwrap().force;
    let dc = c.pull_off_displacement_control().unwrap().force;
    assert!((lc + 1.5).abs() < 2e-2, "load control {lc}");
    assert!((dc + 5.0 / 6.0).abs() < 2e-2, "displacement control {dc}");
    let t = c.turning_point().unwrap();
    assert!((t.delta - Jkr::turning_delta()).abs() < 2e-2, "{t:?}");
    // convergence: the error shrinks with lambda
    let c4 = MdCurve::new(1e4).unwrap();
    assert!((c4.pull_off_load_control().unwrap().force + 1.5).abs() < (lc + 1.5).abs());
}

#[test]
fn large_load_is_hertz() {
    for lambda in [1e-3, 0.5, 5.0, 1e3] {
        let c = MdCurve::new(lambda).unwrap();
        let big = 1e3_f64;
        let p = c.stable_point(big).unwrap();
        // Fbar = A^3 - O(A^2), Delta = A^2 - O(A): relative deviation O(1/A)
        assert!(
            (p.force / big.powf(1.5) - 1.0).abs()
                < 3.0 * lambda.max(1.0).sqrt() / big.sqrt() + 0.05,
            "lambda {lambda}: {p:?}"
        );
        assert!((p.delta / (p.a * p.a) - 1.0).abs() < 0.1);
    }
}

#[test]
fn equations_8_to_10_hold_to_1e12_across_lambda_and_delta() {
    for lambda in [1e-3, 1e-2, 0.1, 0.5, 0.938, 1.0, 5.0, 50.0, 1e3] {
        let c = MdCurve::new(lambda).unwrap();
        let dt = c.turning_point().unwrap().delta;
        for delta in [dt, dt * 0.5, -1.0, -0.1, 0.0, 0.3, 1.0, 10.0, 100.0, 1e3] {
            if delta < dt {
                continue;
            }
            let p = c.stable_point(delta).unwrap();
            assert!(
                (p.delta - delta).abs() <= 1e-12 * delta.abs().max(1.0),
                "lambda {lambda}, Delta {delta}: {p:?}"
            );
            if p.branch == Branch::Contact {
                let (r8, r9, r10) = residuals(lambda, &p);
                assert!(
                    r8 < 1e-12 && r9 < 1e-12 && r10 < 1e-12,
                    "lambda {lambda} Delta {delta}: {r8:e} {r9:e} {r10:e}"
                );
            }
        }
    }
}

#[test]
fn jkr_law_agrees_with_maugis_kim_at_large_lambda() {
    let c = MdCurve::new(2e3).unwrap();
    for delta in [-0.8, -0.5, 0.0, 0.5, 2.0, 10.0] {
        let md = c.force(delta, Path::Retract { from: 20.0 }).unwrap();
        let jkr = Jkr::force_nd(delta, Path::Retract { from: 20.0 }).unwrap();
        assert!(
            (md - jkr).abs() < 0.03 * (1.0 + jkr.abs()),
            "Delta {delta}: MD {md} JKR {jkr}"
        );
    }
}

#[test]
fn dmt_law_agrees_with_maugis_kim_at_small_lambda_in_si() {
    // Ru on a rigid flat; a long Dugdale range makes lambda small. In contact the
    // cohesive zone shifts Delta by (8/3) sqrt(lambda/pi), so MK -> DMT like sqrt(lambda).
    let k = ru_on_rigid_k();
    let (w, r) = (paper::WORK_OF_ADHESION, paper::RADIUS);
    let worst = |z0: f64| {
        let mk = MaugisKim::new(DugdaleParams {
            k,
            work_of_adhesion: w,
            z0,
        })
        .unwrap();
        let dmt = Dmt::new(DugdaleParams {
            k,
            work_of_adhesion: w,
            z0,
        })
        .unwrap();
        let mut e: f64 = 0.0;
        for frac in [-0.8, -0.3, -0.05, 0.0] {
            let delta = frac * z0;
            let a = mk.force(r, delta, Path::Retract { from: 1e-8 }).unwrap();
            let b = dmt.force(r, delta, Path::Retract { from: 1e-8 }).unwrap();
            e = e.max((a - b).abs() / (2.0 * PI * w * r));
        }
        for delta in [1e-9, 5e-9] {
            let a = mk.force(r, delta, Path::Approach).unwrap();
            let b = dmt.force(r, delta, Path::Approach).unwrap();
            e = e.max((a - b).abs() / (2.0 * PI * w * r));
        }
        (mk.lambda(r), e)
    };
    let (l1, e1) = worst(1e-7);
    let (l2, e2) = worst(1e-5);
    assert!((l1 / l2 - 100.0).abs() < 1e-9);
    // (8/3) sqrt(lambda/pi) x (3/2) A with A up to about 3.5 at delta = 5 nm
    assert!(e1 < 4.0 * (l1 / PI).sqrt() * 3.5, "lambda {l1}: {e1}");
    assert!(
        e2 < 0.2 * e1,
        "error must fall like sqrt(lambda): {e1} at {l1}, {e2} at {l2}"
    );
}

#[test]
fn path_rule_jump_in_and_jump_out() {
    for lambda in [0.3, 3.0] {
        let c = MdCurve::new(lambda).unwrap();
        let d_in = c.jump_in_delta();
        let t = c.turning_point().unwrap();
        let mid = 0.5 * (d_in + t.delta);
        assert_eq!(c.force(mid, Path::Approach).unwrap(), 0.0);
        let f = c.force(mid, Path::Retract { from: 1.0 }).unwrap();
        assert!(f < 0.0);
        assert_eq!(
            c.force(t.delta - 1e-9, Path::Retract { from: 1.0 })
                .unwrap(),
            0.0
        );
        // never jumped in: retracting from below Delta_in stays at zero
        assert_eq!(
            c.force(mid, Path::Retract { from: d_in - 1e-3 }).unwrap(),
            0.0
        );
        // the force just past jump-in is the stable branch
        let fin = c.force(d_in, Path::Approach).unwrap();
        assert!(fin < 0.0);
    }
}

#[test]
fn si_law_matches_nondimensional_curve() {
    let k = ru_on_rigid_k();
    let mk = MaugisKim::new(DugdaleParams {
        k,
        work_of_adhesion: paper::WORK_OF_ADHESION,
        z0: paper::Z0,
    })
    .unwrap();
    let r = paper::RADIUS;
    let sc = mk.scales(r).unwrap();
    let c = mk.curve(r).unwrap();
    let delta = 2e-9;
    let f = mk.force(r, delta, Path::Approach).unwrap();
    let fnd = c.stable_point(delta / sc.interference).unwrap().force;
    assert!((f - fnd * PI * r).abs() < 1e-15);
}

#[test]
fn nan_inputs_are_errors_not_zero_forces() {
    let c = MdCurve::new(1.0).unwrap();
    assert!(c.force(f64::NAN, Path::Approach).is_err());
    assert!(c.force(0.0, Path::Retract { from: f64::NAN }).is_err());
    assert!(c.stable_point(f64::NAN).is_err());
    assert!(c.curve(10, f64::NAN).is_err());
    assert!(Jkr::force_nd(f64::NAN, Path::Approach).is_err());
    assert!(MdCurve::new(f64::NAN).is_err() && MdCurve::new(-1.0).is_err());
    let mk = MaugisKim::new(DugdaleParams {
        k: 3e11,
        work_of_adhesion: 1.0,
        z0: 1e-10,
    })
    .unwrap();
    assert!(mk.force(4e-6, f64::NAN, Path::Approach).is_err());
    assert!(mk.force(f64::NAN, 1e-9, Path::Approach).is_err());
}

/// JKR's contact radius at zero load is a0 = (6 pi w R^2 / K)^(1/3) (Johnson, Kendall &
/// Roberts 1971; Maugis 2000 eq 5.112 in K = 4/3 E*), reached at the interference
/// delta0 = a0^2 / (3R) (nondimensionally A = 6^(1/3), Delta = A^2 - (2/3) sqrt(6 A) =
/// 6^(2/3)/3); Maugis-Kim at large lambda approaches it, and at small lambda its contact
/// radius approaches Hertz's sqrt(R delta). The contact radius of a detached sphere is 0.
#[test]
fn contact_radii_meet_their_limits() {
    let k = ru_on_rigid_k();
    let (w, r) = (paper::WORK_OF_ADHESION, paper::RADIUS);
    let jkr = Jkr::new(maugis_kim::JkrParams {
        k,
        work_of_adhesion: w,
    })
    .unwrap();
    let a0 = (6.0 * PI * w * r * r / k).cbrt();
    let delta0 = a0 * a0 / (3.0 * r);
    let a = jkr.contact_radius(r, delta0, Path::Approach).unwrap();
    assert!((a / a0 - 1.0).abs() < 1e-12, "JKR a0: {a} vs {a0}");
    assert!(jkr.force(r, delta0, Path::Approach).unwrap().abs() < 1e-12 * k * r * r);
    // detached on approach below contact
    assert_eq!(jkr.contact_radius(r, -1e-9, Path::Approach).unwrap(), 0.0);
    // Maugis-Kim: a short range (large lambda) approaches JKR's radius at the same delta
    let mk = |z0: f64| {
        MaugisKim::new(DugdaleParams {
            k,
            work_of_adhesion: w,
            z0,
        })
        .unwrap()
    };
    let a_mk = mk(1e-13).contact_radius(r, delta0, Path::Approach).unwrap();
    assert!(
        (a_mk / a0 - 1.0).abs() < 0.01,
        "MK large lambda {a_mk} vs JKR {a0}"
    );
    // a long range (small lambda): Hertz's geometry in contact
    let delta = 2e-9;
    let a_dmt = mk(5e-8).contact_radius(r, delta, Path::Approach).unwrap();
    let hertz = (r * delta).sqrt();
    assert!(
        (a_dmt / hertz - 1.0).abs() < 0.05,
        "MK small lambda {a_dmt} vs Hertz {hertz}"
    );
}
