//! Writers of the instruments' formats, for the reader tests: each follows the published
//! layout its reader cites, with its own byte offsets and constants (nothing is shared with
//! the readers, so a reader that misplaces a field fails its round trip).
//!
//! Every writer takes a [`Grid`]: heights in metres, row-major (x fastest, row 0 at y = 0),
//! NaN for a point the instrument did not measure (written as the format's marker).

//!
//! The compressors come from the test that includes this module (`super::zlib` for a
//! compressed `.sur`, `super::zip_archive` for a `.plux`): the crate's own tests use flate2
//! and zip, a test without those crates (the CLI's) gives its own.

#![allow(dead_code)]

use super::{zip_archive, zlib};

/// A map to write: `nx` x `ny` heights `z` (m, NaN = undefined), spacings `dx`, `dy` (m).
pub struct Grid<'a> {
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
    pub z: &'a [f64],
}

impl Grid<'_> {
    fn max_abs(&self) -> f64 {
        self.z
            .iter()
            .filter(|v| v.is_finite())
            .fold(0.0f64, |m, v| m.max(v.abs()))
            .max(1e-30)
    }
    fn at(&self, i: usize, j: usize) -> f64 {
        self.z[j * self.nx + i]
    }
}

fn put_u16_le(o: &mut [u8], at: usize, v: u16) {
    o[at..at + 2].copy_from_slice(&v.to_le_bytes());
}
fn put_i16_le(o: &mut [u8], at: usize, v: i16) {
    o[at..at + 2].copy_from_slice(&v.to_le_bytes());
}
fn put_u32_le(o: &mut [u8], at: usize, v: u32) {
    o[at..at + 4].copy_from_slice(&v.to_le_bytes());
}
fn put_i32_le(o: &mut [u8], at: usize, v: i32) {
    o[at..at + 4].copy_from_slice(&v.to_le_bytes());
}
fn put_f32_le(o: &mut [u8], at: usize, v: f32) {
    o[at..at + 4].copy_from_slice(&v.to_le_bytes());
}
fn put_f64_le(o: &mut [u8], at: usize, v: f64) {
    o[at..at + 8].copy_from_slice(&v.to_le_bytes());
}
fn put_str(o: &mut [u8], at: usize, len: usize, s: &[u8]) {
    let n = s.len().min(len);
    o[at..at + n].copy_from_slice(&s[..n]);
}

// ---------------------------------------------------------------------------------------
// Nanoscope (S. Manne's descriptions; Command Reference Manual B.6.3)

/// One image list of a Nanoscope file.
pub struct NsImage {
    /// The quoted name in `\@2:Image Data`.
    pub name: &'static str,
    /// `\Line Direction`.
    pub direction: &'static str,
    /// The soft scale of `\@2:Z scale` (`Sens. Zsens` for heights), or None (volts).
    pub soft: Option<&'static str>,
    /// Multiplies the grid's heights for this channel.
    pub factor: f64,
}

/// The quantum (nm per LSB) a Nanoscope writer uses for heights of `max_nm`.
pub fn nanoscope_quantum(max_nm: f64, bpp: u32) -> f64 {
    max_nm / (0.9 * 2f64.powi(8 * bpp as i32 - 1))
}

/// A binary Nanoscope file (version 9.3 header for 4-byte data, 5.12 for 2-byte) with the
/// given image lists; `Sens. Zsens` = 20 nm/V; rows stored bottom up.
pub fn nanoscope(g: &Grid, bpp: u32, images: &[NsImage]) -> Vec<u8> {
    let crlf = "\r\n";
    let sens = 20.0; // nm/V
    let max_nm = g.max_abs() * 1e9 * images.iter().fold(1.0f64, |m, i| m.max(i.factor.abs()));
    let q = nanoscope_quantum(max_nm, bpp); // nm per LSB
    let hard = q * 2f64.powi(8 * bpp as i32) / sens; // V over the full integer range
    let (sx, sy) = (g.nx as f64 * g.dx * 1e6, g.ny as f64 * g.dy * 1e6);
    let n = g.nx * g.ny;
    let header_len = 16384usize;
    let mut h = String::new();
    let version = if bpp == 4 { "0x09300201" } else { "0x05120130" };
    h += &format!("\\*File list{crlf}\\Version: {version}{crlf}\\Date: 10:27:26 AM Fri Oct 17 2014{crlf}\\Start context: OL2{crlf}\\Data length: {header_len}{crlf}");
    h += &format!("\\*Scanner list{crlf}\\Scanner type: Dimension{crlf}\\@Sens. Zsens: V {sens} nm/V{crlf}\\@Sens. Amplitude: V 1.000000{crlf}");
    h += &format!(
        "\\*Ciao scan list{crlf}\\Scan Size: {sx} {sy} ~m{crlf}\\Samps/line: {}{crlf}\\Lines: {}{crlf}\\Aspect Ratio: 1:1{crlf}",
        g.nx, g.ny
    );
    for (k, img) in images.iter().enumerate() {
        let off = header_len + k * n * bpp as usize;
        h += &format!("\\*Ciao image list{crlf}\\Data offset: {off}{crlf}\\Data length: {}{crlf}\\Bytes/pixel: {bpp}{crlf}", n * bpp as usize);
        h += &format!("\\Samps/line: {}{crlf}\\Number of lines: {}{crlf}\\Aspect Ratio: 1:1{crlf}\\Line Direction: {}{crlf}", g.nx, g.ny, img.direction);
        h += &format!("\\Scan Size: {sx} {sy} ~m{crlf}");
        h += &format!(
            "\\@2:Image Data: S [{}] \"{}\"{crlf}",
            img.name.replace(' ', ""),
            img.name
        );
        match img.soft {
            Some(s) => h += &format!("\\@2:Z scale: V [{s}] (0.0003750000 V/LSB) {hard} V{crlf}"),
            None => h += &format!("\\@2:Z scale: V (0.0003750000 V/LSB) {hard} V{crlf}"),
        }
        h += &format!("\\@Z magnify: C [2:Z scale] 0.25{crlf}\\@2:Z offset: V [Sens. Zsens] (0.0003750000 V/LSB) 0 V{crlf}");
    }
    h += &format!("\\*File list end{crlf}");
    let mut out = h.into_bytes();
    out.push(0x1a);
    assert!(out.len() <= header_len);
    out.resize(header_len, 0);
    for img in images {
        for s in 0..g.ny {
            let j = g.ny - 1 - s; // bottom line first
            for i in 0..g.nx {
                let raw = (g.at(i, j) * img.factor * 1e9 / q).round();
                if bpp == 4 {
                    out.extend_from_slice(&(raw as i32).to_le_bytes());
                } else {
                    out.extend_from_slice(&(raw as i16).to_le_bytes());
                }
            }
        }
    }
    out
}

// ---------------------------------------------------------------------------------------
// Wyko OPD (Gwyddion opdfile.c, SurfaceTopography OPD.py)

/// An OPD file: a `RAW_DATA` float array (heights in wavelengths x Mult), an `Image` byte
/// array, Wavelength (nm), Mult, Aspect, Pixel_size (mm), a Title. NaN -> 1e38.
pub fn opd(g: &Grid, wavelength_nm: f32, mult: i16) -> Vec<u8> {
    let n = g.nx * g.ny;
    let mut raw = Vec::new();
    raw.extend_from_slice(&(g.nx as u16).to_le_bytes());
    raw.extend_from_slice(&(g.ny as u16).to_le_bytes());
    raw.extend_from_slice(&4u16.to_le_bytes());
    let mut img = Vec::new();
    img.extend_from_slice(&(g.nx as u16).to_le_bytes());
    img.extend_from_slice(&(g.ny as u16).to_le_bytes());
    img.extend_from_slice(&1u16.to_le_bytes());
    for i in 0..g.nx {
        for jj in 0..g.ny {
            let j = g.ny - 1 - jj; // each column from the top row down
            let v = g.at(i, j);
            let w = if v.is_finite() {
                (v * 1e9 * f64::from(mult) / f64::from(wavelength_nm)) as f32
            } else {
                1e38f32
            };
            raw.extend_from_slice(&w.to_le_bytes());
            img.push(((i + jj) % 256) as u8);
        }
    }
    assert_eq!(raw.len(), 6 + 4 * n);
    let blocks: Vec<(&str, u16, Vec<u8>)> = vec![
        ("Title", 5, b"synthetic\0\0\0".to_vec()),
        ("RAW_DATA", 3, raw),
        ("Empty", 7, Vec::new()),
        ("Image", 3, img),
        ("Wavelength", 7, wavelength_nm.to_le_bytes().to_vec()),
        ("Mult", 6, mult.to_le_bytes().to_vec()),
        ("Aspect", 7, ((g.dy / g.dx) as f32).to_le_bytes().to_vec()),
        (
            "Pixel_size",
            7,
            ((g.dx * 1e3) as f32).to_le_bytes().to_vec(),
        ),
    ];
    let entries = blocks.len() + 1;
    let mut out = vec![1u8, 0];
    let mut entry = |name: &str, ty: u16, size: u32, flags: u16| {
        let mut e = [0u8; 24];
        e[..name.len()].copy_from_slice(name.as_bytes());
        e[16..18].copy_from_slice(&ty.to_le_bytes());
        e[18..22].copy_from_slice(&size.to_le_bytes());
        e[22..24].copy_from_slice(&flags.to_le_bytes());
        out.extend_from_slice(&e);
    };
    entry("Directory", 1, (24 * entries) as u32, 0xffff);
    for (name, ty, data) in &blocks {
        entry(name, *ty, data.len() as u32, 0);
    }
    for (_, _, data) in blocks {
        out.extend_from_slice(&data);
    }
    out
}

// ---------------------------------------------------------------------------------------
// Zygo MetroPro (MetroPro Reference Guide OMP-0347)

/// The MetroPro phase quantum (m per count) for the writer's constants.
pub const MP_WAVELENGTH: f32 = 632.8e-9;
pub const MP_SCALE: f32 = 0.5;
pub const MP_OBLIQUITY: f32 = 1.0;
pub fn metropro_quantum(phase_res: i16) -> f64 {
    let r = [4096.0, 32768.0, 131072.0][phase_res as usize];
    f64::from(MP_SCALE) * f64::from(MP_OBLIQUITY) * f64::from(MP_WAVELENGTH) / r
}

/// A MetroPro file of header format `fmt` (1, 2, 3) with one intensity bucket and the
/// phase data (requires dx = dy); NaN -> the invalid phase 2147483647.
pub fn metropro(g: &Grid, fmt: u16, phase_res: i16, sign: bool) -> Vec<u8> {
    let magic: u32 = [0x881B_036F, 0x881B_0370, 0x881B_0371][fmt as usize - 1];
    let hsize: usize = if fmt == 3 { 4096 } else { 834 };
    let mut h = vec![0u8; hsize];
    let be16 = |h: &mut Vec<u8>, at: usize, v: u16| h[at..at + 2].copy_from_slice(&v.to_be_bytes());
    let be32 = |h: &mut Vec<u8>, at: usize, v: u32| h[at..at + 4].copy_from_slice(&v.to_be_bytes());
    let bef = |h: &mut Vec<u8>, at: usize, v: f32| h[at..at + 4].copy_from_slice(&v.to_be_bytes());
    be32(&mut h, 0, magic);
    be16(&mut h, 4, fmt);
    be32(&mut h, 6, hsize as u32);
    put_str(&mut h, 12, 30, b"Thu Jan  1 00:00:00 2015");
    be16(&mut h, 52, g.nx as u16); // ac_width
    be16(&mut h, 54, g.ny as u16); // ac_height
    be16(&mut h, 56, 1); // ac_n_buckets
    be16(&mut h, 58, 4095); // ac_range
    be32(&mut h, 60, (2 * g.nx * g.ny) as u32); // ac_n_bytes
    be16(&mut h, 68, g.nx as u16); // cn_width
    be16(&mut h, 70, g.ny as u16); // cn_height
    be32(&mut h, 72, (4 * g.nx * g.ny) as u32); // cn_n_bytes
    bef(&mut h, 164, MP_SCALE);
    bef(&mut h, 168, MP_WAVELENGTH);
    bef(&mut h, 172, 0.3); // numerical aperture
    bef(&mut h, 176, MP_OBLIQUITY);
    bef(&mut h, 180, 10.0); // magnification
    bef(&mut h, 184, g.dx as f32); // lateral resolution, m
    be16(&mut h, 218, phase_res as u16);
    be16(&mut h, 232, u16::from(sign));
    be16(&mut h, 234, 640);
    be16(&mut h, 236, 480);
    let q = metropro_quantum(phase_res) * if sign { -1.0 } else { 1.0 };
    for j in 0..g.ny {
        for i in 0..g.nx {
            h.extend_from_slice(&(((i * 7 + j) % 4000) as u16).to_be_bytes());
        }
    }
    for &v in g.z {
        let raw: i32 = if v.is_finite() {
            (v / q).round() as i32
        } else {
            i32::MAX
        };
        h.extend_from_slice(&raw.to_be_bytes());
    }
    h
}

// ---------------------------------------------------------------------------------------
// Digital Surf (MountainsMap SDK layout, as Gwyddion surffile.c / RosettaSciIO / surfalize)

/// One object of a `.sur` file.
pub struct SurObject<'a> {
    pub name: &'a str,
    pub kind: i16,
    pub grid: &'a Grid<'a>,
    pub bits: i16,
    pub compressed: bool,
}

/// The quantum (m per count) of a `.sur` writer for the grid.
pub fn sur_quantum(g: &Grid, bits: i16) -> f64 {
    // the stored values are the heights less the 1 nm z offset
    (g.max_abs() + 1e-9) / (0.9 * 2f64.powi(i32::from(bits) - 1))
}

/// The whole file: objects one after the other, each with a 512-byte header, a comment,
/// no private zone, and its data (zlib-compressed in one stream when asked). Spacings in um,
/// heights in nm, z offset 1 nm; NaN -> zmin - 2 with the non-measured flag.
pub fn sur(objects: &[SurObject]) -> Vec<u8> {
    let mut out = Vec::new();
    for o in objects {
        let g = o.grid;
        let q = sur_quantum(g, o.bits);
        let offset_m = 1e-9;
        let mut h = vec![0u8; 512];
        put_str(
            &mut h,
            0,
            12,
            if o.compressed {
                b"DSCOMPRESSED"
            } else {
                b"DIGITAL SURF"
            },
        );
        put_i16_le(&mut h, 12, 0); // PC format
        put_u16_le(&mut h, 14, objects.len() as u16);
        put_i16_le(&mut h, 16, 1); // version
        put_i16_le(&mut h, 18, o.kind);
        put_str(&mut h, 20, 30, o.name.as_bytes());
        put_str(&mut h, 50, 30, b"tests");
        let special = g.z.iter().any(|v| !v.is_finite());
        put_i16_le(&mut h, 86, i16::from(special));
        put_i16_le(&mut h, 88, 1); // absolute
        put_i16_le(&mut h, 98, o.bits);
        let zmin: i32 = if o.bits == 16 {
            i32::from(i16::MIN) + 2
        } else {
            i32::MIN + 2
        };
        put_i32_le(&mut h, 100, zmin);
        put_i32_le(
            &mut h,
            104,
            if o.bits == 16 {
                i32::from(i16::MAX)
            } else {
                i32::MAX
            },
        );
        put_i32_le(&mut h, 108, g.nx as i32);
        put_i32_le(&mut h, 112, g.ny as i32);
        put_i32_le(&mut h, 116, (g.nx * g.ny) as i32);
        put_f32_le(&mut h, 120, (g.dx * 1e6) as f32);
        put_f32_le(&mut h, 124, (g.dy * 1e6) as f32);
        put_f32_le(&mut h, 128, (q * 1e9) as f32);
        put_str(&mut h, 132, 16, b"X");
        put_str(&mut h, 148, 16, b"Y");
        put_str(&mut h, 164, 16, b"Z");
        put_str(&mut h, 180, 16, b"\xb5m"); // Latin-1 micro sign
        put_str(&mut h, 196, 16, b"\xb5m");
        put_str(&mut h, 212, 16, b"nm");
        put_str(&mut h, 228, 16, b"\xb5m");
        put_str(&mut h, 244, 16, b"\xb5m");
        put_str(&mut h, 260, 16, b"nm");
        put_f32_le(&mut h, 276, 1.0);
        put_f32_le(&mut h, 280, 1.0);
        put_f32_le(&mut h, 284, 1.0);
        let comment = b"$_tests\n$Writer = encoders.rs\n";
        put_i16_le(&mut h, 334, comment.len() as i16);
        put_i16_le(&mut h, 336, 0);
        put_str(&mut h, 338, 128, b"client zone");
        put_f32_le(&mut h, 474, (offset_m * 1e9) as f32);
        // the z quantum as stored (f32), so the expected heights can be recomputed
        let dz = f64::from((q * 1e9) as f32) * 1e-9;
        let mut data = Vec::new();
        for &v in g.z {
            let raw: i64 = if v.is_finite() {
                ((v - offset_m) / dz).round() as i64
            } else {
                i64::from(zmin) - 2
            };
            if o.bits == 16 {
                data.extend_from_slice(&(raw as i16).to_le_bytes());
            } else {
                data.extend_from_slice(&(raw as i32).to_le_bytes());
            }
        }
        if o.compressed {
            let zipped = zlib(&data);
            let mut block = Vec::new();
            block.extend_from_slice(&1u32.to_le_bytes());
            block.extend_from_slice(&(data.len() as u32).to_le_bytes());
            block.extend_from_slice(&(zipped.len() as u32).to_le_bytes());
            block.extend_from_slice(&zipped);
            put_u32_le(&mut h, 324, block.len() as u32);
            data = block;
        }
        out.extend_from_slice(&h);
        out.extend_from_slice(comment);
        out.extend_from_slice(&data);
    }
    out
}

/// The height a `.sur` object stores for `v` (the writer's rounding).
pub fn sur_expected(g: &Grid, bits: i16, v: f64) -> f64 {
    let dz = f64::from((sur_quantum(g, bits) * 1e9) as f32) * 1e-9;
    let off = f64::from((1e-9f64 * 1e9) as f32) * 1e-9;
    ((v - 1e-9) / dz).round() * dz + off
}

// ---------------------------------------------------------------------------------------
// Sensofar PLu (Gwyddion sensofar.c, SurfaceTopography PLU.py) and PLUx

/// A PLu 2006 topography: 500-byte header, one layer of f32 um heights, min and max.
/// NaN -> 1000001.
pub fn plu(g: &Grid, kind: u32) -> Vec<u8> {
    let mut h = vec![0u8; 500];
    put_str(&mut h, 0, 128, b"Tue May 12 10:31:46 2015");
    put_u32_le(&mut h, 128, 1_431_426_706);
    put_str(&mut h, 132, 256, b"written by the reader tests");
    put_u32_le(&mut h, 388, g.ny as u32);
    put_u32_le(&mut h, 392, g.nx as u32);
    put_u32_le(&mut h, 396, 1);
    put_f32_le(&mut h, 400, 1.0); // dy_multip
    put_f32_le(&mut h, 404, (g.dx * 1e6) as f32);
    put_f32_le(&mut h, 408, (g.dy * 1e6) as f32);
    put_u32_le(&mut h, 428, kind);
    put_u32_le(&mut h, 432, 0); // algorithm
    put_u32_le(&mut h, 456, g.nx as u32);
    put_u32_le(&mut h, 460, g.ny as u32);
    put_f64_le(&mut h, 468, 0.1);
    h[489] = 1; // layers
    h[490] = 255; // format version 2006
    put_u32_le(&mut h, 496, 1);
    h.extend_from_slice(&(g.ny as u32).to_le_bytes());
    h.extend_from_slice(&(g.nx as u32).to_le_bytes());
    for &v in g.z {
        let w = if v.is_finite() {
            (v * 1e6) as f32
        } else {
            1_000_001.0
        };
        h.extend_from_slice(&w.to_le_bytes());
    }
    h.extend_from_slice(&(-1.0f32).to_le_bytes());
    h.extend_from_slice(&1.0f32.to_le_bytes());
    h
}

/// A PLUx archive: index.xml and LAYER_0.raw (f32 um, NaN for undefined).
pub fn plux(g: &Grid) -> Vec<u8> {
    let xml = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<xml><GENERAL><DATE>12/05/2015 10:31:46</DATE>\
         <IMAGE_SIZE_X>{}</IMAGE_SIZE_X><IMAGE_SIZE_Y>{}</IMAGE_SIZE_Y><FOV_X>{}</FOV_X><FOV_Y>{}</FOV_Y></GENERAL>\
         <INFO><ITEM_0><NAME>Device</NAME><VALUE>S neox</VALUE></ITEM_0></INFO>\
         <LAYER_0><FILENAME_Z>LAYER_0.raw</FILENAME_Z></LAYER_0></xml>\n",
        g.nx,
        g.ny,
        g.dx * 1e6,
        g.dy * 1e6
    );
    let mut raw = Vec::new();
    for &v in g.z {
        raw.extend_from_slice(&((v * 1e6) as f32).to_le_bytes());
    }
    zip_archive(&[
        ("index.xml", xml.as_bytes()),
        ("recipe.txt", b"<xml/>".as_slice()),
        ("LAYER_0.raw", &raw),
    ])
}

// ---------------------------------------------------------------------------------------
// Keyence VK4 (Gwyddion keyence.c, SurfaceTopography VK.py)

/// A VK4 file with a 32-bit height image and an 8-bit light image; `z_pm` picometres per
/// digit; heights stored from the minimum (unsigned). Spacings are whole picometres.
pub fn vk4(g: &Grid, z_pm: u32) -> Vec<u8> {
    let mut out = vec![0u8; 12 + 72];
    put_str(&mut out, 0, 4, b"VK4_");
    put_u32_le(&mut out, 4, 0x0103_0000); // dll version
    let mut cond = vec![0u8; 512];
    put_u32_le(&mut cond, 0, 512);
    put_u32_le(&mut cond, 4, 2015);
    put_u32_le(&mut cond, 168, (g.dx * 1e12).round() as u32);
    put_u32_le(&mut cond, 172, (g.dy * 1e12).round() as u32);
    put_u32_le(&mut cond, 176, z_pm);
    out.extend_from_slice(&cond);
    let zmin =
        g.z.iter()
            .filter(|v| v.is_finite())
            .fold(f64::INFINITY, |a, &b| a.min(b));
    let image = |out: &mut Vec<u8>, depth: u32, values: &[u32]| -> u32 {
        let at = out.len() as u32;
        let bps = depth / 8;
        for v in [
            g.nx as u32,
            g.ny as u32,
            depth,
            0,
            g.nx as u32 * g.ny as u32 * bps,
            0,
            1000,
        ] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend(std::iter::repeat_n(7u8, 768));
        for &v in values {
            match depth {
                8 => out.push(v as u8),
                16 => out.extend_from_slice(&(v as u16).to_le_bytes()),
                _ => out.extend_from_slice(&v.to_le_bytes()),
            }
        }
        at
    };
    let heights: Vec<u32> =
        g.z.iter()
            .map(|v| ((v - zmin) * 1e12 / f64::from(z_pm)).round() as u32)
            .collect();
    let light: Vec<u32> = (0..g.nx * g.ny).map(|k| (k % 251) as u32).collect();
    let h_at = image(&mut out, 32, &heights);
    let l_at = image(&mut out, 8, &light);
    put_u32_le(&mut out, 12 + 4 * 6, h_at); // height 1
    put_u32_le(&mut out, 12 + 4 * 3, l_at); // light 1
    out
}

// ---------------------------------------------------------------------------------------
// ISO 25178-71 SDF (text and binary)

/// A text SDF (`aISO-1.0`), DataType 7 (double), heights as values x Zscale = 1e-9 m;
/// NaN -> BAD.
pub fn sdf_text(g: &Grid) -> Vec<u8> {
    let mut s = String::from("aISO-1.0\n");
    s += "ManufacID   = encoders\nCreateDate  = 120520151031\nModDate     = 120520151031\n";
    s += &format!("NumPoints   = {}\nNumProfiles = {}\n", g.nx, g.ny);
    s += &format!(
        "Xscale      = {:e}\nYscale      = {:e}\nZscale      = 1e-9\n",
        g.dx, g.dy
    );
    s += "Zresolution = -1\n; a comment line\nCompression = 0\nDataType    = 7\nCheckType   = 0\n*\n";
    for j in 0..g.ny {
        let row: Vec<String> = (0..g.nx)
            .map(|i| {
                let v = g.at(i, j);
                if v.is_finite() {
                    format!("{:e}", v * 1e9)
                } else {
                    "BAD".to_string()
                }
            })
            .collect();
        s += &row.join(" ");
        s += "\n";
    }
    s += "*\nOperator = tests\n*\n";
    s.into_bytes()
}

/// A binary SDF (`bISO-1.0`, 81-byte header) of DataType 7 (f64, Zscale 1) or 5 (i16,
/// Zscale = max / 30000; NaN -> -32768).
pub fn sdf_binary(g: &Grid, data_type: u8) -> Vec<u8> {
    let mut h = vec![0u8; 81];
    put_str(&mut h, 0, 8, b"bISO-1.0");
    put_str(&mut h, 8, 10, b"encoders");
    put_str(&mut h, 18, 12, b"120520151031");
    put_str(&mut h, 30, 12, b"120520151031");
    put_u16_le(&mut h, 42, g.nx as u16);
    put_u16_le(&mut h, 44, g.ny as u16);
    put_f64_le(&mut h, 46, g.dx);
    put_f64_le(&mut h, 54, g.dy);
    let zscale = if data_type == 5 {
        g.max_abs() / 30000.0
    } else {
        1.0
    };
    put_f64_le(&mut h, 62, zscale);
    put_f64_le(&mut h, 70, -1.0);
    h[78] = 0;
    h[79] = data_type;
    h[80] = 0;
    for &v in g.z {
        if data_type == 5 {
            let raw: i16 = if v.is_finite() {
                (v / zscale).round() as i16
            } else {
                i16::MIN
            };
            h.extend_from_slice(&raw.to_le_bytes());
        } else {
            h.extend_from_slice(&(if v.is_finite() { v } else { f64::NAN }).to_le_bytes());
        }
    }
    h
}
