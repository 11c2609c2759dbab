//! The SVG renders the same in rsvg and in ImageMagick's own renderer (MSVG, what most
//! users' `convert plot.svg plot.png` runs): no curve drawn as a filled polygon, no axis
//! label lost, no grid line drawn black. A structural check of every figure (cheap, always run) and a rasterised
//! comparison of a few (needs `rsvg-convert` and ImageMagick's `convert`; skipped with a
//! message when either is missing, a failure with `STICTION_REQUIRE_RASTERISERS=1`, as CI
//! sets it).

mod common;

use design_sweep::{run_map, Grid, Labels, Map, MapRequest};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::process::Command;
use stiction_model::keys::Kind;
use stiction_model::laws::LawRegistry;
use stiction_model::scene::Scene;
use stiction_model::spec::SwitchSpec;
use stiction_model::switch::{SwitchModel, SwitchResult};
use stiction_model::Silent;
use stiction_report::plot::map::map_svg;
use stiction_report::Plot;

fn switch_result() -> SwitchResult {
    let mut scene = Scene::paper(Kind::Switch);
    scene.set_text("accuracy", "fast").unwrap();
    let spec = SwitchSpec::new(&scene, &LawRegistry::builtin()).unwrap();
    SwitchModel::build(&spec).unwrap().run(&Silent).unwrap()
}

fn map_2d() -> Map {
    let request = MapRequest {
        scene: json!({"name": "test"}),
        grid: Grid::parse(&[
            "switch.k_s=3e2:3e4:log:9",
            "surface.sigma_s=1e-9:9e-8:log:7",
        ])
        .unwrap(),
        accuracy: "fast".into(),
        shard: None,
    };
    run_map(request, common::product, |_, _| {})
}

fn map_1d() -> Map {
    let request = MapRequest {
        scene: json!({"name": "test"}),
        grid: Grid::parse(&["switch.k_s=100:2000:lin:20"]).unwrap(),
        accuracy: "fast".into(),
        shard: None,
    };
    run_map(request, common::flaky, |_, _| {})
}

fn labels() -> Labels {
    Labels::new()
        .with_unit("switch.k_s", "Pa/m")
        .with_unit("surface.sigma_s", "m")
}

/// Every figure the structural test reads: (name, SVG).
fn figures() -> Vec<(&'static str, String)> {
    vec![
        ("switch.svg", switch_result().svg().unwrap()),
        ("map_2d.svg", map_svg(&map_2d(), &labels()).unwrap()),
        ("map_1d.svg", map_svg(&map_1d(), &labels()).unwrap()),
        (
            "banded.svg",
            common::against_cycle(12, true, Some((0.0, 1.0))),
        ),
    ]
}

#[test]
fn every_stroke_is_unfilled_and_every_rotation_is_about_the_origin() {
    for (name, svg) in figures() {
        let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
        let mut rotated = 0;
        for n in doc.descendants().filter(|n| n.is_element()) {
            let tag = n.tag_name().name();
            if matches!(tag, "polyline" | "path" | "line") {
                assert_eq!(
                    n.attribute("fill"),
                    if tag == "line" { None } else { Some("none") },
                    "{name}: a {tag} without fill=\"none\""
                );
            }
            // ImageMagick reads an opacity after a fill as the fill, and ignores it on lines
            // and polygons: every opacity is folded into the colours
            assert!(
                n.attribute("opacity").is_none(),
                "{name}: a {tag} with an opacity attribute"
            );
            if let Some(t) = n.attribute("transform") {
                // rotate(a, cx, cy) is lost by ImageMagick: only translate(..) rotate(a)
                let args = t.split("rotate(").nth(1).unwrap_or("");
                assert!(
                    !args.contains(','),
                    "{name}: text rotated about a point: {t}"
                );
                rotated += usize::from(t.contains("rotate("));
            }
        }
        assert!(rotated >= 1, "{name}: no rotated (vertical axis) label");
    }
}

/// An RGB picture.
struct Picture {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

impl Picture {
    /// A binary PPM (P6) or PGM (P5), 8 or 16 bits.
    fn parse(data: &[u8]) -> Picture {
        let mut fields = Vec::new();
        let mut at = 0;
        while fields.len() < 4 {
            while data[at].is_ascii_whitespace() {
                at += 1;
            }
            if data[at] == b'#' {
                while data[at] != b'\n' {
                    at += 1;
                }
                continue;
            }
            let start = at;
            while !data[at].is_ascii_whitespace() {
                at += 1;
            }
            fields.push(String::from_utf8_lossy(&data[start..at]).into_owned());
        }
        at += 1;
        let channels = match fields[0].as_str() {
            "P6" => 3,
            "P5" => 1,
            other => panic!("not a binary PPM/PGM: {other}"),
        };
        let (width, height): (usize, usize) =
            (fields[1].parse().unwrap(), fields[2].parse().unwrap());
        let max: usize = fields[3].parse().unwrap();
        let bytes = if max > 255 { 2 } else { 1 };
        let body = &data[at..];
        assert!(
            body.len() >= width * height * channels * bytes,
            "a PPM cut short"
        );
        let mut rgb = Vec::with_capacity(width * height * 3);
        for px in 0..width * height {
            for c in 0..3 {
                let k = (px * channels + c.min(channels - 1)) * bytes;
                let v = if bytes == 2 {
                    (usize::from(body[k]) << 8 | usize::from(body[k + 1])) * 255 / max
                } else {
                    usize::from(body[k]) * 255 / max
                };
                rgb.push(v as u8);
            }
        }
        Picture { width, height, rgb }
    }

    /// Whether the pixel is dark (luma below 110 of 255).
    fn dark(&self, x: usize, y: usize) -> bool {
        let k = 3 * (y * self.width + x);
        let (r, g, b) = (
            self.rgb[k] as f64,
            self.rgb[k + 1] as f64,
            self.rgb[k + 2] as f64,
        );
        0.299 * r + 0.587 * g + 0.114 * b < 110.0
    }

    /// The share of dark pixels in [x0, x1) x [y0, y1).
    fn dark_share(&self, (x0, x1): (usize, usize), (y0, y1): (usize, usize)) -> f64 {
        let (x1, y1) = (x1.min(self.width), y1.min(self.height));
        let mut n = 0usize;
        for y in y0..y1 {
            for x in x0..x1 {
                n += usize::from(self.dark(x, y));
            }
        }
        n as f64 / ((x1 - x0) * (y1 - y0)).max(1) as f64
    }
}

fn have(program: &str) -> bool {
    Command::new(program)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

fn convert_has_imagemagick() -> bool {
    Command::new("convert")
        .arg("-version")
        .output()
        .is_ok_and(|o| {
            o.status.success() && String::from_utf8_lossy(&o.stdout).contains("ImageMagick")
        })
}

fn run(cmd: &mut Command) -> Vec<u8> {
    let out = cmd.output().expect("the rasteriser runs");
    assert!(
        out.status.success(),
        "{cmd:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// The SVG rasterised by rsvg (decoded through ImageMagick) and by ImageMagick's own
/// renderer, on white.
fn rasterise(dir: &Path, name: &str, svg: &str) -> (Picture, Picture) {
    let file = dir.join(name);
    std::fs::write(&file, svg).unwrap();
    let png: PathBuf = dir.join(format!("{name}.rsvg.png"));
    run(Command::new("rsvg-convert")
        .args(["-b", "white", "-f", "png", "-o"])
        .arg(&png)
        .arg(&file));
    let rsvg = Picture::parse(&run(Command::new("convert")
        .arg(&png)
        .args(["-depth", "8", "ppm:-"])));
    let magick = Picture::parse(&run(Command::new("convert")
        .args(["-background", "white"])
        .arg(format!("msvg:{}", file.display()))
        .args(["-flatten", "-depth", "8", "ppm:-"])));
    (rsvg, magick)
}

#[test]
fn rsvg_and_imagemagick_draw_the_same_figures() {
    let required = std::env::var("STICTION_REQUIRE_RASTERISERS").is_ok_and(|v| v == "1");
    if !(have("rsvg-convert") && convert_has_imagemagick()) {
        assert!(
            !required,
            "STICTION_REQUIRE_RASTERISERS=1 but rsvg-convert or ImageMagick's convert is missing"
        );
        eprintln!(
            "SKIPPED: needs rsvg-convert (librsvg2-bin) and ImageMagick's convert (imagemagick)"
        );
        return;
    }
    let dir = std::env::temp_dir().join(format!("stiction-rasterise-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, svg) in figures() {
        let (a, b) = rasterise(&dir, name, &svg);
        assert_eq!(
            (a.width, a.height),
            (b.width, b.height),
            "{name}: sizes differ"
        );
        let whole = ((0, a.width), (0, a.height));
        let (da, db) = (
            a.dark_share(whole.0, whole.1),
            b.dark_share(whole.0, whole.1),
        );
        // curves are strokes: a filled curve darkens a large part of the picture
        assert!(
            da < 0.08 && db < 0.08,
            "{name}: dark share rsvg {da:.3}, ImageMagick {db:.3}"
        );
        // alike: ImageMagick's glyphs and lines are bolder, about twice the ink
        assert!(
            da.min(db) > 0.3 * da.max(db),
            "{name}: dark share rsvg {da:.3}, ImageMagick {db:.3}"
        );
        // the vertical axis label in the left margin: drawn by both (ImageMagick's glyphs
        // are bolder, and it turns rotated text the other way: the amount of ink only)
        let (la, lb) = (
            a.dark_share((0, 30), (0, a.height)),
            b.dark_share((0, 30), (0, b.height)),
        );
        assert!(
            la > 0.0005 && lb > 0.0005 && la.min(lb) > 0.2 * la.max(lb),
            "{name}: vertical labels' dark share rsvg {la:.4}, ImageMagick {lb:.4}"
        );
        // block by block (32 px): the two pictures agree where there is ink
        let block = 32;
        let (mut diff, mut n) = (0.0, 0usize);
        for by in (0..a.height).step_by(block) {
            for bx in (0..a.width).step_by(block) {
                let r = ((bx, bx + block), (by, by + block));
                diff += (a.dark_share(r.0, r.1) - b.dark_share(r.0, r.1)).abs();
                n += 1;
            }
        }
        let mean = diff / n as f64;
        assert!(mean < 0.02, "{name}: mean block difference {mean:.4}");
        eprintln!("{name}: dark share rsvg {da:.4}, ImageMagick {db:.4}, labels {la:.4}/{lb:.4}, blocks {mean:.4}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
