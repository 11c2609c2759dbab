//! Cycle-runner invariants on the paper's two Ru surfaces (Table 1) under Table 2.

use asperity_plastic::{Elastic, ElastoPlasticAsperity, EtsionKadin, YieldModulus};
use contact_core::numeric::integrate;
use contact_core::{Material, Pair, Path, PlasticityLaw, SurfaceLaw};
use gw_surface::{GreenwoodWilliamson, GwHistory, Quadrature};
use maugis_kim::MaugisKim;
use switch_1d::{end_of_impact, run_cycles, CycleOptions, ImpactFilm};

const SIGMA: f64 = 7.78e-9;

fn surface<P: PlasticityLaw>(
    p: P,
    q: Quadrature,
) -> GreenwoodWilliamson<ElastoPlasticAsperity<P, MaugisKim>> {
    let m = Material::new(410e9, 0.3, 3.42e9).unwrap();
    let pair = Pair::new(m, Some(m), 4e-6).unwrap();
    let mk = MaugisKim::new(pair.k(), 1.0, 0.169e-9).unwrap();
    GreenwoodWilliamson::new(ElastoPlasticAsperity::new(p, mk), SIGMA, 1e13, q).unwrap()
}

fn plastic(q: Quadrature) -> GreenwoodWilliamson<ElastoPlasticAsperity<EtsionKadin, MaugisKim>> {
    let m = Material::new(410e9, 0.3, 3.42e9).unwrap();
    let pair = Pair::new(m, Some(m), 4e-6).unwrap();
    surface(EtsionKadin::new(&pair, YieldModulus::Composite).unwrap(), q)
}

const FILM: ImpactFilm = ImpactFilm {
    thickness: 180e-9,
    youngs_modulus: 410e9,
};

fn quick() -> CycleOptions {
    CycleOptions {
        cycles: 4,
        unloading_points: 24,
        loading_points: 0,
        ..Default::default()
    }
}

#[test]
fn end_of_impact_satisfies_the_energy_balance_of_eq_17() {
    let gw = plastic(Quadrature::default());
    for (hist, e_i) in [
        (GwHistory::VIRGIN, 0.5),
        (
            GwHistory::Flat {
                deepest: 1.3 * SIGMA,
            },
            0.5,
        ),
        (GwHistory::VIRGIN, 0.02),
    ] {
        let d_e = end_of_impact(&gw, &hist, e_i, FILM).unwrap();
        // independent: adaptive tanh-sinh of p_L over [d_e, reach], split at the kink
        let top = gw.reach(&hist).unwrap();
        let p = |x: f64| gw.pressure(x, &hist, Path::Approach).unwrap();
        let mut cuts = vec![d_e];
        cuts.extend(gw.kinks(&hist).into_iter().filter(|&k| k > d_e && k < top));
        cuts.push(top);
        let scale = p(d_e).abs() * SIGMA;
        let work: f64 = cuts
            .windows(2)
            .map(|w| {
                integrate("eq 17 check", p, w[0], w[1], 1e-11 * scale, 12)
                    .unwrap()
                    .value
            })
            .sum();
        let energy = work + FILM.energy(p(d_e));
        assert!(
            (energy - e_i).abs() <= 1e-7 * e_i,
            "E_I {e_i}: balance {energy} at d_e {d_e}"
        );
    }
}

#[test]
fn history_only_deepens_and_pull_out_grows_until_accommodation() {
    let gw = plastic(Quadrature::GaussLegendre {
        nodes: 12,
        panel_sigmas: 0.5,
    });
    let run = run_cycles(&gw, gw.virgin(), 0.5, FILM, quick()).unwrap();
    let mut deepest = f64::INFINITY;
    let mut pull = 0.0;
    for c in &run.cycles {
        let d = c.history.deepest().unwrap();
        assert!(
            d <= deepest,
            "cycle {}: deepest {d} above {deepest}",
            c.cycle
        );
        assert!(c.d_e >= d);
        // contact hardening: each impact flattens more asperities, pull-out does not fall
        assert!(
            c.unloading.pull_out_pressure >= pull * (1.0 - 1e-12),
            "cycle {}",
            c.cycle
        );
        deepest = d;
        pull = c.unloading.pull_out_pressure;
    }
    assert!(
        run.cycles[0].d_e > run.cycles[1].d_e,
        "the second impact goes deeper"
    );
}

#[test]
fn once_an_impact_stays_above_the_deepest_point_every_later_cycle_repeats_exactly() {
    let gw = plastic(Quadrature::GaussLegendre {
        nodes: 12,
        panel_sigmas: 0.5,
    });
    // a strong first impact, then weaker ones that stay above it
    let strong = run_cycles(
        &gw,
        gw.virgin(),
        1.0,
        FILM,
        CycleOptions {
            cycles: 1,
            ..quick()
        },
    )
    .unwrap();
    let hist = strong.cycles[0].history.clone();
    let weak = run_cycles(
        &gw,
        hist.clone(),
        0.3,
        FILM,
        CycleOptions {
            cycles: 3,
            ..quick()
        },
    )
    .unwrap();
    for c in &weak.cycles {
        assert!(c.d_e > hist.deepest().unwrap());
        assert_eq!(c.history, hist, "history must not change");
        assert_eq!(c.d_e, weak.cycles[0].d_e);
        assert_eq!(c.unloading, weak.cycles[0].unloading);
    }
    assert_eq!(weak.accommodated_after, Some(1));
}

#[test]
fn elastic_surface_repeats_every_cycle() {
    let gw = surface(
        Elastic::new(4e-6).unwrap(),
        Quadrature::GaussLegendre {
            nodes: 12,
            panel_sigmas: 0.5,
        },
    );
    let run = run_cycles(
        &gw,
        gw.virgin(),
        0.5,
        FILM,
        CycleOptions {
            cycles: 3,
            ..quick()
        },
    )
    .unwrap();
    for c in &run.cycles[1..] {
        assert_eq!(c.d_e, run.cycles[0].d_e);
        assert_eq!(c.unloading, run.cycles[0].unloading);
    }
    assert_eq!(run.accommodated_after, Some(1));
}

#[test]
fn an_energy_the_surface_cannot_absorb_is_an_error() {
    let gw = plastic(Quadrature::GaussLegendre {
        nodes: 6,
        panel_sigmas: 1.0,
    });
    let e = end_of_impact(&gw, &GwHistory::VIRGIN, 1e12, FILM).unwrap_err();
    assert!(
        matches!(e, switch_1d::SwitchError::EnergyNotAbsorbed { .. }),
        "{e}"
    );
    assert!(end_of_impact(&gw, &GwHistory::VIRGIN, -1.0, FILM).is_err());
}
