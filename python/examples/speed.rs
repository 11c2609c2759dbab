//! The Rust side of the Python package's speed measurements (docs/performance.md,
//! "The Python package"): the same work as `python/benches/speed.py` does through the
//! package, done by the library directly, so that the binding's cost per point is the
//! difference.
//!
//! ```sh
//! cargo run --release --manifest-path python/Cargo.toml --example speed -- LAW.json N
//! ```
//!
//! Prints JSON: nanoseconds per point of the contact law's stateless evaluation over N
//! points (a serial loop, as `ContactLaw.evaluate` runs it), and of the paper switch's
//! surface pressure (fast and accurate modes, serial and on the rayon pool).

use std::time::Instant;
use stiction_model::contact_core::{par, Path, SurfaceLaw};
use stiction_model::contact_law::{ContactLaw, Path as LawPath};
use stiction_model::gw_surface::GwHistory;
use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene;
use stiction_model::spec::SwitchSpec;
use stiction_model::switch::rough_surface;
use stiction_model::Accuracy;

/// The points of both sides: separations in [5, 25] nm, histories in [5, 9] nm (a
/// deterministic low-discrepancy sequence, the same in `speed.py`).
fn points(n: usize) -> (Vec<f64>, Vec<f64>) {
    let d = (0..n)
        .map(|i| 5e-9 + 20e-9 * ((i as f64 * 0.6180339887498949) % 1.0))
        .collect();
    let m = (0..n)
        .map(|i| 5e-9 + 4e-9 * ((i as f64 * 0.7548776662466927) % 1.0))
        .collect();
    (d, m)
}

fn best_of<F: FnMut() -> f64>(repeats: usize, mut f: F) -> f64 {
    (0..repeats).map(|_| f()).fold(f64::INFINITY, f64::min)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let law_path = args.get(1).expect("usage: speed LAW.json [N]");
    let n: usize = args.get(2).map_or(100_000, |s| s.parse().expect("N"));
    let law = ContactLaw::from_path(law_path).expect("a law file");
    let (d, d_min) = points(n);
    let mut sink = 0.0;
    let eval_ns = best_of(7, || {
        let t = Instant::now();
        for i in 0..n {
            sink += law
                .evaluate(d[i], d_min[i], LawPath::Retract)
                .expect("inside the law")
                .pressure;
        }
        t.elapsed().as_secs_f64() * 1e9 / n as f64
    });

    let scene = Scene::paper(Kind::Switch);
    let spec = SwitchSpec::new(&scene, &LawRegistry::builtin()).expect("the paper scene");
    let m = 2000;
    let (sd, _) = points(m);
    let hist = GwHistory::Flat { deepest: 5e-9 };
    let path = Path::Retract { from: 5e-9 };
    let mut surface = Vec::new();
    for accuracy in [Accuracy::Fast, Accuracy::Accurate] {
        let gw = rough_surface(spec.contact(), spec.roughness(), accuracy, 0.0, false).expect("gw");
        let serial = best_of(3, || {
            let t = Instant::now();
            for &x in &sd {
                sink += gw.pressure(x, &hist, path).expect("pressure");
            }
            t.elapsed().as_secs_f64() * 1e9 / m as f64
        });
        let parallel = best_of(3, || {
            let t = Instant::now();
            let p = par::map(&sd, |&x| gw.pressure(x, &hist, path)).expect("pressure");
            sink += p[0];
            t.elapsed().as_secs_f64() * 1e9 / m as f64
        });
        surface.push(format!(
            "\"{}\": {{\"serial_ns\": {serial:.1}, \"parallel_ns\": {parallel:.1}}}",
            accuracy.as_str()
        ));
    }
    println!(
        "{{\"points\": {n}, \"law_evaluate_ns\": {eval_ns:.2}, \"surface_points\": {m}, \"surface\": {{{}}}, \"threads\": {}, \"sink\": {}}}",
        surface.join(", "),
        rayon_threads(),
        sink.is_finite()
    );
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}
