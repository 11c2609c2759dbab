use asperity_plastic::{ElastoPlasticAsperity, EtsionKadin, YieldModulus};
use contact_core::{Material, Pair, Path, SurfaceLaw};
use criterion::{criterion_group, criterion_main, Criterion};
use gw_surface::{GreenwoodWilliamson, GwHistory, Quadrature};
use maugis_kim::MaugisKim;
use std::hint::black_box;

const SIGMA: f64 = 7.78e-9;

fn modes() -> [(&'static str, Quadrature); 3] {
    [
        ("accurate", Quadrature::Adaptive { rel_tol: 1e-10 }),
        (
            "balanced",
            Quadrature::GaussLegendre {
                nodes: 12,
                panel_sigmas: 0.5,
            },
        ),
        (
            "fast",
            Quadrature::GaussLegendre {
                nodes: 6,
                panel_sigmas: 1.0,
            },
        ),
    ]
}

fn bench(c: &mut Criterion) {
    let m = Material::new(410e9, 0.3, 3.42e9).unwrap();
    let pair = Pair::new(m, Some(m), 4e-6).unwrap();
    let asp = ElastoPlasticAsperity::new(
        EtsionKadin::new(&pair, YieldModulus::Composite).unwrap(),
        MaugisKim::new(pair.k(), 1.0, 0.169e-9).unwrap(),
    );
    let hist = GwHistory::Flat {
        deepest: 1.25 * SIGMA,
    };
    let path = Path::Retract { from: 1.25 * SIGMA };
    for (name, q) in modes() {
        let gw = GreenwoodWilliamson::new(asp, SIGMA, 1e13, q).unwrap();
        c.bench_function(&format!("surface pressure {name}"), |b| {
            b.iter(|| gw.pressure(black_box(2.5 * SIGMA), &hist, path).unwrap())
        });
        let mut g = c.benchmark_group("surface curve");
        g.sample_size(10);
        g.bench_function(format!("200 points {name}"), |b| {
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
