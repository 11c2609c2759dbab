// scratch experiment: error of rules in d_min (not committed)
use stiction_model::contact_core::{Path as SP, SurfaceLaw};
use stiction_model::gw_surface::GwHistory;
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene; use stiction_model::keys::Kind;
use stiction_model::spec::Spec;
use stiction_model::Accuracy;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let scene = if args.len() > 1 { Scene::read(std::path::Path::new(&args[1])).unwrap() } else { Scene::paper(Kind::Switch) };
    let reg = LawRegistry::builtin();
    let spec = Spec::new(&scene, &reg).unwrap();
    let Spec::Switch(sw) = spec else { panic!() };
    let gw = stiction_model::switch::surface_of(&sw, Accuracy::Fast, 0.0, false).unwrap();
    let sigma = gw.sigma_s();
    let lo: f64 = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(4.549e-9);
    let hi: f64 = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(32.39e-9);
    let pv = |d: f64| gw.pressure(d, &GwHistory::VIRGIN, SP::Approach).unwrap();
    let br = |d: f64, dm: f64, retract: bool| {
        let h = GwHistory::Flat { deepest: dm };
        let path = if retract { SP::Retract { from: dm } } else { SP::Approach };
        gw.pressure(d, &h, path).unwrap()
    };
    let reach = |dm: f64, retract: bool| {
        let h = GwHistory::Flat { deepest: dm };
        let path = if retract { SP::Retract { from: dm } } else { SP::Approach };
        gw.reach(&h, path).unwrap()
    };
    let po = |dm: f64| {
        let u = stiction_model::switch_1d::unload(&gw, &GwHistory::Flat { deepest: dm }, dm, 0, Accuracy::Fast.precision()).unwrap();
        u.pull_out_pressure
    };
    let floor_abs = 1e-3 * po(lo).abs();
    println!("sigma {sigma:e} po(lo) {:e} floor {floor_abs:e}", po(lo));
    for &nint in &[4usize, 8, 16, 32, 64] {
        let h = (hi - lo) / nint as f64;
        let mut worst = [[0.0f64; 2]; 4]; // rule x path
        let mut worst_f = [[0.0f64; 2]; 4];
        for k in 0..nint {
            let d0 = lo + h * k as f64;
            let dm = d0 + 0.5 * h;
            let pom = po(dm).abs();
            for (ip, &retract) in [false, true].iter().enumerate() {
                let len = reach(dm, retract) - dm;
                let mut xs: Vec<f64> = (1..=120).map(|i| len * (i as f64 / 120.0).powi(2)).collect();
                let mut g = 1e-4 * sigma; while g < len / 120.0 { xs.push(g); g *= 1.6; }
                for x in xs {
                    let direct = br(dm + x, dm, retract);
                    let p = |j: i64| -> f64 { let d = lo + h * (k as i64 + j) as f64; if d < lo - 1e-15 { f64::NAN } else { br(d + x, d, retract) } };
                    let (a, b) = (p(0), p(1));
                    let lin = 0.5 * (a + b);
                    let (am, bp) = (p(-1), p(2));
                    let cub = if am.is_nan() { 3.0/8.0*a + 3.0/4.0*b - 1.0/8.0*p(2) } else { (-am + 9.0*a + 9.0*b - bp) / 16.0 };
                    // normalized by virgin pressure at d_min (scale sign)
                    let s = |j: i64| { let d = lo + h * (k as i64 + j) as f64; pv(d).abs() + po(d).abs() };
                    let sm = pv(dm).abs() + pom;
                    let nlin = sm * 0.5 * (a / s(0) + b / s(1));
                    let ncub = if am.is_nan() { f64::NAN } else { sm * (-am/s(-1) + 9.0*a/s(0) + 9.0*b/s(1) - bp/s(2)) / 16.0 };
                    for (ir, v) in [lin, cub, nlin, ncub].iter().enumerate() {
                        if v.is_nan() { continue; }
                        let e = (v - direct).abs() / (direct.abs() + pom);
                        let ef = (v - direct).abs() / (direct.abs() + pom + floor_abs);
                        worst[ir][ip] = worst[ir][ip].max(e);
                        worst_f[ir][ip] = worst_f[ir][ip].max(ef);
                    }
                }
            }
        }
        println!("h {:.3} nm ({:.4} sigma): lin {:.1e}/{:.1e} cub {:.1e}/{:.1e} nlin {:.1e}/{:.1e} ncub {:.1e}/{:.1e} | floor: lin {:.1e}/{:.1e} cub {:.1e}/{:.1e} nlin {:.1e}/{:.1e} ncub {:.1e}/{:.1e}",
            h*1e9, h/sigma, worst[0][0], worst[0][1], worst[1][0], worst[1][1], worst[2][0], worst[2][1], worst[3][0], worst[3][1],
            worst_f[0][0], worst_f[0][1], worst_f[1][0], worst_f[1][1], worst_f[2][0], worst_f[2][1], worst_f[3][0], worst_f[3][1]);
    }
}
