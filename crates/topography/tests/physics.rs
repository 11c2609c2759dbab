//! The analysis against known surfaces: analytic spectra, independent computations of the
//! moments and of the summit statistics, and the direction of the sampling dependence.

use std::f64::consts::PI;

use topography::io::{decode, encode};
use topography::{
    analyze, finite_difference_moments, mccool, scene_fragment, spectral_moments, synthesize,
    Amplitudes, AnalysisOptions, Format, HeightMap, Normalization, ReadOptions, Route,
    SelfAffinePsd, SumSurface, SynthesisOptions,
};

fn psd(h: f64, lambda_l: f64, lambda_s: f64) -> SelfAffinePsd {
    SelfAffinePsd::new(h, lambda_l, None, lambda_s, Normalization::RmsHeight(4e-9)).unwrap()
}

fn opts(n: usize, dx: f64, seed: u64, amplitudes: Amplitudes) -> SynthesisOptions {
    SynthesisOptions {
        nx: n,
        ny: n,
        dx,
        dy: dx,
        seed,
        amplitudes,
    }
}

/// Fixed-amplitude synthesis reproduces the analytic moments of the spectrum: m0 exactly,
/// m2 and m4 to the lattice quadrature (the cells' powers are integrals of C, their
/// wavevectors the cell centres): 1% for bands of 16 to 256 lattice steps.
#[test]
fn synthetic_surfaces_have_the_analytic_moments() {
    for &(h, ls, lr) in &[
        (0.8, 16.0, None),
        (0.5, 8.0, Some(64.0)),
        (1.0, 6.0, None),
        (0.3, 4.0, None),
    ] {
        let dx = 4e-9;
        let psd = SelfAffinePsd::new(
            h,
            128.0 * dx,
            lr.map(|l: f64| l * dx),
            ls * dx,
            Normalization::RmsHeight(4e-9),
        )
        .unwrap();
        let map = synthesize(&psd, &opts(256, dx, 3, Amplitudes::Fixed)).unwrap();
        let (a, s) = (psd.moments(), spectral_moments(&map));
        assert!(
            (s.m0 / a.m0 - 1.0).abs() < 1e-9,
            "H {h}: m0 {} vs {}",
            s.m0,
            a.m0
        );
        assert!(
            (s.m2 / a.m2 - 1.0).abs() < 0.01,
            "H {h}: m2 ratio {}",
            s.m2 / a.m2
        );
        assert!(
            (s.m4 / a.m4 - 1.0).abs() < 0.01,
            "H {h}: m4 ratio {}",
            s.m4 / a.m4
        );
        assert!((s.slope_anisotropy() - 1.0).abs() < 0.05);
        // and the GW parameters of the realisation follow
        let (ga, gs) = (mccool(&a), mccool(&s));
        assert!((gs.asperity_density / ga.asperity_density - 1.0).abs() < 0.02);
        assert!((gs.radius / ga.radius - 1.0).abs() < 0.01);
    }
}

/// Gaussian synthesis scatters around the spectrum: over 8 seeds the mean of m2/m2_analytic
/// and m4/m4_analytic is 1 within 3 standard errors plus the 0.5% lattice bias.
#[test]
fn gaussian_fields_scatter_around_the_analytic_moments() {
    let dx = 4e-9;
    let psd = psd(0.7, 128.0 * dx, 8.0 * dx);
    let a = psd.moments();
    let (mut r2, mut r4) = (Vec::new(), Vec::new());
    for seed in 0..8 {
        let s = spectral_moments(
            &synthesize(&psd, &opts(256, dx, seed, Amplitudes::Gaussian)).unwrap(),
        );
        r2.push(s.m2 / a.m2);
        r4.push(s.m4 / a.m4);
    }
    for r in [r2, r4] {
        let n = r.len() as f64;
        let mean = r.iter().sum::<f64>() / n;
        let sd = (r.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0)).sqrt();
        assert!(
            (mean - 1.0).abs() < 3.0 * sd / n.sqrt() + 0.005,
            "mean {mean}, sd {sd}"
        );
        assert!(sd > 0.0);
    }
    // the same seed gives the same surface
    let m1 = synthesize(&psd, &opts(64, dx * 4.0, 9, Amplitudes::Gaussian));
    let m2 = synthesize(&psd, &opts(64, dx * 4.0, 9, Amplitudes::Gaussian));
    assert_eq!(m1.unwrap(), m2.unwrap());
}

/// Finite-difference moments against an independent computation: the lattice sum of the
/// realisation's Fourier powers times the difference operators' transfer functions,
/// |e^{i q h} - 1|^2 / h^2 = (2 sin(q h/2)/h)^2 for slopes, (2 sin(q h/2)/h)^4 for
/// curvatures. The FD averages skip the wrap-around pairs of the periodic map: 1%.
#[test]
fn finite_difference_moments_follow_the_difference_transfer_functions() {
    let dx = 5e-9;
    let psd = psd(0.8, 64.0 * dx, 3.0 * dx);
    let map = synthesize(&psd, &opts(128, dx, 11, Amplitudes::Gaussian)).unwrap();
    let (n, z) = (map.nx(), map.heights());
    // direct DFT power at each bin (independent of the crate's FFT), summed with weights
    let mut m20 = 0.0;
    let mut m40 = 0.0;
    let k_of = |k: usize| {
        if k <= n / 2 {
            k as f64
        } else {
            k as f64 - n as f64
        }
    };
    // separable DFT: rows first
    let mut rows = vec![(0.0f64, 0.0f64); n * n];
    for j in 0..n {
        for kx in 0..n {
            let (mut re, mut im) = (0.0, 0.0);
            for i in 0..n {
                let ph = -2.0 * PI * (kx * i) as f64 / n as f64;
                re += z[j * n + i] * ph.cos();
                im += z[j * n + i] * ph.sin();
            }
            rows[j * n + kx] = (re, im);
        }
    }
    for kx in 0..n {
        let q = 2.0 * PI * k_of(kx) / (n as f64 * dx);
        let t = (2.0 * (q * dx / 2.0).sin() / dx).powi(2);
        for ky in 0..n {
            let (mut re, mut im) = (0.0, 0.0);
            for j in 0..n {
                let ph = -2.0 * PI * (ky * j) as f64 / n as f64;
                let (a, b) = rows[j * n + kx];
                re += a * ph.cos() - b * ph.sin();
                im += a * ph.sin() + b * ph.cos();
            }
            let p = (re * re + im * im) / (n * n * n * n) as f64;
            if kx == 0 && ky == 0 {
                continue;
            }
            m20 += p * t;
            m40 += p * t * t;
        }
    }
    let f = finite_difference_moments(&map);
    assert!((f.m20 / m20 - 1.0).abs() < 0.01, "m20 {} vs {m20}", f.m20);
    assert!((f.m40 / m40 - 1.0).abs() < 0.01, "m40 {} vs {m40}", f.m40);
    // and near Nyquist the FD moments fall well below the continuous ones
    let s = spectral_moments(&map);
    assert!(f.m40 < 0.8 * s.m40);
}

/// The summit statistics against a brute-force recomputation written independently: linear
/// indices for the tie rule, a two-pass mean and standard deviation.
#[test]
fn summit_statistics_match_a_brute_force_count() {
    let dx = 3e-9;
    let psd = psd(0.6, 96.0 * dx, 4.0 * dx);
    let mut map = synthesize(&psd, &opts(192, dx, 5, Amplitudes::Gaussian)).unwrap();
    // quantise to 0.2 nm steps to create ties, as instrument data have
    let q: Vec<f64> = map
        .heights()
        .iter()
        .map(|v| (v / 2e-10).round() * 2e-10)
        .collect();
    map = HeightMap::new(map.nx(), map.ny(), dx, dx, q).unwrap();
    let report = analyze(
        &map,
        &AnalysisOptions {
            detrend: topography::Detrend::Mean,
            ..Default::default()
        },
    )
    .unwrap();
    let s = report.summits.as_ref().unwrap();

    let (n, z) = (map.nx(), map.heights());
    let mean_all = z.iter().sum::<f64>() / z.len() as f64;
    let mut h = Vec::new();
    let mut curv = Vec::new();
    for p in 0..z.len() {
        let (i, j) = (p % n, p / n);
        if i == 0 || j == 0 || i == n - 1 || j == n - 1 {
            continue;
        }
        let mut is_max = true;
        for dj in [-1i64, 0, 1] {
            for di in [-1i64, 0, 1] {
                if di == 0 && dj == 0 {
                    continue;
                }
                let q = ((j as i64 + dj) as usize) * n + (i as i64 + di) as usize;
                let ok = if q < p { z[p] >= z[q] } else { z[p] > z[q] };
                is_max &= ok;
            }
        }
        if is_max {
            h.push(z[p] - mean_all);
            let zxx = (z[p + 1] - 2.0 * z[p] + z[p - 1]) / (dx * dx);
            let zyy = (z[p + n] - 2.0 * z[p] + z[p - n]) / (dx * dx);
            curv.push(-(zxx + zyy) / 2.0);
        }
    }
    let k = h.len() as f64;
    let mean = h.iter().sum::<f64>() / k;
    let sd = (h.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (k - 1.0)).sqrt();
    let kappa = curv.iter().sum::<f64>() / k;
    let area = ((n - 2) * (n - 2)) as f64 * dx * dx;
    assert_eq!(s.count, h.len());
    assert!(s.ties > 0);
    let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-9;
    assert!(
        close(s.gw.sigma_s, sd) && close(s.gw.offset, mean),
        "{} {sd} {} {mean}",
        s.gw.sigma_s,
        s.gw.offset
    );
    assert!(close(s.gw.radius, 1.0 / kappa) && close(s.gw.asperity_density, k / area));
}

/// Well-resolved Gaussian surfaces (shortest wavelength 16 grid steps): the summits found
/// on the grid agree with Nayak's continuous theory, through McCool's formulas applied to
/// the realisation's own (Fourier) moments: density and radius within 10%, sigma_s within
/// 10%, offset within 25% (the summits of one map are a few hundred: their mean height
/// scatters most). Against the analytic spectrum, the radius agrees within 10% and the
/// density within the scatter of the count.
#[test]
fn grid_summits_agree_with_nayak_on_well_resolved_surfaces() {
    let dx = 5e-9;
    for (h, seed) in [(0.8, 1u64), (0.5, 2), (0.8, 3)] {
        let psd = psd(h, 256.0 * dx, 16.0 * dx);
        let map = synthesize(&psd, &opts(512, dx, seed, Amplitudes::Gaussian)).unwrap();
        let r = analyze(&map, &AnalysisOptions::default()).unwrap();
        let (a, s) = (
            mccool(&spectral_moments(&map)),
            r.summits.as_ref().unwrap().gw,
        );
        let rel = |x: f64, y: f64| (x / y - 1.0).abs();
        assert!(
            rel(s.asperity_density, a.asperity_density) < 0.10,
            "N {} vs {}",
            s.asperity_density,
            a.asperity_density
        );
        assert!(
            rel(s.radius, a.radius) < 0.10,
            "R {} vs {}",
            s.radius,
            a.radius
        );
        assert!(
            rel(s.sigma_s, a.sigma_s) < 0.10,
            "sigma_s {} vs {}",
            s.sigma_s,
            a.sigma_s
        );
        assert!(
            rel(s.offset, a.offset) < 0.25,
            "offset {} vs {}",
            s.offset,
            a.offset
        );
        // against the analytic spectrum, the count itself scatters: 3 / sqrt(count) (3 sigma of
        // a Poisson count, an upper bound: summits are more regular than Poisson points)
        let count = r.summits.as_ref().unwrap().count;
        let an = psd.gw_parameters();
        assert!(
            rel(s.asperity_density, an.asperity_density) < 3.0 / (count as f64).sqrt()
                && rel(s.radius, an.radius) < 0.10,
            "H {h} seed {seed}: N {} vs {}, R {} vs {}",
            s.asperity_density,
            an.asperity_density,
            s.radius,
            an.radius
        );
        assert!(!r
            .warnings
            .iter()
            .any(|w| w.code == "routes_disagree" || w.code == "non_gaussian_heights"));
    }
}

/// Coarsening the sampling (block averaging by 2, 4, 8) of a self-affine surface whose
/// spectrum reaches the grid scale: fewer summits, blunter summits, smaller slopes and
/// curvatures, by both routes.
#[test]
fn coarser_sampling_gives_fewer_blunter_summits() {
    let dx = 4e-9;
    let psd = psd(0.8, 256.0 * dx, 2.0 * dx);
    let map = synthesize(&psd, &opts(512, dx, 4, Amplitudes::Gaussian)).unwrap();
    let r = analyze(&map, &AnalysisOptions::default()).unwrap();
    assert_eq!(
        r.sampling.iter().map(|s| s.factor).collect::<Vec<_>>(),
        vec![1, 2, 4, 8]
    );
    for w in r.sampling.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        assert!(b.dx == 2.0 * a.dx);
        assert!(b.m2 < a.m2 && b.m4 < a.m4);
        assert!(b.spectral.asperity_density < a.spectral.asperity_density);
        assert!(b.spectral.radius > a.spectral.radius);
        let (sa, sb) = (a.summits.unwrap(), b.summits.unwrap());
        assert!(sb.asperity_density < sa.asperity_density && sb.radius > sa.radius);
    }
    assert!(r.warnings.iter().any(|w| w.code == "sampling_dependent"));
    // smaller scans of a surface with long waves have smaller rms heights
    assert_eq!(
        r.scan_size.iter().map(|s| s.tiles).collect::<Vec<_>>(),
        vec![1, 4, 16]
    );
    assert!(r.scan_size[2].rms_height < r.scan_size[0].rms_height);
}

/// The short-wavelength cutoff (docs/topography.md section 10): a cutoff at the pixel scale
/// (at or below the Nyquist wavelength 2 dx) leaves the analysis exactly as without one;
/// longer cutoffs remove the short wavelengths, so the summits grow fewer and blunter,
/// monotonically across the band table, and the report's parameters are its chosen row.
#[test]
fn a_cutoff_at_the_pixel_scale_changes_nothing_and_longer_ones_lower_the_summit_density() {
    use topography::Cutoff;
    let dx = 4e-9;
    let psd = psd(0.8, 256.0 * dx, 2.0 * dx);
    let map = synthesize(&psd, &opts(256, dx, 4, Amplitudes::Gaussian)).unwrap();
    let plain = analyze(&map, &AnalysisOptions::default()).unwrap();
    assert_eq!(plain.cutoff.wavelength, None);
    assert!(!plain.cutoff.applied && plain.band[0].chosen && plain.band[0].cutoff.is_none());
    for w in [dx, 2.0 * dx] {
        let r = analyze(
            &map,
            &AnalysisOptions {
                cutoff: Cutoff::Wavelength(w),
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(r.cutoff.wavelength, Some(w));
        assert!(!r.cutoff.applied, "{w:e}");
        assert_eq!(r.summits, plain.summits, "{w:e}");
        assert_eq!(r.spectral, plain.spectral, "{w:e}");
        assert_eq!((r.m2, r.m4), (plain.m2, plain.m4));
        assert_eq!(r.band, plain.band);
    }
    // the band table: the map as sampled, then 2, 4, 8, ... Nyquist wavelengths (8 nm) up to
    // a quarter of the scan (256 nm)
    assert!(plain.band.len() >= 5, "{}", plain.band.len());
    for (k, b) in plain.band.iter().enumerate().skip(1) {
        let want = 8e-9 * 2f64.powi(k as i32);
        assert!((b.cutoff.unwrap() / want - 1.0).abs() < 1e-12);
        assert!(b.cutoff.unwrap() <= 256e-9 * (1.0 + 1e-12) && !b.chosen);
    }
    for w in plain.band.windows(2) {
        let (a, b) = (w[0].summits.unwrap(), w[1].summits.unwrap());
        assert!(
            b.asperity_density < a.asperity_density,
            "density {:e} -> {:e}",
            a.asperity_density,
            b.asperity_density
        );
        assert!(b.radius > a.radius);
        assert!(w[1].m4 < w[0].m4 && w[1].m2 < w[0].m2);
        assert!(w[1].spectral.asperity_density < w[0].spectral.asperity_density);
    }
    // a cutoff inside the band: the report is that row, the rms height barely moves (the
    // long waves carry it), the density falls
    let w = 48e-9;
    let r = analyze(
        &map,
        &AnalysisOptions {
            cutoff: Cutoff::Wavelength(w),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(r.cutoff.applied && r.cutoff.from == "given");
    let row = r.band.iter().find(|b| b.chosen).unwrap();
    assert_eq!(row.cutoff, Some(w));
    assert_eq!(r.band.iter().filter(|b| b.chosen).count(), 1);
    assert_eq!(row.summits, r.summits.as_ref().map(|s| s.gw));
    assert_eq!(row.spectral, r.spectral.gw);
    let (a, b) = (
        plain.summits.as_ref().unwrap().gw,
        r.summits.as_ref().unwrap().gw,
    );
    assert!(b.asperity_density < 0.5 * a.asperity_density);
    assert!(r.rms_height < plain.rms_height && r.rms_height > 0.9 * plain.rms_height);
    assert!(scene_fragment(&r, Route::Summits)
        .unwrap()
        .contains("# Band: wavelengths longer than the cutoff"));
    // from the contact's scale: 4 sqrt(R sigma_s) with sigma_s of the summits as sampled
    let radius = 1e-7;
    let r = analyze(
        &map,
        &AnalysisOptions {
            cutoff: Cutoff::ContactRadius(radius),
            ..Default::default()
        },
    )
    .unwrap();
    let a = (radius * plain.summits.as_ref().unwrap().gw.sigma_s).sqrt();
    assert_eq!(r.cutoff.from, "contact_radius");
    assert_eq!(r.cutoff.spot_radius, Some(a));
    assert_eq!(r.cutoff.wavelength, Some(4.0 * a));
    // refused: not a length, longer than half the scan
    for c in [
        Cutoff::Wavelength(0.0),
        Cutoff::Wavelength(f64::NAN),
        Cutoff::ContactRadius(-1.0),
        Cutoff::Wavelength(0.6e-6),
        Cutoff::ContactRadius(1.0),
    ] {
        let e = analyze(
            &map,
            &AnalysisOptions {
                cutoff: c,
                ..Default::default()
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("cutoff") || e.contains("contact radius"), "{e}");
    }
}

/// z = A (cos kx + cos ky) end to end: moments, both routes, on whole periods.
#[test]
fn egg_crate_report_is_exact() {
    let (per, cells, a, h) = (16usize, 8usize, 2e-9, 5e-9);
    let n = per * cells;
    let k = 2.0 * PI / (per as f64 * h);
    let z: Vec<f64> = (0..n * n)
        .map(|p| a * ((k * (p % n) as f64 * h).cos() + (k * (p / n) as f64 * h).cos()))
        .collect();
    let map = HeightMap::new(n, n, h, h, z).unwrap();
    let r = analyze(
        &map,
        &AnalysisOptions {
            detrend: topography::Detrend::Mean,
            ..Default::default()
        },
    )
    .unwrap();
    assert!((r.rms_height / a - 1.0).abs() < 1e-9);
    let s = r.summits.as_ref().unwrap();
    assert_eq!(s.count, (cells - 1) * (cells - 1));
    assert!((s.gw.offset - 2.0 * a).abs() < 1e-18 && s.gw.sigma_s < 1e-18);
    let curv = 4.0 * a / (h * h) * (k * h / 2.0).sin().powi(2);
    assert!((s.gw.radius * curv - 1.0).abs() < 1e-9);
    assert!(
        r.warnings.iter().any(|w| w.code == "narrow_band"),
        "{:?}",
        r.warnings
    );
}

#[test]
fn the_json_report_carries_the_contract_keys() {
    let dx = 5e-9;
    let map = synthesize(
        &psd(0.8, 64.0 * dx, 4.0 * dx),
        &opts(128, dx, 1, Amplitudes::Gaussian),
    )
    .unwrap();
    let r = analyze(&map, &AnalysisOptions::default()).unwrap();
    let v: serde_json::Value = serde_json::to_value(&r).unwrap();
    for key in ["rms_height", "m0", "m2", "m4", "alpha"] {
        assert!(v[key].as_f64().unwrap() > 0.0, "{key}");
    }
    for obj in ["spectral", "summits"] {
        for key in ["sigma_s", "asperity_density", "radius", "offset"] {
            assert!(v[obj][key].as_f64().unwrap() > 0.0, "{obj}.{key}");
        }
    }
    assert!((v["m0"].as_f64().unwrap() / (r.rms_height * r.rms_height) - 1.0).abs() < 1e-12);
    assert!(
        v["sampling"].as_array().unwrap().len() == 4
            && v["plots"]["psd"].as_array().unwrap().len() > 10
    );
    assert_eq!(v["detrending"]["method"], "plane");
}

#[test]
fn the_scene_fragment_is_toml_with_the_reports_numbers() {
    let dx = 5e-9;
    let map = synthesize(
        &psd(0.8, 64.0 * dx, 4.0 * dx),
        &opts(128, dx, 1, Amplitudes::Gaussian),
    )
    .unwrap();
    let r = analyze(&map, &AnalysisOptions::default()).unwrap();
    for (route, gw) in [
        (Route::Summits, r.summits.as_ref().unwrap().gw),
        (Route::Spectral, r.spectral.gw),
    ] {
        let text = scene_fragment(&r, route).unwrap();
        let t: toml::Table = text.parse().unwrap();
        let get = |a: &str, b: &str| t[a][b].as_float().unwrap();
        assert_eq!(get("surface", "sigma_s"), gw.sigma_s);
        assert_eq!(get("surface", "asperity_density"), gw.asperity_density);
        assert_eq!(get("contact", "radius"), gw.radius);
        assert!(text.contains("route") && text.contains("# "));
    }
}

/// The sum surface of two independent surfaces on one grid: its moments are the sums of
/// the moments (cross terms average out: within 5% for these 128 x 128 maps), so
/// `SumSurface` from the two reports matches the analysis of z1 + z2.
#[test]
fn sum_surface_moments_add() {
    let dx = 5e-9;
    let a = synthesize(
        &psd(0.8, 64.0 * dx, 4.0 * dx),
        &opts(128, dx, 21, Amplitudes::Gaussian),
    )
    .unwrap();
    let b = synthesize(
        &psd(0.4, 32.0 * dx, 6.0 * dx),
        &opts(128, dx, 22, Amplitudes::Gaussian),
    )
    .unwrap();
    let o = AnalysisOptions::default();
    let (ra, rb) = (analyze(&a, &o).unwrap(), analyze(&b, &o).unwrap());
    let rs = analyze(&a.sum_surface(&b).unwrap(), &o).unwrap();
    let sum = SumSurface::from_reports(&ra, &rb);
    for (x, y) in [
        (sum.moments.m0, rs.m0),
        (sum.moments.m2, rs.m2),
        (sum.moments.m4, rs.m4),
    ] {
        assert!((x / y - 1.0).abs() < 0.05, "{x} vs {y}");
    }
    assert!((sum.spectral.radius / rs.spectral.gw.radius - 1.0).abs() < 0.05);
    let rule = sum.parameter_rule.unwrap();
    assert!(
        rule.radius
            < ra.summits
                .as_ref()
                .unwrap()
                .gw
                .radius
                .min(rb.summits.as_ref().unwrap().gw.radius)
    );
    let c = HeightMap::new(64, 64, dx, dx, vec![0.0; 64 * 64]).unwrap();
    assert!(a.sum_surface(&c).is_err());
}

/// Tilt is removed and reported; the GW parameters do not see it.
#[test]
fn tilt_is_removed_and_reported() {
    let dx = 5e-9;
    let map = synthesize(
        &psd(0.8, 64.0 * dx, 4.0 * dx),
        &opts(128, dx, 2, Amplitudes::Gaussian),
    )
    .unwrap();
    let tilted: Vec<f64> = map
        .heights()
        .iter()
        .enumerate()
        .map(|(k, v)| v + 0.02 * (k % 128) as f64 * dx - 0.01 * (k / 128) as f64 * dx + 1e-6)
        .collect();
    let tilted = HeightMap::new(128, 128, dx, dx, tilted).unwrap();
    let o = AnalysisOptions::default();
    let (r0, r1) = (analyze(&map, &o).unwrap(), analyze(&tilted, &o).unwrap());
    let (tx, ty) = (
        r1.detrending.tilt_x - r0.detrending.tilt_x,
        r1.detrending.tilt_y - r0.detrending.tilt_y,
    );
    assert!(
        (tx - 0.02).abs() < 1e-9 && (ty + 0.01).abs() < 1e-9,
        "{tx} {ty}"
    );
    assert!(
        (r1.detrending.mean_height - r0.detrending.mean_height - 1e-6 - 0.01 * 63.5 * dx).abs()
            < 1e-15
    );
    assert!(
        (r1.summits.as_ref().unwrap().gw.sigma_s / r0.summits.as_ref().unwrap().gw.sigma_s - 1.0)
            .abs()
            < 1e-6
    );
    assert!((r1.spectral.gw.radius / r0.spectral.gw.radius - 1.0).abs() < 1e-6);
}

/// A skewed surface (exponential of a Gaussian field) is flagged as non-Gaussian; a Gaussian
/// one is not.
#[test]
fn non_gaussian_surfaces_are_flagged() {
    let dx = 5e-9;
    let map = synthesize(
        &psd(0.8, 64.0 * dx, 4.0 * dx),
        &opts(128, dx, 8, Amplitudes::Gaussian),
    )
    .unwrap();
    let skewed: Vec<f64> = map
        .heights()
        .iter()
        .map(|v| 4e-9 * (v / 2e-9).exp())
        .collect();
    let skewed = HeightMap::new(128, 128, dx, dx, skewed).unwrap();
    let o = AnalysisOptions::default();
    let r = analyze(&skewed, &o).unwrap();
    assert!(r.heights.skewness > 1.0);
    assert!(r.warnings.iter().any(|w| w.code == "non_gaussian_heights"));
    assert!(!analyze(&map, &o)
        .unwrap()
        .warnings
        .iter()
        .any(|w| w.code == "non_gaussian_heights"));
}

/// A synthetic surface written in every format and read back gives the same report (gsf's
/// 32-bit floats aside).
#[test]
fn the_analysis_is_the_same_through_every_format() {
    let dx = 5e-9;
    let map = synthesize(
        &psd(0.8, 48.0 * dx, 4.0 * dx),
        &opts(96, dx, 12, Amplitudes::Gaussian),
    )
    .unwrap();
    let o = AnalysisOptions::default();
    let r0 = analyze(&map, &o).unwrap();
    let ro = ReadOptions {
        spacing: Some(dx),
        height_unit: Some(topography::LengthUnit::METRE),
        ..ReadOptions::default()
    };
    for f in Format::WRITABLE {
        let m = decode(
            std::path::Path::new("synthetic"),
            &encode(&map, f).unwrap(),
            f,
            &ro,
        )
        .unwrap();
        let r = topography::analyze_measurement(&m, &o).unwrap();
        let tol = if f == Format::Gsf { 1e-5 } else { 1e-12 };
        assert!((r.m4 / r0.m4 - 1.0).abs() < tol, "{f}");
        assert!(
            (r.spectral.gw.sigma_s / r0.spectral.gw.sigma_s - 1.0).abs() < tol,
            "{f}"
        );
        assert_eq!(r.source.as_ref().unwrap().format, f);
    }
}

/// Heights so large that a moment, a parameter or a statistic overflows double precision
/// (up to +-1e308 m) are refused naming what overflowed, never analysed into NaN or
/// infinite moments and parameters; heights large but analysable give finite numbers
/// throughout.
#[test]
fn overflowing_heights_are_refused_never_analysed_into_non_finite_values() {
    let n = 32;
    for scale in [1e308, 1e250, 1e160, 1e120, 1e100, 1e-9] {
        let z: Vec<f64> = (0..n * n)
            .map(|k| {
                let (i, j) = (k % n, k / n);
                scale * (((i * 7919 + j * 104_729 + i * j * 31) % 97) as f64 / 48.5 - 1.0)
            })
            .collect();
        let map = HeightMap::new(n, n, 1e-8, 1e-8, z).unwrap();
        match analyze(&map, &AnalysisOptions::default()) {
            Err(e) => {
                let e = e.to_string();
                assert!(
                    e.contains("height map") && e.contains("overflow"),
                    "{scale:e}: {e}"
                );
                assert!(scale > 1.0, "{scale:e}: refused: {e}");
            }
            Ok(r) => {
                let mut v = vec![
                    r.rms_height,
                    r.m0,
                    r.m2,
                    r.m4,
                    r.alpha,
                    r.heights.skewness,
                    r.heights.kurtosis,
                    r.spectral.gw.sigma_s,
                    r.spectral.gw.asperity_density,
                    r.spectral.gw.radius,
                    r.spectral.gw.offset,
                    r.moments_fourier.m0,
                    r.moments_fourier.m4,
                ];
                if let Some(s) = &r.summits {
                    v.extend([
                        s.gw.sigma_s,
                        s.gw.asperity_density,
                        s.gw.radius,
                        s.gw.offset,
                        s.skewness,
                        s.kurtosis,
                    ]);
                }
                for row in r.sampling.iter().chain(r.scan_size.iter()) {
                    v.extend([
                        row.rms_height,
                        row.m2,
                        row.m4,
                        row.alpha,
                        row.spectral.sigma_s,
                    ]);
                }
                assert!(v.iter().all(|x| x.is_finite()), "{scale:e}: {v:?}");
                for w in &r.warnings {
                    assert!(
                        !w.message.contains("inf") && !w.message.contains("NaN"),
                        "{scale:e}: {}",
                        w.message
                    );
                }
            }
        }
    }
}
