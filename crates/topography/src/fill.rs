//! Harmonic (Laplace) filling of undefined points.
//!
//! Instruments mark points they could not measure (dropouts on steep slopes, dust,
//! saturation); the readers turn each marker into NaN. With `--undefined fill` those points
//! get the **discrete harmonic interpolant** of the defined ones: the values that make the
//! 5-point Laplacian vanish at every undefined point,
//!
//!   sum over the grid neighbours q of p of (z_p - z_q) = 0   for every undefined p,
//!
//! with the defined points fixed (Dirichlet data) and, at the edge of the map, only the
//! neighbours that exist (a natural, zero-flux condition). Each filled value is the mean of
//! its neighbours: the smoothest surface through the defined points, with no new extrema
//! (maximum principle), and exact for any plane inside the map (a linear function has zero
//! discrete Laplacian). It adds no roughness of its own, so filled regions lower the slope
//! and curvature moments and hold no summits; the report says how many points were filled.
//!
//! The linear system (symmetric positive definite whenever one point is defined) is solved
//! by conjugate gradients with a Jacobi preconditioner, from a start that propagates the
//! defined values inwards (breadth-first, each point the mean of its reached neighbours),
//! to a residual below 1e-12 of the right-hand side (max norm). The iterations needed grow
//! with the width of the widest undefined region (a 300 x 300 hole takes about a thousand);
//! the work is capped (iterations x undefined points <= 1e10) and a fill that does not reach
//! 1e-8 within it is refused.

use std::collections::VecDeque;

use crate::error::{Result, TopographyError};

/// What [`fill_harmonic`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FillSummary {
    /// Points filled.
    pub filled: usize,
    /// Conjugate-gradient iterations.
    pub iterations: usize,
    /// Final residual, relative to the right-hand side (max norm).
    pub relative_residual: f64,
}

const NONE: u32 = u32::MAX;
/// Work allowed to the solver (iterations x unknowns, about a few seconds): a fill that
/// needs more (an undefined region thousands of points wide) is refused, naming the region's
/// size, rather than left running.
const WORK_BUDGET: u64 = 10_000_000_000;

/// Fills the non-finite entries of the `nx` x `ny` row-major grid `z` (x fastest) by
/// harmonic interpolation from the finite ones (module docs). Errors if every point is
/// undefined, if the grid does not match `z`, or if the solver does not converge.
pub fn fill_harmonic(nx: usize, ny: usize, z: &mut [f64]) -> Result<FillSummary> {
    let n = nx
        .checked_mul(ny)
        .filter(|&n| n == z.len())
        .ok_or_else(|| {
            TopographyError::param(
                "grid",
                format!("{nx} x {ny}"),
                format!("does not hold the {} heights given", z.len()),
            )
        })?;
    let unknown: Vec<usize> = (0..n).filter(|&k| !z[k].is_finite()).collect();
    let m = unknown.len();
    if m == 0 {
        return Ok(FillSummary {
            filled: 0,
            iterations: 0,
            relative_residual: 0.0,
        });
    }
    if m == n {
        return Err(TopographyError::param(
            "heights",
            format!("{n} undefined points"),
            "every point is undefined: nothing to interpolate from",
        ));
    }
    if m > NONE as usize - 1 {
        return Err(TopographyError::param(
            "heights",
            format!("{m} undefined points"),
            "too many to fill",
        ));
    }
    // number of each unknown in the grid
    let mut num = vec![NONE; n];
    for (u, &k) in unknown.iter().enumerate() {
        num[k] = u as u32;
    }
    // each unknown's neighbours: unknown ones (as numbers), the sum of the known ones, the degree
    let mut nb = vec![NONE; 4 * m];
    let mut b = vec![0.0; m];
    let mut deg = vec![0.0; m];
    for (u, &k) in unknown.iter().enumerate() {
        let (i, j) = (k % nx, k / nx);
        let mut slot = 0;
        let mut visit = |q: usize| {
            deg[u] += 1.0;
            if num[q] == NONE {
                b[u] += z[q];
            } else {
                nb[4 * u + slot] = num[q];
                slot += 1;
            }
        };
        if i > 0 {
            visit(k - 1);
        }
        if i + 1 < nx {
            visit(k + 1);
        }
        if j > 0 {
            visit(k - nx);
        }
        if j + 1 < ny {
            visit(k + nx);
        }
    }
    let mut x = initial_guess(nx, ny, z, &unknown, &num);
    let apply = |v: &[f64], out: &mut [f64]| {
        for u in 0..m {
            let mut s = deg[u] * v[u];
            for &q in &nb[4 * u..4 * u + 4] {
                if q != NONE {
                    s -= v[q as usize];
                }
            }
            out[u] = s;
        }
    };
    let max_abs = |v: &[f64]| v.iter().fold(0.0f64, |a, &x| a.max(x.abs()));
    let b_norm = max_abs(&b);
    let scale = if b_norm > 0.0 { b_norm } else { 1.0 };
    let tol = 1e-12 * scale;
    let mut r = vec![0.0; m];
    apply(&x, &mut r);
    r.iter_mut().zip(&b).for_each(|(ri, bi)| *ri = bi - *ri);
    let mut zz: Vec<f64> = r.iter().zip(&deg).map(|(ri, d)| ri / d).collect();
    let mut p = zz.clone();
    let mut ap = vec![0.0; m];
    let mut rz: f64 = r.iter().zip(&zz).map(|(a, b)| a * b).sum();
    let max_iter = (20 * (nx + ny) + 1000).min((WORK_BUDGET / m as u64).max(100) as usize);
    let mut iterations = 0;
    let mut res = max_abs(&r);
    while res > tol {
        if iterations >= max_iter {
            break;
        }
        iterations += 1;
        apply(&p, &mut ap);
        let pap: f64 = p.iter().zip(&ap).map(|(a, b)| a * b).sum();
        if !(pap > 0.0) {
            break;
        }
        let alpha = rz / pap;
        for u in 0..m {
            x[u] += alpha * p[u];
            r[u] -= alpha * ap[u];
        }
        res = max_abs(&r);
        for u in 0..m {
            zz[u] = r[u] / deg[u];
        }
        let rz_new: f64 = r.iter().zip(&zz).map(|(a, b)| a * b).sum();
        let beta = rz_new / rz;
        rz = rz_new;
        for u in 0..m {
            p[u] = zz[u] + beta * p[u];
        }
    }
    let relative_residual = res / scale;
    if !(relative_residual <= 1e-8) || x.iter().any(|v| !v.is_finite()) {
        return Err(TopographyError::param(
            "undefined points",
            format!("{m} of {n}"),
            format!(
                "the harmonic fill did not converge ({iterations} iterations, relative residual {relative_residual:e}): \
                 the undefined regions are too large to fill; crop them"
            ),
        ));
    }
    for (u, &k) in unknown.iter().enumerate() {
        z[k] = x[u];
    }
    Ok(FillSummary {
        filled: m,
        iterations,
        relative_residual,
    })
}

/// A start for the solver: the defined values carried inwards breadth-first, each unknown
/// the mean of its neighbours reached before it.
fn initial_guess(nx: usize, ny: usize, z: &[f64], unknown: &[usize], num: &[u32]) -> Vec<f64> {
    let m = unknown.len();
    let mut x = vec![f64::NAN; m];
    let mut queued = vec![false; m];
    let mut queue = VecDeque::new();
    let neighbours = |k: usize| {
        let (i, j) = (k % nx, k / nx);
        [
            (i > 0).then(|| k - 1),
            (i + 1 < nx).then(|| k + 1),
            (j > 0).then(|| k - nx),
            (j + 1 < ny).then(|| k + nx),
        ]
    };
    for (u, &k) in unknown.iter().enumerate() {
        if neighbours(k).into_iter().flatten().any(|q| num[q] == NONE) {
            queued[u] = true;
            queue.push_back(u);
        }
    }
    while let Some(u) = queue.pop_front() {
        let k = unknown[u];
        let (mut s, mut c) = (0.0, 0.0);
        for q in neighbours(k).into_iter().flatten() {
            let v = if num[q] == NONE {
                z[q]
            } else {
                x[num[q] as usize]
            };
            if v.is_finite() {
                s += v;
                c += 1.0;
            } else if num[q] != NONE && !queued[num[q] as usize] {
                queued[num[q] as usize] = true;
                queue.push_back(num[q] as usize);
            }
        }
        x[u] = if c > 0.0 { s / c } else { 0.0 };
    }
    x.iter_mut()
        .filter(|v| !v.is_finite())
        .for_each(|v| *v = 0.0);
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plane_with_holes_is_filled_exactly() {
        let (nx, ny) = (40, 30);
        let plane = |i: usize, j: usize| 3.0 + 0.25 * i as f64 - 0.75 * j as f64;
        let mut z: Vec<f64> = (0..nx * ny).map(|k| plane(k % nx, k / nx)).collect();
        // a large interior hole and scattered points
        for j in 5..25 {
            for i in 8..30 {
                z[j * nx + i] = f64::NAN;
            }
        }
        z[nx + 1] = f64::NAN;
        z[33 + 20 * nx] = f64::INFINITY;
        let s = fill_harmonic(nx, ny, &mut z).unwrap();
        assert_eq!(s.filled, 20 * 22 + 2);
        for (k, v) in z.iter().enumerate() {
            assert!((v - plane(k % nx, k / nx)).abs() < 1e-9, "{k}: {v}");
        }
    }

    #[test]
    fn every_point_undefined_is_refused() {
        let mut z = vec![f64::NAN; 9];
        assert!(fill_harmonic(3, 3, &mut z).is_err());
        let mut z = vec![1.0; 8];
        assert!(fill_harmonic(3, 3, &mut z).is_err());
    }

    #[test]
    fn a_hole_at_the_edge_takes_the_mean_of_its_neighbours() {
        // one defined point: the whole map takes its value
        let mut z = vec![f64::NAN; 25];
        z[12] = 2.5;
        fill_harmonic(5, 5, &mut z).unwrap();
        assert!(z.iter().all(|v| (v - 2.5).abs() < 1e-12));
    }
}
