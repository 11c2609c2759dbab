//! A scene whose surface comes from a measured height map (`[surface] topography`, issue
//! 45 item 4) and scenes merged from several files: the map's GW parameters set the keys
//! the scene leaves out, a key the scene gives wins with a note naming both values, the
//! echo holds the file, the route and the band, relative paths are the scene file's, and
//! errors name the key and the file that gave it.

use std::path::{Path, PathBuf};
use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::scene::{self, Scene};
use stiction_model::spec::{self, SurfaceSpec, SwitchSpec};
use stiction_model::topography::{
    self as topo, io, synthesize, Amplitudes, Format, Normalization, SelfAffinePsd,
    SynthesisOptions, TopographyRequest,
};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "stiction-scene-topography-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A self-affine map, 128 x 128 at 20 nm (2.56 um), rms 6 nm, written as x3p in `dir`.
fn write_map(dir: &Path, name: &str) -> PathBuf {
    let psd =
        SelfAffinePsd::new(0.8, 1.28e-6, None, 80e-9, Normalization::RmsHeight(6e-9)).unwrap();
    let grid = SynthesisOptions {
        nx: 128,
        ny: 128,
        dx: 20e-9,
        dy: 20e-9,
        seed: 45,
        amplitudes: Amplitudes::Gaussian,
    };
    let map = synthesize(&psd, &grid).unwrap();
    let p = dir.join(name);
    io::write_path(&p, &map, Format::X3p).unwrap();
    p
}

/// The paper's switch scene without the three keys a topography sets, with `extra` lines
/// in `[surface]`, written as `scene.toml` in `dir`.
fn switch_scene(dir: &Path, extra: &str, keep: &[&str]) -> PathBuf {
    let mut text = String::new();
    for line in scene::PAPER_SWITCH.lines() {
        let body = line.split('#').next().unwrap_or("").trim();
        let drop = ["radius =", "sigma_s =", "asperity_density ="]
            .iter()
            .any(|k| body.starts_with(k) && !keep.iter().any(|kk| body.starts_with(kk)));
        if drop {
            continue;
        }
        text.push_str(line);
        text.push('\n');
        if line.starts_with("[surface]") {
            text.push_str(extra);
            text.push('\n');
        }
    }
    let p = dir.join("scene.toml");
    std::fs::write(&p, text).unwrap();
    p
}

fn registry() -> LawRegistry {
    LawRegistry::builtin()
}

fn resolved<'a>(s: &'a SwitchSpec, key: &str) -> &'a toml::Value {
    let (section, leaf) = key.split_once('.').unwrap();
    &s.common().resolved()[section][leaf]
}

#[test]
fn a_switch_scene_takes_its_roughness_and_radius_from_a_map_beside_it() {
    let d = dir("plain");
    write_map(&d, "afm.x3p");
    let p = switch_scene(&d, "topography = \"afm.x3p\"", &[]);
    // run from another folder: the path is the scene file's
    let s = SwitchSpec::new(&Scene::read(&p).unwrap(), &registry()).unwrap();
    let want = topo::scene_surface(&d.join("afm.x3p"), &TopographyRequest::default()).unwrap();
    assert_eq!(want.route, topo::Route::Summits);
    assert_eq!(s.roughness().sigma_s(), want.gw.sigma_s);
    assert_eq!(s.roughness().asperity_density(), want.gw.asperity_density);
    assert_eq!(s.contact().radius(), want.gw.radius);
    // the same numbers as `stiction topography` (summit route, no cutoff)
    let run = topo::run(&d.join("afm.x3p"), &TopographyRequest::default()).unwrap();
    assert_eq!(run.report.summits.as_ref().unwrap().gw, want.gw);
    // the echo: the file, the route, the band (0: the map as sampled, as no contact radius
    // was given) and the values
    assert_eq!(
        resolved(&s, "surface.topography").as_str(),
        Some(d.join("afm.x3p").display().to_string().as_str())
    );
    assert_eq!(
        resolved(&s, "surface.topography_route").as_str(),
        Some("summits")
    );
    assert_eq!(
        resolved(&s, "surface.topography_cutoff").as_float(),
        Some(0.0)
    );
    assert_eq!(
        resolved(&s, "surface.topography_undefined").as_str(),
        Some("refuse")
    );
    assert_eq!(
        resolved(&s, "surface.sigma_s").as_float(),
        Some(want.gw.sigma_s)
    );
    assert_eq!(
        resolved(&s, "contact.radius").as_float(),
        Some(want.gw.radius)
    );
    assert!(s.common().notes().is_empty());
    // the echo runs as the scene it came from
    let echo = Scene::from_tree("echo", s.common().resolved().clone());
    let again = SwitchSpec::new(&echo, &registry()).unwrap();
    assert_eq!(again.roughness(), s.roughness());
    assert_eq!(again.contact().radius(), s.contact().radius());
    assert!(
        again.common().notes().is_empty(),
        "{:?}",
        again.common().notes()
    );
    // the spectral route
    let p = switch_scene(
        &d,
        "topography = \"afm.x3p\"\ntopography_route = \"spectral\"",
        &[],
    );
    let s = SwitchSpec::new(&Scene::read(&p).unwrap(), &registry()).unwrap();
    assert_eq!(s.roughness().sigma_s(), run.report.spectral.gw.sigma_s);
    assert_eq!(s.contact().radius(), run.report.spectral.gw.radius);
}

#[test]
fn keys_the_scene_gives_win_with_a_note_naming_both_values() {
    let d = dir("override");
    write_map(&d, "afm.x3p");
    let p = switch_scene(
        &d,
        "topography = \"afm.x3p\"\nsigma_s = 5e-9",
        &["radius ="],
    );
    let scene = Scene::read(&p).unwrap();
    let s = SwitchSpec::new(&scene, &registry()).unwrap();
    assert_eq!(s.roughness().sigma_s(), 5e-9);
    assert_eq!(s.contact().radius(), 4e-6);
    // contact.radius given: the band is the contact's, 4 sqrt(R sigma_s)
    let w = resolved(&s, "surface.topography_cutoff")
        .as_float()
        .unwrap();
    let req = TopographyRequest {
        contact_radius: Some(4e-6),
        ..TopographyRequest::default()
    };
    let want = topo::scene_surface(&d.join("afm.x3p"), &req).unwrap();
    assert_eq!(Some(w), want.cutoff.wavelength);
    assert!(w > 0.0 && want.cutoff.applied);
    assert_eq!(s.roughness().asperity_density(), want.gw.asperity_density);
    let notes = s.common().notes();
    assert_eq!(notes.len(), 2, "{notes:?}");
    for (n, key, given, map) in [
        (&notes[0], "surface.sigma_s", "5e-9", want.gw.sigma_s),
        (&notes[1], "contact.radius", "4e-6", want.gw.radius),
    ] {
        assert_eq!(n.code, topo::TOPOGRAPHY_VALUE_OVERRIDDEN);
        assert!(!n.breaks_validity);
        assert!(
            n.message.contains(key)
                && n.message.contains(given)
                && n.message.contains(&format!("{map:.4e}"))
                && n.message.contains("afm.x3p")
                && n.message.contains("scene.toml"),
            "{}",
            n.message
        );
    }
    // the front ends' early look gives the same notes
    assert_eq!(&spec::topography_notes(&scene), notes);
    // a cutoff given wins over the contact's; 0 is the map as sampled
    let mut e = scene.clone();
    e.set_number("surface.topography_cutoff", 0.0).unwrap();
    let s0 = SwitchSpec::new(&e, &registry()).unwrap();
    let plain = topo::scene_surface(&d.join("afm.x3p"), &TopographyRequest::default()).unwrap();
    assert_eq!(s0.roughness().asperity_density(), plain.gw.asperity_density);
    // a longer cutoff, fewer asperities
    e.set_number("surface.topography_cutoff", 0.4e-6).unwrap();
    let s1 = SwitchSpec::new(&e, &registry()).unwrap();
    assert!(s1.roughness().asperity_density() < s0.roughness().asperity_density());
}

#[test]
fn a_surface_scene_takes_a_map_too_and_options_without_a_map_are_refused() {
    let d = dir("surface");
    let map = write_map(&d, "afm.x3p");
    let mut s = Scene::paper(Kind::Surface);
    s.remove("surface.sigma_s");
    s.remove("unload_from");
    s.set_text(
        "surface.topography",
        &format!("{:?}", map.display().to_string()),
    )
    .unwrap();
    let spec = SurfaceSpec::new(&s, &registry()).unwrap();
    assert!(spec.roughness().sigma_s() > 1e-9 && spec.roughness().sigma_s() < 2e-8);
    // an option without the file
    let mut s = Scene::paper(Kind::Switch);
    s.set_text("surface.topography_route", "spectral").unwrap();
    let e = SwitchSpec::new(&s, &registry()).unwrap_err().to_string();
    assert!(
        e.contains("surface.topography_route") && e.contains("given with surface.topography"),
        "{e}"
    );
    // an option outside its domain is refused as such
    let mut s = Scene::paper(Kind::Switch);
    s.set_text("surface.topography_detrend", "poly:9").unwrap();
    let e = SwitchSpec::new(&s, &registry()).unwrap_err().to_string();
    assert!(
        e.contains("surface.topography_detrend") && e.contains("poly:6"),
        "{e}"
    );
    // not a key of an asperity scene
    let mut s = Scene::paper(Kind::Asperity);
    s.set_text("surface.topography", "afm.x3p").unwrap();
    let e = stiction_model::spec::AsperitySpec::new(&s, &registry())
        .unwrap_err()
        .to_string();
    assert!(e.contains("unknown key `surface`"), "{e}");
}

#[test]
fn errors_name_the_key_the_scene_file_and_the_map() {
    let d = dir("errors");
    // a map that is not there
    let p = switch_scene(&d, "topography = \"missing.x3p\"", &[]);
    let e = SwitchSpec::new(&Scene::read(&p).unwrap(), &registry())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("scene.toml")
            && e.contains("`surface.topography`")
            && e.contains("missing.x3p")
            && e.contains("(line "),
        "{e}"
    );
    // a map with a hole: refused by default, naming the key that fills it
    let rows: Vec<String> = (0..16)
        .map(|j| {
            (0..16)
                .map(|i| {
                    if (i, j) == (7, 8) {
                        "NaN".to_string()
                    } else {
                        format!("{}", ((i * 7 + j * 13 + i * j) % 11) as f64 * 0.8)
                    }
                })
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    std::fs::write(
        d.join("hole.txt"),
        format!(
            "# spacing = 20 nm\n# height_unit = nm\n{}\n",
            rows.join("\n")
        ),
    )
    .unwrap();
    let p = switch_scene(&d, "topography = \"hole.txt\"", &[]);
    let e = SwitchSpec::new(&Scene::read(&p).unwrap(), &registry())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("1 of 256 heights are undefined")
            && e.contains("surface.topography_undefined = \"fill\"")
            && !e.contains("--undefined"),
        "{e}"
    );
    let p = switch_scene(
        &d,
        "topography = \"hole.txt\"\ntopography_undefined = \"fill\"\ntopography_channel = 0\ntopography_cutoff = 0.0",
        &[],
    );
    let s = SwitchSpec::new(&Scene::read(&p).unwrap(), &registry()).unwrap();
    assert_eq!(
        resolved(&s, "surface.topography_channel").as_integer(),
        Some(0)
    );
    // a cutoff the map cannot take names the cutoff key
    let p = switch_scene(
        &d,
        "topography = \"hole.txt\"\ntopography_undefined = \"fill\"\ntopography_cutoff = 1e-6",
        &[],
    );
    let e = SwitchSpec::new(&Scene::read(&p).unwrap(), &registry())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`surface.topography_cutoff` = 1e-6")
            && e.contains("half the shorter scan side"),
        "{e}"
    );
    // the contact's cutoff on a map too small for it names the cutoff and the radius
    let p = switch_scene(
        &d,
        "topography = \"hole.txt\"\ntopography_undefined = \"fill\"",
        &["radius ="],
    );
    let e = SwitchSpec::new(&Scene::read(&p).unwrap(), &registry())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("surface.topography_cutoff") && e.contains("contact.radius = R = 4e-6"),
        "{e}"
    );
    // a map whose radius lies outside contact.radius's domain (femtometre heights over
    // micrometre pixels): named, with what to do
    let flat: String = std::fs::read_to_string(d.join("hole.txt"))
        .unwrap()
        .replace("NaN", "1")
        .replace("# spacing = 20 nm", "# spacing = 1000 nm")
        .replace("# height_unit = nm", "# height_unit = 1e-15");
    std::fs::write(d.join("smooth.txt"), flat).unwrap();
    let p = switch_scene(&d, "topography = \"smooth.txt\"", &[]);
    let e = SwitchSpec::new(&Scene::read(&p).unwrap(), &registry())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`surface.topography`")
            && e.contains("smooth.txt")
            && e.contains("lies in the key's domain")
            && e.contains("in the scene, or choose another band"),
        "{e}"
    );
    eprintln!("{e}");
}

#[test]
fn merged_scenes_take_the_later_value_and_name_the_file_of_each_key() {
    let d = dir("merge");
    let a = d.join("a");
    let b = d.join("b");
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    std::fs::write(a.join("switch.toml"), scene::PAPER_SWITCH).unwrap();
    write_map(&b, "afm.x3p");
    // a fragment beside its map: a relative path is the fragment's
    std::fs::write(
        b.join("surface.toml"),
        "[surface]\nsigma_s = 6e-9\ntopography = \"afm.x3p\"\ntopography_cutoff = 0.0\n\n[switch]\nd0 = 3e-6\n",
    )
    .unwrap();
    let s = Scene::read_merged(
        &[a.join("switch.toml"), b.join("surface.toml")],
        Kind::Switch,
    )
    .unwrap();
    assert!(s.file().contains("switch.toml + ") && s.file().ends_with("surface.toml"));
    assert_eq!(s.get("switch.d0"), Some(&toml::Value::Float(3e-6)));
    assert_eq!(s.get("switch.t_d"), Some(&toml::Value::Float(0.15e-6)));
    assert!(s.file_of("switch.d0").ends_with("surface.toml"));
    assert!(s.file_of("switch.t_d").ends_with("switch.toml"));
    assert_eq!(s.dir_of("surface.topography"), Some(b.as_path()));
    assert_eq!(s.line_of("switch.d0"), Some(7));
    let spec = SwitchSpec::new(&s, &registry()).unwrap();
    assert_eq!(spec.switch().d0(), 3e-6);
    assert_eq!(spec.roughness().sigma_s(), 6e-9);
    // explicit keys of either file win over the map: sigma_s (b) and radius (a)
    assert_eq!(spec.contact().radius(), 4e-6);
    let plain = topo::scene_surface(
        &b.join("afm.x3p"),
        &TopographyRequest {
            cutoff: Some(0.0),
            ..TopographyRequest::default()
        },
    )
    .unwrap();
    assert_eq!(
        spec.roughness().asperity_density(),
        1e13,
        "switch.toml gives it"
    );
    assert_eq!(
        spec.common().notes().len(),
        3,
        "{:?}",
        spec.common().notes()
    );
    assert!(spec.common().notes()[0].message.contains("surface.toml"));
    assert!(spec.common().notes()[1].message.contains("switch.toml"));
    assert!(plain.gw.sigma_s > 0.0);
    // an error names the file that gave the key, with its line
    std::fs::write(b.join("bad.toml"), "[switch]\n\nd0 = -1.0\n").unwrap();
    let s = Scene::read_merged(&[a.join("switch.toml"), b.join("bad.toml")], Kind::Switch).unwrap();
    let e = SwitchSpec::new(&s, &registry()).unwrap_err().to_string();
    assert!(
        e.contains("bad.toml: invalid `switch.d0` = -1e0 (line 3)"),
        "{e}"
    );
    let e = {
        let mut s = s.clone();
        s.set_number("switch.d0", 2e-6).unwrap();
        s.set_number("switch.t_d", -1.0).unwrap();
        SwitchSpec::new(&s, &registry()).unwrap_err().to_string()
    };
    // an edited key is no file's: the merged scene's name
    assert!(
        e.starts_with(&format!("{}: invalid `switch.t_d`", s.file())),
        "{e}"
    );
    // no files: the paper's scene
    assert!(Scene::read_merged(&[], Kind::Switch).unwrap().is_paper());
}

#[test]
fn a_relative_map_set_by_an_edit_is_the_working_directorys() {
    let d = dir("edit");
    let p = switch_scene(&d, "", &["radius =", "sigma_s =", "asperity_density ="]);
    let mut s = Scene::read(&p).unwrap();
    assert_eq!(s.dir_of("switch.d0"), Some(d.as_path()));
    s.set_text("surface.topography", "afm.x3p").unwrap();
    assert_eq!(s.dir_of("surface.topography"), None);
    assert_eq!(s.dir_of("switch.d0"), Some(d.as_path()));
}

#[test]
fn the_scene_keys_name_every_map_format() {
    let names: Vec<&str> = Format::ALL.iter().map(|f| f.name()).collect();
    assert_eq!(names, stiction_model::keys::TOPOGRAPHY_FORMATS);
}
