//! The Maugis-Kim force on the contact branch above the junction, read from a table instead
//! of solved: the fast path of [`crate::MaugisKim::interpolated`].
//!
//! Fbar is tabulated on a uniform grid in x = ln lambda and y = ln(Delta - Delta_j), where it
//! is smooth (Delta - Delta_j spans many decades; near the junction Fbar tends to its
//! junction value exponentially in y), and read by 6 x 6-point Lagrange interpolation,
//! exact for polynomials of degree 5 in each variable. The error was measured before the
//! table was written (`docs/performance.md` section 9): it falls as h^6 everywhere except
//! in the corner where the turning point meets the junction (lambda near lambda_c, Delta
//! near Delta_j), which the table leaves to the solver. At the step used here the largest
//! error over the domain, relative to max(|Fbar|, 1), is [`MAX_ERROR`] (test
//! `the_table_holds_its_bound_over_the_whole_domain`).
//!
//! The table is never built whole: each entry is solved (by the exact stable-point solve)
//! the first time a stencil reaches it and kept for the life of the process, in a cell of
//! its own. A switch run needs some ten thousand entries (the lambdas of its asperities
//! span a narrow band; the paper's switch in fast mode 13,900 of the 606,651); a design map
//! shares them between all its points. (Tiles of 16 x 16 stencil origins, solved whole
//! when first reached, solved 2.9 times as many entries on the paper's switch: a fifth of
//! a fast run's instructions.)

use crate::md::MdCurve;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::OnceLock;

/// Grid: ln lambda from X0 in NX steps of H; y = ln(Delta - Delta_j) from Y0 in NY steps.
const H: f64 = 0.02;
const X0: f64 = -4.0;
const NX: usize = 551; // to ln lambda = 7
const Y0: f64 = -12.0;
const NY: usize = 1101; // to y = 10

/// Largest interpolation error relative to max(|Fbar|, 1) over the table's domain: 2.2e-10
/// measured on 40,000 random points (median 9.6e-13, 99th percentile 2.0e-11, the largest
/// ones along the edges of the corner left to the solver; at a step of 0.015 the largest
/// was 3.9e-11 for 1.8 times the entries), bounded here with a margin above two.
pub const MAX_ERROR: f64 = 5e-10;

/// The corner left to the solver: |ln lambda - ln lambda_c| < CORNER_X and y < CORNER_Y
/// (with 0.35 and -3 the largest error was 2.2e-10, all of it next to the corner; the
/// wider corner sends 0.3 % of the T1 film's solves to the solver instead of 0.15 %).
const CORNER_X: f64 = 0.5;
/// ln lambda_c, the corner's centre (test `the_corner_is_centred_on_lambda_c`).
const LN_LAMBDA_CRITICAL: f64 = -0.064_061_347_311_685_31;
const CORNER_Y: f64 = -2.0;

/// The table's entries by their bits, row-major (i, j); 0 (the bits of +0.0) until solved.
/// A solve that fails leaves a NaN, which makes every stencil holding it decline; a solved
/// +0.0 is kept as -0.0. Two threads that reach a new entry at once may both solve it:
/// the solve is deterministic, so both store the same bits.
static ENTRIES: [AtomicU64; NX * NY] = [const { AtomicU64::new(0) }; NX * NY];

/// The Maugis-Kim curve of each row (lambda_i), made once.
static ROWS: [OnceLock<Option<MdCurve>>; NX] = [const { OnceLock::new() }; NX];

/// One bit per stencil origin (i0, j0), by i0 NY + j0: set once all 36 entries of the
/// stencil are solved (Release after their stores, so a reader that sees it (Acquire)
/// sees them).
static READY: [AtomicU64; (NX * NY).div_ceil(64)] =
    [const { AtomicU64::new(0) }; (NX * NY).div_ceil(64)];

/// Solves the six entries of row `i` from column `j0` not solved yet (NaN where the solve
/// fails; the caller keeps the stencil inside the grid).
#[cold]
#[inline(never)]
fn solve_row(i: usize, j0: usize) {
    let curve = ROWS[i]
        .get_or_init(|| MdCurve::new((X0 + H * i as f64).exp()).ok())
        .as_ref();
    for dj in 0..6 {
        let cell = &ENTRIES[i * NY + j0 + dj];
        if cell.load(Ordering::Relaxed) == 0 {
            let f = node(curve, j0 + dj);
            let f = if f == 0.0 { -0.0 } else { f };
            cell.store(f.to_bits(), Ordering::Relaxed);
        }
    }
}

/// Fbar at the grid node (i, j) of one row's `curve` (lambda_i), by the exact solve; NaN
/// where it fails or off the grid.
fn node(curve: Option<&MdCurve>, j: usize) -> f64 {
    let Some(curve) = curve else {
        return f64::NAN;
    };
    if j >= NY {
        return f64::NAN;
    }
    let delta = curve.junction().delta + (Y0 + H * j as f64).exp();
    curve.stable_point(delta).map_or(f64::NAN, |p| p.force)
}

/// Lagrange weights of the nodes at -2, -1, 0, 1, 2, 3 for the point f in [0, 1).
fn weights(f: f64) -> [f64; 6] {
    // 1 / prod_{m != k} (t_k - t_m)
    const INV_DEN: [f64; 6] = [
        -1.0 / 120.0,
        1.0 / 24.0,
        -1.0 / 12.0,
        1.0 / 12.0,
        -1.0 / 24.0,
        1.0 / 120.0,
    ];
    let d = [f + 2.0, f + 1.0, f, f - 1.0, f - 2.0, f - 3.0];
    // prefix and suffix products: prod over m != k without a division
    let mut w = [0.0; 6];
    let mut left = 1.0;
    for k in 0..6 {
        w[k] = left * INV_DEN[k];
        left *= d[k];
    }
    let mut right = 1.0;
    for k in (0..6).rev() {
        w[k] *= right;
        right *= d[k];
    }
    w
}

/// Fbar on the stable contact branch at `lambda` and Delta = Delta_j + `above_junction`,
/// interpolated within [`MAX_ERROR`]; None outside the table (beyond its lambda or Delta
/// range, in the corner near lambda_c, or where a stencil holds a failed solve): the caller
/// then solves.
pub(crate) fn force(lambda: f64, above_junction: f64) -> Option<f64> {
    if !(above_junction > 0.0 && lambda > 0.0) {
        return None;
    }
    let (lx, ly) = (lambda.ln(), above_junction.ln());
    if ly < CORNER_Y && (lx - LN_LAMBDA_CRITICAL).abs() < CORNER_X {
        return None;
    }
    let x = (lx - X0) / H;
    let y = (ly - Y0) / H;
    // the stencil i - 2 ..= i + 3 inside the grid
    if !(x >= 2.0 && x < (NX - 4) as f64 && y >= 2.0 && y < (NY - 4) as f64) {
        return None;
    }
    let (i, j) = (x as usize, y as usize);
    let wx = weights(x - i as f64);
    let wy = weights(y - j as f64);
    // the stencil's origin (i - 2, j - 2): its 36 entries, solved the first time
    let (i0, j0) = (i - 2, j - 2);
    let origin = i0 * NY + j0;
    let (word, bit) = (&READY[origin / 64], 1u64 << (origin % 64));
    if word.load(Ordering::Acquire) & bit == 0 {
        for di in 0..6 {
            solve_row(i0 + di, j0);
        }
        word.fetch_or(bit, Ordering::Release);
    }
    let mut f = 0.0;
    for (di, wi) in wx.iter().enumerate() {
        let start = origin + di * NY;
        let mut s = 0.0;
        for (w, cell) in wy.iter().zip(&ENTRIES[start..start + 6]) {
            s += w * f64::from_bits(cell.load(Ordering::Relaxed));
        }
        f += wi * s;
    }
    // a failed solve in the stencil makes the sum NaN
    f.is_finite().then_some(f)
}

/// The turning point's interference Delta_t (where a retracting sphere jumps out) on a
/// grid of ln lambda: from TX0 in steps of TH to TX0 + (TN - 1) TH. Below TX0 (lambda within
/// e^0.5 of lambda_c, where Delta_t meets the junction and is not smooth in lambda) and
/// above the grid the solver answers.
const TH: f64 = 0.01;
const TX0: f64 = LN_LAMBDA_CRITICAL + CORNER_X;
const TN: usize = 1000; // to ln lambda = 9.9, lambda = 2e4

/// Largest error of the interpolated Delta_t relative to max(|Delta_t|, 1): 4.2e-14 measured
/// on 20,000 random points of the grid's range (test
/// `the_turning_table_holds_its_bound`), bounded here with a margin; far inside
/// [`MAX_ERROR`], so that every caller allowed the force table may read this one too.
pub(crate) const TURNING_ERROR: f64 = 1e-12;
// every caller allowed the force table may read the turning table
const _: () = assert!(TURNING_ERROR <= MAX_ERROR);

/// The turning table's entries by their bits, 0 until solved (as [`ENTRIES`]).
static TURNING: [AtomicU64; TN] = [const { AtomicU64::new(0) }; TN];

/// Delta_t at the turning grid's node `i`, solved the first time it is asked for.
fn turning_entry(i: usize) -> f64 {
    let cell = &TURNING[i];
    let bits = cell.load(Ordering::Relaxed);
    if bits != 0 {
        return f64::from_bits(bits);
    }
    let v = turning_node(i);
    let v = if v == 0.0 { -0.0 } else { v };
    cell.store(v.to_bits(), Ordering::Relaxed);
    v
}

/// Delta_t at the grid's node `i`, by the exact solve (NaN where it fails).
fn turning_node(i: usize) -> f64 {
    MdCurve::new((TX0 + TH * i as f64).exp())
        .and_then(|c| c.turning_point())
        .map_or(f64::NAN, |p| p.delta)
}

/// The turning point's Delta_t at `lambda`, interpolated within [`TURNING_ERROR`] of
/// max(|Delta_t|, 1) by 6-point Lagrange on a grid of ln lambda whose entries are solved
/// when first asked for (1000 in all, about 13 M instructions had they all been solved at
/// once; a switch run asks for a few dozen); None where the solver must answer (lambda
/// within e^0.5 of lambda_c or beyond 2e4, or a failed solve in the stencil).
pub(crate) fn turning_delta(lambda: f64) -> Option<f64> {
    if !(lambda > 0.0) {
        return None;
    }
    let x = (lambda.ln() - TX0) / TH;
    if !(x >= 2.0 && x < (TN - 4) as f64) {
        return None;
    }
    let i = x as usize;
    let w = weights(x - i as f64);
    let d: f64 = w
        .iter()
        .enumerate()
        .map(|(k, w)| w * turning_entry(i - 2 + k))
        .sum();
    d.is_finite().then_some(d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::md::LAMBDA_CRITICAL;
    use contact_core::Path;

    /// A repeatable stream of uniform numbers in [0, 1) (xorshift64 from `seed` != 0).
    fn uniforms(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Random points over the turning table's range: the interpolated Delta_t against the
    /// exact solve, relative to max(|Delta_t|, 1), within TURNING_ERROR; None outside it.
    #[test]
    fn the_turning_table_holds_its_bound() {
        let mut uniform = uniforms(0x9e37_79b9_7f4a_7c15);
        let (x_lo, x_hi) = (TX0 + 2.0 * TH, TX0 + (TN - 4) as f64 * TH);
        let mut worst = (0.0f64, 0.0f64);
        for k in 0..20_000 {
            // every fourth point within 0.5 of the grid's low end, where lambda_c is near
            let span = if k % 4 == 0 { 0.5 } else { x_hi - x_lo };
            let lx = x_lo + span * uniform();
            let exact = MdCurve::new(lx.exp())
                .unwrap()
                .turning_point()
                .unwrap()
                .delta;
            let got =
                turning_delta(lx.exp()).unwrap_or_else(|| panic!("no entry at ln lambda {lx}"));
            let e = (got - exact).abs() / exact.abs().max(1.0);
            if e > worst.0 {
                worst = (e, lx);
            }
        }
        eprintln!(
            "turning table: max error {:.1e} at ln lambda {:.3}",
            worst.0, worst.1
        );
        assert!(worst.0 <= TURNING_ERROR, "max {worst:?}");
        // next to lambda_c and beyond the grid the solver answers
        assert!(turning_delta(LAMBDA_CRITICAL * 1.2).is_none());
        assert!(turning_delta(1e5).is_none());
        assert!(turning_delta(0.0).is_none());
        assert!(turning_delta(f64::NAN).is_none());
    }

    /// Random points over the whole table (x from the third node to the fifth-last, every
    /// y likewise, the corner left out): the interpolated force against the exact solve,
    /// relative to max(|Fbar|, 1), within MAX_ERROR; and None exactly where promised.
    #[test]
    fn the_table_holds_its_bound_over_the_whole_domain() {
        let mut uniform = uniforms(0x2545_f491_4f6c_dd1d);
        let (x_lo, x_hi) = (X0 + 2.0 * H, X0 + (NX - 4) as f64 * H);
        let (y_lo, y_hi) = (Y0 + 2.0 * H, Y0 + (NY - 4) as f64 * H);
        let mut errors = Vec::new();
        while errors.len() < 10_000 {
            let lx = x_lo + (x_hi - x_lo) * uniform();
            let ly = y_lo + (y_hi - y_lo) * uniform();
            let lambda = lx.exp();
            let in_corner = ly < CORNER_Y && (lx - LN_LAMBDA_CRITICAL).abs() < CORNER_X;
            let got = force(lambda, ly.exp());
            if in_corner {
                assert!(got.is_none(), "the corner is the solver's: {lx} {ly}");
                continue;
            }
            let curve = MdCurve::new(lambda).unwrap();
            let exact = curve
                .stable_point(curve.junction().delta + ly.exp())
                .unwrap()
                .force;
            let got = got.unwrap_or_else(|| panic!("no entry at ln lambda {lx}, y {ly}"));
            errors.push(((got - exact).abs() / exact.abs().max(1.0), lx, ly));
        }
        errors.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (median, p99, worst) = (
            errors[errors.len() / 2].0,
            errors[errors.len() * 99 / 100].0,
            errors[errors.len() - 1],
        );
        eprintln!("interpolation error: median {median:.1e}, 99 % {p99:.1e}, max {:.1e} at ln lambda {:.3}, y {:.3}", worst.0, worst.1, worst.2);
        assert!(worst.0 <= MAX_ERROR, "max {worst:?}");
        // outside the grid the solver answers
        assert!(force(1e-3, 1.0).is_none());
        assert!(force(2.0, 1e-9).is_none());
        assert!(force(2.0, 0.0).is_none());
    }

    /// A retracting sphere between the table's Delta_t and the solved one gets the
    /// solver's answer (detached below the solved turning point): near its Delta_t the
    /// table defers to the solve. Without that, such a point, a few 1e-14 below the
    /// turning point, was put on the stable branch (Fbar -0.835 against 0). The points are
    /// found where the table errs low, so that they lie below the solved turning point.
    #[test]
    fn the_retracting_force_next_to_the_tables_turning_point_is_the_solvers() {
        let mut checked = 0;
        for k in 0..4000 {
            let lx = TX0 + 2.5 * TH + k as f64 * 0.002_137;
            if lx >= TX0 + (TN - 5) as f64 * TH {
                break;
            }
            let curve = MdCurve::new(lx.exp()).unwrap();
            let exact = curve.turning_point().unwrap().delta;
            let table = turning_delta(lx.exp()).unwrap();
            if !(table < exact) {
                continue;
            }
            let mid = 0.5 * (table + exact);
            if !(mid > table && mid < exact) {
                continue;
            }
            let path = Path::Retract { from: 10.0 };
            let f = curve.force_interpolated(mid, path).unwrap();
            assert_eq!(f, curve.force(mid, path).unwrap(), "ln lambda {lx}");
            checked += 1;
        }
        assert!(
            checked > 10,
            "{checked} points between the two turning points"
        );
    }

    #[test]
    fn the_corner_is_centred_on_lambda_c() {
        assert_eq!(LN_LAMBDA_CRITICAL, LAMBDA_CRITICAL.ln());
    }

    /// The weights reproduce polynomials of degree 5 exactly and sum to one.
    #[test]
    fn weights_are_exact_for_quintics() {
        for f in [0.0, 0.1, 0.5, 0.77, 0.999] {
            let w = weights(f);
            for p in 0..=5 {
                let interpolated: f64 = (0..6).map(|k| w[k] * ((k as f64) - 2.0).powi(p)).sum();
                assert!(
                    (interpolated - f.powi(p)).abs() < 1e-13,
                    "f {f}, degree {p}: {interpolated}"
                );
            }
        }
    }
}
