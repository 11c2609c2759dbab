//! The statistics of a probability run: exact binomial (Clopper-Pearson) intervals and
//! Spearman's rank correlation.

use statrs::distribution::{Beta, ContinuousCDF, Normal};

/// The exact binomial interval of Clopper and Pearson (1934) for `successes` out of
/// `trials` at `confidence` (e.g. 0.95): the set of p for which neither tail of the
/// binomial distribution has probability below (1 - confidence)/2,
///
/// ```text
/// lower = B^-1(alpha/2; x, n - x + 1)      (0 if x = 0)
/// upper = B^-1(1 - alpha/2; x + 1, n - x)  (1 if x = n)
/// ```
///
/// with B^-1 the inverse CDF of the beta distribution (`statrs`). Its coverage is at least
/// `confidence` for every p and n. `None` when `trials = 0`, `successes > trials` or the
/// confidence is not in (0, 1).
pub fn clopper_pearson(successes: usize, trials: usize, confidence: f64) -> Option<(f64, f64)> {
    if trials == 0 || successes > trials || !(confidence > 0.0 && confidence < 1.0) {
        return None;
    }
    let (x, n) = (successes as f64, trials as f64);
    let alpha = 1.0 - confidence;
    let lower = if successes == 0 {
        0.0
    } else {
        Beta::new(x, n - x + 1.0).ok()?.inverse_cdf(alpha / 2.0)
    };
    let upper = if successes == trials {
        1.0
    } else {
        Beta::new(x + 1.0, n - x)
            .ok()?
            .inverse_cdf(1.0 - alpha / 2.0)
    };
    Some((lower.clamp(0.0, 1.0), upper.clamp(0.0, 1.0)))
}

/// Ranks 1..=n of `v`, ties sharing their average rank. `v` must hold no NaN.
pub fn ranks(v: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&a, &b| v[a].total_cmp(&v[b]).then(a.cmp(&b)));
    let mut r = vec![0.0; v.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j + 1 < order.len() && v[order[j + 1]] == v[order[i]] {
            j += 1;
        }
        let avg = (i + j) as f64 / 2.0 + 1.0;
        for &k in &order[i..=j] {
            r[k] = avg;
        }
        i = j + 1;
    }
    r
}

/// Spearman's rank correlation of `x` and `y` (Pearson's correlation of their ranks, ties
/// averaged). `None` with fewer than 3 pairs or when either has a single value.
pub fn spearman(x: &[f64], y: &[f64]) -> Option<f64> {
    let n = x.len();
    if n < 3 || y.len() != n {
        return None;
    }
    let (rx, ry) = (ranks(x), ranks(y));
    let mean = (n as f64 + 1.0) / 2.0;
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in rx.iter().zip(&ry) {
        let (a, b) = (a - mean, b - mean);
        sxy += a * b;
        sxx += a * a;
        syy += b * b;
    }
    if sxx == 0.0 || syy == 0.0 {
        return None;
    }
    Some((sxy / (sxx * syy).sqrt()).clamp(-1.0, 1.0))
}

/// An approximate interval of Spearman's rho from `n` pairs: Fisher's z = atanh(rho) with
/// the standard error sqrt(1.06 / (n - 3)) of Fieller, Hartley and Pearson (1957). `None`
/// for n <= 3.
pub fn spearman_interval(rho: f64, n: usize, confidence: f64) -> Option<(f64, f64)> {
    if n <= 3 || !(confidence > 0.0 && confidence < 1.0) {
        return None;
    }
    let q = Normal::standard().inverse_cdf(0.5 + confidence / 2.0);
    let se = (1.06 / (n as f64 - 3.0)).sqrt();
    let z = rho.clamp(-1.0 + 1e-15, 1.0 - 1e-15).atanh();
    Some(((z - q * se).tanh(), (z + q * se).tanh()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clopper_pearson_matches_published_values() {
        // x = 0: the upper end is 1 - (alpha/2)^(1/n)
        let (lo, hi) = clopper_pearson(0, 10, 0.95).unwrap();
        assert_eq!(lo, 0.0);
        assert!((hi - (1.0 - 0.025f64.powf(0.1))).abs() < 1e-12, "{hi}");
        assert!((hi - 0.3085).abs() < 5e-5);
        // x = 5 of 10: [0.1871, 0.8129] (symmetric)
        let (lo, hi) = clopper_pearson(5, 10, 0.95).unwrap();
        assert!(
            (lo - 0.187086).abs() < 1e-6 && (hi - 0.812914).abs() < 1e-6,
            "{lo} {hi}"
        );
        assert!((lo + hi - 1.0).abs() < 1e-12);
        // x = n mirrors x = 0
        let (lo, hi) = clopper_pearson(10, 10, 0.95).unwrap();
        assert!((lo - 0.025f64.powf(0.1)).abs() < 1e-12 && hi == 1.0);
        // 1 of 1000 at 95 %: [2.5317e-5, 5.5589e-3]
        let (lo, hi) = clopper_pearson(1, 1000, 0.95).unwrap();
        assert!((lo / 2.531749e-5 - 1.0).abs() < 1e-5, "{lo}");
        assert!((hi / 5.558924e-3 - 1.0).abs() < 1e-5, "{hi}");
        // 30 of 100 at 90 %: [0.224923, 0.384221] (binomial tails summed exactly)
        let (lo, hi) = clopper_pearson(30, 100, 0.9).unwrap();
        assert!(
            (lo - 0.2249232).abs() < 1e-7 && (hi - 0.3842206).abs() < 1e-7,
            "{lo} {hi}"
        );
        assert!(clopper_pearson(0, 0, 0.95).is_none());
        assert!(clopper_pearson(1, 1, 1.0).is_none());
        // large n stays accurate: the interval brackets x/n and narrows like 1/sqrt(n)
        let (lo, hi) = clopper_pearson(250_000, 1_000_000, 0.95).unwrap();
        let half = 1.959964 * (0.25f64 * 0.75 / 1e6).sqrt();
        assert!((0.25 - lo - half).abs() < 2e-5 && (hi - 0.25 - half).abs() < 2e-5);
    }

    #[test]
    fn spearman_is_one_for_any_increasing_relation_and_handles_ties() {
        let x = [1.0, 2.0, 3.0, 4.0, 5.0];
        let y: Vec<f64> = x.iter().map(|v: &f64| v.powi(3)).collect();
        assert_eq!(spearman(&x, &y), Some(1.0));
        let neg: Vec<f64> = x.iter().map(|v| -v.exp()).collect();
        assert_eq!(spearman(&x, &neg), Some(-1.0));
        assert_eq!(ranks(&[3.0, 1.0, 3.0, 2.0]), vec![3.5, 1.0, 3.5, 2.0]);
        assert_eq!(spearman(&x, &[1.0; 5]), None);
        // a textbook example: rho = 1 - 6 sum d^2 / (n (n^2 - 1)) without ties
        let a = [
            106.0, 86.0, 100.0, 101.0, 99.0, 103.0, 97.0, 113.0, 112.0, 110.0,
        ];
        let b = [7.0, 0.0, 27.0, 50.0, 28.0, 29.0, 20.0, 12.0, 6.0, 17.0];
        assert!((spearman(&a, &b).unwrap() + 29.0 / 165.0).abs() < 1e-12);
        let (lo, hi) = spearman_interval(0.5, 103, 0.95).unwrap();
        assert!(lo < 0.5 && hi > 0.5 && lo > 0.3 && hi < 0.65, "{lo} {hi}");
    }
}
