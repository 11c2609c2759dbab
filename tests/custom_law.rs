//! The user-defined law of `examples/custom_law.rs` works inside `ElastoPlasticAsperity`
//! and inside the rough surface, with no change to any crate, and the surface meets its
//! tolerance although the law declares none of its kinks.

#[path = "../examples/custom_law.rs"]
mod custom_law;

use std::f64::consts::PI;
use stiction::asperity_plastic::{Elastic, ElastoPlasticAsperity};
use stiction::contact_core::numeric::GaussLegendre;
use stiction::contact_core::{
    paper, AsperityHistory, AsperityModel, Path, PlasticityLaw, SurfaceLaw,
};
use stiction::gw_surface::{GreenwoodWilliamson, Quadrature, Roughness};

#[test]
fn custom_law_pull_off_is_dmt_on_the_residual_radius() {
    let asp = custom_law::ru_asperity(1e-9);
    for dmax in [17e-9, 34e-9] {
        let st = asp.plastic_state(AsperityHistory { delta_max: dmax });
        // DMT: the most tensile force is -2 pi w R at contact, with R_eff = R_res there
        let expect = -2.0 * PI * 1.0 * st.r_res;
        let got = asp.pull_off(dmax).unwrap().force;
        assert!((got / expect - 1.0).abs() < 1e-9, "{got} vs {expect}");
    }
}

#[test]
fn custom_law_range_changes_where_the_asperity_lets_go() {
    let short = custom_law::ru_asperity(0.5e-9);
    let long = custom_law::ru_asperity(2e-9);
    let h = AsperityHistory { delta_max: 20e-9 };
    let st = short.plasticity.state(20e-9);
    let probe = st.delta_res - 1e-9;
    assert_eq!(
        short
            .force(probe, h, Path::Retract { from: 20e-9 })
            .unwrap(),
        0.0
    );
    assert!(long.force(probe, h, Path::Retract { from: 20e-9 }).unwrap() < 0.0);
}

fn phi(u: f64) -> f64 {
    (-0.5 * u * u).exp() / (2.0 * PI).sqrt()
}

/// A rough surface of elastic asperities with the custom law against an independent
/// integral: composite 40-point Gauss-Legendre split at the law's two kinks (contact,
/// delta = 0, and the end of the range, delta = -range), which the law never declared.
#[test]
fn custom_law_drives_a_rough_surface_to_its_tolerance_without_declared_kinks() {
    let (sigma, n, range) = (paper::SIGMA_S, paper::ASPERITY_DENSITY, 1e-9);
    let law = custom_law::ru_asperity(range).adhesion;
    let asperity = ElastoPlasticAsperity::new(Elastic::new(paper::RADIUS).unwrap(), law);
    let rough = Roughness {
        sigma_s: sigma,
        asperity_density: n,
    };
    for rel in [1e-6, 1e-10] {
        let gw = GreenwoodWilliamson::new(
            asperity,
            rough,
            Quadrature {
                rel_tol: rel,
                ..Default::default()
            },
        )
        .unwrap();
        for t in [-1.0, 0.3, 1.7, 3.2] {
            let d = t * sigma;
            let got = gw
                .pressure_integral(d, &gw.virgin(), Path::Approach)
                .unwrap();
            let gl = GaussLegendre::new(40);
            let f = |u: f64| {
                let delta = u * sigma - d;
                stiction::contact_core::AdhesionLaw::force(
                    &law,
                    paper::RADIUS,
                    delta,
                    Path::Approach,
                )
                .unwrap()
                    * phi(u)
            };
            let cuts = [(d - range) / sigma, d / sigma, 9.0];
            let mut expect = 0.0;
            for w in cuts.windows(2) {
                for k in 0..200 {
                    let (a, b) = (
                        w[0] + (w[1] - w[0]) * k as f64 / 200.0,
                        w[0] + (w[1] - w[0]) * (k + 1) as f64 / 200.0,
                    );
                    expect += gl.integrate(f, a, b);
                }
            }
            expect *= n;
            let err = (got.value - expect).abs();
            assert!(
                err <= got.error.max(1e-12 * expect.abs()),
                "rel {rel} t {t}: {} vs {expect} (estimate {:e})",
                got.value,
                got.error
            );
            assert!(
                err <= 10.0 * rel * expect.abs().max(1e-300),
                "rel {rel} t {t}: error {err:e}"
            );
        }
    }
}
