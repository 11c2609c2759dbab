use asperity_plastic::{Elastic, ElastoPlasticAsperity, EtsionKadin, YieldModulus};
use contact_core::{Material, Pair, Path, SurfaceLaw};
use gw_surface::{GreenwoodWilliamson, GwHistory, Quadrature};
use maugis_kim::MaugisKim;
use std::time::Instant;
use switch_1d::*;

fn main() {
    let m = Material::new(410e9, 0.3, 3.42e9).unwrap();
    let pair = Pair::new(m, Some(m), 4e-6).unwrap();
    let mk = MaugisKim::new(pair.k(), 1.0, 0.169e-9).unwrap();
    let ek = EtsionKadin::new(&pair, YieldModulus::AsPrinted).unwrap();
    let sigma = 7.78e-9;
    let gw = GreenwoodWilliamson::new(
        ElastoPlasticAsperity::new(ek, mk),
        sigma,
        1e13,
        Quadrature::default(),
    )
    .unwrap();
    println!("lambda at R = {}", mk.lambda(4e-6));
    let t = Instant::now();
    let (p, e, n) = gw
        .pressure_detailed(1.0 * sigma, &GwHistory::VIRGIN, Path::Approach)
        .unwrap();
    println!(
        "p(1 sigma) = {p:e} err {e:e} evals {n} in {:?}",
        t.elapsed()
    );
    let t = Instant::now();
    let (p, e, n) = gw
        .pressure_detailed(
            1.0 * sigma,
            &GwHistory::Flat {
                deepest: 0.5 * sigma,
            },
            Path::Retract { from: 0.5 * sigma },
        )
        .unwrap();
    println!(
        "p_U(1 sigma) = {p:e} err {e:e} evals {n} in {:?}",
        t.elapsed()
    );
    let film = ImpactFilm {
        thickness: 180e-9,
        youngs_modulus: 410e9,
    };
    let t = Instant::now();
    let run = run_cycles(
        &gw,
        gw.virgin(),
        0.5,
        film,
        CycleOptions {
            cycles: 10,
            unloading_points: 50,
            loading_points: 0,
            ..Default::default()
        },
    )
    .unwrap();
    println!("cycles in {:?}", t.elapsed());
    for c in &run.cycles {
        println!(
            "cycle {} d_e {:.4} nm pull-out {:.6e} Pa at {:.3} nm",
            c.cycle,
            c.d_e * 1e9,
            c.unloading.pull_out_pressure,
            c.unloading.pull_out_separation * 1e9
        );
    }
    println!("accommodated after {:?}", run.accommodated_after);
    let gwe = GreenwoodWilliamson::new(
        ElastoPlasticAsperity::new(Elastic::new(4e-6).unwrap(), mk),
        sigma,
        1e13,
        Quadrature::default(),
    )
    .unwrap();
    let run = run_cycles(
        &gwe,
        gwe.virgin(),
        0.5,
        film,
        CycleOptions {
            cycles: 2,
            unloading_points: 50,
            loading_points: 0,
            ..Default::default()
        },
    )
    .unwrap();
    for c in &run.cycles {
        println!(
            "elastic cycle {} d_e {:.4} nm pull-out {:.6e} Pa",
            c.cycle,
            c.d_e * 1e9,
            c.unloading.pull_out_pressure
        );
    }
}
