//! The `adhesion_coupled` law (theory 2.8): its limits and invariants.

use asperity_plastic::{
    AdhesionCoupled, Elastic, ElastoPlasticAsperity, EtsionKadin, KogutEtsion, YieldModulus,
};
use contact_core::{
    paper, AdhesionLaw, AsperityHistory, AsperityModel, Material, MaterialProps, Pair, Path,
    PlasticityLaw,
};
use maugis_kim::{DugdaleParams, Hertz, Jkr, JkrParams, MaugisKim};

/// Gold films against each other (E 79 GPa, nu 0.42, S_Y 0.25 GPa, R 2 um).
fn gold(yield_stress: f64) -> Pair {
    let m = Material::new(MaterialProps {
        youngs_modulus: 79e9,
        poisson_ratio: 0.42,
        yield_stress,
    })
    .unwrap();
    Pair::new(m, Some(m), 2e-6).unwrap()
}

fn mk(pair: &Pair, w: f64) -> MaugisKim {
    MaugisKim::new(DugdaleParams::for_pair(pair, w, 0.2e-9)).unwrap()
}

fn ek(pair: &Pair) -> EtsionKadin {
    EtsionKadin::new(pair, YieldModulus::Composite).unwrap()
}

/// A law with no adhesion is its base law, to the bit: the Hertz contact adds no adhesive
/// displacement (a^2/R = delta).
#[test]
fn without_adhesion_it_is_the_base_law() {
    let pair = gold(0.25e9);
    let hertz = Hertz::new(pair.k()).unwrap();
    let coupled = AdhesionCoupled::new(ek(&pair), hertz).unwrap();
    let base = ek(&pair);
    let dcp = base.delta_cp();
    for omega in [0.5, 1.0, 2.0, 7.5, 30.0, 110.0, 300.0] {
        let d = omega * dcp;
        assert_eq!(coupled.state(d).delta_res, base.state(d).delta_res);
        assert_eq!(coupled.state(d).r_res, base.state(d).r_res);
        let a = ElastoPlasticAsperity::new(coupled.clone(), hertz);
        let b = ElastoPlasticAsperity::new(base, hertz);
        for x in [0.3, 0.8, 1.0] {
            for path in [Path::Approach, Path::Retract { from: d }] {
                let h = AsperityHistory { delta_max: d };
                assert_eq!(
                    a.force(x * d, h, path).unwrap(),
                    b.force(x * d, h, path).unwrap()
                );
            }
        }
    }
}

/// Weak adhesion: the paper's Ru asperity with w = 1e-3 J/m^2 is within 2e-3 of
/// etsion_kadin in its residual height, its forces and its pull-off.
#[test]
fn weak_adhesion_reduces_to_etsion_kadin() {
    let pair = Pair::new(
        Material::new(paper::RU).unwrap(),
        Some(Material::new(paper::RU).unwrap()),
        paper::RADIUS,
    )
    .unwrap();
    let base = EtsionKadin::new(&pair, YieldModulus::AsPrinted).unwrap();
    let adhesion = MaugisKim::new(DugdaleParams::for_pair(&pair, 1e-3, paper::Z0)).unwrap();
    let coupled = AdhesionCoupled::new(base, adhesion).unwrap();
    let a = ElastoPlasticAsperity::new(coupled, adhesion);
    let b = ElastoPlasticAsperity::new(base, adhesion);
    let dcp = base.delta_cp();
    for omega in [2.0, 5.0, 20.0, 60.0] {
        let d = omega * dcp;
        let (sa, sb) = (a.plasticity.state(d), b.plasticity.state(d));
        // delta_res is second order in omega - 1 near yield: compared on delta_max's scale
        assert!(
            (sa.delta_res - sb.delta_res).abs() <= 2e-3 * d,
            "omega {omega}: {} vs {}",
            sa.delta_res,
            sb.delta_res
        );
        let fa = a.force(d, AsperityHistory::VIRGIN, Path::Approach).unwrap();
        let fb = b.force(d, AsperityHistory::VIRGIN, Path::Approach).unwrap();
        assert!(
            (fa - fb).abs() <= 2e-3 * fb.abs(),
            "omega {omega}: {fa} vs {fb}"
        );
        let (pa, pb) = (a.pull_off(d).unwrap(), b.pull_off(d).unwrap());
        assert!(
            (pa.force - pb.force).abs() <= 2e-3 * pb.force.abs(),
            "omega {omega}: {pa:?} {pb:?}"
        );
    }
}

/// A film that cannot yield within reach is the elastic adhesive law, whatever the
/// adhesion: the force on both paths is the adhesion law's on the virgin sphere.
#[test]
fn without_plastic_flow_it_is_the_elastic_adhesive_law() {
    let pair = gold(1e13);
    let adhesion = mk(&pair, 0.3);
    let coupled = AdhesionCoupled::new(ek(&pair), adhesion).unwrap();
    let elastic = ElastoPlasticAsperity::new(Elastic::new(2e-6).unwrap(), adhesion);
    let asperity = ElastoPlasticAsperity::new(coupled, adhesion);
    let top = 5e-9;
    assert!(asperity.plasticity.state(top).delta_res == 0.0);
    for k in 0..=40 {
        let d = -1e-9 + 6e-9 * k as f64 / 40.0;
        for path in [Path::Approach, Path::Retract { from: top }] {
            let f = asperity.force(d, AsperityHistory::VIRGIN, path).unwrap();
            let g = elastic.force(d, AsperityHistory::VIRGIN, path).unwrap();
            assert!(
                (f - g).abs() <= 1e-12 * g.abs().max(1e-9),
                "{d:e} {path:?}: {f} vs {g}"
            );
        }
    }
}

/// Maugis & Pollock's onset: yield begins where the Hertz part of the adhesive pressure
/// peaks at C_v S_Y, 2 E* a/(pi R) = C_v S_Y (eq 1 with E*), a the virgin JKR contact
/// radius there; the geometric interference is below delta_CP by the adhesive
/// displacement sqrt(2 pi w a/E*) (JKR, Johnson 1985 eq 5.59 for delta).
#[test]
fn yield_begins_where_the_hertz_core_reaches_delta_cp() {
    let pair = Pair::new(
        Material::new(paper::RU).unwrap(),
        Some(Material::new(paper::RU).unwrap()),
        paper::RADIUS,
    )
    .unwrap();
    let base = ek(&pair);
    let w = 0.05;
    let jkr = Jkr::new(JkrParams {
        k: pair.k(),
        work_of_adhesion: w,
    })
    .unwrap();
    let coupled = AdhesionCoupled::new(base, jkr).unwrap();
    let onset = coupled.yield_onset();
    let r = paper::RADIUS;
    let a = jkr.contact_radius(r, onset, Path::Approach).unwrap();
    let e_star = pair.e_star();
    let peak = 2.0 * e_star * a / (std::f64::consts::PI * r);
    let cv_sy = 2.0 * e_star * (base.delta_cp() / r).sqrt() / std::f64::consts::PI;
    assert!((peak / cv_sy - 1.0).abs() < 1e-9, "{peak} vs {cv_sy}");
    let punch = (2.0 * std::f64::consts::PI * w * a / e_star).sqrt();
    assert!((base.delta_cp() - onset - punch).abs() < 1e-9 * base.delta_cp());
    // below the onset the state is elastic, above it plastic
    assert_eq!(coupled.state(onset * 0.999).delta_res, 0.0);
    assert!(
        coupled
            .state(onset * 1.01 + 1e-3 * base.delta_cp())
            .delta_res
            > 0.0
    );
}

/// On gold, adhesion alone yields the asperity: the state jumps at the jump-in, and the
/// Hertz interference is the fixed point of theory 2.8 (the tabulated value against the
/// direct solve, to the table's tolerance).
#[test]
fn on_gold_adhesion_alone_yields_and_the_table_meets_the_solve() {
    let pair = gold(0.25e9);
    for w in [0.1, 0.3, 1.0] {
        let adhesion = mk(&pair, w);
        for coupled in [AdhesionCoupled::new(ek(&pair), adhesion).unwrap()] {
            let j = coupled.jump_in();
            assert_eq!(coupled.state(j).delta_res, 0.0);
            if w >= 0.3 {
                // the zero-load contact alone yields: the state jumps at the jump-in
                assert_eq!(coupled.yield_onset(), j);
                assert!(coupled.state(j + 1e-13).delta_res > 0.0);
            } else {
                let onset = coupled.yield_onset();
                assert!(j < onset && onset < coupled.base().delta_cp(), "{onset:e}");
                assert_eq!(coupled.state(onset - 1e-13).delta_res, 0.0);
            }
            let scale = coupled.base().delta_cp().max(j.abs());
            for k in 0..200 {
                let d = j + 1e-11 * 1.07f64.powi(k);
                let exact = coupled.hertz_interference_solved(d).unwrap();
                let table = coupled.hertz_interference(d).unwrap();
                assert!(
                    (exact - table).abs() <= 1e-8 * (scale + (d - j)),
                    "w {w}, delta_max {d:e}: {table:e} vs {exact:e}"
                );
            }
        }
    }
    let sizes = AdhesionCoupled::new(ek(&pair), mk(&pair, 0.3))
        .unwrap()
        .table_sizes();
    assert!(
        sizes.iter().all(|&(_, n, dev)| n <= 4097 && dev <= 1e-8),
        "{sizes:?}"
    );
}

/// A deeper loading never lowers the pull-off, and the loading and the unloading meet at
/// the deepest point, for both base laws.
#[test]
fn deeper_loading_never_lowers_the_pull_off() {
    let pair = gold(0.25e9);
    let adhesion = mk(&pair, 0.3);
    let ek_c = AdhesionCoupled::new(ek(&pair), adhesion).unwrap();
    let ke_c = AdhesionCoupled::new(
        KogutEtsion::new(&pair, YieldModulus::Composite).unwrap(),
        adhesion,
    )
    .unwrap();
    let dcp = ek(&pair).delta_cp();
    for law in [
        Box::new(ElastoPlasticAsperity::new(ek_c, adhesion)) as Box<dyn AsperityModel>,
        Box::new(ElastoPlasticAsperity::new(ke_c, adhesion)),
    ] {
        let mut last = 0.0f64;
        for k in 0..40 {
            let d = 0.1 * dcp * 1.2f64.powi(k);
            let h = AsperityHistory { delta_max: d };
            let load = law
                .force(d, AsperityHistory::VIRGIN, Path::Approach)
                .unwrap();
            let unload = law.force(d, h, Path::Retract { from: d }).unwrap();
            assert!(
                (load - unload).abs() <= 1e-9 * load.abs().max(1e-9),
                "{d:e}: {load} {unload}"
            );
            let j = law.jumps(h).unwrap();
            let mut worst = 0.0f64;
            for i in 1..400 {
                let x = j.jump_out + (d - j.jump_out) * i as f64 / 400.0;
                worst = worst.min(law.force(x, h, Path::Retract { from: d }).unwrap());
            }
            assert!(
                -worst >= last * (1.0 - 1e-3),
                "delta_max {d:e}: pull-off {worst} after {last}"
            );
            last = last.max(-worst);
        }
    }
}

/// A plastically flattened JKR contact cannot pull harder than the flat punch of its
/// largest contact (Kendall 1971: sqrt(8 pi w E* a^3)), the bound Mesarovic & Johnson
/// (2000) find the unloading of an elastic-plastic adhesive sphere tends to.
#[test]
fn the_pull_off_stays_within_kendalls_flat_punch() {
    let pair = gold(0.25e9);
    let w = 0.3;
    let jkr = Jkr::new(JkrParams {
        k: pair.k(),
        work_of_adhesion: w,
    })
    .unwrap();
    let asperity = ElastoPlasticAsperity::new(AdhesionCoupled::new(ek(&pair), jkr).unwrap(), jkr);
    let dcp = ek(&pair).delta_cp();
    for omega in [0.5, 2.0, 10.0, 50.0, 110.0] {
        let d = omega * dcp;
        let h = AsperityHistory { delta_max: d };
        let a = asperity
            .contact_radius(d, h, Path::Retract { from: d })
            .unwrap();
        let kendall = (8.0 * std::f64::consts::PI * w * pair.e_star() * a.powi(3)).sqrt();
        let pull = asperity.pull_off(d).unwrap();
        assert!(
            -pull.force <= kendall,
            "omega {omega}: {} > {kendall}",
            -pull.force
        );
    }
}
