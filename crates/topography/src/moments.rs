//! Spectral moments of a height map and its power spectral density.

use rustfft::num_complex::Complex;
use rustfft::FftPlanner;
use serde::Serialize;

use crate::map::HeightMap;

/// How the moments were estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MomentMethod {
    /// Finite differences on the grid (the report's choice): first differences for slopes,
    /// three-point second differences for curvatures. No periodicity or window assumed.
    FiniteDifference,
    /// Sums over the discrete Fourier spectrum of the map taken as periodic (exact for a
    /// periodic map such as a synthetic one; on a measured map the jump between opposite
    /// edges leaks into the high wavevectors and inflates m2 and m4).
    Spectral,
    /// Analytic integrals of a model PSD ([`crate::SelfAffinePsd`]).
    Analytic,
    /// Sum of two surfaces' moments (the sum surface of two independent rough surfaces).
    Sum,
}

/// Spectral moments of a surface, SI units.
///
/// `m_pq = <(d^p z/dx^p)(d^q z/dy^q)>`-type averages: `m20 = <z_x^2>`, `m02 = <z_y^2>`,
/// `m11 = <z_x z_y>`, `m40 = <z_xx^2>`, `m04 = <z_yy^2>`, `m22 = <z_xx z_yy>` (= `<z_xy^2>`
/// for a stationary surface). McCool's profile moments of the equivalent isotropic surface
/// are their averages over the profile direction theta:
///
/// * m0 = <z^2> (m^2)
/// * m2 = (1/2 pi) integral m2(theta) dtheta = (m20 + m02)/2 (dimensionless)
/// * m4 = (1/2 pi) integral m4(theta) dtheta = (3 m40 + 6 m22 + 3 m04)/8 (1/m^2)
///
/// with m2(theta) = m20 cos^2 + 2 m11 cos sin + m02 sin^2 and m4(theta) = m40 cos^4 +
/// 6 m22 cos^2 sin^2 + m04 sin^4 + odd terms; for an isotropic surface they equal the
/// moments of any profile.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Moments {
    /// Variance of heights about the mean plane (m^2).
    pub m0: f64,
    /// Direction-averaged mean square profile slope (dimensionless).
    pub m2: f64,
    /// Direction-averaged mean square profile curvature (1/m^2).
    pub m4: f64,
    /// <z_x^2>.
    pub m20: f64,
    /// <z_y^2>.
    pub m02: f64,
    /// <z_x z_y>.
    pub m11: f64,
    /// <z_xx^2> (1/m^2).
    pub m40: f64,
    /// <z_yy^2> (1/m^2).
    pub m04: f64,
    /// <z_xx z_yy> (1/m^2).
    pub m22: f64,
    /// How they were estimated.
    pub method: MomentMethod,
}

impl Moments {
    /// Moments of an isotropic surface from its profile moments m0, m2, m4
    /// (m20 = m02 = m2, m11 = 0, m40 = m04 = m4, m22 = m4/3).
    pub fn isotropic(m0: f64, m2: f64, m4: f64, method: MomentMethod) -> Self {
        Moments {
            m0,
            m2,
            m4,
            m20: m2,
            m02: m2,
            m11: 0.0,
            m40: m4,
            m04: m4,
            m22: m4 / 3.0,
            method,
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn from_parts(
        m0: f64,
        m20: f64,
        m02: f64,
        m11: f64,
        m40: f64,
        m04: f64,
        m22: f64,
        method: MomentMethod,
    ) -> Self {
        Moments {
            m0,
            m2: 0.5 * (m20 + m02),
            m4: (3.0 * m40 + 6.0 * m22 + 3.0 * m04) / 8.0,
            m20,
            m02,
            m11,
            m40,
            m04,
            m22,
            method,
        }
    }

    /// Nayak's bandwidth parameter alpha = m0 m4 / m2^2 (>= 1.5 for an isotropic surface;
    /// large for a broad spectrum).
    pub fn alpha(&self) -> f64 {
        self.m0 * self.m4 / (self.m2 * self.m2)
    }

    /// Rms height sqrt(m0) (m).
    pub fn rms_height(&self) -> f64 {
        self.m0.sqrt()
    }

    /// Anisotropy of the slopes: the ratio of the largest to the smallest eigenvalue of
    /// [[m20, m11], [m11, m02]] (1 for an isotropic surface; infinite for a surface
    /// constant in one direction).
    pub fn slope_anisotropy(&self) -> f64 {
        let tr = self.m20 + self.m02;
        let det = self.m20 * self.m02 - self.m11 * self.m11;
        let disc = (0.25 * tr * tr - det).max(0.0).sqrt();
        let (hi, lo) = (0.5 * tr + disc, 0.5 * tr - disc);
        if lo > 0.0 {
            hi / lo
        } else {
            f64::INFINITY
        }
    }

    /// Moments of the sum of two independent surfaces: every moment adds (the spectra add).
    pub fn sum(&self, other: &Moments) -> Moments {
        Moments::from_parts(
            self.m0 + other.m0,
            self.m20 + other.m20,
            self.m02 + other.m02,
            self.m11 + other.m11,
            self.m40 + other.m40,
            self.m04 + other.m04,
            self.m22 + other.m22,
            MomentMethod::Sum,
        )
    }
}

/// Moments by finite differences on the grid (used by the report).
///
/// m0 is the variance of the heights; `m20 = <((z[i+1,j] - z[i,j])/dx)^2>` over all
/// (nx - 1) ny pairs; `m40 = <((z[i+1,j] - 2 z[i,j] + z[i-1,j])/dx^2)^2>` over the (nx - 2) ny
/// interior points; likewise along y; `m11` pairs the forward differences at the same
/// point, `m22` the second differences. For a spectral component of wavevector q the
/// differences see q_eff = 2 sin(q h / 2)/h instead of q, so these are the moments of the
/// surface *as sampled at h*: they fall below the continuous moments as the spectrum
/// approaches the Nyquist wavevector pi/h, which is part of why GW parameters depend on
/// the sampling interval.
pub fn finite_difference_moments(map: &HeightMap) -> Moments {
    let (nx, ny, dx, dy) = (map.nx(), map.ny(), map.dx(), map.dy());
    let z = map.heights();
    let n = z.len() as f64;
    let mean = z.iter().sum::<f64>() / n;
    let m0 = z.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    let (mut s20, mut s02, mut s11, mut s40, mut s04, mut s22) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let (idx, idy) = (1.0 / dx, 1.0 / dy);
    let (idx2, idy2) = (idx * idx, idy * idy);
    for j in 0..ny {
        let row = &z[j * nx..(j + 1) * nx];
        for i in 0..nx - 1 {
            let gx = (row[i + 1] - row[i]) * idx;
            s20 += gx * gx;
            if j + 1 < ny {
                let gy = (z[(j + 1) * nx + i] - row[i]) * idy;
                s11 += gx * gy;
            }
        }
        for i in 1..nx - 1 {
            let cx = (row[i + 1] - 2.0 * row[i] + row[i - 1]) * idx2;
            s40 += cx * cx;
            if j >= 1 && j + 1 < ny {
                let cy = (z[(j + 1) * nx + i] - 2.0 * row[i] + z[(j - 1) * nx + i]) * idy2;
                s22 += cx * cy;
            }
        }
    }
    for j in 0..ny - 1 {
        for i in 0..nx {
            let gy = (z[(j + 1) * nx + i] - z[j * nx + i]) * idy;
            s02 += gy * gy;
        }
    }
    for j in 1..ny - 1 {
        for i in 0..nx {
            let cy = (z[(j + 1) * nx + i] - 2.0 * z[j * nx + i] + z[(j - 1) * nx + i]) * idy2;
            s04 += cy * cy;
        }
    }
    let (fx, fy) = (nx as f64, ny as f64);
    Moments::from_parts(
        m0,
        s20 / ((fx - 1.0) * fy),
        s02 / (fx * (fy - 1.0)),
        s11 / ((fx - 1.0) * (fy - 1.0)),
        s40 / ((fx - 2.0) * fy),
        s04 / (fx * (fy - 2.0)),
        s22 / ((fx - 2.0) * (fy - 2.0)),
        MomentMethod::FiniteDifference,
    )
}

/// Wavevector (rad/m) of FFT bin `k` of `n` at spacing `h` (negative above n/2).
pub(crate) fn wavevector(k: usize, n: usize, h: f64) -> f64 {
    let kk = if k <= n / 2 {
        k as f64
    } else {
        k as f64 - n as f64
    };
    2.0 * std::f64::consts::PI * kk / (n as f64 * h)
}

/// In-place 2-D FFT of a row-major `nx` x `ny` array (forward if `inverse` is false,
/// unnormalised).
pub(crate) fn fft2(data: &mut [Complex<f64>], nx: usize, ny: usize, inverse: bool) {
    let mut planner = FftPlanner::<f64>::new();
    let (fx, fy) = if inverse {
        (planner.plan_fft_inverse(nx), planner.plan_fft_inverse(ny))
    } else {
        (planner.plan_fft_forward(nx), planner.plan_fft_forward(ny))
    };
    fx.process(data);
    let mut col = vec![Complex::new(0.0, 0.0); ny];
    let mut scratch = vec![Complex::new(0.0, 0.0); fy.get_inplace_scratch_len()];
    for i in 0..nx {
        for j in 0..ny {
            col[j] = data[j * nx + i];
        }
        fy.process_with_scratch(&mut col, &mut scratch);
        for j in 0..ny {
            data[j * nx + i] = col[j];
        }
    }
}

/// Fourier coefficients h_k = FFT(z)/N of the map taken as periodic (row-major).
fn fourier_coefficients(map: &HeightMap, window: bool) -> Vec<Complex<f64>> {
    let (nx, ny) = (map.nx(), map.ny());
    let z = map.heights();
    let n = z.len() as f64;
    let mean = z.iter().sum::<f64>() / n;
    let (wx, wy) = (hann(nx, window), hann(ny, window));
    let w2 = wx.iter().map(|w| w * w).sum::<f64>() / nx as f64
        * wy.iter().map(|w| w * w).sum::<f64>()
        / ny as f64;
    // Normalised so that sum |h_k|^2 estimates the variance whatever the window.
    let scale = 1.0 / (n * w2.sqrt());
    let mut data: Vec<Complex<f64>> = z
        .iter()
        .enumerate()
        .map(|(k, &v)| Complex::new((v - mean) * wx[k % nx] * wy[k / nx] * scale, 0.0))
        .collect();
    fft2(&mut data, nx, ny, false);
    data
}

fn hann(n: usize, on: bool) -> Vec<f64> {
    if !on {
        return vec![1.0; n];
    }
    (0..n)
        .map(|k| {
            let s = (std::f64::consts::PI * (k as f64 + 0.5) / n as f64).sin();
            s * s
        })
        .collect()
}

/// Moments from the discrete Fourier spectrum of the map taken as **periodic**:
/// `m_pq = sum_k |h_k|^2 q_x^p q_y^q` with h_k = FFT(z)/N and q the bin's wavevector.
/// Exact (to rounding) for a periodic map, e.g. one from [`crate::synthesize`]; biased
/// upwards on a measured map by the jump between opposite edges (use
/// [`finite_difference_moments`] there).
pub fn spectral_moments(map: &HeightMap) -> Moments {
    let (nx, ny, dx, dy) = (map.nx(), map.ny(), map.dx(), map.dy());
    let h = fourier_coefficients(map, false);
    let (mut m0, mut m20, mut m02, mut m11, mut m40, mut m04, mut m22) =
        (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for j in 0..ny {
        let qy = wavevector(j, ny, dy);
        // The Nyquist row/column has no sign: it contributes nothing to the odd moment m11.
        let sy = if 2 * j == ny { 0.0 } else { 1.0 };
        for i in 0..nx {
            let qx = wavevector(i, nx, dx);
            let sx = if 2 * i == nx { 0.0 } else { 1.0 };
            let p = h[j * nx + i].norm_sqr();
            let (qx2, qy2) = (qx * qx, qy * qy);
            m0 += p;
            m20 += p * qx2;
            m02 += p * qy2;
            m11 += p * qx * qy * sx * sy;
            m40 += p * qx2 * qx2;
            m04 += p * qy2 * qy2;
            m22 += p * qx2 * qy2;
        }
    }
    Moments::from_parts(m0, m20, m02, m11, m40, m04, m22, MomentMethod::Spectral)
}

/// One point of a radially averaged PSD.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PsdPoint {
    /// Wavevector magnitude |q| (rad/m), the bin's mean.
    pub q: f64,
    /// Isotropic 2-D PSD C(q) (m^4), normalised so that the integral of C over the
    /// wavevector plane, 2 pi integral q C(q) dq, is the variance m0 (Persson's convention).
    pub c: f64,
    /// Number of Fourier coefficients averaged.
    pub count: usize,
}

/// The radially averaged PSD C(|q|) of the map (Hann-windowed periodogram, so that a
/// measured map's edges do not leak), in `bins` logarithmic bins from the fundamental
/// 2 pi / min(scan) to the Nyquist wavevector pi / max(dx, dy). For the plot; the report's
/// moments come from finite differences.
pub fn radial_psd(map: &HeightMap, bins: usize) -> Vec<PsdPoint> {
    let (nx, ny, dx, dy) = (map.nx(), map.ny(), map.dx(), map.dy());
    let bins = bins.max(1);
    let h = fourier_coefficients(map, true);
    let dqx = 2.0 * std::f64::consts::PI / map.scan_x();
    let dqy = 2.0 * std::f64::consts::PI / map.scan_y();
    let qmin = dqx.min(dqy);
    let qmax = std::f64::consts::PI / dx.max(dy);
    if !(qmax > qmin) {
        return Vec::new();
    }
    let lr = (qmax / qmin).ln();
    let mut sum_c = vec![0.0; bins];
    let mut sum_q = vec![0.0; bins];
    let mut count = vec![0usize; bins];
    for j in 0..ny {
        let qy = wavevector(j, ny, dy);
        for i in 0..nx {
            let qx = wavevector(i, nx, dx);
            let q = qx.hypot(qy);
            if q < qmin * (1.0 - 1e-12) || q > qmax * (1.0 + 1e-12) {
                continue;
            }
            let b = (((q / qmin).ln() / lr) * bins as f64)
                .floor()
                .clamp(0.0, (bins - 1) as f64) as usize;
            sum_c[b] += h[j * nx + i].norm_sqr() / (dqx * dqy);
            sum_q[b] += q;
            count[b] += 1;
        }
    }
    (0..bins)
        .filter(|&b| count[b] > 0)
        .map(|b| PsdPoint {
            q: sum_q[b] / count[b] as f64,
            c: sum_c[b] / count[b] as f64,
            count: count[b],
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// z = A (cos kx + cos ky) on whole periods: every moment is known in closed form, with
    /// q_eff = 2 sin(k h/2)/h for the finite differences.
    #[test]
    fn egg_crate_moments_are_exact() {
        let (n, per, a, h) = (96usize, 16usize, 3e-9, 5e-9);
        let k = 2.0 * PI / (per as f64 * h);
        let z: Vec<f64> = (0..n * n)
            .map(|p| a * ((k * (p % n) as f64 * h).cos() + (k * (p / n) as f64 * h).cos()))
            .collect();
        let map = HeightMap::new(n, n, h, h, z).unwrap();
        let s = spectral_moments(&map);
        let rel = |x: f64, y: f64| (x / y - 1.0).abs();
        assert!(rel(s.m0, a * a) < 1e-12);
        assert!(rel(s.m2, a * a * k * k / 2.0) < 1e-12);
        assert!(rel(s.m4, 3.0 * a * a * k.powi(4) / 8.0) < 1e-12);
        assert!(s.m22.abs() < 1e-12 * s.m40 && s.m11.abs() < 1e-12 * s.m20);
        assert!(rel(s.alpha(), 1.5) < 1e-12);
        // Finite differences: whole periods in the interior averages are not exact (the
        // averages skip edge points), so compare to the q_eff prediction at 1e-2.
        let f = finite_difference_moments(&map);
        let ke = 2.0 * (k * h / 2.0).sin() / h;
        assert!(rel(f.m0, a * a) < 1e-12);
        assert!(
            rel(f.m20, a * a * ke * ke / 2.0) < 2e-2,
            "{}",
            rel(f.m20, a * a * ke * ke / 2.0)
        );
        assert!(rel(f.m40, a * a * ke.powi(4) / 2.0) < 2e-2);
        // (the interior average of cos kx cos ky misses the edge points: ~(2/n)^2)
        assert!(f.m22.abs() < 1e-3 * f.m40, "{}", f.m22 / f.m40);
        assert!((f.slope_anisotropy() - 1.0).abs() < 1e-3); // m11 over incomplete periods
    }

    #[test]
    fn a_ridge_is_infinitely_anisotropic() {
        let z: Vec<f64> = (0..32 * 32)
            .map(|p| ((p % 32) as f64 * 0.7).sin())
            .collect();
        let m = finite_difference_moments(&HeightMap::new(32, 32, 1.0, 1.0, z).unwrap());
        assert!(m.m02 == 0.0 && m.slope_anisotropy().is_infinite());
    }
}
