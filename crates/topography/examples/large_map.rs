//! docs/performance.md (topography): a large synthetic map written as an instrument would.
//!
//! `cargo run --release -p topography --example large_map -- OUT_DIR [N]` synthesises a
//! self-affine surface of N x N points (default 1024; H = 0.8, rms 8 nm, 10 nm pixels) and
//! writes it as `OUT_DIR/map.x3p` (ISO 25178-72, 64-bit floats) and `OUT_DIR/map.sur`
//! (Digital Surf, 32-bit integers, by the tests' independent writer), to time
//! `stiction topography` on a map of that size.

use std::io::Write;
use std::path::PathBuf;

use topography::{
    io::write_path, synthesize, Amplitudes, Format, Normalization, SelfAffinePsd, SynthesisOptions,
};

#[path = "../tests/encoders/mod.rs"]
mod encoders;

/// zlib-compresses `data` (the encoders' compressed `.sur`).
#[allow(dead_code)]
fn zlib(data: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
    e.write_all(data).unwrap();
    e.finish().unwrap()
}

/// A zip archive of `entries`, deflated (the encoders' `.plux`).
#[allow(dead_code)]
fn zip_archive(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let mut w = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let opt = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (name, data) in entries {
        w.start_file(*name, opt).unwrap();
        w.write_all(data).unwrap();
    }
    w.finish().unwrap().into_inner()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().unwrap_or_else(|| "large-map".into()));
    let n: usize = match args.next() {
        Some(a) => a.parse()?,
        None => 1024,
    };
    std::fs::create_dir_all(&out)?;
    let dx = 10e-9;
    let psd = SelfAffinePsd::new(
        0.8,
        n as f64 * dx / 2.0,
        None,
        4.0 * dx,
        Normalization::RmsHeight(8e-9),
    )?;
    let o = SynthesisOptions {
        nx: n,
        ny: n,
        dx,
        dy: dx,
        seed: 2026,
        amplitudes: Amplitudes::Gaussian,
    };
    let map = synthesize(&psd, &o)?;
    write_path(out.join("map.x3p"), &map, Format::X3p)?;
    let g = encoders::Grid {
        nx: n,
        ny: n,
        dx,
        dy: dx,
        z: map.heights(),
    };
    let sur = encoders::sur(&[encoders::SurObject {
        name: "Height",
        kind: 2,
        grid: &g,
        bits: 32,
        compressed: false,
    }]);
    std::fs::write(out.join("map.sur"), sur)?;
    println!(
        "wrote {} and {} ({n} x {n} points)",
        out.join("map.x3p").display(),
        out.join("map.sur").display()
    );
    Ok(())
}
