//! The switch in time (issue 44): the squeeze film against its series, the flight against
//! the closed-form work and an independent integration, the ledger, the tolerance, and the
//! reduction to eq 17 in vacuum.

use asperity_plastic::{ElastoPlasticAsperity, EtsionKadin, YieldModulus};
use contact_core::{paper, Material, Pair, Path, SurfaceLaw};
use gw_surface::{GreenwoodWilliamson, GwHistory, Quadrature, Roughness};
use maugis_kim::{DugdaleParams, MaugisKim};
use switch_1d::{end_of_impact, ImpactFilm, Precision, Switch, SwitchGeometry};
use switch_dynamics::{
    close, geometry_factor, release, DynamicsOptions, Plate, SqueezeFilm, REFERENCE_PRESSURE,
};

type Surface = GreenwoodWilliamson<ElastoPlasticAsperity<EtsionKadin, MaugisKim>>;

/// The paper's Ru surface (Table 1), two Ru films.
fn ru() -> Surface {
    let m = Material::new(paper::RU).unwrap();
    let pair = Pair::new(m, Some(m), paper::RADIUS).unwrap();
    let mk = MaugisKim::new(DugdaleParams::for_pair(
        &pair,
        paper::WORK_OF_ADHESION,
        paper::Z0,
    ))
    .unwrap();
    let ek = EtsionKadin::new(&pair, YieldModulus::AsPrinted).unwrap();
    GreenwoodWilliamson::new(
        ElastoPlasticAsperity::new(ek, mk),
        Roughness {
            sigma_s: paper::SIGMA_S,
            asperity_density: paper::ASPERITY_DENSITY,
        },
        Quadrature {
            rel_tol: 1e-9,
            ..Quadrature::default()
        },
    )
    .unwrap()
}

/// The paper's switch (Table 2) with dimples 0.3 um high on 20 % of the electrode, a
/// 20 N/m spring on (100 um)^2, 1.2 V_PI, a 2 um gold plate (38.6 g/m^2).
fn plate(squeeze: Option<SqueezeFilm>) -> Plate {
    let sw = Switch::new(SwitchGeometry {
        d0: paper::D0,
        t_d: paper::T_D,
        epsilon_r: paper::EPSILON_R,
        epsilon_0: paper::EPSILON_0,
    })
    .unwrap()
    .with_dimple_height(0.3e-6)
    .unwrap();
    let k_s = 20.0 / 1e-8;
    Plate {
        switch: sw,
        k_s,
        voltage: 1.2 * sw.pull_in_voltage(k_s),
        areal_mass: 19_300.0 * 2e-6,
        contact_area_fraction: 0.2,
        squeeze,
    }
}

fn air() -> SqueezeFilm {
    SqueezeFilm::new(100e-6, 100e-6, 1.85e-5, 68e-9, REFERENCE_PRESSURE).unwrap()
}

/// beta of Griffin et al. (1966) / Blech (1983): 0.4217 for a square, 1 for a long strip
/// (r -> 0: 1 - 192 zeta(5)(1 - 2^-5) r / pi^5 = 1 - 0.6302 r), monotone between.
#[test]
fn the_squeeze_factor_meets_its_series_limits() {
    assert!(
        (geometry_factor(1.0) - 0.4217).abs() < 5e-5,
        "{}",
        geometry_factor(1.0)
    );
    let r = 1e-3;
    // zeta(5) (1 - 2^-5) = 1.004523
    let strip = 1.0 - 192.0 * 1.036_927_755 * (1.0 - 1.0 / 32.0) * r / std::f64::consts::PI.powi(5);
    assert!(
        (geometry_factor(r) - strip).abs() < 1e-9,
        "{}",
        geometry_factor(r)
    );
    let mut last = 1.0;
    for k in 1..=20 {
        let b = geometry_factor(k as f64 / 20.0);
        assert!(b < last);
        last = b;
    }
    // Veijola's rarefaction at Kn = 1: mu / (1 + 9.638)
    let f = SqueezeFilm::new(1e-4, 1e-4, 1.85e-5, 68e-9, REFERENCE_PRESSURE).unwrap();
    assert!((f.effective_viscosity(68e-9) - 1.85e-5 / 10.638).abs() < 1e-12);
    // c'' = beta mu_eff W^2 / x^3
    let x = 0.3e-6;
    let c = geometry_factor(1.0) * f.effective_viscosity(x) * 1e-8 / x.powi(3);
    assert!((f.coefficient(x) / c - 1.0).abs() < 1e-14);
}

/// In vacuum the flight is conservative: the kinetic energy at the contact's reach is the
/// electrostatic work less the spring's, in closed form.
#[test]
fn the_vacuum_flight_meets_the_closed_form_work() {
    let gw = ru();
    let p = plate(None);
    let c = close(&gw, &gw.virgin(), &p, &DynamicsOptions::for_target(1e-6)).unwrap();
    let reach = c.impact.separation;
    let y = p.travel() - reach;
    let work = p.electrostatic_work(p.switch.d0() - y) - 0.5 * p.k_s * y * y;
    assert!(
        (c.impact.energy / work - 1.0).abs() < 1e-7,
        "{} vs {work}",
        c.impact.energy
    );
    assert!(c.ledger.residual.abs() < 1e-6, "{:?}", c.ledger);
}

/// With gas, against an independent integration: classical RK4 at a fixed step of 1e-5 of
/// the natural time, to the reach.
#[test]
fn the_flight_through_gas_meets_an_independent_integration() {
    let gw = ru();
    let p = plate(Some(air()));
    let c = close(&gw, &gw.virgin(), &p, &DynamicsOptions::for_target(1e-6)).unwrap();
    let target = p.travel() - c.impact.separation;
    let f = |y: f64, v: f64| {
        let x = p.switch.d0() - y;
        (p.electrostatic(x) - p.k_s * y - p.damping(x) * v) / p.areal_mass
    };
    let h = 1e-5 * p.natural_time();
    let (mut y, mut v, mut t) = (0.0f64, 0.0f64, 0.0f64);
    loop {
        let (k1y, k1v) = (v, f(y, v));
        let (k2y, k2v) = (v + 0.5 * h * k1v, f(y + 0.5 * h * k1y, v + 0.5 * h * k1v));
        let (k3y, k3v) = (v + 0.5 * h * k2v, f(y + 0.5 * h * k2y, v + 0.5 * h * k2v));
        let (k4y, k4v) = (v + h * k3v, f(y + h * k3y, v + h * k3v));
        let yn = y + h / 6.0 * (k1y + 2.0 * k2y + 2.0 * k3y + k4y);
        let vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if yn >= target {
            // linear in the last step to the crossing
            let a = (target - y) / (yn - y);
            t += a * h;
            v += a * (vn - v);
            break;
        }
        y = yn;
        v = vn;
        t += h;
    }
    assert!(
        (c.impact.flight_time / t - 1.0).abs() < 1e-5,
        "{} vs {t}",
        c.impact.flight_time
    );
    assert!(
        (c.impact.velocity / v - 1.0).abs() < 1e-4,
        "{} vs {v}",
        c.impact.velocity
    );
    // the gas took energy: less than the vacuum's
    let vac = close(
        &gw,
        &gw.virgin(),
        &plate(None),
        &DynamicsOptions::for_target(1e-6),
    )
    .unwrap();
    assert!(c.impact.energy < 0.95 * vac.impact.energy);
    assert!(
        c.ledger.gas > 0.0 && c.ledger.residual.abs() < 1e-6,
        "{:?}",
        c.ledger
    );
}

/// In vacuum without a bounce the first impact is eq 17's end of impact for the energy that
/// arrived: the kinetic energy at the reach plus the electrostatic and spring work done
/// while the contact decelerates the plate, per contact area (eq 17's film term is left
/// out of the dynamics: a film of zero thickness).
#[test]
fn in_vacuum_the_impact_ends_where_eq_17_says() {
    let gw = ru();
    let p = plate(None);
    let c = close(&gw, &gw.virgin(), &p, &DynamicsOptions::for_target(1e-8)).unwrap();
    let y = p.travel() - c.d_e;
    let arrived = p.electrostatic_work(p.switch.d0() - y) - 0.5 * p.k_s * y * y;
    let film = ImpactFilm {
        thickness: 1e-30,
        youngs_modulus: paper::RU.youngs_modulus,
    };
    let e = end_of_impact(
        &gw,
        &gw.virgin(),
        arrived / p.contact_area_fraction,
        film,
        Precision::default(),
    )
    .unwrap();
    assert!(
        (c.d_e - e.d_e).abs() < 1e-6 * paper::SIGMA_S,
        "{} vs {}",
        c.d_e,
        e.d_e
    );
    // the electrostatic and spring work during the contact adds to the kinetic energy
    // (on this dimpled switch about a quarter of it: theory 13.4)
    assert!(arrived > c.impact.energy);
}

/// The bounce count, the capture and the depth do not depend on the tolerance.
#[test]
fn the_result_does_not_depend_on_the_tolerance() {
    let gw = ru();
    for squeeze in [None, Some(air())] {
        let p = plate(squeeze);
        let runs: Vec<_> = [1e-7, 1e-9, 1e-11]
            .iter()
            .map(|&t| {
                close(
                    &gw,
                    &gw.virgin(),
                    &p,
                    &DynamicsOptions {
                        tolerance: t,
                        max_bounces: 50,
                        trace: false,
                    },
                )
                .unwrap()
            })
            .collect();
        for r in &runs[1..] {
            assert_eq!(r.bounces.len(), runs[0].bounces.len());
            assert!((r.d_e - runs[2].d_e).abs() < 1e-4 * paper::SIGMA_S);
        }
    }
}

/// The release with the voltage off, from rest where the contact pulls hardest (the
/// pull-out's separation): a spring far weaker than the pull-out (phi p_po / (K_s s) = 10)
/// leaves the plate held, one far stronger (ratio 0.1) opens it, in a time of order the
/// natural time. (From the capture under the voltage the compressed contact's elastic
/// energy is released with it and can throw the plate off a contact that holds
/// quasi-statically: theory 13.5.)
#[test]
fn the_release_holds_or_opens_by_the_pull_out() {
    let gw = ru();
    let p = plate(None);
    let c = close(&gw, &gw.virgin(), &p, &DynamicsOptions::for_target(1e-6)).unwrap();
    let u = switch_1d::unload(&gw, &c.history, c.deepest, 0, Precision::default()).unwrap();
    let spring = |ratio: f64| Plate {
        k_s: p.contact_area_fraction * u.pull_out_pressure / (ratio * p.travel()),
        ..p
    };
    let at = u.pull_out_separation;
    let held = release(&gw, &c.history, at, c.deepest, &spring(10.0), 1e-9).unwrap();
    assert!(!held.opens, "{held:?}");
    let opened = release(&gw, &c.history, at, c.deepest, &spring(0.1), 1e-9).unwrap();
    assert!(opened.opens, "{opened:?}");
    let t = opened.opening_time.unwrap();
    assert!(t > 0.0 && t < 10.0 * spring(0.1).natural_time());
    let _ = (GwHistory::VIRGIN, Path::Approach);
}
