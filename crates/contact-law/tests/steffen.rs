//! Properties of the Steffen (1990) interpolant: monotone where the data are, no overshoot
//! at a near-discontinuity, locality, C1, and convergence on smooth data.

use contact_law::steffen::Steffen;
use proptest::prelude::*;

/// Strictly increasing abscissae from positive gaps.
fn abscissae(gaps: &[f64]) -> Vec<f64> {
    let mut x = vec![0.0];
    for g in gaps {
        x.push(x[x.len() - 1] + g);
    }
    x
}

/// 40 points in each interval, both ends included.
fn fine(x: &[f64]) -> Vec<f64> {
    let mut t = Vec::new();
    for w in x.windows(2) {
        for k in 0..=40 {
            t.push(w[0] + (w[1] - w[0]) * k as f64 / 40.0);
        }
    }
    t
}

proptest! {
    #[test]
    fn monotone_data_give_a_monotone_interpolant_without_overshoot(
        gaps in prop::collection::vec(1e-3f64..1.0, 2..30),
        steps in prop::collection::vec(0.0f64..10.0, 30),
        decreasing in any::<bool>(),
    ) {
        let x = abscissae(&gaps);
        let mut y = vec![0.0];
        for i in 1..x.len() {
            let s = if decreasing { -steps[i - 1] } else { steps[i - 1] };
            y.push(y[i - 1] + s);
        }
        let s = Steffen::new(&x, &y).unwrap();
        let sign = if decreasing { -1.0 } else { 1.0 };
        let mut prev = f64::NEG_INFINITY;
        for t in fine(&x) {
            let (v, dv) = s.value_and_slope(t);
            prop_assert!(sign * dv >= -1e-9 * (1.0 + dv.abs()));
            prop_assert!(sign * v >= prev - 1e-9 * (1.0 + v.abs()));
            prev = sign * v;
        }
        // within the data range on every interval
        for i in 0..x.len() - 1 {
            let (lo, hi) = (y[i].min(y[i + 1]), y[i].max(y[i + 1]));
            for k in 0..=20 {
                let v = s.value_and_slope(x[i] + (x[i + 1] - x[i]) * k as f64 / 20.0).0;
                prop_assert!(v >= lo - 1e-9 * (1.0 + lo.abs()) && v <= hi + 1e-9 * (1.0 + hi.abs()));
            }
        }
    }

    #[test]
    fn the_interpolant_passes_through_the_nodes_and_is_c1(
        gaps in prop::collection::vec(1e-2f64..1.0, 2..20),
        ys in prop::collection::vec(-1e9f64..1e9, 21),
    ) {
        let x = abscissae(&gaps);
        let y = &ys[..x.len()];
        let s = Steffen::new(&x, y).unwrap();
        for i in 0..x.len() {
            prop_assert_eq!(s.value_and_slope(x[i]).0, y[i]);
        }
        let scale = x.windows(2).zip(y.windows(2)).map(|(a, b)| ((b[1] - b[0]) / (a[1] - a[0])).abs()).fold(1.0, f64::max);
        for &xi in &x[1..x.len() - 1] {
            let h = 1e-12;
            let (l, r) = (s.value_and_slope(xi - h).1, s.value_and_slope(xi + h).1);
            prop_assert!((l - r).abs() <= 1e-6 * scale, "{} {} {}", l, r, scale);
        }
    }

    #[test]
    fn a_node_changes_the_interpolant_only_nearby(
        gaps in prop::collection::vec(1e-2f64..1.0, 8..20),
        ys in prop::collection::vec(-1.0f64..1.0, 21),
        k in 0usize..100,
        delta in 0.1f64..5.0,
    ) {
        let x = abscissae(&gaps);
        let y = ys[..x.len()].to_vec();
        let k = k % x.len();
        let mut y2 = y.clone();
        y2[k] += delta;
        let (a, b) = (Steffen::new(&x, &y).unwrap(), Steffen::new(&x, &y2).unwrap());
        // slopes depend on the two neighbours: intervals beyond x[k-2]..x[k+2] are untouched
        for t in fine(&x) {
            if t < x[k.saturating_sub(2)] || t > x[(k + 2).min(x.len() - 1)] {
                prop_assert_eq!(a.value_and_slope(t), b.value_and_slope(t));
            }
        }
    }
}

#[test]
fn a_near_discontinuity_does_not_ring() {
    // a step over 1e-6 of the grid, like a retract branch dropping at d_min
    let x = [0.0, 0.25, 0.5, 0.5 + 1e-6, 0.75, 1.0];
    let y = [1.0, 1.0, 1.0, -1.0, -1.0, -1.0];
    let s = Steffen::new(&x, &y).unwrap();
    let mut prev = f64::INFINITY;
    for t in fine(&x) {
        let (v, dv) = s.value_and_slope(t);
        assert!((-1.0..=1.0).contains(&v), "{t}: {v}");
        assert!(dv <= 0.0 && v <= prev, "{t}: {v} {dv}");
        prev = v;
    }
    // flat data stay exactly flat next to the step
    assert_eq!(s.value_and_slope(0.3), (1.0, 0.0));
    assert_eq!(s.value_and_slope(0.9), (-1.0, 0.0));
}

fn max_error(f: impl Fn(f64) -> f64, n: usize) -> f64 {
    let x: Vec<f64> = (0..=n).map(|i| 2.0 * i as f64 / n as f64).collect();
    let y: Vec<f64> = x.iter().map(|&v| f(v)).collect();
    let s = Steffen::new(&x, &y).unwrap();
    fine(&x)
        .iter()
        .map(|&t| (s.value_and_slope(t).0 - f(t)).abs())
        .fold(0.0, f64::max)
}

#[test]
fn the_error_on_smooth_monotone_data_falls_at_least_as_h_cubed() {
    let f = |x: f64| (3.0 * (x - 1.0)).tanh();
    let (e1, e2, e3) = (max_error(f, 20), max_error(f, 40), max_error(f, 80));
    assert!(e2 < e1 / 8.0 && e3 < e2 / 8.0, "{e1:e} {e2:e} {e3:e}");
}

/// Near an extremum between nodes the slope limiter costs accuracy (the tabulator adds the
/// most tensile point as a node for that reason); the error still converges.
#[test]
fn the_error_near_extrema_still_converges() {
    let f = |x: f64| (3.0 * x).sin() * (-x).exp();
    let (e1, e3) = (max_error(f, 20), max_error(f, 80));
    assert!(e3 < e1 / 4.0, "{e1:e} {e3:e}");
}
