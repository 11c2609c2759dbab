//! Speed of the analysis of a 1024 x 1024 map (issue 26: "well under a second").

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use topography::io::{decode, encode};
use topography::{
    analyze, find_summits, finite_difference_moments, lowpass, synthesize, Amplitudes,
    AnalysisOptions, Format, HeightMap, Normalization, ReadOptions, SelfAffinePsd,
    SynthesisOptions,
};

fn map_1024() -> HeightMap {
    let dx = 10e-9;
    let psd = SelfAffinePsd::new(
        0.8,
        512.0 * dx,
        None,
        4.0 * dx,
        Normalization::RmsHeight(5e-9),
    )
    .unwrap();
    let o = SynthesisOptions {
        nx: 1024,
        ny: 1024,
        dx,
        dy: dx,
        seed: 1,
        amplitudes: Amplitudes::Gaussian,
    };
    synthesize(&psd, &o).unwrap()
}

fn bench(c: &mut Criterion) {
    let map = map_1024();
    let mut g = c.benchmark_group("1024x1024");
    g.sample_size(10);
    g.bench_function("analyze (full report)", |b| {
        b.iter(|| analyze(black_box(&map), &AnalysisOptions::default()).unwrap())
    });
    let lean = AnalysisOptions {
        coarsen: vec![],
        scan_divisors: vec![],
        psd_bins: 0,
        band: vec![],
        ..AnalysisOptions::default()
    };
    g.bench_function("analyze (full report, no band table)", |b| {
        let o = AnalysisOptions {
            band: vec![],
            ..AnalysisOptions::default()
        };
        b.iter(|| analyze(black_box(&map), &o).unwrap())
    });
    g.bench_function("Gaussian low-pass (cutoff 160 nm)", |b| {
        b.iter(|| lowpass(black_box(&map), 160e-9))
    });
    g.bench_function("analyze (no tables, no band)", |b| {
        b.iter(|| analyze(black_box(&map), &lean).unwrap())
    });
    g.bench_function("finite-difference moments", |b| {
        b.iter(|| finite_difference_moments(black_box(&map)))
    });
    g.bench_function("summits", |b| b.iter(|| find_summits(black_box(&map))));
    let x3p = encode(&map, Format::X3p).unwrap();
    g.bench_function("read x3p", |b| {
        b.iter(|| {
            decode(
                std::path::Path::new("b.x3p"),
                black_box(&x3p),
                Format::X3p,
                &ReadOptions::default(),
            )
            .unwrap()
        })
    });
    g.bench_function("synthesize", |b| b.iter(map_1024));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
