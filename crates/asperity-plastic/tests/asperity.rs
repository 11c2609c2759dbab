//! Behaviour of the elasto-plastic adhesive asperity (paper section 2.2) with the
//! Maugis-Kim law on the Ru sphere of Table 1 against a rigid flat.

use asperity_plastic::{Elastic, ElastoPlasticAsperity, EtsionKadin, Reload, YieldModulus};
use contact_core::{
    paper, AdhesionLaw, AsperityHistory, AsperityModel, Material, Pair, Path, PlasticityLaw,
};
use maugis_kim::{DugdaleParams, MaugisKim};

/// Table 1 Ru on a rigid flat (Fig 2), eq 1 with E* (the E-reading is tested alongside
/// where it matters).
fn ru() -> (EtsionKadin, MaugisKim, Pair) {
    ru_with(YieldModulus::Composite)
}

fn ru_with(modulus: YieldModulus) -> (EtsionKadin, MaugisKim, Pair) {
    let m = Material::new(paper::RU).unwrap();
    let pair = Pair::new(m, None, paper::RADIUS).unwrap();
    let ek = EtsionKadin::new(&pair, modulus).unwrap();
    let mk = MaugisKim::new(DugdaleParams::for_pair(
        &pair,
        paper::WORK_OF_ADHESION,
        paper::Z0,
    ))
    .unwrap();
    (ek, mk, pair)
}

#[test]
fn below_yield_the_asperity_is_exactly_the_elastic_law() {
    let (ek, mk, _) = ru();
    let dcp = ek.delta_cp();
    let plastic = ElastoPlasticAsperity::new(ek, mk);
    let elastic = ElastoPlasticAsperity::new(Elastic::new(paper::RADIUS).unwrap(), mk);
    for delta in [-0.3e-9, -0.1e-9, 0.0, 0.2 * dcp, 0.9 * dcp, dcp] {
        for path in [Path::Approach, Path::Retract { from: dcp }] {
            let a = plastic.force(delta, AsperityHistory::VIRGIN, path).unwrap();
            let b = elastic.force(delta, AsperityHistory::VIRGIN, path).unwrap();
            let c = mk.force(paper::RADIUS, delta, path).unwrap();
            assert_eq!(a, b);
            assert_eq!(a, c);
        }
    }
}

#[test]
fn loading_and_unloading_meet_at_delta_max() {
    let (ek, mk, _) = ru();
    let asp = ElastoPlasticAsperity::new(ek, mk);
    for dmax in [17e-9, 34e-9, 51e-9] {
        let load = asp
            .force(dmax, AsperityHistory::VIRGIN, Path::Approach)
            .unwrap();
        let unload = asp
            .force(dmax, AsperityHistory::VIRGIN, Path::Retract { from: dmax })
            .unwrap();
        assert!(
            (load - unload).abs() <= 1e-12 * load.abs(),
            "{load} vs {unload}"
        );
    }
}

#[test]
fn reloading_up_to_delta_max_retraces_the_unloading_curve() {
    let (ek, mk, _) = ru();
    let asp = ElastoPlasticAsperity::new(ek, mk);
    let dmax = 34e-9;
    let hist = asp.load(AsperityHistory::VIRGIN, dmax);
    let st = asp.plastic_state(hist);
    for i in 0..=50 {
        // from just past jump-in (delta_res - z0) to delta_max
        let delta = st.delta_res - 0.1e-9 + (dmax - st.delta_res + 0.1e-9) * i as f64 / 50.0;
        let un = asp
            .force(delta, hist, Path::Retract { from: dmax })
            .unwrap();
        let re = asp.force(delta, hist, Path::Approach).unwrap();
        assert_eq!(un, re, "delta {delta}");
    }
    // and loading further yields again: the loading force beyond delta_max is the virgin one
    let beyond = 40e-9;
    assert_eq!(
        asp.force(beyond, hist, Path::Approach).unwrap(),
        asp.force(beyond, AsperityHistory::VIRGIN, Path::Approach)
            .unwrap()
    );
}

#[test]
fn force_is_continuous_where_the_effective_radius_changes() {
    let (ek, mk, _) = ru();
    let asp = ElastoPlasticAsperity::new(ek, mk);
    for dmax in [17e-9, 51e-9] {
        let hist = AsperityHistory { delta_max: dmax };
        let st = asp.plastic_state(hist);
        let path = Path::Retract { from: dmax };
        // at delta_res R_eff switches from R_res to eq 12
        let f0 = asp.force(st.delta_res, hist, path).unwrap();
        for eps in [1e-15, 1e-13, 1e-12] {
            let fp = asp.force(st.delta_res + eps, hist, path).unwrap();
            let fm = asp.force(st.delta_res - eps, hist, path).unwrap();
            let scale = std::f64::consts::PI * 1.0 * st.r_res;
            assert!(
                (fp - f0).abs() < 1e-2 * scale && (fm - f0).abs() < 1e-2 * scale,
                "{fm} {f0} {fp}"
            );
        }
        // and along the virgin loading curve through yield onset
        let dcp = ek.delta_cp();
        let a = asp
            .force(dcp * (1.0 - 1e-9), AsperityHistory::VIRGIN, Path::Approach)
            .unwrap();
        let b = asp
            .force(dcp * (1.0 + 1e-9), AsperityHistory::VIRGIN, Path::Approach)
            .unwrap();
        assert!((a - b).abs() < 1e-6 * a.abs());
    }
}

#[test]
fn plastic_unloading_is_more_adhesive_than_elastic() {
    // the paper's central claim for one asperity: the flattened tip adheres more
    let (ek, mk, _) = ru();
    let plastic = ElastoPlasticAsperity::new(ek, mk);
    let elastic = ElastoPlasticAsperity::new(Elastic::new(paper::RADIUS).unwrap(), mk);
    let pull_off = |asp: &dyn AsperityModel, dmax: f64| {
        let hist = AsperityHistory { delta_max: dmax };
        let j = asp.jumps(hist).unwrap();
        let mut min: f64 = 0.0;
        for i in 0..=4000 {
            let d = j.jump_out + (dmax - j.jump_out) * i as f64 / 4000.0;
            min = min.min(asp.force(d, hist, Path::Retract { from: dmax }).unwrap());
        }
        min
    };
    let fe = pull_off(&elastic, 34e-9);
    let fp = pull_off(&plastic, 34e-9);
    assert!(fp < fe && fe < 0.0, "plastic {fp} elastic {fe}");
    // the crate's own search finds the same minimum, never a shallower one
    let p = plastic.pull_off(34e-9).unwrap();
    let e = elastic.pull_off(34e-9).unwrap();
    assert!(
        p.force <= fp && p.force > fp * (1.0 + 1e-3),
        "{p:?} vs dense {fp}"
    );
    assert!(
        e.force <= fe && e.force > fe * (1.0 + 1e-3),
        "{e:?} vs dense {fe}"
    );
}

/// Pins a property of the paper's eq 12 as printed (theory 2.5): for delta_max/delta_CP
/// above about 15.8 the unloading force just after delta_max rises *above* the loading
/// force at delta_max, which a finite-element unloading does not do. Hertz estimate (by
/// hand, theory 2.5): +5.8 % at omega = 22.9 and +16.0 % at omega = 34.4, none below 15.8.
/// A corrected effective-radius law makes this test fail, as it should.
#[test]
fn eq_12_as_printed_overshoots_the_loading_force_beyond_omega_16() {
    let (ek, mk, _) = ru();
    let asp = ElastoPlasticAsperity::new(ek, mk);
    let dcp = ek.delta_cp();
    let overshoot = |omega: f64| {
        let dmax = omega * dcp;
        let hist = AsperityHistory { delta_max: dmax };
        let load = asp
            .force(dmax, AsperityHistory::VIRGIN, Path::Approach)
            .unwrap();
        let st = asp.plastic_state(hist);
        let peak = (0..=2000)
            .map(|i| st.delta_res + (dmax - st.delta_res) * i as f64 / 2000.0)
            .map(|d| asp.force(d, hist, Path::Retract { from: dmax }).unwrap())
            .fold(f64::NEG_INFINITY, f64::max);
        peak / load - 1.0
    };
    let (o23, o34) = (overshoot(22.92), overshoot(34.39));
    assert!((0.04..0.08).contains(&o23), "omega 22.9: {o23}");
    assert!((0.13..0.19).contains(&o34), "omega 34.4: {o34}");
    for omega in [2.0, 5.0, 10.0, 15.0] {
        assert!(
            overshoot(omega) < 1e-9,
            "omega {omega}: {}",
            overshoot(omega)
        );
    }
}

#[test]
fn pull_off_is_found_whatever_the_reading_of_eq_1_and_grows_with_delta_max() {
    for modulus in [YieldModulus::Composite, YieldModulus::AsPrinted] {
        let (ek, mk, _) = ru_with(modulus);
        let asp = ElastoPlasticAsperity::new(ek, mk);
        let mut last = 0.0;
        for dmax in paper::FIG2_DELTA_MAX {
            let p = asp.pull_off(dmax).unwrap();
            // a flattened tip adheres like a sphere of radius R_res near the JKR end:
            // between 1.2 and 1.6 pi w R_res
            let r_res = asp.plastic_state(AsperityHistory { delta_max: dmax }).r_res;
            let ratio = -p.force / (std::f64::consts::PI * paper::WORK_OF_ADHESION * r_res);
            assert!((1.2..1.6).contains(&ratio), "{modulus:?} {dmax}: {ratio}");
            assert!(p.force < last, "{modulus:?}: pull-off grows with delta_max");
            last = p.force;
        }
    }
}

/// Work of loading from out of contact to `dmax`, on the virgin curve or on the reload
/// curve of an asperity that has already been to `dmax` (midpoint rule, 20000 steps).
fn works(asp: &impl AsperityModel, dmax: f64) -> (f64, f64) {
    let (lo, n) = (-0.5e-9, 20000);
    let h = (dmax - lo) / n as f64;
    let hist = AsperityHistory { delta_max: dmax };
    (0..n).fold((0.0, 0.0), |(v, r), i| {
        let d = lo + (i as f64 + 0.5) * h;
        (
            v + h * asp
                .force(d, AsperityHistory::VIRGIN, Path::Approach)
                .unwrap(),
            r + h * asp.force(d, hist, Path::Approach).unwrap(),
        )
    })
}

/// Records a property of the paper's fits, not of this code: just past yield onset eq 5
/// grows the radius linearly in (omega - 1) while eq 4 lowers the tip only quadratically,
/// so reloading does more work than virgin loading (an energy gain no dissipative material
/// has). Past omega ~ 1.4 the height loss wins. If a corrected law replaces eqs 4-5 this
/// test says so.
#[test]
fn fits_near_yield_onset_make_reloading_stiffer_than_virgin_loading() {
    // Hertz isolates the plasticity fits from adhesion (which, on reloading a larger
    // R_res, adds attraction and can hide the effect for small delta_CP)
    let (ek, _, pair) = ru();
    let asp = ElastoPlasticAsperity::new(ek, maugis_kim::Hertz::new(pair.k()).unwrap());
    let dcp = ek.delta_cp();
    let (v, r) = works(&asp, 1.1 * dcp);
    assert!(r > v * 1.005, "omega 1.1: reload {r} virgin {v}");
    let (v, r) = works(&asp, 3.0 * dcp);
    assert!(r < v * 0.9, "omega 3: reload {r} virgin {v}");
}

/// `kink(i)` is the i-th entry of `kinks` for every pairing of the built-in plasticity
/// laws (elastic, Etsion-Kadin, Kogut-Etsion, whose kink list has an entry of its own) and
/// adhesion laws (Maugis-Kim with its junction kind, DMT with its Hertz onset), at
/// histories below, at and far beyond yield, and past the end of the list.
#[test]
fn one_kink_is_the_entry_of_the_list() {
    use asperity_plastic::KogutEtsion;
    use maugis_kim::Dmt;
    let (ek, mk, pair) = ru();
    let ke = KogutEtsion::new(&pair, YieldModulus::Composite).unwrap();
    let dmt = Dmt::new(DugdaleParams::for_pair(
        &pair,
        paper::WORK_OF_ADHESION,
        paper::Z0,
    ))
    .unwrap();
    let elastic = Elastic::new(paper::RADIUS).unwrap();
    let dcp = ek.delta_cp();
    fn check(asp: &impl AsperityModel, dcp: f64, name: &str) -> usize {
        let mut present = 0;
        for omega in [0.0, 0.5, 1.0, 1.0 + 1e-9, 3.0, 6.0, 40.0, 110.0, 1e4] {
            let h = AsperityHistory {
                delta_max: omega * dcp,
            };
            let list = asp.kinks(h).unwrap();
            for i in 0..list.len() + 2 {
                let one = asp.kink(i, h).unwrap();
                assert_eq!(
                    one,
                    list.get(i).copied().flatten(),
                    "{name}: kink {i} at omega {omega}"
                );
                present += usize::from(one.is_some());
            }
        }
        present
    }
    let n = [
        check(&ElastoPlasticAsperity::new(ek, mk), dcp, "EK + MK"),
        check(&ElastoPlasticAsperity::new(ke, mk), dcp, "KE + MK"),
        check(&ElastoPlasticAsperity::new(ek, dmt), dcp, "EK + DMT"),
        check(&ElastoPlasticAsperity::new(ke, dmt), dcp, "KE + DMT"),
        check(
            &ElastoPlasticAsperity::new(elastic, mk),
            dcp,
            "elastic + MK",
        ),
        check(
            &ElastoPlasticAsperity::new(ke, dmt).with_reload(Reload::Bounded),
            dcp,
            "KE + DMT, bounded reload",
        ),
    ];
    // the comparison is not vacuous: every plastic pairing has kinks at some history (the
    // elastic asperity has none here: no delta_res, and Maugis-Kim's junction is a kink
    // only at lambda <= lambda_c, below the paper's lambda)
    assert!(n[..4].iter().all(|&k| k > 0), "{n:?}");
    // under the bounded reload the cap (the virgin loading force) bends at delta_CP and
    // jumps at Kogut-Etsion's omega = 6: both are declared below delta_max, and only there
    let bounded = ElastoPlasticAsperity::new(ke, dmt).with_reload(Reload::Bounded);
    let breaks = bounded.plastic_breaks();
    assert!(breaks.len() >= 2, "{breaks:?}");
    for omega in [3.0, 40.0] {
        let h = AsperityHistory {
            delta_max: omega * ke.delta_cp(),
        };
        let list = bounded.kinks(h).unwrap();
        for &b in &breaks {
            assert_eq!(
                list.contains(&Some(b)),
                b < h.delta_max,
                "break {b:e} at omega {omega}: {list:?}"
            );
        }
    }
}

/// The tension bound of a plastically deformed asperity holds on every path that does not
/// load it further (retraction from delta_max and any reload up to it), for both
/// plasticity laws, both readings of eq 1 and interferences up to the fits' end and
/// beyond; and it is the adhesion law's bound on the larger end of eq 12's radius, so it
/// follows R_res as the tip flattens.
#[test]
fn no_unloading_asperity_pulls_harder_than_its_bound() {
    use asperity_plastic::KogutEtsion;
    for modulus in [YieldModulus::Composite, YieldModulus::AsPrinted] {
        let (ek, mk, pair) = ru_with(modulus);
        let ke = KogutEtsion::new(&pair, modulus).unwrap();
        let dcp = ek.delta_cp();
        let laws: [(&str, Box<dyn AsperityModel>); 2] = [
            ("etsion_kadin", Box::new(ElastoPlasticAsperity::new(ek, mk))),
            ("kogut_etsion", Box::new(ElastoPlasticAsperity::new(ke, mk))),
        ];
        for (name, asp) in &laws {
            for omega in [0.5, 1.0, 1.5, 4.0, 16.0, 60.0, 110.0, 300.0] {
                let dmax = omega * dcp;
                let hist = AsperityHistory { delta_max: dmax };
                let bound = asp.max_tension(hist).unwrap();
                let r_res = asp.plastic_state(hist).r_res;
                // never below the adhesion law's bound on R_res itself
                assert!(bound >= mk.max_tension(r_res).unwrap(), "{name} {omega}");
                let j = asp.jumps(hist).unwrap();
                let mut least = f64::INFINITY;
                for k in 0..=2000 {
                    let d = j.jump_out + (dmax - j.jump_out) * k as f64 / 2000.0;
                    let back = asp.force(d, hist, Path::Retract { from: dmax }).unwrap();
                    let again = asp.force(d, hist, Path::Approach).unwrap();
                    least = least.min(back).min(again);
                }
                assert!(
                    -least <= bound,
                    "{name} {modulus:?} omega {omega}: {least} beyond {bound}"
                );
                // the bound is the DMT limit 2 pi w R_eff: at least 3/4 of it is reached
                // (the pull-off lies between 1.5 and 2 pi w R_eff)
                assert!(-least >= 0.7 * bound, "{name} {omega}: {least} vs {bound}");
            }
        }
    }
}
