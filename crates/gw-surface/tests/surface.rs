//! The Greenwood-Williamson surface against independent evaluations and its invariants.

use asperity_plastic::{Elastic, ElastoPlasticAsperity, EtsionKadin, YieldModulus};
use contact_core::numeric::GaussLegendre;
use contact_core::{AsperityModel, Material, Pair, Path, SurfaceLaw};
use gw_surface::{GreenwoodWilliamson, GwHistory, HeightTable, Quadrature};
use maugis_kim::{Dmt, Hertz, MaugisKim};
use std::f64::consts::PI;

const SIGMA: f64 = 7.78e-9;
const DENSITY: f64 = 1e13;
const R: f64 = 4e-6;

fn ru_pair() -> Pair {
    let m = Material::new(410e9, 0.3, 3.42e9).unwrap();
    Pair::new(m, Some(m), R).unwrap()
}

fn phi(u: f64) -> f64 {
    (-0.5 * u * u).exp() / (2.0 * PI).sqrt()
}

/// Independent: integral over s >= t of g(s - t) phi(s) ds with s = t + v^2, composite
/// 40-point Gauss-Legendre on 200 panels of v in [0, 6] (v^2 = 36 sigma beyond contact).
fn independent(t: f64, g: impl Fn(f64) -> f64) -> f64 {
    let gl = GaussLegendre::new(40);
    let n = 200;
    let vmax = 6.0 + (-t).max(0.0).sqrt();
    (0..n)
        .map(|i| {
            let (a, b) = (vmax * i as f64 / n as f64, vmax * (i + 1) as f64 / n as f64);
            gl.integrate(|v| 2.0 * v * g(v * v) * phi(t + v * v), a, b)
        })
        .sum()
}

#[test]
fn hertz_surface_matches_the_classic_gw_integral() {
    let pair = ru_pair();
    let asp = ElastoPlasticAsperity::new(Elastic::new(R).unwrap(), Hertz::new(pair.k()).unwrap());
    let gw = GreenwoodWilliamson::new(asp, SIGMA, DENSITY, Quadrature::default()).unwrap();
    for t in [-2.0, -0.5, 0.0, 0.7, 1.5, 3.0, 5.0] {
        let d = t * SIGMA;
        let p = gw.pressure(d, &GwHistory::VIRGIN, Path::Approach).unwrap();
        // p = N K sqrt(R) sigma^(3/2) F_{3/2}(t)
        let f32 = independent(t, |x: f64| x.powf(1.5));
        let expect = DENSITY * pair.k() * R.sqrt() * SIGMA.powf(1.5) * f32;
        assert!((p / expect - 1.0).abs() < 1e-9, "t {t}: {p} vs {expect}");
    }
}

#[test]
fn dmt_surface_matches_an_independent_integral() {
    let pair = ru_pair();
    let (w, z0) = (1.0, 0.169e-9);
    let dmt = Dmt::new(pair.k(), w, z0).unwrap();
    let asp = ElastoPlasticAsperity::new(Elastic::new(R).unwrap(), dmt);
    let gw = GreenwoodWilliamson::new(asp, SIGMA, DENSITY, Quadrature::default()).unwrap();
    for t in [-1.0, 0.0, 1.0, 2.5, 4.0] {
        let d = t * SIGMA;
        let p = gw.pressure(d, &GwHistory::VIRGIN, Path::Approach).unwrap();
        let adh = 2.0 * PI * w * R;
        // contact part (Hertz - 2 pi w R) over h >= d, Dugdale ramp over d - z0 < h < d
        let contact = independent(t, |x: f64| {
            pair.k() * R.sqrt() * (x * SIGMA).powf(1.5) - adh
        });
        let gl = GaussLegendre::new(30);
        let ramp = gl.integrate(
            |u| -adh * (1.0 + (u * SIGMA - d) / z0) * phi(u),
            t - z0 / SIGMA,
            t,
        );
        let expect = DENSITY * (contact + ramp);
        assert!(
            (p - expect).abs() < 1e-9 * expect.abs().max(DENSITY * adh * phi(t)),
            "t {t}: {p} vs {expect}"
        );
    }
}

fn ru_surface(q: Quadrature) -> GreenwoodWilliamson<ElastoPlasticAsperity<EtsionKadin, MaugisKim>> {
    let pair = ru_pair();
    let ek = EtsionKadin::new(&pair, YieldModulus::Composite).unwrap();
    let mk = MaugisKim::new(pair.k(), 1.0, 0.169e-9).unwrap();
    GreenwoodWilliamson::new(ElastoPlasticAsperity::new(ek, mk), SIGMA, DENSITY, q).unwrap()
}

#[test]
fn adaptive_quadrature_converges_to_1e8() {
    let loose = ru_surface(Quadrature::Adaptive { rel_tol: 1e-10 });
    let tight = ru_surface(Quadrature::Adaptive { rel_tol: 1e-13 });
    let hist = GwHistory::Flat {
        deepest: 0.5 * SIGMA,
    };
    for (d, path) in [
        (2.0 * SIGMA, Path::Approach),
        (0.2 * SIGMA, Path::Approach),
        (0.8 * SIGMA, Path::Retract { from: 0.5 * SIGMA }),
        (1.6 * SIGMA, Path::Retract { from: 0.5 * SIGMA }),
    ] {
        let (a, _, _) = loose.pressure_detailed(d, &hist, path).unwrap();
        let (b, _, _) = tight.pressure_detailed(d, &hist, path).unwrap();
        assert!(
            (a - b).abs() <= 1e-8 * b.abs(),
            "d {d} {path:?}: {a} vs {b}"
        );
    }
}

#[test]
fn gauss_legendre_mode_converges_to_the_adaptive_mode() {
    let acc = ru_surface(Quadrature::Adaptive { rel_tol: 1e-12 });
    let hist = GwHistory::Flat {
        deepest: 0.5 * SIGMA,
    };
    let path = Path::Retract { from: 0.5 * SIGMA };
    let d = 1.2 * SIGMA;
    let exact = acc.pressure(d, &hist, path).unwrap();
    let mut last = f64::INFINITY;
    for nodes in [4, 8, 16, 32] {
        let gl = ru_surface(Quadrature::GaussLegendre {
            nodes,
            panel_sigmas: 0.5,
        });
        let e = (gl.pressure(d, &hist, path).unwrap() - exact).abs() / exact.abs();
        assert!(e < last.max(1e-12), "nodes {nodes}: error {e} after {last}");
        last = e;
    }
    assert!(last < 1e-6, "{last}");
}

#[test]
fn one_number_history_agrees_with_the_general_history() {
    let gw = ru_surface(Quadrature::default());
    let deepest = 0.4 * SIGMA;
    let flat = GwHistory::VIRGIN.loaded(2.0 * SIGMA).loaded(deepest);
    let table = GwHistory::Table(HeightTable::virgin(-9.0 * SIGMA, 9.0 * SIGMA, 20001))
        .loaded(2.0 * SIGMA)
        .loaded(deepest);
    assert_eq!(flat, GwHistory::Flat { deepest });
    for d in [0.6 * SIGMA, 1.0 * SIGMA, 2.0 * SIGMA] {
        let path = Path::Retract { from: deepest };
        let a = gw.pressure(d, &flat, path).unwrap();
        let b = gw.pressure(d, &table, path).unwrap();
        assert!((a - b).abs() <= 1e-9 * a.abs(), "d {d}: {a} vs {b}");
    }
}

#[test]
fn elastic_loading_pressure_is_continuous_and_monotone() {
    let pair = ru_pair();
    let mk = MaugisKim::new(pair.k(), 1.0, 0.169e-9).unwrap();
    let gw = GreenwoodWilliamson::new(
        ElastoPlasticAsperity::new(Elastic::new(R).unwrap(), mk),
        SIGMA,
        DENSITY,
        Quadrature::default(),
    )
    .unwrap();
    // compressive region: pressure decreases with d
    let mut prev = f64::INFINITY;
    for i in 0..40 {
        let d = -1.0 * SIGMA + 0.1 * SIGMA * i as f64;
        let p = gw.pressure(d, &GwHistory::VIRGIN, Path::Approach).unwrap();
        if p > 0.0 {
            assert!(p < prev, "d {d}: {p} !< {prev}");
            assert!(
                prev == f64::INFINITY || (prev - p) < 0.5 * prev,
                "jump at d {d}"
            );
        }
        prev = p;
    }
}

#[test]
fn history_only_deepens() {
    let gw = ru_surface(Quadrature::default());
    let h = gw.load(&gw.virgin(), 1.0 * SIGMA);
    let h2 = gw.load(&h, 2.0 * SIGMA);
    assert_eq!(h, h2);
    let h3 = gw.load(&h, 0.5 * SIGMA);
    assert_eq!(h3.deepest(), Some(0.5 * SIGMA));
    assert!(gw.asperity().yield_interference() > 0.0);
}

#[test]
fn fraction_beyond_the_fit_range_follows_the_gaussian_tail() {
    let gw = ru_surface(Quadrature::default());
    let dcp = gw.asperity().yield_interference();
    // delta_max(h) = h - deepest exceeds 10 delta_CP above h = deepest + 10 delta_CP
    let deepest = -10.0 * dcp;
    let flat = GwHistory::Flat { deepest };
    assert!((gw.fraction_beyond(&flat, 10.0) - 0.5).abs() < 1e-15);
    let shifted = GwHistory::Flat {
        deepest: deepest + SIGMA,
    };
    assert!((gw.fraction_beyond(&shifted, 10.0) - 0.15865525393145707).abs() < 1e-9);
    let table = GwHistory::Table(HeightTable::virgin(-9.0 * SIGMA, 9.0 * SIGMA, 2001))
        .loaded(deepest + SIGMA);
    assert!((gw.fraction_beyond(&table, 10.0) - 0.15865525393145707).abs() < 1e-3);
    assert_eq!(gw.fraction_beyond(&GwHistory::VIRGIN, 10.0), 0.0);
}
