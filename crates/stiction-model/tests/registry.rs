//! The key registry is the enforced truth: for every key of every scene kind, each end of a
//! numeric domain is accepted just inside and refused just outside (naming the key), and a
//! key left out takes exactly the registry's default. The docs' table is the registry's
//! (`tests/domains.rs` at the root), so documented, enforced and defaulted agree.

use stiction_model::keys::{self, Default, Domain, Key, Kind};
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene;
use stiction_model::spec::{AsperitySpec, Spec, SurfaceSpec, SwitchSpec};
use stiction_model::ModelError;

/// A rough 64 x 64 height map at 25 nm (1.6 um scan), as a text file: the
/// `surface.topography` of the scenes whose topography options are probed.
fn height_map() -> &'static str {
    static PATH: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    PATH.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("stiction-registry-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("map.txt");
        let rows: Vec<String> = (0..64)
            .map(|j| {
                (0..64)
                    .map(|i| {
                        let (x, y) = (i as f64, j as f64);
                        let noise = ((i * 7919 + j * 104_729) % 97) as f64 / 97.0 - 0.5;
                        format!(
                            "{:.6}",
                            3.0 * (0.37 * x + 1.1 * y).sin()
                                + 2.0 * (0.23 * x - 0.71 * y).cos()
                                + noise
                        )
                    })
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .collect();
        std::fs::write(
            &p,
            format!(
                "# spacing = 25 nm\n# height_unit = nm\n{}\n",
                rows.join("\n")
            ),
        )
        .unwrap();
        p.display().to_string()
    })
}

/// A valid scene of `kind` on which `key` applies (the drive or counter it needs; for the
/// options of `surface.topography`, the file, analysed as sampled unless the key is the
/// cutoff).
fn base(kind: Kind, key: &str) -> Scene {
    let mut s = Scene::paper(kind);
    if key.starts_with("surface.topography") {
        s.set_text("surface.topography", &format!("{:?}", height_map()))
            .unwrap();
        if key != "surface.topography" && key != "surface.topography_cutoff" {
            s.set_number("surface.topography_cutoff", 0.0).unwrap();
        }
    }
    if key.starts_with("contact.counter_") {
        s.set_text("contact.counter", "material").unwrap();
        s.set_number("contact.counter_youngs_modulus", 168e9)
            .unwrap();
        s.set_number("contact.counter_poisson_ratio", 0.38).unwrap();
    }
    if key == "switch.k_s" || key == "switch.voltage" {
        s.remove("switch.impact_energy");
        s.set_number("switch.k_s", 8.44e9).unwrap();
    }
    if key.starts_with("dynamics.") {
        // a [dynamics] section: drive B, a mass (one of the two), dimples under a gas
        s.remove("switch.impact_energy");
        s.set_number("switch.k_s", 8.44e9).unwrap();
        s.set_number("switch.dimple_height", 0.3e-6).unwrap();
        s.set_number("switch.electrode_area", 1e-8).unwrap();
        if key != "dynamics.areal_mass" {
            s.set_number("dynamics.resonance_frequency", 93e3).unwrap();
        }
    }
    if key == "switch.spring_constant" {
        s.remove("switch.impact_energy");
        s.set_number("switch.electrode_area", 1e-8).unwrap();
        s.set_number("switch.spring_constant", 84.4).unwrap();
    }
    if kind == Kind::Surface && key == "surface.sigma_s" {
        // unload_from must lie within 20 sigma_s: leave it out while sigma_s goes to its ends
        s.remove("unload_from");
    }
    if key == "d_start" || key == "unload_from" {
        // 20 sigma_s = 2e-5 m: the relative rule meets the documented absolute ends
        s.set_number("surface.sigma_s", 1e-6).unwrap();
    }
    s
}

fn spec(kind: Kind, s: &Scene) -> Result<(), ModelError> {
    let r = LawRegistry::builtin();
    match kind {
        Kind::Asperity => AsperitySpec::new(s, &r).map(|_| ()),
        Kind::Surface => SurfaceSpec::new(s, &r).map(|_| ()),
        _ => SwitchSpec::new(s, &r).map(|_| ()),
    }
}

/// Just outside each end of a numeric domain (None where an end is unbounded).
fn outside(d: Domain) -> [Option<f64>; 2] {
    match d {
        Domain::Range {
            lo,
            hi,
            open_below,
            open_above,
        } => {
            let below = if open_below {
                lo
            } else if lo == 0.0 {
                -1e-300
            } else {
                lo - lo.abs() * 1e-9
            };
            let above = if open_above { hi } else { hi + hi.abs() * 1e-9 };
            [Some(below), Some(above)]
        }
        Domain::RangeOrInfinite { lo } => [Some(lo - lo.abs() * 1e-9), None],
        Domain::Count { lo, hi } => [(lo > 0).then_some(lo as f64 - 1.0), Some(hi as f64 + 1.0)],
        _ => [None, None],
    }
}

/// Just inside each end.
fn inside(d: Domain) -> [f64; 2] {
    match d {
        Domain::Range {
            lo,
            hi,
            open_below,
            open_above,
        } => [
            if open_below {
                if lo == 0.0 {
                    1e-300
                } else {
                    lo + lo.abs() * 1e-9
                }
            } else {
                lo
            },
            if open_above { hi - hi.abs() * 1e-9 } else { hi },
        ],
        Domain::RangeOrInfinite { lo } => [lo, f64::INFINITY],
        Domain::Count { lo, hi } => [lo as f64, hi as f64],
        _ => [f64::NAN, f64::NAN],
    }
}

/// Keys whose inside end another rule of the same scene refuses (said by the rule's own
/// message): the lower end of `points` where a kind needs curves; a dimple height at or
/// above the scene's gap d0 (2 um: the domain's upper end, 1 mm, is d0's own end); a
/// topography cutoff longer than half the map's scan.
fn inside_refused_by_another_rule(kind: Kind, k: &Key, v: f64) -> bool {
    (k.key == "points" && kind != Kind::Switch && v < 2.0)
        || (k.key == "switch.dimple_height" && v >= 2e-6)
        // a cutoff beyond half the scan of the map (0.8 um) leaves it no wavelength
        || (k.key == "surface.topography_cutoff" && v > 0.8e-6)
}

#[test]
fn every_numeric_domain_is_enforced_at_both_ends_for_every_kind() {
    let mut checked = 0;
    for kind in Kind::ALL {
        for k in keys::of(kind).filter(|k| k.domain.is_numeric()) {
            for bad in outside(k.domain).into_iter().flatten() {
                let mut s = base(kind, k.key);
                s.set_number(k.key, bad).unwrap();
                let e = spec(kind, &s).expect_err(&format!("{kind} {} = {bad:e}", k.key));
                assert!(
                    e.to_string().contains(k.key),
                    "{kind} {} = {bad:e}: {e}",
                    k.key
                );
                checked += 1;
            }
            for good in inside(k.domain) {
                let mut s = base(kind, k.key);
                if good.is_infinite() {
                    // a yield stress that never yields goes with the elastic law
                    s.set_text("contact.plasticity_law", "elastic").unwrap();
                }
                s.set_number(k.key, good).unwrap();
                if inside_refused_by_another_rule(kind, k, good) {
                    continue;
                }
                spec(kind, &s).unwrap_or_else(|e| panic!("{kind} {} = {good:e}: {e}", k.key));
                checked += 1;
            }
        }
    }
    assert!(checked > 100, "{checked}");
}

#[test]
fn a_key_left_out_takes_the_registry_default_for_every_kind() {
    let registry = LawRegistry::builtin();
    let mut checked = 0;
    for kind in Kind::ALL {
        for k in keys::of(kind) {
            // the paper's scene (with another material for the counter keys): the drive
            // keys are alternatives, each absent when another is given
            let mut s = if k.key.starts_with("contact.counter_")
                || k.key.starts_with("surface.topography")
                || k.key.starts_with("dynamics.")
            {
                base(kind, k.key)
            } else {
                Scene::paper(kind)
            };
            s.remove(k.key);
            if k.key == "dynamics.resonance_frequency" {
                // the electrode's mass is given one way or the other
                s.set_number("dynamics.areal_mass", 0.0246).unwrap();
            }
            let resolved = match Spec::new(&s, &registry) {
                Ok(spec) => spec.common().resolved().clone(),
                Err(e) => {
                    // a required key's absence is an error that names it
                    assert!(
                        matches!(k.default, Default::Required | Default::RequiredWhen(_)),
                        "{kind} {}: {e}",
                        k.key
                    );
                    assert!(e.to_string().contains(k.key), "{e}");
                    checked += 1;
                    continue;
                }
            };
            let got = lookup(&resolved, k.key);
            let expect: Option<toml::Value> = match k.default {
                Default::Number(x) => Some(toml::Value::Float(x)),
                Default::Count(n) => Some(toml::Value::Integer(n as i64)),
                Default::Word(w) => Some(toml::Value::String(w.into())),
                Default::Flag(b) => Some(toml::Value::Boolean(b)),
                Default::Triple(t) => Some(toml::Value::Array(
                    t.iter().map(|&x| toml::Value::Float(x)).collect(),
                )),
                Default::Key(other) => lookup(&resolved, other).cloned(),
                Default::Required | Default::RequiredWhen(_) => {
                    panic!("{kind} {}: required yet accepted absent", k.key)
                }
                Default::Absent => None,
                _ => panic!("a default kind this test does not know"),
            };
            match (&expect, k.domain) {
                (None, _) => {}
                // law tables resolve to their laws' parameter lists
                (_, Domain::LawTable) => {}
                (Some(v), _) => assert_eq!(got, Some(v), "{kind} {}", k.key),
            }
            checked += 1;
        }
    }
    assert!(checked > 60, "{checked}");
}

/// The value at `key` (`section.key`) of a resolved tree.
fn lookup<'a>(t: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let mut node = t;
    let parts: Vec<&str> = key.split('.').collect();
    for p in &parts[..parts.len() - 1] {
        node = node.get(*p)?.as_table()?;
    }
    node.get(parts[parts.len() - 1])
}

#[test]
fn the_law_parameter_defaults_are_the_laws_declared_ones() {
    // etsion_kadin's c1, c2 left out resolve to eq 13's paper constants
    let mut s = Scene::paper(Kind::Switch);
    s.remove("contact.effective_radius");
    let spec = SwitchSpec::new(&s, &LawRegistry::builtin()).unwrap();
    let p = spec.contact().plasticity().params();
    assert_eq!(p.triple("c1"), Some([0.22, 0.6242, 0.092]));
    assert_eq!(p.triple("c2"), Some([10.0, 10.0, 5.0]));
}
