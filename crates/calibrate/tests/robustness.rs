//! Model failures: at the start they are errors naming the data line; during the
//! iteration a failing trial step is rejected (more damping), never a crash.

mod common;

use asperity_plastic::{EffectiveRadiusFit, EtsionKadin, YieldModulus};
use calibrate::{CalibError, Calibrator, FitOptions, StopReason};
use common::*;
use contact_core::{paper, AdhesionLaw, CoreError, Jumps, LawError, Material, Pair, Path};
use maugis_kim::{DugdaleParams, MaugisKim};
use std::cell::Cell;
use std::rc::Rc;

/// Maugis-Kim that fails on exactly one numbered force call (counted across clones).
#[derive(Clone)]
struct FailOnce {
    law: MaugisKim,
    calls: Rc<Cell<usize>>,
    fail_at: usize,
}

impl AdhesionLaw for FailOnce {
    fn force(&self, radius: f64, delta: f64, path: Path) -> Result<f64, LawError> {
        self.calls.set(self.calls.get() + 1);
        if self.calls.get() == self.fail_at {
            return Err(CoreError::NotFinite {
                what: "injected failure",
                x: delta,
            }
            .into());
        }
        self.law.force(radius, delta, path)
    }
    fn jumps(&self, radius: f64) -> Result<Jumps, LawError> {
        self.law.jumps(radius)
    }
}

fn calibrator(fail_at: usize) -> (Calibrator<FailOnce>, Rc<Cell<usize>>) {
    let pair = Pair::new(Material::new(paper::RU).unwrap(), None, paper::RADIUS).unwrap();
    let calls = Rc::new(Cell::new(0));
    let law = FailOnce {
        law: MaugisKim::new(DugdaleParams::for_pair(
            &pair,
            paper::WORK_OF_ADHESION,
            paper::Z0,
        ))
        .unwrap(),
        calls: calls.clone(),
        fail_at,
    };
    (
        Calibrator::new(
            EtsionKadin::new(&pair, YieldModulus::AsPrinted).unwrap(),
            law,
        ),
        calls,
    )
}

#[test]
fn a_failing_trial_step_is_rejected_and_the_fit_goes_on() {
    let data = {
        let cal = ru(YieldModulus::AsPrinted);
        cal.synthesize(truth(), &spec(&cal, &OMEGAS, 20, 20, 0.0, 1))
            .unwrap()
    };
    let from_paper = FitOptions {
        start: Some(EffectiveRadiusFit::PAPER),
        ..FitOptions::default()
    };
    // calls made before the first trial step: the start's residuals and Jacobian
    let (dry, calls) = calibrator(usize::MAX);
    let rep = dry
        .fit(
            &data,
            &FitOptions {
                max_iterations: 0,
                ..from_paper
            },
        )
        .unwrap();
    assert_eq!((rep.stop, rep.iterations), (StopReason::IterationCap, 0));
    assert!(!rep.converged);
    let before_trial = calls.get();
    let clean = calibrator(usize::MAX).0.fit(&data, &from_paper).unwrap();
    // fail the first force call of the first trial step
    let (cal, _) = calibrator(before_trial + 1);
    let rep = cal.fit(&data, &from_paper).unwrap();
    assert!(rep.converged, "{:?}", rep.stop);
    assert_eq!(
        rep.evaluations,
        clean.evaluations + 1,
        "one more (rejected) evaluation"
    );
    for k in 0..3 {
        assert!(
            (rep.c1[k] - truth().c1[k]).abs() < 1e-8 && (rep.c2[k] - truth().c2[k]).abs() < 1e-7
        );
    }
}

#[test]
fn a_failure_at_the_start_names_the_data_line() {
    let data = {
        let cal = ru(YieldModulus::AsPrinted);
        cal.synthesize(truth(), &spec(&cal, &[10.0], 10, 10, 0.0, 1))
            .unwrap()
    };
    let (cal, _) = calibrator(5);
    match cal.fit(&data, &FitOptions::default()) {
        // the 5th point of the file, after the header: line 6
        Err(CalibError::Model { line, .. }) => assert_eq!(line, 6),
        other => panic!("expected a model error, got {other:?}"),
    }
}
