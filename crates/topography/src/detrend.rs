//! Removal of the mean plane (or a polynomial form) before any statistics.

use serde::Serialize;

use crate::error::{Result, TopographyError};
use crate::map::HeightMap;

/// What is removed from the map before its statistics are taken.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind", content = "order")]
pub enum Detrend {
    /// The mean height only (order 0).
    Mean,
    /// The least-squares plane z = a + b x + c y (order 1): the default. Removes the
    /// sample's tilt in the instrument, which would otherwise count as slope.
    #[default]
    Plane,
    /// The least-squares polynomial of total degree `order` in x and y (2 to
    /// [`Detrend::MAX_ORDER`]): removes bow or form as well (a scanner's bow, a curved
    /// electrode). It also removes the longest wavelengths of the roughness itself.
    Polynomial(usize),
}

impl Detrend {
    /// The highest polynomial degree accepted.
    pub const MAX_ORDER: usize = 6;

    /// The total degree of the fitted polynomial.
    pub fn order(self) -> usize {
        match self {
            Detrend::Mean => 0,
            Detrend::Plane => 1,
            Detrend::Polynomial(n) => n,
        }
    }

    /// The detrending of total degree `order` (0 mean, 1 plane, 2..=6 polynomial).
    pub fn from_order(order: usize) -> Result<Self> {
        match order {
            0 => Ok(Detrend::Mean),
            1 => Ok(Detrend::Plane),
            n if n <= Self::MAX_ORDER => Ok(Detrend::Polynomial(n)),
            n => Err(TopographyError::param(
                "detrend order",
                n,
                format!("must be 0 (mean), 1 (plane) or up to {}", Self::MAX_ORDER),
            )),
        }
    }
}

/// What detrending removed: stated in every report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DetrendSummary {
    /// "mean", "plane" or "polynomial".
    pub method: &'static str,
    /// Total polynomial degree removed (0, 1, 2, ...).
    pub order: usize,
    /// Mean height of the raw map (m): the height of the mean plane at the map's centre.
    pub mean_height: f64,
    /// Slope dz/dx of the removed form at the map's centre (m/m).
    pub tilt_x: f64,
    /// Slope dz/dy of the removed form at the map's centre (m/m).
    pub tilt_y: f64,
    /// Inclination of the removed plane, atan(sqrt(tilt_x^2 + tilt_y^2)) (degrees).
    pub tilt_degrees: f64,
    /// Rms of the removed form about its mean (m): how much height the detrending took away.
    pub removed_rms: f64,
}

/// Legendre polynomials P_0..=P_n at x.
fn legendre(n: usize, x: f64, out: &mut [f64]) {
    out[0] = 1.0;
    if n >= 1 {
        out[1] = x;
    }
    for k in 2..=n {
        let kf = k as f64;
        out[k] = ((2.0 * kf - 1.0) * x * out[k - 1] - (kf - 1.0) * out[k - 2]) / kf;
    }
}

/// Solves the symmetric positive definite system `a x = b` (row-major `a`, n x n) by Cholesky.
fn cholesky_solve(a: &mut [f64], b: &mut [f64], n: usize) -> bool {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if !(d > 0.0) {
            return false;
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= a[i * n + k] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= a[k * n + i] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
    true
}

/// Removes the least-squares polynomial of total degree `how.order()` from the map.
///
/// The fit uses Legendre polynomials P_a(u) P_b(v), a + b <= order, in the coordinates
/// scaled to [-1, 1] (well conditioned up to degree 6); the grid being a product grid, the
/// normal matrix factorises into x and y sums, so the cost is O(nx ny order) rather than
/// O(nx ny order^4). Returns the detrended map (mean zero) and what was removed.
pub fn detrend(map: &HeightMap, how: Detrend) -> Result<(HeightMap, DetrendSummary)> {
    let n = how.order();
    if n > Detrend::MAX_ORDER {
        return Err(TopographyError::param(
            "detrend order",
            n,
            format!("at most {}", Detrend::MAX_ORDER),
        ));
    }
    let (nx, ny) = (map.nx(), map.ny());
    if n >= nx.min(ny) {
        return Err(TopographyError::param(
            "detrend order",
            n,
            format!(
                "a {nx} x {ny} map supports a polynomial of degree below {}",
                nx.min(ny)
            ),
        ));
    }
    let z = map.heights();
    let m = n + 1;
    let scaled = |k: usize, len: usize| 2.0 * k as f64 / (len - 1) as f64 - 1.0;
    let mut pu = vec![0.0; nx * m]; // pu[i * m + a]
    for i in 0..nx {
        legendre(n, scaled(i, nx), &mut pu[i * m..(i + 1) * m]);
    }
    let mut pv = vec![0.0; ny * m];
    for j in 0..ny {
        legendre(n, scaled(j, ny), &mut pv[j * m..(j + 1) * m]);
    }
    let gram = |p: &[f64], len: usize| {
        let mut s = vec![0.0; m * m];
        for k in 0..len {
            for a in 0..m {
                for c in 0..m {
                    s[a * m + c] += p[k * m + a] * p[k * m + c];
                }
            }
        }
        s
    };
    let (su, sv) = (gram(&pu, nx), gram(&pv, ny));
    // Row projections rp[j][a] = sum_i z[j, i] P_a(u_i).
    let mut rp = vec![0.0; ny * m];
    for j in 0..ny {
        let row = &z[j * nx..(j + 1) * nx];
        for (i, &zi) in row.iter().enumerate() {
            for a in 0..m {
                rp[j * m + a] += zi * pu[i * m + a];
            }
        }
    }
    let terms: Vec<(usize, usize)> = (0..m)
        .flat_map(|a| (0..m - a).map(move |b| (a, b)))
        .collect();
    let t = terms.len();
    let mut g = vec![0.0; t * t];
    let mut rhs = vec![0.0; t];
    for (p, &(a, b)) in terms.iter().enumerate() {
        for (q, &(c, d)) in terms.iter().enumerate() {
            g[p * t + q] = su[a * m + c] * sv[b * m + d];
        }
        rhs[p] = (0..ny).map(|j| pv[j * m + b] * rp[j * m + a]).sum();
    }
    if !cholesky_solve(&mut g, &mut rhs, t) {
        return Err(TopographyError::param(
            "detrend order",
            n,
            "the fit is singular on this grid",
        ));
    }
    let coef = rhs;
    let mean_raw = z.iter().sum::<f64>() / z.len() as f64;
    let mut out = Vec::with_capacity(z.len());
    let mut trend_sum = 0.0;
    let mut trend_sq = 0.0;
    let mut row_coef = vec![0.0; m];
    for j in 0..ny {
        row_coef.iter_mut().for_each(|v| *v = 0.0);
        for (p, &(a, b)) in terms.iter().enumerate() {
            row_coef[a] += coef[p] * pv[j * m + b];
        }
        for i in 0..nx {
            let tr: f64 = (0..m).map(|a| row_coef[a] * pu[i * m + a]).sum();
            trend_sum += tr;
            trend_sq += tr * tr;
            out.push(z[j * nx + i] - tr);
        }
    }
    let np = z.len() as f64;
    let trend_mean = trend_sum / np;
    let removed_rms = (trend_sq / np - trend_mean * trend_mean).max(0.0).sqrt();
    // The fit's constant term absorbs the mean; subtract any rounding residue.
    let resid_mean = out.iter().sum::<f64>() / np;
    out.iter_mut().for_each(|v| *v -= resid_mean);
    // Slopes of the form at the centre: d/du P_a(0) P_b(0), with P_a'(0) = a P_{a-1}(0).
    let mut p0 = vec![0.0; m];
    legendre(n, 0.0, &mut p0);
    let dp0 = |a: usize| if a == 0 { 0.0 } else { a as f64 * p0[a - 1] };
    let (mut gu, mut gv) = (0.0, 0.0);
    for (p, &(a, b)) in terms.iter().enumerate() {
        gu += coef[p] * dp0(a) * p0[b];
        gv += coef[p] * p0[a] * dp0(b);
    }
    let tilt_x = gu * 2.0 / ((nx - 1) as f64 * map.dx());
    let tilt_y = gv * 2.0 / ((ny - 1) as f64 * map.dy());
    let summary = DetrendSummary {
        method: match how {
            Detrend::Mean => "mean",
            Detrend::Plane => "plane",
            Detrend::Polynomial(_) => "polynomial",
        },
        order: n,
        mean_height: mean_raw,
        tilt_x,
        tilt_y,
        tilt_degrees: tilt_x.hypot(tilt_y).atan().to_degrees(),
        removed_rms,
    };
    Ok((map.with_heights(out), summary))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_is_removed_exactly_and_reported() {
        let (nx, ny, dx, dy) = (40, 30, 2e-9, 3e-9);
        let z: Vec<f64> = (0..nx * ny)
            .map(|k| {
                let (i, j) = ((k % nx) as f64, (k / nx) as f64);
                5e-9 + 0.01 * i * dx - 0.02 * j * dy
            })
            .collect();
        let map = HeightMap::new(nx, ny, dx, dy, z).unwrap();
        let (flat, s) = detrend(&map, Detrend::Plane).unwrap();
        assert!(flat.heights().iter().all(|v| v.abs() < 1e-20));
        assert!((s.tilt_x - 0.01).abs() < 1e-12 && (s.tilt_y + 0.02).abs() < 1e-12);
        let centre = 5e-9 + 0.01 * 19.5 * dx - 0.02 * 14.5 * dy;
        assert!((s.mean_height - centre).abs() < 1e-20);
    }

    #[test]
    fn quadratic_bow_needs_order_two() {
        let (nx, ny) = (33, 21);
        let z: Vec<f64> = (0..nx * ny)
            .map(|k| {
                let (x, y) = ((k % nx) as f64 - 7.0, (k / nx) as f64 + 2.0);
                1.0 + 0.3 * x - 0.1 * y + 0.05 * x * x + 0.02 * x * y - 0.04 * y * y
            })
            .collect();
        let map = HeightMap::new(nx, ny, 1.0, 1.0, z).unwrap();
        let (res1, _) = detrend(&map, Detrend::Plane).unwrap();
        assert!(res1.heights().iter().any(|v| v.abs() > 0.1));
        let (res2, s) = detrend(&map, Detrend::Polynomial(2)).unwrap();
        assert!(
            res2.heights().iter().all(|v| v.abs() < 1e-10),
            "{:?}",
            &res2.heights()[..4]
        );
        // slope at the centre (x = 16 - 7 = 9, y = 10 + 2 = 12)
        assert!((s.tilt_x - (0.3 + 0.1 * 9.0 + 0.02 * 12.0)).abs() < 1e-10);
        assert!((s.tilt_y - (-0.1 + 0.02 * 9.0 - 0.08 * 12.0)).abs() < 1e-10);
        assert!(detrend(&map, Detrend::Polynomial(7)).is_err());
        assert!(Detrend::from_order(7).is_err());
    }
}
