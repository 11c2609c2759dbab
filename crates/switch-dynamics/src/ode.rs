//! One phase of the motion: diffsol's explicit tsit45 (Tsitouras 2011, 5(4) with error
//! control) on a small state, stopped at the first wanted crossing of a threshold.

use crate::DynamicsError;
use diffsol::{NalgebraMat, OdeBuilder, OdeSolverMethod, OdeSolverStopReason, Vector};
use std::cell::RefCell;

/// A threshold on one state component: the phase ends when `component` crosses `level`
/// in the given direction (diffsol reports both directions; the other is stepped over).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Threshold {
    pub component: usize,
    pub level: f64,
    pub rising: bool,
}

/// The scaled speed (component 1 of every phase's state) below which `settled` is asked.
const REST_SPEED: f64 = 1e-3;

/// How a phase ended.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum End {
    /// Threshold `which` was crossed at `t` with the state `y`.
    Crossed { t: f64, y: Vec<f64>, which: usize },
    /// The time limit came first.
    Timeout { t: f64, y: Vec<f64> },
    /// The state came to rest (the caller's `settled` said so at an accepted step): an
    /// overdamped plate creeps into its equilibrium without ever turning.
    Settled { t: f64, y: Vec<f64> },
}

/// An accepted step: time and state (for traces).
pub(crate) type Step = (f64, Vec<f64>);

/// Integrates dy/dt = rhs(t, y) from `y0` at t = 0 until a wanted crossing of one of
/// `thresholds` or `t_max`, with the relative and absolute tolerance `tol` on every
/// component (the state is scaled by the caller to order one). `rhs` may fail: the first
/// error stops the phase and is returned. `on_step` sees every accepted step; `settled`
/// ends the phase at an accepted step where it holds (asked where the scaled speed, state
/// component 1, is below [`REST_SPEED`]); `poll` is asked before every step
/// whether the caller lets the phase go on (its error stops it).
#[allow(clippy::too_many_arguments)]
pub(crate) fn run<E>(
    phase: &'static str,
    rhs: impl Fn(f64, &[f64], &mut [f64]) -> Result<(), E>,
    thresholds: &[Threshold],
    y0: &[f64],
    t_max: f64,
    tol: f64,
    on_step: &mut dyn FnMut(&Step),
    settled: &dyn Fn(&[f64]) -> bool,
    poll: &dyn Fn() -> Result<(), contact_core::LawError>,
) -> Result<End, DynamicsError>
where
    DynamicsError: From<E>,
{
    let n = y0.len();
    let failure: RefCell<Option<E>> = RefCell::new(None);
    let eval = |t: f64, x: &[f64], dy: &mut [f64]| {
        if failure.borrow().is_some() {
            dy.iter_mut().for_each(|v| *v = 0.0);
            return;
        }
        if let Err(e) = rhs(t, x, dy) {
            dy.iter_mut().for_each(|v| *v = 0.0);
            *failure.borrow_mut() = Some(e);
        }
    };
    let start = y0.to_vec();
    let levels: Vec<(usize, f64)> = thresholds.iter().map(|t| (t.component, t.level)).collect();
    let fail = |message: String| DynamicsError::Integrator { phase, message };
    let problem = OdeBuilder::<NalgebraMat<f64>>::new()
        .rtol(tol)
        .atol(vec![tol; n])
        .h0(1e-3)
        .rhs(|x: &[f64], _p: &[f64], t: f64, dy: &mut [f64]| eval(t, x, dy))
        .init(
            move |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(&start),
            n,
        )
        .root(
            move |x: &[f64], _p: &[f64], _t: f64, g: &mut [f64]| {
                for (gi, &(c, level)) in g.iter_mut().zip(&levels) {
                    *gi = x[c] - level;
                }
            },
            thresholds.len(),
        )
        .build()
        .map_err(|e| fail(e.to_string()))?;
    let mut solver = problem.tsit45().map_err(|e| fail(e.to_string()))?;
    solver
        .set_stop_time(t_max)
        .map_err(|e| fail(e.to_string()))?;
    let mut derivative = vec![0.0; n];
    loop {
        poll()?;
        let reason = solver.step().map_err(|e| fail(e.to_string()));
        if let Some(e) = failure.borrow_mut().take() {
            return Err(e.into());
        }
        match reason? {
            OdeSolverStopReason::InternalTimestep => {
                let s = solver.state();
                let (t, y) = (s.t, s.y.clone_as_vec());
                on_step(&(t, y.clone()));
                // the plate is asked about rest only where it is slow on its phase's own
                // scale (component 1 is the scaled speed in every phase): a step's two
                // pressure lookups spared on the way
                if y[1].abs() < REST_SPEED && settled(&y) {
                    return Ok(End::Settled { t, y });
                }
            }
            OdeSolverStopReason::TstopReached => {
                let s = solver.state();
                return Ok(End::Timeout {
                    t: s.t,
                    y: s.y.clone_as_vec(),
                });
            }
            OdeSolverStopReason::RootFound(t, _) => {
                let y = solver.interpolate(t).map_err(|e| fail(e.to_string()))?;
                let y = y.clone_as_vec();
                eval(t, &y, &mut derivative);
                if let Some(e) = failure.borrow_mut().take() {
                    return Err(e.into());
                }
                // the threshold crossed here, in the direction asked for
                let which = thresholds.iter().enumerate().find(|(_, th)| {
                    let g = y[th.component] - th.level;
                    let slope = derivative[th.component];
                    g.abs() <= 1e-6 * th.level.abs().max(1.0) && (slope > 0.0) == th.rising
                });
                if let Some((which, _)) = which {
                    on_step(&(t, y.clone()));
                    return Ok(End::Crossed { t, y, which });
                }
                solver.state_mut_back(t).map_err(|e| fail(e.to_string()))?;
            }
        }
    }
}
