//! Whole scenes, each accuracy mode: the asperity curves of Fig 2 and the switch of
//! Fig 4 (10 cycles and the elastic comparison).

use criterion::{criterion_group, criterion_main, Criterion};
use stiction::run;
use stiction::scene::{self, Accuracy, AsperityScene, SwitchScene};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("scenes");
    g.sample_size(10);
    let a: AsperityScene = scene::parse("bench", scene::DEFAULT_ASPERITY).unwrap();
    g.bench_function("asperity Fig 2, 3 cases x 200 points", |b| {
        b.iter(|| run::asperity(&a).unwrap())
    });
    for acc in [Accuracy::Accurate, Accuracy::Balanced, Accuracy::Fast] {
        for points in [0usize, 200] {
            let mut s: SwitchScene = scene::parse("bench", scene::DEFAULT_SWITCH).unwrap();
            s.accuracy = acc;
            s.points = points;
            g.bench_function(
                format!("switch 10 cycles + elastic, {acc:?}, {points} curve points"),
                |b| b.iter(|| run::switch(&s).unwrap()),
            );
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
