//! Whole scenes, each accuracy mode: the asperity curves of Fig 2 and the paper's switch
//! (10 cycles and the elastic comparison, pull-out only and with 200-point curves).

use criterion::{criterion_group, criterion_main, Criterion};
use stiction::model::keys::Kind;
use stiction::model::laws::LawRegistry;
use stiction::model::scene::Scene;
use stiction::model::spec::{AsperitySpec, SwitchSpec};
use stiction::model::switch::SwitchModel;
use stiction::model::{asperity, Accuracy, Silent};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("scenes");
    g.sample_size(10);
    let registry = LawRegistry::builtin();
    let asperity = AsperitySpec::new(&Scene::paper(Kind::Asperity), &registry).unwrap();
    g.bench_function("asperity Fig 2, 3 cases x 200 points", |b| {
        b.iter(|| asperity::run(&asperity).unwrap())
    });
    let paper = SwitchSpec::new(&Scene::paper(Kind::Switch), &registry).unwrap();
    for acc in [Accuracy::Accurate, Accuracy::Balanced, Accuracy::Fast] {
        for points in [0usize, 200] {
            let spec = paper
                .with_accuracy(acc)
                .and_then(|s| s.with_points(points))
                .unwrap();
            g.bench_function(
                format!("switch 10 cycles + elastic, {acc}, {points} curve points"),
                |b| b.iter(|| SwitchModel::build(&spec).unwrap().run(&Silent).unwrap()),
            );
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
