//! The short-wavelength cutoff: a Gaussian low-pass filter of the height map (ISO 16610-61's
//! areal Gaussian), so that the GW parameters describe the band of wavelengths longer than
//! the cutoff and not whatever the instrument's pixel happened to resolve.

use rustfft::{num_complex::Complex, FftPlanner};

use crate::map::HeightMap;

/// alpha of ISO 16610-61 (and ISO 11562): sqrt(ln 2 / pi), so that the Gaussian weighting
/// function transmits half the amplitude of a wavelength equal to the cutoff.
pub const GAUSSIAN_ALPHA: f64 = 0.469_718_639_349_825_66;

/// The filter, stated (the report's `cutoff.filter`).
pub const FILTER_METHOD: &str = "Gaussian low-pass (ISO 16610-61 areal Gaussian: amplitude \
transmission exp(-pi (alpha lambda_c / lambda)^2), alpha = sqrt(ln 2 / pi), 50% at the cutoff \
lambda_c), separable, applied along x and y by FFT of each line mirrored at its ends (no \
wrap-around jump); a direction whose Nyquist wavelength 2 dx is at least the cutoff is left \
as sampled";

/// The amplitude transmission of the Gaussian filter of cutoff `cutoff` at spatial
/// frequency `f` = 1/lambda (same length unit): exp(-pi (alpha cutoff f)^2) =
/// 2^-(cutoff f)^2, 1/2 at f = 1/cutoff.
pub fn gaussian_transmission(cutoff: f64, f: f64) -> f64 {
    let x = GAUSSIAN_ALPHA * cutoff * f;
    (-std::f64::consts::PI * x * x).exp()
}

/// The Nyquist wavelength of a spacing: 2 d, the shortest wavelength a grid of spacing d
/// holds.
pub fn nyquist_wavelength(spacing: f64) -> f64 {
    2.0 * spacing
}

/// Whether a cutoff filters a direction of spacing `spacing`: only above its Nyquist
/// wavelength (at or below it the map is taken as sampled: the grid holds no shorter
/// wavelength to remove).
pub fn filters(cutoff: f64, spacing: f64) -> bool {
    cutoff > nyquist_wavelength(spacing)
}

/// The map low-pass filtered at wavelength `cutoff` (m) by the Gaussian of ISO 16610-61,
/// separably: every row, then every column, mirrored at its ends (the sequence
/// z0 .. z(n-1) z(n-1) .. z0, so the filter sees no jump between the map's opposite
/// edges), transformed, multiplied by the transmission, transformed back. A direction with
/// `cutoff` at or below its Nyquist wavelength is left as it is ([`filters`]); so is the
/// whole map when neither direction is filtered. The mean height is kept (transmission 1
/// at zero frequency).
pub fn lowpass(map: &HeightMap, cutoff: f64) -> HeightMap {
    let (nx, ny) = (map.nx(), map.ny());
    let mut z = map.heights().to_vec();
    let mut planner = FftPlanner::new();
    if filters(cutoff, map.dx()) {
        // rows are contiguous
        filter_lines(&mut z, nx, ny, 1, nx, map.dx(), cutoff, &mut planner);
    }
    if filters(cutoff, map.dy()) {
        // columns: stride nx
        filter_lines(&mut z, ny, nx, nx, 1, map.dy(), cutoff, &mut planner);
    }
    map.with_heights(z)
}

/// Filters `count` lines of `n` points each: line k's point i is `z[k * line_stride + i *
/// step]`. Two real lines share one complex transform (the filter is real and even, so the
/// real part of the result is the first line's, the imaginary part the second's).
#[allow(clippy::too_many_arguments)]
fn filter_lines(
    z: &mut [f64],
    n: usize,
    count: usize,
    step: usize,
    line_stride: usize,
    spacing: f64,
    cutoff: f64,
    planner: &mut FftPlanner<f64>,
) {
    let m = 2 * n;
    let fwd = planner.plan_fft_forward(m);
    let inv = planner.plan_fft_inverse(m);
    // transmission of bin k of the mirrored line (frequency k / (m spacing), folded)
    let h: Vec<f64> = (0..m)
        .map(|k| {
            let kk = k.min(m - k) as f64;
            gaussian_transmission(cutoff, kk / (m as f64 * spacing)) / m as f64
        })
        .collect();
    let mut buf = vec![Complex::new(0.0, 0.0); m];
    let mut scratch = vec![Complex::new(0.0, 0.0); fwd.get_inplace_scratch_len()];
    let at = |line: usize, i: usize| line * line_stride + i * step;
    let mut line = 0;
    while line < count {
        let pair = line + 1 < count;
        for i in 0..n {
            let a = z[at(line, i)];
            let b = if pair { z[at(line + 1, i)] } else { 0.0 };
            buf[i] = Complex::new(a, b);
            buf[m - 1 - i] = Complex::new(a, b);
        }
        fwd.process_with_scratch(&mut buf, &mut scratch);
        for (v, w) in buf.iter_mut().zip(&h) {
            *v *= *w;
        }
        inv.process_with_scratch(&mut buf, &mut scratch);
        for i in 0..n {
            z[at(line, i)] = buf[i].re;
            if pair {
                z[at(line + 1, i)] = buf[i].im;
            }
        }
        line += if pair { 2 } else { 1 };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sine(nx: usize, ny: usize, d: f64, wavelength: f64) -> HeightMap {
        let z = (0..ny)
            .flat_map(|_| {
                (0..nx).map(move |i| {
                    (2.0 * std::f64::consts::PI * (i as f64 + 0.5) * d / wavelength).cos()
                })
            })
            .collect();
        HeightMap::new(nx, ny, d, d, z).unwrap()
    }

    #[test]
    fn the_transmission_is_one_half_at_the_cutoff() {
        assert!((gaussian_transmission(3.0, 1.0 / 3.0) - 0.5).abs() < 1e-15);
        assert_eq!(gaussian_transmission(3.0, 0.0), 1.0);
        assert!((GAUSSIAN_ALPHA - (2f64.ln() / std::f64::consts::PI).sqrt()).abs() < 1e-15);
    }

    /// A cosine symmetric about the line's ends (sampled at i + 1/2, a whole number of
    /// periods in the mirrored line) is scaled by the transmission at its frequency;
    /// constants pass.
    #[test]
    fn a_cosine_is_scaled_by_the_transmission_and_a_constant_passes() {
        let (n, d) = (64, 1.0);
        // wavelength 16: the mirrored line of 128 points holds 8 whole periods
        let m = sine(n, 5, d, 16.0);
        let f = lowpass(&m, 16.0);
        for (a, b) in f.heights().iter().zip(m.heights()) {
            assert!((a - 0.5 * b).abs() < 1e-12, "{a} vs {}", 0.5 * b);
        }
        let c = HeightMap::new(n, 5, d, d, vec![2.5; n * 5]).unwrap();
        let g = lowpass(&c, 10.0);
        assert!(g.heights().iter().all(|v| (v - 2.5).abs() < 1e-12));
    }

    /// Rows and columns are filtered alike: a map and its transpose give transposed
    /// results (an odd number of lines exercises the unpaired last line).
    #[test]
    fn rows_and_columns_are_filtered_alike() {
        let (nx, ny) = (9, 7);
        let z: Vec<f64> = (0..nx * ny).map(|k| ((k * 37 % 11) as f64).sin()).collect();
        let m = HeightMap::new(nx, ny, 1.0, 1.0, z.clone()).unwrap();
        let zt: Vec<f64> = (0..nx * ny).map(|k| z[(k % ny) * nx + k / ny]).collect();
        let t = HeightMap::new(ny, nx, 1.0, 1.0, zt).unwrap();
        let (a, b) = (lowpass(&m, 5.0), lowpass(&t, 5.0));
        for j in 0..ny {
            for i in 0..nx {
                assert!((a.at(i, j) - b.at(j, i)).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn a_cutoff_at_or_below_the_nyquist_wavelength_leaves_the_map_as_sampled() {
        let m = sine(16, 16, 1e-8, 4e-8);
        assert_eq!(lowpass(&m, 2e-8), m);
        assert_eq!(lowpass(&m, 1e-8), m);
        assert_ne!(lowpass(&m, 2.1e-8), m);
    }
}
