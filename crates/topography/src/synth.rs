//! Seeded FFT synthesis of periodic surfaces with a given spectrum.

use rand_chacha::rand_core::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rustfft::num_complex::Complex;
use serde::Serialize;

use crate::error::{Result, TopographyError};
use crate::map::HeightMap;
use crate::moments::{fft2, wavevector};
use crate::psd::SelfAffinePsd;

/// How the Fourier amplitudes of a synthetic surface are drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Amplitudes {
    /// Complex Gaussian coefficients of variance C(q) dq_x dq_y: a Gaussian random field,
    /// whose moments scatter around the spectrum's from one seed to the next.
    #[default]
    Gaussian,
    /// Modulus exactly sqrt(C(q) dq_x dq_y), random phase: the realisation's spectral
    /// moments equal the lattice sums of the spectrum (heights still near-Gaussian by the
    /// central limit theorem).
    Fixed,
}

/// The grid and the randomness of a synthetic surface.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SynthesisOptions {
    /// Points along x.
    pub nx: usize,
    /// Points along y.
    pub ny: usize,
    /// Spacing along x (m).
    pub dx: f64,
    /// Spacing along y (m).
    pub dy: f64,
    /// Seed of the ChaCha8 generator: the same seed gives the same surface on every platform.
    pub seed: u64,
    /// How amplitudes are drawn.
    pub amplitudes: Amplitudes,
}

/// Largest synthetic grid (points): 2^26, as the readers' default cap.
pub const MAX_POINTS: usize = 1 << 26;

fn uniform(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

fn normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1 = 1.0 - uniform(rng); // (0, 1]
    let u2 = uniform(rng);
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

/// The integral of C over the lattice cell centred on (qx, qy) of sides dqx, dqy: the
/// midpoint rule on s x s sub-cells, s from 1 (cells far from the origin, where C varies
/// little across a cell) to 8 (cells straddling a cut-off) and 32 (the few cells next to
/// the origin, which carry most of m0 for a steep spectrum). The cells tile the wavevector plane, so the powers
/// of all cells add up to the integral of C, the analytic m0, to the sub-cell quadrature.
fn cell_power(psd: &SelfAffinePsd, qx: f64, qy: f64, dqx: f64, dqy: f64) -> f64 {
    let (hx, hy) = (0.5 * dqx, 0.5 * dqy);
    let near = |c: f64, h: f64| if c.abs() <= h { 0.0 } else { c.abs() - h };
    let qmin = near(qx, hx).hypot(near(qy, hy));
    let qmax = (qx.abs() + hx).hypot(qy.abs() + hy);
    if qmax < psd.q_l || qmin > psd.q_s {
        return 0.0;
    }
    let straddles = [psd.q_l, psd.q_r, psd.q_s]
        .iter()
        .any(|&b| qmin < b && b < qmax);
    let near_origin = qmax < 6.0 * dqx.max(dqy);
    let s = if near_origin {
        // few cells carry most of m0 for a steep spectrum: resolve the cut-off finely
        32
    } else if straddles {
        8
    } else {
        ((8.0 * dqx.max(dqy) / qmin).ceil() as usize).clamp(1, 8)
    };
    let mut sum = 0.0;
    for a in 0..s {
        let x = qx - hx + dqx * (a as f64 + 0.5) / s as f64;
        for b in 0..s {
            let y = qy - hy + dqy * (b as f64 + 0.5) / s as f64;
            sum += psd.c(x.hypot(y));
        }
    }
    sum * dqx * dqy / (s * s) as f64
}

/// A periodic surface with the isotropic spectrum `psd`, by inverse FFT of random Fourier
/// coefficients with Hermitian symmetry (so the surface is real):
///
/// z(x) = sum over the lattice q = (2 pi i / L_x, 2 pi j / L_y) of h_q exp(i q.x), with
/// <|h_q|^2> = the integral of C over the lattice cell of q (dq = 2 pi / L on a side), so that
/// <z^2> = integral of C d^2q = m0 of `psd`, and m2, m4 follow the spectrum to the
/// discreteness of the lattice (about 1% when the band spans tens of lattice steps).
///
/// With [`Amplitudes::Fixed`] the map is finally scaled so that its rms height is
/// **exactly** sqrt(m0) (a correction of the sub-cell quadrature, ~1e-3); with
/// [`Amplitudes::Gaussian`] it is a sample of the Gaussian random field, whose moments
/// scatter around the spectrum's (mostly m0, carried by the few longest waves), and is not
/// rescaled, so that m2 and m4 stay unbiased. Errors if the spectrum does not fit the grid: lambda_s below 2 dx or 2 dy
/// (beyond Nyquist), lambda_l above the scan size, or no lattice wavevector in [q_l, q_s].
pub fn synthesize(psd: &SelfAffinePsd, o: &SynthesisOptions) -> Result<HeightMap> {
    let (nx, ny, dx, dy) = (o.nx, o.ny, o.dx, o.dy);
    if nx < HeightMap::MIN_SIDE || ny < HeightMap::MIN_SIDE {
        return Err(TopographyError::param(
            "grid",
            format!("{nx} x {ny}"),
            "needs at least 3 x 3 points",
        ));
    }
    let n = nx
        .checked_mul(ny)
        .filter(|&n| n <= MAX_POINTS)
        .ok_or_else(|| {
            TopographyError::param(
                "grid",
                format!("{nx} x {ny}"),
                format!("at most {MAX_POINTS} points"),
            )
        })?;
    for (name, v) in [("dx", dx), ("dy", dy)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(TopographyError::param(
                name,
                v,
                "a grid spacing must be finite and > 0 (m)",
            ));
        }
    }
    let tau = 2.0 * std::f64::consts::PI;
    let (lx, ly) = (nx as f64 * dx, ny as f64 * dy);
    if psd.q_s > std::f64::consts::PI / dx.max(dy) * (1.0 + 1e-12) {
        return Err(TopographyError::param(
            "lambda_s",
            tau / psd.q_s,
            format!(
                "the shortest wavelength must be at least 2 x the spacing ({:e} m)",
                2.0 * dx.max(dy)
            ),
        ));
    }
    if psd.q_l < tau / lx.min(ly) * (1.0 - 1e-12) {
        return Err(TopographyError::param(
            "lambda_l",
            tau / psd.q_l,
            format!(
                "the longest wavelength must fit in the scan ({:e} m)",
                lx.min(ly)
            ),
        ));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(o.seed);
    let mut h = vec![Complex::new(0.0, 0.0); n];
    for j in 0..ny {
        let qy = wavevector(j, ny, dy);
        for i in 0..nx {
            let k = j * nx + i;
            let partner = ((ny - j) % ny) * nx + (nx - i) % nx;
            if partner < k {
                continue; // filled with its conjugate
            }
            let var = cell_power(psd, wavevector(i, nx, dx), qy, tau / lx, tau / ly);
            // draw even for var = 0 so the stream does not depend on the cut-offs
            let (g1, g2, phase) = (normal(&mut rng), normal(&mut rng), uniform(&mut rng) * tau);
            if var == 0.0 {
                continue;
            }
            let s = var.sqrt();
            if partner == k {
                // self-conjugate bin: a real coefficient
                h[k] = Complex::new(
                    match o.amplitudes {
                        Amplitudes::Gaussian => s * g1,
                        Amplitudes::Fixed => {
                            s * if phase < std::f64::consts::PI {
                                1.0
                            } else {
                                -1.0
                            }
                        }
                    },
                    0.0,
                );
            } else {
                let c = match o.amplitudes {
                    Amplitudes::Gaussian => Complex::new(g1, g2) * (s / 2f64.sqrt()),
                    Amplitudes::Fixed => Complex::from_polar(s, phase),
                };
                h[k] = c;
                h[partner] = c.conj();
            }
        }
    }
    if h.iter().all(|c| c.norm_sqr() == 0.0) {
        return Err(TopographyError::param(
            "spectrum",
            format!("q in [{:e}, {:e}] rad/m", psd.q_l, psd.q_s),
            "no wavevector of this grid lies in the band",
        ));
    }
    fft2(&mut h, nx, ny, true);
    let mut z: Vec<f64> = h.iter().map(|c| c.re).collect();
    let mean = z.iter().sum::<f64>() / n as f64;
    let rms = (z.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n as f64).sqrt();
    let scale = match o.amplitudes {
        Amplitudes::Fixed => psd.moments().m0.sqrt() / rms,
        Amplitudes::Gaussian => 1.0,
    };
    z.iter_mut().for_each(|v| *v = (*v - mean) * scale);
    HeightMap::new(nx, ny, dx, dy, z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::psd::Normalization;

    fn o(n: usize, dx: f64) -> SynthesisOptions {
        SynthesisOptions {
            nx: n,
            ny: n,
            dx,
            dy: dx,
            seed: 0,
            amplitudes: Amplitudes::Fixed,
        }
    }

    #[test]
    fn spectra_that_do_not_fit_the_grid_are_refused() {
        let psd =
            SelfAffinePsd::new(0.8, 1e-6, None, 10e-9, Normalization::RmsHeight(1e-9)).unwrap();
        // lambda_s = 10 nm below 2 dx = 20 nm
        assert!(synthesize(&psd, &o(256, 10e-9))
            .unwrap_err()
            .to_string()
            .contains("lambda_s"));
        // lambda_l = 1 um above the 64 x 4 nm scan
        assert!(synthesize(&psd, &o(64, 4e-9))
            .unwrap_err()
            .to_string()
            .contains("lambda_l"));
        assert!(synthesize(&psd, &o(2, 4e-9)).is_err());
        assert!(synthesize(&psd, &o(1 << 14, 4e-9)).is_err()); // 2^28 points
        assert!(synthesize(
            &psd,
            &SynthesisOptions {
                dy: -1.0,
                ..o(256, 4e-9)
            }
        )
        .is_err());
        assert!(synthesize(&psd, &o(256, 4e-9)).is_ok());
    }

    #[test]
    fn fixed_amplitudes_give_the_exact_rms_and_a_real_zero_mean_surface() {
        let psd = SelfAffinePsd::new(
            0.5,
            380e-9,
            Some(200e-9),
            16e-9,
            Normalization::RmsHeight(3e-9),
        )
        .unwrap();
        let map = synthesize(
            &psd,
            &SynthesisOptions {
                ny: 96,
                ..o(128, 4e-9)
            },
        )
        .unwrap();
        let z = map.heights();
        let n = z.len() as f64;
        let mean = z.iter().sum::<f64>() / n;
        let rms = (z.iter().map(|v| v * v).sum::<f64>() / n).sqrt();
        assert!(mean.abs() < 1e-12 * rms);
        assert!((rms / 3e-9 - 1.0).abs() < 1e-12);
    }
}
