//! Whole scenes, each accuracy mode: the asperity curves of Fig 2 and the paper's switch
//! (10 cycles and the elastic comparison, pull-out only and with 200-point curves).

use criterion::{criterion_group, criterion_main, Criterion};
use stiction::accuracy::Accuracy;
use stiction::commands::asperity::AsperityCommand;
use stiction::commands::{switch, Command};
use stiction::render::Format;
use stiction::scene::{self, AsperityScene, Loaded, Scene, SwitchScene};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("scenes");
    g.sample_size(10);
    let mut a: AsperityScene = scene::parse("bench", scene::DEFAULT_ASPERITY).unwrap();
    a.validate("bench").unwrap();
    let asperity = Loaded {
        file: "bench".into(),
        scene: a,
        is_paper: true,
    };
    let cmd = AsperityCommand {
        scene: None,
        delta_max: vec![],
        format: Format::Json,
        plot: None,
    };
    g.bench_function("asperity Fig 2, 3 cases x 200 points", |b| {
        b.iter(|| cmd.run(&asperity).unwrap())
    });
    for acc in [Accuracy::Accurate, Accuracy::Balanced, Accuracy::Fast] {
        for points in [0usize, 200] {
            let mut s: SwitchScene = scene::parse("bench", scene::DEFAULT_SWITCH).unwrap();
            s.accuracy = acc;
            s.points = points;
            s.validate("bench").unwrap();
            let loaded = Loaded {
                file: "bench".into(),
                scene: s,
                is_paper: true,
            };
            g.bench_function(
                format!("switch 10 cycles + elastic, {acc}, {points} curve points"),
                |b| b.iter(|| switch::run(&loaded, false).unwrap()),
            );
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
