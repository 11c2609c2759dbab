//! Evaluation speed of a tabulated law (release build only is meaningful).
use contact_law::tabulate::{tabulate, Tabulation};
use contact_law::toy::ToyLaw;
use contact_law::{Path, State};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let law = tabulate(&ToyLaw::default(), &Tabulation::adaptive(1.5e-9, 15e-9)).unwrap();
    // separations spread over the retract branches between tabulated d_min
    let ds: Vec<f64> = (0..1024)
        .map(|i| 4.1e-9 + 6e-9 * (i as f64 / 1024.0))
        .collect();
    c.bench_function("evaluate stateless retract (between branches)", |b| {
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & 1023;
            law.evaluate(black_box(ds[i]), black_box(4.05e-9), Path::Retract)
                .unwrap()
                .pressure
        })
    });
    c.bench_function("pressure with state (retract)", |b| {
        let mut state = State::VIRGIN;
        law.pressure(4.05e-9, &mut state).unwrap();
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & 1023;
            let mut s = state;
            law.pressure(black_box(ds[i]), &mut s).unwrap().0
        })
    });
    c.bench_function("virgin envelope", |b| {
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & 1023;
            law.evaluate(black_box(ds[i] - 2e-9), f64::INFINITY, Path::Approach)
                .unwrap()
                .pressure
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
