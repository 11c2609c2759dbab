//! Summits identified on the grid: points higher than their 8 neighbours.

use serde::Serialize;

use crate::gw::GwParameters;
use crate::map::HeightMap;
use crate::stats::Moments4;

/// One summit of the grid.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Summit {
    /// Column.
    pub i: usize,
    /// Row.
    pub j: usize,
    /// Height above the mean plane of the heights (m).
    pub height: f64,
    /// Mean curvature -(z_xx + z_yy)/2 by three-point differences (1/m), > 0 at a summit
    /// except in degenerate cases.
    pub curvature: f64,
}

/// Summit statistics of a (detrended) map.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SummitStatistics {
    /// The GW parameters from the summits: `sigma_s` is the standard deviation of the summit
    /// heights, `asperity_density` the count over the interior area (nx - 2)(ny - 2) dx dy,
    /// `radius` = 1 / (mean curvature), `offset` the mean summit height.
    pub gw: GwParameters,
    /// Number of summits.
    pub count: usize,
    /// Mean summit curvature (1/m).
    pub mean_curvature: f64,
    /// Median of the per-summit radii 1/curvature (m), for comparison.
    pub median_radius: f64,
    /// Skewness of the summit heights (0 for a Gaussian).
    pub skewness: f64,
    /// Kurtosis of the summit heights (3 for a Gaussian).
    pub kurtosis: f64,
    /// Interior points that tie with a neighbour (equal heights), a sign of quantised
    /// heights; ties are broken by position (see [`find_summits`]).
    pub ties: usize,
}

/// The summits of the map: interior points (1 <= i <= nx - 2, 1 <= j <= ny - 2; edge points
/// have no complete neighbourhood and are never summits) higher than their 8 neighbours.
///
/// Ties (equal heights, common in quantised instrument data) are broken by raster order: a
/// point must be strictly higher than the neighbours that follow it in row-major order and
/// not lower than those that precede it, so a flat top of several equal samples yields one
/// summit (its last sample in raster order) instead of none. Returns the summits in raster
/// order and the number of interior points with a tied neighbour.
pub fn find_summits(map: &HeightMap) -> (Vec<Summit>, usize) {
    let (nx, ny) = (map.nx(), map.ny());
    let (idx2, idy2) = (1.0 / (map.dx() * map.dx()), 1.0 / (map.dy() * map.dy()));
    let z = map.heights();
    let mut out = Vec::new();
    let mut ties = 0usize;
    for j in 1..ny - 1 {
        let (up, row, down) = (
            &z[(j - 1) * nx..j * nx],
            &z[j * nx..(j + 1) * nx],
            &z[(j + 1) * nx..(j + 2) * nx],
        );
        for i in 1..nx - 1 {
            let c = row[i];
            // preceding neighbours (raster order): the row above and the left point
            let before = [up[i - 1], up[i], up[i + 1], row[i - 1]];
            let after = [row[i + 1], down[i - 1], down[i], down[i + 1]];
            let tied = before.iter().chain(&after).any(|&v| v == c);
            ties += usize::from(tied);
            if before.iter().all(|&v| c >= v) && after.iter().all(|&v| c > v) {
                let zxx = (row[i + 1] - 2.0 * c + row[i - 1]) * idx2;
                let zyy = (down[i] - 2.0 * c + up[i]) * idy2;
                out.push(Summit {
                    i,
                    j,
                    height: c,
                    curvature: -0.5 * (zxx + zyy),
                });
            }
        }
    }
    (out, ties)
}

/// Summit statistics of a detrended map (heights measured from its mean plane).
///
/// * `sigma_s`: standard deviation of the summit heights (divisor n - 1);
/// * `offset`: their mean, minus the mean height of the map (0 after detrending);
/// * `asperity_density`: count / ((nx - 2)(ny - 2) dx dy), the area where summits can be found;
/// * `radius`: 1 / mean(curvature), the radius of the mean curvature. The mean of the radii
///   is not used: nearly flat summits (curvature -> 0) make it diverge, and the GW model
///   (like McCool's R) is built on the mean curvature.
///
/// `None` if fewer than 2 summits were found.
pub fn summit_statistics(map: &HeightMap) -> Option<SummitStatistics> {
    let (s, ties) = find_summits(map);
    let n = s.len();
    if n < 2 {
        return None;
    }
    let z = map.heights();
    let mean_height = z.iter().sum::<f64>() / z.len() as f64;
    let heights: Vec<f64> = s.iter().map(|p| p.height - mean_height).collect();
    let hm = Moments4::of(&heights);
    let mean_curvature = s.iter().map(|p| p.curvature).sum::<f64>() / n as f64;
    let mut radii: Vec<f64> = s.iter().map(|p| 1.0 / p.curvature).collect();
    radii.sort_by(|a, b| a.total_cmp(b));
    let median_radius = if n % 2 == 1 {
        radii[n / 2]
    } else {
        0.5 * (radii[n / 2 - 1] + radii[n / 2])
    };
    let area = (map.nx() - 2) as f64 * (map.ny() - 2) as f64 * map.dx() * map.dy();
    Some(SummitStatistics {
        gw: GwParameters {
            sigma_s: hm.std_sample(),
            asperity_density: n as f64 / area,
            radius: 1.0 / mean_curvature,
            offset: hm.mean,
        },
        count: n,
        mean_curvature,
        median_radius,
        skewness: hm.skewness(),
        kurtosis: hm.kurtosis(),
        ties,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// z = A (cos kx + cos ky): summits at the lattice of crests, height 2A, curvature
    /// (4A/h^2) sin^2(k h/2) by three-point differences, density 1/lambda^2.
    #[test]
    fn egg_crate_summits_are_the_crests() {
        let (per, cells, a, h) = (12usize, 8usize, 2e-9, 4e-9);
        let n = per * cells + 1;
        let k = 2.0 * PI / (per as f64 * h);
        let z: Vec<f64> = (0..n * n)
            .map(|p| a * ((k * (p % n) as f64 * h).cos() + (k * (p / n) as f64 * h).cos()))
            .collect();
        let map = HeightMap::new(n, n, h, h, z).unwrap();
        let (s, ties) = find_summits(&map);
        // crests at i, j = 12, 24, ..., 84: 7 x 7 interior crests (0 and 96 are edges)
        assert_eq!(s.len(), (cells - 1) * (cells - 1));
        assert!(s.iter().all(|p| p.i % per == 0 && p.j % per == 0));
        let curv = 4.0 * a / (h * h) * (k * h / 2.0).sin().powi(2);
        assert!(
            s.iter()
                .all(|p| (p.height - 2.0 * a).abs() < 1e-20
                    && (p.curvature / curv - 1.0).abs() < 1e-9)
        );
        // by symmetry, points at equal distance from a crest tie: cos is even
        assert!(ties > 0);
        let st = summit_statistics(&map).unwrap();
        assert!((st.gw.radius * curv - 1.0).abs() < 1e-9);
        assert!(st.gw.sigma_s < 1e-20);
    }

    #[test]
    fn a_flat_top_of_equal_samples_is_one_summit() {
        let mut z = vec![0.0; 6 * 6];
        for (i, j) in [(2, 2), (3, 2), (2, 3), (3, 3)] {
            z[j * 6 + i] = 1.0;
        }
        let map = HeightMap::new(6, 6, 1.0, 1.0, z).unwrap();
        let (s, _) = find_summits(&map);
        assert_eq!(s.len(), 1);
        assert_eq!((s[0].i, s[0].j), (3, 3));
        // a plateau at the edge is not a summit
        let mut z = vec![0.0; 25];
        z[2] = 1.0;
        assert!(find_summits(&HeightMap::new(5, 5, 1.0, 1.0, z).unwrap())
            .0
            .is_empty());
    }
}
