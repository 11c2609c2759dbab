//! The user-defined law of `examples/custom_law.rs` works inside `ElastoPlasticAsperity`
//! and inside the rough surface, with no change to any crate.

#[path = "../examples/custom_law.rs"]
mod custom_law;

use std::f64::consts::PI;
use stiction::contact_core::{AsperityHistory, AsperityModel, Path, PlasticityLaw, SurfaceLaw};
use stiction::gw_surface::{GreenwoodWilliamson, Quadrature};

#[test]
fn custom_law_pull_off_is_dmt_on_the_residual_radius() {
    let asp = custom_law::ru_asperity(1e-9);
    for dmax in [17e-9, 34e-9] {
        let st = asp.plastic_state(AsperityHistory { delta_max: dmax });
        // DMT: the most tensile force is -2 pi w R at contact, with R_eff = R_res there
        let expect = -2.0 * PI * 1.0 * st.r_res;
        let got = custom_law::pull_off(&asp, dmax).unwrap();
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

#[test]
fn custom_law_drives_a_rough_surface() {
    let gw = GreenwoodWilliamson::new(
        custom_law::ru_asperity(1e-9),
        7.78e-9,
        1e13,
        Quadrature::default(),
    )
    .unwrap();
    let p = gw
        .pressure(3.0 * 7.78e-9, &gw.virgin(), Path::Approach)
        .unwrap();
    assert!(p.is_finite() && p != 0.0);
}
