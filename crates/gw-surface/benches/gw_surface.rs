//! One surface pressure and a 200-point curve at the quadrature tolerance of each accuracy
//! mode (the paper's Ru surface, unloading after pressing to 1.25 sigma_s).

use asperity_plastic::{ElastoPlasticAsperity, EtsionKadin, YieldModulus};
use contact_core::{paper, Material, Pair, Path, SurfaceLaw};
use criterion::{criterion_group, criterion_main, Criterion};
use gw_surface::{GreenwoodWilliamson, GwHistory, Quadrature, Roughness};
use maugis_kim::{DugdaleParams, MaugisKim};
use std::hint::black_box;

const SIGMA: f64 = paper::SIGMA_S;

fn bench(c: &mut Criterion) {
    let m = Material::new(paper::RU).unwrap();
    let pair = Pair::new(m, Some(m), paper::RADIUS).unwrap();
    let asp = ElastoPlasticAsperity::new(
        EtsionKadin::new(&pair, YieldModulus::AsPrinted).unwrap(),
        MaugisKim::new(DugdaleParams::for_pair(
            &pair,
            paper::WORK_OF_ADHESION,
            paper::Z0,
        ))
        .unwrap(),
    );
    let hist = GwHistory::Flat {
        deepest: 1.25 * SIGMA,
    };
    let path = Path::Retract { from: 1.25 * SIGMA };
    let rough = Roughness {
        sigma_s: SIGMA,
        asperity_density: paper::ASPERITY_DENSITY,
    };
    // the surface tolerances of the accurate, balanced and fast modes
    for (name, rel_tol) in [("1e-10", 1e-10), ("1e-7", 1e-7), ("1e-5", 1e-5)] {
        let q = Quadrature {
            rel_tol,
            ..Quadrature::default()
        };
        let gw = GreenwoodWilliamson::new(asp, rough, q).unwrap();
        c.bench_function(&format!("surface pressure rel {name}"), |b| {
            b.iter(|| gw.pressure(black_box(2.5 * SIGMA), &hist, path).unwrap())
        });
        let mut g = c.benchmark_group("surface curve");
        g.sample_size(10);
        g.bench_function(format!("200 points rel {name}"), |b| {
            b.iter(|| {
                (0..200)
                    .map(|i| {
                        gw.pressure(1.25 * SIGMA + 8.0 * SIGMA * i as f64 / 199.0, &hist, path)
                            .unwrap()
                    })
                    .sum::<f64>()
            })
        });
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
