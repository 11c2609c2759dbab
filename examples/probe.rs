//! probe: run random scenes in each mode and print errors
use stiction::accuracy::Accuracy;
use stiction::commands::switch;
use stiction::scene::{Loaded, Scene};
use stiction::scenegen::{self, Domain, Rng};

fn main() {
    if let Ok(v) = std::env::var("PROFILE") { let a: Vec<String> = std::env::args().collect(); profile(a[1].parse().unwrap(), a[2].parse().unwrap(), v.parse().unwrap()); return; }
    if std::env::var("DETAIL").is_ok() { let a: Vec<String> = std::env::args().collect(); detail(a[1].parse().unwrap(), a[2].parse().unwrap(), if a.get(3).map(|s| s.as_str()) == Some("wide") { Domain::Wide } else { Domain::Mems }); return; }
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(20);
    let dom = if args.get(2).map(|s| s.as_str()) == Some("wide") { Domain::Wide } else { Domain::Mems };
    let seed: u64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
    let mut rng = Rng::new(seed);
    for i in 0..n {
        let mut s = scenegen::switch_scene(&mut rng, dom);
        if let Err(e) = s.validate("gen") { println!("{i}: invalid: {e}"); continue; }
        let mut res = Vec::new();
        for acc in [Accuracy::Reference, Accuracy::Accurate, Accuracy::Balanced, Accuracy::Fast] {
            let mut s2 = s.clone(); s2.accuracy = acc;
            let t = std::time::Instant::now();
            let r = switch::run(&Loaded { file: "gen".into(), scene: s2, is_paper: false }, false);
            res.push((acc, r, t.elapsed().as_secs_f64()));
        }
        let Ok(refr) = &res[0].1 else { println!("{i}: ref failed: {}  [{:?} {:?} {:?}]", res[0].1.as_ref().unwrap_err(), s.contact.adhesion_law, s.contact.plasticity_law, s.contact.counter); continue };
        let sig = s.surface.sigma_s;
        let mut line = format!("{i:3} {:?}/{:?}/{:?} ratio {:.3e} t_ref {:.2}s |", s.contact.adhesion_law, s.contact.plasticity_law, s.contact.yield_modulus, refr.pull_out_ratio, res[0].2);
        for (acc, r, t) in &res[1..] {
            match r {
                Err(e) => line += &format!(" {acc}: FAIL {e} |"),
                Ok(r) => {
                    let mut de: f64 = 0.0; let mut po: f64 = 0.0;
                    for (a, b) in refr.cycles.iter().zip(&r.cycles) {
                        de = de.max((a.d_e - b.d_e).abs() / sig);
                        let floor = 1e-9 * refr.restoring_pressure / s.switch.contact_area_fraction;
                        po = po.max((a.pull_out_pressure - b.pull_out_pressure).abs() / a.pull_out_pressure.abs().max(floor / 1.0).max(1e-300));
                    }
                    line += &format!(" {acc}: de {de:.1e} po {po:.1e} t {t:.3} |");
                }
            }
        }
        // d_e rise
        let mut rise: f64 = 0.0;
        for w in refr.cycles.windows(2) { rise = rise.max((w[1].d_e - w[0].d_e) / sig); }
        line += &format!(" rise {rise:.1e}");
        println!("{line}");
    }
}
#[allow(dead_code)]
fn detail(seed: u64, idx: usize, dom: Domain) {
    let mut rng = Rng::new(seed);
    let mut s = scenegen::switch_scene(&mut rng, dom);
    for _ in 0..idx { s = scenegen::switch_scene(&mut rng, dom); }
    s.validate("gen").unwrap();
    println!("{}", toml::to_string(&s).unwrap());
    s.accuracy = Accuracy::Accurate;
    let r = switch::run(&Loaded { file: "gen".into(), scene: s.clone(), is_paper: false }, false).unwrap();
    for c in &r.cycles { println!("cycle {} d_e {:e} ({:.4} sigma) p_L {:e} pull {:e} at {:e}", c.cycle, c.d_e, c.d_e / s.surface.sigma_s, c.contact_pressure, c.pull_out_pressure, c.pull_out_separation); }
}
#[allow(dead_code)]
fn profile(seed: u64, idx: usize, deepest: f64) {
    use stiction::contact_core::{SurfaceLaw, Path};
    let mut rng = Rng::new(seed);
    let mut s = scenegen::switch_scene(&mut rng, Domain::Mems);
    for _ in 0..idx { s = scenegen::switch_scene(&mut rng, Domain::Mems); }
    s.validate("gen").unwrap();
    let gw = stiction::model::surface(&s.contact, &s.surface, Accuracy::Accurate, 0.0, false).unwrap();
    let hist = gw.load(&gw.virgin(), deepest);
    let top = gw.reach(&hist, Path::Approach).unwrap();
    let film = stiction::switch_1d::ImpactFilm { thickness: s.switch.film_thickness, youngs_modulus: s.contact.youngs_modulus };
    println!("top {top:e}");
    let n = 60;
    for i in 0..=n {
        let d = top + (deepest - 1e-9 - top) * i as f64 / n as f64;
        let p = gw.pressure(d, &hist, Path::Approach).unwrap();
        let g = stiction::switch_1d::eq17_residual(&gw, &hist, d, s.switch.impact_energy.unwrap(), film).unwrap();
        println!("d {d:.4e} p {p:.4e} G {g:.4e}");
    }
}
