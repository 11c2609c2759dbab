//! Each accuracy mode's error against the accurate mode, bounded on every embedded scene
//! that has modes (the asperity scene solves every point exactly and has none).
//! Bounds: balanced 1e-9, fast 1e-4 (relative); measured values in docs/performance.md.

use stiction::run;
use stiction::scene::{self, Accuracy, SurfaceScene, SwitchScene};

const BOUND: [(Accuracy, f64); 2] = [(Accuracy::Balanced, 1e-9), (Accuracy::Fast, 1e-4)];

#[test]
fn surface_scene_modes_stay_within_their_bounds() {
    let mut s: SurfaceScene = scene::parse("test", scene::DEFAULT_SURFACE).unwrap();
    s.points = 25;
    s.accuracy = Accuracy::Accurate;
    let exact = run::surface(&s).unwrap();
    let scale = exact
        .loading
        .iter()
        .chain(&exact.unloading)
        .map(|p| p.pressure.abs())
        .fold(0.0, f64::max);
    for (mode, bound) in BOUND {
        s.accuracy = mode;
        let r = run::surface(&s).unwrap();
        for (a, b) in exact
            .loading
            .iter()
            .zip(&r.loading)
            .chain(exact.unloading.iter().zip(&r.unloading))
        {
            assert_eq!(a.d, b.d);
            // relative to the pressure, or to the curve's scale where the pressure crosses zero
            let err = (a.pressure - b.pressure).abs() / a.pressure.abs().max(1e-3 * scale);
            assert!(
                err <= bound,
                "{mode:?} at d = {}: {} vs {} ({err:e})",
                a.d,
                b.pressure,
                a.pressure
            );
        }
        let (pa, pb) = (
            exact.pull_out_pressure.unwrap(),
            r.pull_out_pressure.unwrap(),
        );
        assert!(
            (pa - pb).abs() <= bound * pa,
            "{mode:?} pull-out {pb} vs {pa}"
        );
    }
}

#[test]
fn switch_scene_modes_stay_within_their_bounds() {
    let mut s: SwitchScene = scene::parse("test", scene::DEFAULT_SWITCH).unwrap();
    s.points = 0;
    s.accuracy = Accuracy::Accurate;
    let exact = run::switch(&s).unwrap();
    for (mode, bound) in BOUND {
        s.accuracy = mode;
        let r = run::switch(&s).unwrap();
        for (a, b) in exact.cycles.iter().zip(&r.cycles) {
            let e = (a.pull_out_pressure - b.pull_out_pressure).abs() / a.pull_out_pressure;
            assert!(
                e <= bound,
                "{mode:?} cycle {}: pull-out error {e:e}",
                a.cycle
            );
            assert!(
                (a.d_e - b.d_e).abs() <= bound * s.surface.sigma_s,
                "{mode:?} cycle {}: d_e",
                a.cycle
            );
        }
        let (ea, eb) = (exact.elastic.as_ref().unwrap(), r.elastic.as_ref().unwrap());
        assert!((ea.d_e - eb.d_e).abs() <= bound * s.surface.sigma_s);
        assert_eq!(exact.stiction, r.stiction);
        assert_eq!(exact.accommodated_after, r.accommodated_after);
    }
}
