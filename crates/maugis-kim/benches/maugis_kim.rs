//! Cost of one Maugis-Kim point (a new curve per point, as the asperity law does).
use criterion::{criterion_group, criterion_main, Criterion};
use maugis_kim::MdCurve;
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    for lambda in [0.5, 5.0] {
        c.bench_function(&format!("md point accurate lambda={lambda}"), |b| {
            b.iter(|| {
                // a new curve per point, as the asperity law does (lambda varies with R_eff)
                let curve = MdCurve::new(black_box(lambda)).unwrap();
                curve.stable_point(black_box(1.234)).unwrap().force
            })
        });
        c.bench_function(
            &format!("md point on the jump-out window lambda={lambda}"),
            |b| {
                b.iter(|| {
                    let curve = MdCurve::new(black_box(lambda)).unwrap();
                    let t = curve.turning_point().unwrap().delta;
                    curve.stable_point(black_box(0.99 * t)).unwrap().force
                })
            },
        );
        c.bench_function(&format!("md curve 200 points lambda={lambda}"), |b| {
            b.iter(|| {
                MdCurve::new(black_box(lambda))
                    .unwrap()
                    .curve(200, 5.0)
                    .unwrap()
                    .len()
            })
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
