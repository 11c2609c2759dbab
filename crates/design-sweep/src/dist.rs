//! Distributions of scattered fields (`FIELD=DIST`), their correlations, and the sampler
//! that gives the values of sample `i` from `(seed, i)` alone.

use crate::point::check_field;
use crate::DesignError;
use rand_chacha::rand_core::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use statrs::distribution::{Continuous, ContinuousCDF, LogNormal, Normal, Uniform, Weibull};
use std::fmt;

/// The parameters of a distribution, as the user writes them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DistSpec {
    /// `normal(mean,sd)`: Gaussian with this mean and standard deviation (sd > 0).
    Normal {
        /// Mean.
        mean: f64,
        /// Standard deviation.
        sd: f64,
    },
    /// `lognormal(median,factor)`: ln X is Gaussian with mean ln(median) and standard
    /// deviation sigma = ln(factor) (factor > 1: the multiplicative scatter, X/median lies
    /// within [1/factor, factor] with probability 68 %).
    LogNormal {
        /// Median, exp(mu) (> 0).
        median: f64,
        /// exp(sigma) (> 1).
        factor: f64,
    },
    /// `uniform(lo,hi)`: flat on [lo, hi] (lo < hi).
    Uniform {
        /// Lower end.
        lo: f64,
        /// Upper end.
        hi: f64,
    },
    /// `weibull(scale,shape)`: F(x) = 1 - exp(-(x/scale)^shape), x >= 0 (both > 0).
    Weibull {
        /// Scale lambda (the 63.2 % quantile).
        scale: f64,
        /// Shape k (the Weibull modulus).
        shape: f64,
    },
}

/// A validated distribution of one field: the parameters and the `statrs` distribution
/// built from them. Sampling is by inverse CDF ([`Dist::quantile`]) on seeded uniforms.
#[derive(Debug, Clone, PartialEq)]
pub struct Dist {
    spec: DistSpec,
    law: Law,
}

#[derive(Debug, Clone, PartialEq)]
enum Law {
    Normal(Normal),
    LogNormal(LogNormal),
    Uniform(Uniform),
    Weibull(Weibull),
}

/// The names `DIST` may take, for messages.
pub const DISTRIBUTIONS: &str =
    "normal(mean,sd), lognormal(median,factor), uniform(lo,hi), weibull(scale,shape)";

/// A number as echoes and messages write it: shortest round-trip digits, in scientific
/// notation outside [1e-3, 1e6).
pub(crate) fn short(v: f64) -> String {
    if v == 0.0 || (1e-3..1e6).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

impl Dist {
    /// A validated distribution. Every parameter must be finite; `sd > 0`; `median > 0`,
    /// `factor > 1`; `lo < hi`; `scale > 0`, `shape > 0`.
    pub fn new(spec: DistSpec) -> Result<Dist, String> {
        let finite = |name: &str, v: f64| {
            if v.is_finite() {
                Ok(())
            } else {
                Err(format!("{name} = {v} must be a finite number"))
            }
        };
        let positive = |name: &str, v: f64| {
            finite(name, v)?;
            if v > 0.0 {
                Ok(())
            } else {
                Err(format!("{name} = {} must be > 0", short(v)))
            }
        };
        let statrs_err = |e: String| format!("statrs refused the parameters: {e}");
        let law = match spec {
            DistSpec::Normal { mean, sd } => {
                finite("mean", mean)?;
                positive("sd", sd)?;
                Law::Normal(Normal::new(mean, sd).map_err(|e| statrs_err(e.to_string()))?)
            }
            DistSpec::LogNormal { median, factor } => {
                positive("median", median)?;
                finite("factor", factor)?;
                if !(factor > 1.0) {
                    return Err(format!(
                        "factor = {} must be > 1 (factor = exp(sigma): 1.2 is a 20 % scatter, 1 none)",
                        short(factor)
                    ));
                }
                Law::LogNormal(
                    LogNormal::new(median.ln(), factor.ln())
                        .map_err(|e| statrs_err(e.to_string()))?,
                )
            }
            DistSpec::Uniform { lo, hi } => {
                finite("lo", lo)?;
                finite("hi", hi)?;
                if !(lo < hi) {
                    return Err(format!(
                        "lo = {} must be below hi = {}",
                        short(lo),
                        short(hi)
                    ));
                }
                if !(hi - lo).is_finite() {
                    return Err("hi - lo overflows".into());
                }
                Law::Uniform(Uniform::new(lo, hi).map_err(|e| statrs_err(e.to_string()))?)
            }
            DistSpec::Weibull { scale, shape } => {
                positive("scale", scale)?;
                positive("shape", shape)?;
                Law::Weibull(Weibull::new(shape, scale).map_err(|e| statrs_err(e.to_string()))?)
            }
        };
        Ok(Dist { spec, law })
    }

    /// Parses `normal(mean,sd)`, `lognormal(median,factor)`, `uniform(lo,hi)` or
    /// `weibull(scale,shape)` (names in any case, spaces allowed, numbers in SI).
    pub fn parse(text: &str) -> Result<Dist, String> {
        let t = text.trim();
        let bad = |why: &str| format!("`{t}`: {why}; expected one of {DISTRIBUTIONS}");
        let (name, rest) = t
            .split_once('(')
            .ok_or_else(|| bad("no parameters in parentheses"))?;
        let inner = rest
            .trim_end()
            .strip_suffix(')')
            .ok_or_else(|| bad("no closing parenthesis"))?;
        let args: Vec<&str> = inner.split(',').map(str::trim).collect();
        let name = name.trim().to_ascii_lowercase();
        let params: [&str; 2] = match name.as_str() {
            "normal" => ["mean", "sd"],
            "lognormal" => ["median", "factor"],
            "uniform" => ["lo", "hi"],
            "weibull" => ["scale", "shape"],
            _ => return Err(bad(&format!("unknown distribution `{name}`"))),
        };
        if args.len() != 2 {
            return Err(bad(&format!(
                "{name} takes 2 parameters ({}, {}), {} given",
                params[0],
                params[1],
                args.len()
            )));
        }
        let mut v = [0.0; 2];
        for (k, a) in args.iter().enumerate() {
            v[k] = a
                .parse::<f64>()
                .map_err(|_| bad(&format!("{} `{a}` is not a number", params[k])))?;
        }
        let spec = match name.as_str() {
            "normal" => DistSpec::Normal {
                mean: v[0],
                sd: v[1],
            },
            "lognormal" => DistSpec::LogNormal {
                median: v[0],
                factor: v[1],
            },
            "uniform" => DistSpec::Uniform { lo: v[0], hi: v[1] },
            _ => DistSpec::Weibull {
                scale: v[0],
                shape: v[1],
            },
        };
        Dist::new(spec).map_err(|e| format!("`{t}`: {e}"))
    }

    /// The parameters.
    pub fn spec(&self) -> DistSpec {
        self.spec
    }

    /// The inverse CDF at `p` in (0, 1) (`statrs`' `inverse_cdf`).
    pub fn quantile(&self, p: f64) -> f64 {
        match &self.law {
            Law::Normal(d) => d.inverse_cdf(p),
            Law::LogNormal(d) => d.inverse_cdf(p),
            Law::Uniform(d) => d.inverse_cdf(p),
            Law::Weibull(d) => d.inverse_cdf(p),
        }
    }

    /// P(X <= x).
    pub fn cdf(&self, x: f64) -> f64 {
        match &self.law {
            Law::Normal(d) => d.cdf(x),
            Law::LogNormal(d) => d.cdf(x),
            Law::Uniform(d) => d.cdf(x),
            Law::Weibull(d) => d.cdf(x),
        }
    }

    /// P(X > x), computed without cancellation in the upper tail.
    pub fn sf(&self, x: f64) -> f64 {
        match &self.law {
            Law::Normal(d) => d.sf(x),
            Law::LogNormal(d) => d.sf(x),
            Law::Uniform(d) => d.sf(x),
            Law::Weibull(d) => d.sf(x),
        }
    }

    /// The density at `x`.
    pub fn pdf(&self, x: f64) -> f64 {
        match &self.law {
            Law::Normal(d) => d.pdf(x),
            Law::LogNormal(d) => d.pdf(x),
            Law::Uniform(d) => d.pdf(x),
            Law::Weibull(d) => d.pdf(x),
        }
    }

    /// The mass below `lo` plus the mass above `hi` (the distribution's mass outside a
    /// domain; `hi` may be infinite).
    pub fn mass_outside(&self, lo: f64, hi: f64) -> f64 {
        let below = if lo == f64::NEG_INFINITY {
            0.0
        } else {
            self.cdf(lo)
        };
        let above = if hi == f64::INFINITY {
            0.0
        } else {
            self.sf(hi)
        };
        below + above
    }

    /// The value whose normal score is `z`: F^-1(Phi(z)), computed without the round trip
    /// where a closed form exists (normal, lognormal) and from the tail that keeps its
    /// digits otherwise. Used for correlated fields (Gaussian copula).
    pub fn from_normal_score(&self, z: f64) -> f64 {
        let std = Normal::standard();
        match self.spec {
            DistSpec::Normal { mean, sd } => mean + sd * z,
            DistSpec::LogNormal { median, factor } => (median.ln() + factor.ln() * z).exp(),
            DistSpec::Uniform { lo, hi } => {
                if z <= 0.0 {
                    lo + (hi - lo) * std.cdf(z)
                } else {
                    hi - (hi - lo) * std.cdf(-z)
                }
            }
            DistSpec::Weibull { scale, shape } => {
                // -ln(1 - F) = -ln(Phi(-z))
                let h = if z <= 0.0 {
                    -(-std.cdf(z)).ln_1p()
                } else {
                    -std.cdf(-z).ln()
                };
                scale * h.powf(1.0 / shape)
            }
        }
    }
}

impl fmt::Display for Dist {
    /// The canonical text, which [`Dist::parse`] reads back to the same bits.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (name, a, b) = match self.spec {
            DistSpec::Normal { mean, sd } => ("normal", mean, sd),
            DistSpec::LogNormal { median, factor } => ("lognormal", median, factor),
            DistSpec::Uniform { lo, hi } => ("uniform", lo, hi),
            DistSpec::Weibull { scale, shape } => ("weibull", scale, shape),
        };
        write!(f, "{name}({},{})", short(a), short(b))
    }
}

/// One scattered field: `FIELD=DIST`.
#[derive(Debug, Clone, PartialEq)]
pub struct Scatter {
    /// The scene key, `section.key`.
    pub field: String,
    /// Its distribution.
    pub dist: Dist,
}

impl Scatter {
    /// Parses `FIELD=DIST`, e.g. `surface.sigma_s=lognormal(7.78e-9,1.2)`.
    pub fn parse(option: &str) -> Result<Scatter, DesignError> {
        let err = |reason: String| DesignError::Scatter {
            option: option.to_owned(),
            reason,
        };
        let (field, dist) = option.split_once('=').ok_or_else(|| {
            err(format!(
                "expected FIELD=DIST with DIST one of {DISTRIBUTIONS}"
            ))
        })?;
        let field = field.trim();
        check_field(field).map_err(err)?;
        let dist = Dist::parse(dist).map_err(|e| err(format!("{field}: {e}")))?;
        Ok(Scatter {
            field: field.to_owned(),
            dist,
        })
    }
}

impl fmt::Display for Scatter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}={}", self.field, self.dist)
    }
}

/// A correlation between two scattered fields: `A,B=RHO`, the correlation of their normal
/// scores (a Gaussian copula: for normal fields the correlation of the values, for
/// lognormal ones that of their logarithms; Spearman's rank correlation is then
/// (6/pi) asin(rho/2)).
#[derive(Debug, Clone, PartialEq)]
pub struct Correlation {
    /// First field.
    pub a: String,
    /// Second field.
    pub b: String,
    /// Correlation of the normal scores, in (-1, 1).
    pub rho: f64,
}

impl Correlation {
    /// Parses `A,B=RHO`, e.g. `surface.sigma_s,contact.work_of_adhesion=-0.5`.
    pub fn parse(option: &str) -> Result<Correlation, DesignError> {
        let err = |reason: String| DesignError::Correlation {
            option: option.to_owned(),
            reason,
        };
        let (pair, rho) = option.split_once('=').ok_or_else(|| {
            err("expected A,B=RHO (two scattered fields and a correlation in (-1, 1))".into())
        })?;
        let (a, b) = pair
            .split_once(',')
            .ok_or_else(|| err("expected A,B=RHO: two fields separated by a comma".into()))?;
        let (a, b) = (a.trim(), b.trim());
        check_field(a).map_err(err)?;
        check_field(b).map_err(err)?;
        if a == b {
            return Err(err(format!("{a} is correlated with itself")));
        }
        let rho: f64 = rho
            .trim()
            .parse()
            .map_err(|_| err(format!("RHO `{}` is not a number", rho.trim())))?;
        if !(rho > -1.0 && rho < 1.0) {
            return Err(err(format!(
                "RHO = {rho} must be in (-1, 1) (a correlation of +-1 makes one field a function of the other: scatter one and derive the other in the scene)"
            )));
        }
        Ok(Correlation {
            a: a.to_owned(),
            b: b.to_owned(),
            rho,
        })
    }
}

impl fmt::Display for Correlation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{},{}={}", self.a, self.b, self.rho)
    }
}

/// The values of every sample: sample `i` of seed `s` depends on `(s, i)` alone, so any
/// subset of samples (a shard, a run stopped early) holds exactly the values of the same
/// samples of a full run, on any machine and thread count.
///
/// Uniforms: a ChaCha8 stream (`rand_chacha`) keyed by the seed (its 8 little-endian
/// bytes, the rest of the key zero) with stream number `i`; one 64-bit word per field in
/// the order given, u = (top 53 bits + 1/2) / 2^53, strictly inside (0, 1). A field in no
/// correlation takes F^-1(u) ([`Dist::quantile`]); correlated fields take normal scores
/// z = Phi^-1(u), mixed by the Cholesky factor of their correlation matrix, each turned
/// back by [`Dist::from_normal_score`].
#[derive(Debug, Clone, PartialEq)]
pub struct Sampler {
    scatter: Vec<Scatter>,
    seed: u64,
    /// Lower-triangular Cholesky factor of the correlation matrix, when any field is
    /// correlated; `correlated[j]` says whether field j takes part.
    cholesky: Option<Vec<Vec<f64>>>,
    correlated: Vec<bool>,
}

impl Sampler {
    /// A sampler of `scatter` (distinct fields) with `correlations` between them.
    pub fn new(
        scatter: &[Scatter],
        correlations: &[Correlation],
        seed: u64,
    ) -> Result<Sampler, DesignError> {
        let k = scatter.len();
        if k == 0 {
            return Err(DesignError::Probability(
                "no scattered field: give at least one --scatter FIELD=DIST".into(),
            ));
        }
        for (j, s) in scatter.iter().enumerate() {
            if scatter[..j].iter().any(|t| t.field == s.field) {
                return Err(DesignError::Scatter {
                    option: s.to_string(),
                    reason: format!("{} is scattered twice", s.field),
                });
            }
        }
        let pos = |c: &Correlation, f: &str| {
            scatter
                .iter()
                .position(|s| s.field == f)
                .ok_or_else(|| DesignError::Correlation {
                    option: c.to_string(),
                    reason: format!(
                        "{f} is not a scattered field (give it a --scatter first; scattered: {})",
                        scatter
                            .iter()
                            .map(|s| s.field.as_str())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                })
        };
        let mut c = vec![vec![0.0; k]; k];
        for (j, row) in c.iter_mut().enumerate() {
            row[j] = 1.0;
        }
        let mut correlated = vec![false; k];
        for (n, cor) in correlations.iter().enumerate() {
            let (a, b) = (pos(cor, &cor.a)?, pos(cor, &cor.b)?);
            if correlations[..n]
                .iter()
                .any(|o| (o.a == cor.a && o.b == cor.b) || (o.a == cor.b && o.b == cor.a))
            {
                return Err(DesignError::Correlation {
                    option: cor.to_string(),
                    reason: format!("{} and {} are correlated twice", cor.a, cor.b),
                });
            }
            c[a][b] = cor.rho;
            c[b][a] = cor.rho;
            correlated[a] = true;
            correlated[b] = true;
        }
        let cholesky = if correlations.is_empty() {
            None
        } else {
            Some(cholesky(&c).ok_or_else(|| {
                DesignError::Probability(format!(
                    "the correlations {} do not make a correlation matrix (it is not positive definite): lower their magnitudes",
                    correlations
                        .iter()
                        .map(|c| c.to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                ))
            })?)
        };
        Ok(Sampler {
            scatter: scatter.to_vec(),
            seed,
            cholesky,
            correlated,
        })
    }

    /// The scattered fields, in order.
    pub fn scatter(&self) -> &[Scatter] {
        &self.scatter
    }

    /// The uniforms of sample `index`, one per field, in (0, 1).
    pub fn uniforms(&self, index: usize) -> Vec<f64> {
        let mut key = [0u8; 32];
        key[..8].copy_from_slice(&self.seed.to_le_bytes());
        let mut rng = ChaCha8Rng::from_seed(key);
        rng.set_stream(index as u64);
        (0..self.scatter.len())
            .map(|_| ((rng.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64))
            .collect()
    }

    /// The field values of sample `index`, in the order of the scattered fields.
    pub fn values(&self, index: usize) -> Vec<f64> {
        let u = self.uniforms(index);
        let Some(l) = &self.cholesky else {
            return self
                .scatter
                .iter()
                .zip(&u)
                .map(|(s, &u)| s.dist.quantile(u))
                .collect();
        };
        let std = Normal::standard();
        let z: Vec<f64> = u.iter().map(|&u| std.inverse_cdf(u)).collect();
        self.scatter
            .iter()
            .enumerate()
            .map(|(j, s)| {
                if self.correlated[j] {
                    let y: f64 = (0..=j).map(|m| l[j][m] * z[m]).sum();
                    s.dist.from_normal_score(y)
                } else {
                    s.dist.quantile(u[j])
                }
            })
            .collect()
    }
}

/// The lower Cholesky factor of a symmetric matrix, `None` unless positive definite (each
/// pivot above 1e-10).
fn cholesky(c: &[Vec<f64>]) -> Option<Vec<Vec<f64>>> {
    let k = c.len();
    let mut l = vec![vec![0.0; k]; k];
    for i in 0..k {
        for j in 0..=i {
            let s: f64 = (0..j).map(|m| l[i][m] * l[j][m]).sum();
            if i == j {
                let d = c[i][i] - s;
                if !(d > 1e-10) {
                    return None;
                }
                l[i][j] = d.sqrt();
            } else {
                l[i][j] = (c[i][j] - s) / l[j][j];
            }
        }
    }
    Some(l)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distributions_parse_validate_and_print_back_to_the_same_bits() {
        for t in [
            "normal(1.5,0.2)",
            "lognormal(7.78e-9,1.2)",
            "uniform(-3,4.25)",
            "weibull(2.5e8,12)",
            "normal(1e20,3e19)",
        ] {
            let d = Dist::parse(t).unwrap();
            assert_eq!(d.to_string(), t);
            assert_eq!(Dist::parse(&d.to_string()).unwrap(), d);
        }
        assert_eq!(
            Dist::parse(" LogNormal( 2e-9 , 1.5 ) ")
                .unwrap()
                .to_string(),
            "lognormal(2e-9,1.5)"
        );
        for (t, frag) in [
            ("normal(1,0)", "sd = 0 must be > 0"),
            ("normal(1,-2)", "must be > 0"),
            ("lognormal(-1,2)", "median"),
            ("lognormal(1,1)", "factor = 1 must be > 1"),
            ("uniform(2,1)", "must be below"),
            ("weibull(1,0)", "shape"),
            ("gamma(1,2)", "unknown distribution `gamma`"),
            ("normal(1)", "2 parameters"),
            ("normal(1,x)", "sd `x` is not a number"),
            ("normal(nan,1)", "finite"),
            ("normal 1,2", "no parameters"),
        ] {
            let e = Dist::parse(t).unwrap_err();
            assert!(e.contains(frag), "{t}: {e}");
        }
    }

    #[test]
    fn quantiles_invert_the_cdf_and_normal_scores_agree_with_them() {
        let std = Normal::standard();
        for t in [
            "normal(3,2)",
            "lognormal(7.78e-9,1.2)",
            "uniform(-1,3)",
            "weibull(2,1.7)",
        ] {
            let d = Dist::parse(t).unwrap();
            for p in [1e-9, 0.01, 0.3, 0.5, 0.77, 0.999] {
                let x = d.quantile(p);
                assert!((d.cdf(x) - p).abs() < 1e-9 * p.max(1e-3), "{t} {p}");
                let y = d.from_normal_score(std.inverse_cdf(p));
                assert!(
                    (y - x).abs() <= 1e-9 * x.abs().max(1.0),
                    "{t} {p}: {y} vs {x}"
                );
            }
        }
        let ln = Dist::parse("lognormal(2,1.5)").unwrap();
        assert!((ln.quantile(0.5) - 2.0).abs() < 1e-12);
        assert!(
            (ln.cdf(3.0) - std.cdf(1.0)).abs() < 1e-12,
            "factor = exp(sigma)"
        );
        let w = Dist::parse("weibull(2,3)").unwrap();
        assert!((w.cdf(2.0) - (1.0 - (-1.0f64).exp())).abs() < 1e-14);
        assert!((w.mass_outside(1.0, f64::INFINITY) - (1.0 - (-0.125f64).exp())).abs() < 1e-14);
    }

    #[test]
    fn sample_values_depend_on_seed_and_index_alone() {
        let s = vec![
            Scatter::parse("a.x=normal(0,1)").unwrap(),
            Scatter::parse("a.y=uniform(0,1)").unwrap(),
        ];
        let one = Sampler::new(&s, &[], 7).unwrap();
        let two = Sampler::new(&s, &[], 7).unwrap();
        assert_eq!(one.values(12345), two.values(12345));
        assert_ne!(one.values(1), one.values(2));
        assert_ne!(
            one.values(1),
            Sampler::new(&s, &[], 8).unwrap().values(1),
            "the seed matters"
        );
        // the first field's value does not depend on how many fields follow
        let first = Sampler::new(&s[..1], &[], 7).unwrap();
        assert_eq!(first.values(99)[0], one.values(99)[0]);
        for i in 0..1000 {
            for u in one.uniforms(i) {
                assert!(u > 0.0 && u < 1.0);
            }
        }
    }

    /// The values drawn follow each field's distribution: the Kolmogorov-Smirnov distance
    /// between 20 000 draws and the CDF is below its 1 % critical value 1.63/sqrt(n), and the
    /// empirical quantiles land on the distribution's (so nothing is clipped or truncated).
    #[test]
    fn drawn_values_follow_each_distribution() {
        let s: Vec<Scatter> = [
            "a.n=normal(3,2)",
            "a.l=lognormal(7.78e-9,1.2)",
            "a.u=uniform(-1,3)",
            "a.w=weibull(2.5e8,12)",
        ]
        .iter()
        .map(|t| Scatter::parse(t).unwrap())
        .collect();
        let sam = Sampler::new(&s, &[], 11).unwrap();
        let n = 20_000;
        let mut columns = vec![Vec::with_capacity(n); s.len()];
        for i in 0..n {
            for (c, v) in columns.iter_mut().zip(sam.values(i)) {
                c.push(v);
            }
        }
        let critical = 1.63 / (n as f64).sqrt();
        for (sc, c) in s.iter().zip(columns.iter_mut()) {
            c.sort_by(f64::total_cmp);
            let d = c
                .iter()
                .enumerate()
                .map(|(i, &x)| {
                    let f = sc.dist.cdf(x);
                    (f - i as f64 / n as f64).max((i + 1) as f64 / n as f64 - f)
                })
                .fold(0.0f64, f64::max);
            assert!(d < critical, "{}: KS distance {d} >= {critical}", sc.field);
            // the extremes stay where the distribution puts them
            for p in [0.01, 0.5, 0.99] {
                let q = c[(p * n as f64) as usize];
                let f = sc.dist.cdf(q);
                assert!(
                    (f - p).abs() < 4.0 * (p * (1.0 - p) / n as f64).sqrt() + 1e-4,
                    "{}: {p} {f}",
                    sc.field
                );
            }
        }
    }

    #[test]
    fn correlated_normal_scores_have_the_requested_correlation() {
        let s = vec![
            Scatter::parse("a.x=normal(0,1)").unwrap(),
            Scatter::parse("a.y=lognormal(1,2)").unwrap(),
            Scatter::parse("a.z=uniform(0,1)").unwrap(),
        ];
        let c = vec![Correlation::parse("a.y,a.x=-0.6").unwrap()];
        let sam = Sampler::new(&s, &c, 3).unwrap();
        let n = 20000;
        let (mut sxy, mut sxx, mut syy, mut sx, mut sy) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let plain = Sampler::new(&s, &[], 3).unwrap();
        for i in 0..n {
            let v = sam.values(i);
            // the uncorrelated field keeps the values of an uncorrelated run
            assert_eq!(v[2], plain.values(i)[2]);
            let (x, y) = (v[0], v[1].ln() / 2f64.ln());
            sx += x;
            sy += y;
            sxy += x * y;
            sxx += x * x;
            syy += y * y;
        }
        let nf = n as f64;
        let r = (sxy / nf - sx * sy / nf / nf)
            / ((sxx / nf - (sx / nf).powi(2)) * (syy / nf - (sy / nf).powi(2))).sqrt();
        assert!((r + 0.6).abs() < 0.02, "r = {r}");
        let bad = Sampler::new(
            &s,
            &[
                Correlation::parse("a.x,a.y=0.9").unwrap(),
                Correlation::parse("a.x,a.z=0.9").unwrap(),
                Correlation::parse("a.y,a.z=-0.9").unwrap(),
            ],
            1,
        )
        .unwrap_err();
        assert!(bad.to_string().contains("not positive definite"), "{bad}");
        let e = Sampler::new(&s, &[Correlation::parse("a.x,b.q=0.1").unwrap()], 1).unwrap_err();
        assert!(
            e.to_string().contains("b.q is not a scattered field"),
            "{e}"
        );
        assert!(Correlation::parse("a.x,a.y=1").is_err());
        assert!(Correlation::parse("a.x,a.x=0.5").is_err());
    }
}
