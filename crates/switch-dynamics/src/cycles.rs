//! Cycles of the switch in time: each closure integrated, the surface's history carried
//! from impact to impact, the pull-out judged as the quasi-static runner does.

use crate::motion::{
    close_with, Bounce, DynamicsOptions, EnergyLedger, ImpactState, Plate, TracePoint,
};
use crate::release::{release, Release};
use crate::DynamicsError;
use contact_core::{Path, SurfaceLaw};
use switch_1d::{
    against_before, carry_history_errors, unload, Cycle, CycleOptions, CycleRun, EndOfImpact,
    Impact, ImpactFilm, PressurePoint,
};

/// What the time integration adds to a cycle.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct DynamicCycle {
    /// The first impact of the closure.
    pub impact: ImpactState,
    /// The impacts after bounces, each with its deepest separation.
    pub bounces: Vec<Bounce>,
    /// The closure's energy ledger (voltage step to capture).
    pub energy_ledger: EnergyLedger,
    /// Time from the voltage step to the capture (s).
    pub capture_time: f64,
    /// The release with the voltage off, from rest at the pull-out's separation.
    pub release: Release,
    /// The motion of the closure (the first cycle only, when asked for).
    pub trace: Vec<TracePoint>,
}

/// Runs `options.cycles` closures of `plate` on `surface` from `history`: each integrates
/// the flight, the impact and the bounces ([`crate::close`]); the history after the last impact
/// is unloaded for the pull-out (`switch_1d::unload`), judged against the spring's
/// restoring pressure K_s (d0 - h), and released ([`release`]). The cycles come back as the
/// quasi-static runner's (`switch_1d::CycleRun`: d_e is the deepest separation of the
/// closure, its error the integration's tolerance on the roughness scale) with the
/// time-domain record of each beside them. Accommodation as in `switch_1d::run_cycles`.
pub fn run_cycles<S: SurfaceLaw>(
    surface: &S,
    history: S::History,
    plate: &Plate,
    options: CycleOptions,
    dynamics: DynamicsOptions,
    on_cycle: &mut dyn FnMut(usize),
) -> Result<(CycleRun<S::History>, Vec<DynamicCycle>), DynamicsError> {
    let plate = plate.validated()?;
    let restoring = plate.k_s * plate.travel();
    let judge = Impact {
        energy: 1.0,
        film: ImpactFilm {
            thickness: 0.0,
            youngs_modulus: 1.0,
        },
        contact_area_fraction: plate.contact_area_fraction,
        restoring_pressure: restoring,
    };
    let tol = options.accommodation_tolerance;
    let start = history.clone();
    let mut hist = history;
    let mut cycles: Vec<Cycle<S::History>> = Vec::new();
    let mut records = Vec::new();
    let mut accommodated_after = None;
    let mut accommodation_cause = None;
    let mut loading = Vec::new();
    // the approach table the last closure's bounces used: the next closure's first impact
    // approaches the same history
    let mut approach_table = None;
    for k in 1..=options.cycles {
        let scale = surface.length_scales(&hist)?.roughness;
        let closure = close_with(
            surface,
            &hist,
            &plate,
            &DynamicsOptions {
                trace: dynamics.trace && k == 1,
                ..dynamics
            },
            &mut approach_table,
        )?;
        let d_e = closure.deepest;
        let pressure = surface.pressure(d_e, &hist, Path::Approach)?;
        let new_hist = closure.history.clone();
        if k == 1 && options.loading_points > 0 {
            // the first (virgin) loading curve, from d_e to the reach, as the quasi-static
            // runner draws it
            let top = surface.reach(&hist, Path::Approach)?;
            let n = options.loading_points.max(2);
            for i in 0..n {
                let d = d_e + (top - d_e) * i as f64 / (n - 1) as f64;
                loading.push(PressurePoint {
                    d,
                    pressure: surface.pressure(d, &hist, Path::Approach)?,
                });
            }
        }
        let unloading = unload(
            surface,
            &new_hist,
            d_e,
            options.unloading_points,
            options.precision,
        )?;
        let released = release(
            surface,
            &new_hist,
            unloading.pull_out_separation,
            d_e,
            &plate,
            dynamics.tolerance,
        )?;
        let (deepened, shallower_by, repeats) =
            against_before(&cycles, d_e, unloading.pull_out_pressure, tol, scale);
        if let (None, Some((after, cause))) = (accommodated_after, repeats) {
            accommodated_after = Some(after);
            accommodation_cause = Some(cause);
        }
        let ratio = judge.pull_out_ratio(unloading.pull_out_pressure);
        cycles.push(Cycle {
            cycle: k,
            end: EndOfImpact {
                d_e,
                error: closure.deepest_error,
                pressure,
            },
            history: new_hist.clone(),
            unloading,
            pull_out_ratio: ratio,
            sticks: ratio > 1.0,
            deepened,
            shallower_by,
        });
        records.push(DynamicCycle {
            impact: closure.impact,
            bounces: closure.bounces,
            energy_ledger: closure.ledger,
            capture_time: closure.capture_time,
            release: released,
            trace: closure.trace,
        });
        hist = new_hist;
        on_cycle(k);
        if options.until_accommodated && accommodated_after.is_some() {
            break;
        }
    }
    // each d_e and pull-out was found on the history the cycles before left, itself known
    // to its estimate: carried as the quasi-static runner does (docs/theory.md 6.6)
    carry_history_errors(surface, &start, &mut cycles)?;
    let largest_pull_out = cycles
        .iter()
        .map(|c| c.unloading.pull_out_pressure)
        .fold(0.0, f64::max);
    let first_sticking_cycle = cycles.iter().find(|c| c.sticks).map(|c| c.cycle);
    Ok((
        CycleRun {
            loading,
            cycles,
            accommodated_after,
            accommodation_cause,
            stopping_error: 0.0,
            largest_pull_out,
            pull_out_ratio: judge.pull_out_ratio(largest_pull_out),
            first_sticking_cycle,
            stiction: first_sticking_cycle.is_some(),
        },
        records,
    ))
}
