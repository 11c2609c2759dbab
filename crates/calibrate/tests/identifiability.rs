//! Data that cannot determine every constant: the fit says so, fits what it can, and
//! reports no standard error for what it cannot.

mod common;

use asperity_plastic::{EffectiveRadiusFit, YieldModulus};
use calibrate::{CalibError, Constant, FeData, FitOptions, Selection, StopReason};
use common::*;

const B: [Constant; 3] = [Constant::B1, Constant::B2, Constant::B3];

fn from_paper() -> FitOptions {
    FitOptions {
        start: Some(EffectiveRadiusFit::PAPER),
        ..FitOptions::default()
    }
}

/// One delta_max (omega = 20), both branches: unloading sees c2 at one omega only, so
/// b1, b2, b3 are not determined (two exact null directions among them); only c2(20) is.
/// c1 is still determined, because the loading branch sweeps omega from 1 to 20.
#[test]
fn one_delta_max_leaves_b1_b2_b3_undetermined() {
    for modulus in [YieldModulus::AsPrinted, YieldModulus::Composite] {
        let cal = ru(modulus);
        let data = cal
            .synthesize(truth(), &spec(&cal, &[20.0], 30, 30, 0.0, 1))
            .unwrap();
        let rep = cal.fit(&data, &from_paper()).unwrap();
        assert!(rep.converged, "{:?}", rep.stop);
        assert_eq!(rep.rank, 4);
        assert_eq!(rep.not_determined, B);
        for c in B {
            assert!(
                rep.standard_errors.get(c).is_none(),
                "{c} must have no standard error"
            );
        }
        assert_eq!(
            rep.correlation.names,
            [Constant::A1, Constant::A2, Constant::A3]
        );
        assert_eq!(rep.undetermined_directions.len(), 2);
        for d in &rep.undetermined_directions {
            assert!(d.relative_singular_value < 1e-12);
            assert!(d.components.iter().all(|c| B.contains(&c.constant)));
        }
        // the determined combination c2(20) is the truth's; b1, b2, b3 themselves are not
        let (fit, t) = (rep.fit(), truth());
        assert!(
            (fit.c2(20.0) - t.c2(20.0)).abs() < 1e-8,
            "{} vs {}",
            fit.c2(20.0),
            t.c2(20.0)
        );
        assert!((fit.c2[0] - t.c2[0]).abs() > 1.0);
        for k in 0..3 {
            assert!((fit.c1[k] - t.c1[k]).abs() < 1e-8 * t.c1[k], "{:?}", fit.c1);
        }
        assert!(worst_relative_rms(&cal, fit, &data) < 1e-10);
        // a subset to try: the three a's and one b (the b columns tie: the first, b1)
        assert_eq!(
            rep.suggested_fit,
            [Constant::A1, Constant::A2, Constant::A3, Constant::B1]
        );
        let table = rep.to_table();
        assert!(
            table.contains("not determined by the data") && table.contains("such as a1,a2,a3,b1"),
            "{table}"
        );
    }
}

/// With the suggested subset, everything fitted is determined.
#[test]
fn the_suggested_subset_is_determined() {
    let cal = ru(YieldModulus::AsPrinted);
    let data = cal
        .synthesize(truth(), &spec(&cal, &[20.0], 30, 30, 0.005, 2))
        .unwrap();
    let rep = cal.fit(&data, &from_paper()).unwrap();
    let subset = Selection::of(&rep.suggested_fit);
    let again = cal
        .fit(
            &data,
            &FitOptions {
                select: subset,
                ..from_paper()
            },
        )
        .unwrap();
    assert!(again.converged && again.not_determined.is_empty());
    assert_eq!(again.rank, 4);
    assert_eq!(
        again.standard_errors.c1.len() + again.standard_errors.c2.len(),
        4
    );
    // the same curves either way
    assert!((again.residual_rms_n - rep.residual_rms_n).abs() < 1e-6 * rep.residual_rms_n);
}

/// Loading branches only: c2 has no effect at all (x = 1, f = 1), so its columns are zero;
/// b1, b2, b3 stay exactly at the start, without standard errors; c1 is fitted.
#[test]
fn loading_only_leaves_c2_untouched_and_undetermined() {
    let cal = ru(YieldModulus::AsPrinted);
    let clean = cal
        .synthesize(truth(), &spec(&cal, &OMEGAS, 25, 0, 0.0, 3))
        .unwrap();
    let noisy = cal
        .synthesize(truth(), &spec(&cal, &OMEGAS, 25, 0, 0.005, 3))
        .unwrap();
    for (data, noise) in [(&clean, 0.0), (&noisy, 0.005)] {
        let rep = cal.fit(data, &from_paper()).unwrap();
        assert!(rep.converged);
        assert_eq!(rep.rank, 3);
        assert_eq!(rep.not_determined, B);
        assert_eq!(rep.c2, EffectiveRadiusFit::PAPER.c2);
        assert!(rep.standard_errors.c2.is_empty());
        assert_eq!(rep.standard_errors.c1.len(), 3);
        assert_eq!(&rep.singular_values[3..], &[0.0; 3]);
        for c in [Constant::A1, Constant::A2, Constant::A3] {
            let se = rep.standard_errors.get(c).unwrap();
            let (got, want) = (value(&rep.fit(), c), value(&truth(), c));
            if noise > 0.0 {
                assert!(
                    (got - want).abs() <= 3.0 * se,
                    "{c}: {got} vs {want} (se {se})"
                );
            } else {
                // exact data: the standard error measures rounding only
                assert!((got - want).abs() <= 1e-8 * want, "{c}: {got} vs {want}");
            }
        }
        assert!(worst_relative_rms(&cal, rep.fit(), &clean) < 0.01);
    }
    // asking for c2 alone on loading data: nothing to fit, said so
    let rep = cal
        .fit(
            &clean,
            &FitOptions {
                select: Selection::C2,
                ..from_paper()
            },
        )
        .unwrap();
    assert_eq!(
        (rep.stop, rep.converged, rep.rank),
        (StopReason::NothingDetermined, false, 0)
    );
    assert_eq!(rep.c2, EffectiveRadiusFit::PAPER.c2);
    assert_eq!(rep.not_determined, B);
}

#[test]
fn bad_requests_are_errors() {
    let cal = ru(YieldModulus::AsPrinted);
    let few = FeData::parse_csv(
        "delta_max_m,delta_m,force_n,branch\n3e-8,1e-8,1e-3,loading\n3e-8,3e-8,5e-3,loading\n\
         3e-8,3e-8,5e-3,unloading\n3e-8,2.5e-8,1e-3,unloading\n",
    )
    .unwrap();
    assert!(matches!(
        cal.fit(&few, &FitOptions::default()),
        Err(CalibError::TooFewPoints {
            line: 5,
            points: 4,
            constants: 6
        })
    ));
    assert!(cal
        .fit(
            &few,
            &FitOptions {
                select: Selection::C1,
                ..FitOptions::default()
            }
        )
        .is_ok());
    let bad_start = FitOptions {
        start: Some(EffectiveRadiusFit {
            c1: [0.2, 0.6, -0.1],
            c2: [10.0, 10.0, 5.0],
        }),
        ..FitOptions::default()
    };
    assert!(matches!(
        cal.fit(&few, &bad_start),
        Err(CalibError::Start(_))
    ));
    let bad_tol = FitOptions {
        rank_tolerance: f64::NAN,
        ..FitOptions::default()
    };
    assert!(matches!(
        cal.fit(&few, &bad_tol),
        Err(CalibError::Option {
            field: "rank_tolerance",
            ..
        })
    ));
    let none = FitOptions {
        select: Selection::of(&[]),
        ..FitOptions::default()
    };
    assert!(matches!(
        cal.fit(&few, &none),
        Err(CalibError::Selection { .. })
    ));
}
