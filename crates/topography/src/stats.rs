//! Distribution statistics: skewness, kurtosis, histograms against the Gaussian.

use serde::Serialize;

/// Mean and central moments 2-4 of a sample (population normalisation, 1/n).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Moments4 {
    pub n: usize,
    pub mean: f64,
    pub m2: f64,
    pub m3: f64,
    pub m4: f64,
}

impl Moments4 {
    /// Two-pass moments (the mean first, then the centred powers).
    pub fn of(x: &[f64]) -> Self {
        let n = x.len();
        let nf = n.max(1) as f64;
        let mean = x.iter().sum::<f64>() / nf;
        let (mut m2, mut m3, mut m4) = (0.0, 0.0, 0.0);
        for &v in x {
            let d = v - mean;
            let d2 = d * d;
            m2 += d2;
            m3 += d2 * d;
            m4 += d2 * d2;
        }
        Moments4 {
            n,
            mean,
            m2: m2 / nf,
            m3: m3 / nf,
            m4: m4 / nf,
        }
    }
    /// Standard deviation with the n - 1 divisor.
    pub fn std_sample(&self) -> f64 {
        if self.n < 2 {
            return 0.0;
        }
        (self.m2 * self.n as f64 / (self.n - 1) as f64).sqrt()
    }
    /// Skewness m3 / m2^(3/2) (0 for a Gaussian; 0 if the sample has no spread).
    pub fn skewness(&self) -> f64 {
        if self.m2 > 0.0 {
            self.m3 / self.m2.powf(1.5)
        } else {
            0.0
        }
    }
    /// Kurtosis m4 / m2^2 (Pearson's, 3 for a Gaussian; 3 if the sample has no spread).
    pub fn kurtosis(&self) -> f64 {
        if self.m2 > 0.0 {
            self.m4 / (self.m2 * self.m2)
        } else {
            3.0
        }
    }
}

/// Shape of a distribution of heights.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Shape {
    /// Skewness (0 for a Gaussian).
    pub skewness: f64,
    /// Kurtosis, Pearson's (3 for a Gaussian).
    pub kurtosis: f64,
}

/// Thresholds beyond which a distribution is reported as far from the Gaussian the GW model
/// assumes: |skewness| > 0.5 or |kurtosis - 3| > 1 (rules of thumb: at these values the
/// upper tail that carries the contacts differs from the Gaussian's by tens of percent at
/// 2-3 standard deviations).
pub const SKEWNESS_LIMIT: f64 = 0.5;
/// See [`SKEWNESS_LIMIT`].
pub const EXCESS_KURTOSIS_LIMIT: f64 = 1.0;

impl Shape {
    /// Whether this shape is within the Gaussian limits.
    pub fn is_near_gaussian(&self) -> bool {
        self.skewness.abs() <= SKEWNESS_LIMIT
            && (self.kurtosis - 3.0).abs() <= EXCESS_KURTOSIS_LIMIT
    }
}

/// Skewness and kurtosis of the values.
pub fn shape(x: &[f64]) -> Shape {
    let m = Moments4::of(x);
    Shape {
        skewness: m.skewness(),
        kurtosis: m.kurtosis(),
    }
}

/// A histogram normalised as a probability density, with the Gaussian of the same mean
/// and standard deviation at the bin centres (the distribution the GW model assumes).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Histogram {
    /// Bin centres (m).
    pub centres: Vec<f64>,
    /// Bin width (m).
    pub width: f64,
    /// Probability density of the sample in each bin (1/m).
    pub density: Vec<f64>,
    /// Gaussian density N(mean, std) at the centres (1/m).
    pub gaussian: Vec<f64>,
    /// Mean of the Gaussian (m).
    pub mean: f64,
    /// Standard deviation of the Gaussian (m).
    pub std: f64,
}

/// Histogram of `x` in `bins` equal bins over [min, max], against N(mean, std).
pub fn histogram(x: &[f64], bins: usize, mean: f64, std: f64) -> Histogram {
    let bins = bins.max(1);
    let (lo, hi) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    if x.is_empty() || !(hi > lo) {
        return Histogram {
            centres: Vec::new(),
            width: 0.0,
            density: Vec::new(),
            gaussian: Vec::new(),
            mean,
            std,
        };
    }
    let width = (hi - lo) / bins as f64;
    let mut count = vec![0usize; bins];
    for &v in x {
        let b = (((v - lo) / width) as usize).min(bins - 1);
        count[b] += 1;
    }
    let n = x.len() as f64;
    let centres: Vec<f64> = (0..bins).map(|b| lo + (b as f64 + 0.5) * width).collect();
    let gaussian = centres
        .iter()
        .map(|&c| {
            if std > 0.0 {
                let t = (c - mean) / std;
                (-0.5 * t * t).exp() / (std * (2.0 * std::f64::consts::PI).sqrt())
            } else {
                0.0
            }
        })
        .collect();
    Histogram {
        density: count.iter().map(|&c| c as f64 / (n * width)).collect(),
        centres,
        width,
        gaussian,
        mean,
        std,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moments_of_known_samples() {
        let m = Moments4::of(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(m.mean, 2.5);
        assert!((m.std_sample() - (5.0f64 / 3.0).sqrt()).abs() < 1e-15);
        assert!(m.skewness().abs() < 1e-15);
        // uniform 4-point: m2 = 1.25, m4 = (2*1.5^4 + 2*0.5^4)/4 = 2.5625
        assert!((m.kurtosis() - 2.5625 / 1.5625).abs() < 1e-15);
        let s = shape(&[0.0, 0.0, 0.0, 10.0]);
        assert!(s.skewness > 1.0 && !s.is_near_gaussian());
    }

    #[test]
    fn histogram_integrates_to_one() {
        let x: Vec<f64> = (0..1000).map(|k| (k as f64 * 0.37).sin()).collect();
        let h = histogram(&x, 20, 0.0, 0.7);
        let total: f64 = h.density.iter().sum::<f64>() * h.width;
        assert!((total - 1.0).abs() < 1e-12);
        assert_eq!(h.gaussian.len(), 20);
    }
}
