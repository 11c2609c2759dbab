//! Monotone piecewise-cubic Hermite interpolation after M. Steffen, "A simple method for
//! monotonic interpolation in one dimension", Astron. Astrophys. 239, 443-450 (1990).
//!
//! The slope at an interior node is the slope of the parabola through the node and its two
//! neighbours, limited so that the cubic on each interval stays monotone wherever the data
//! are monotone (zero at a local extremum of the data, at most twice the smaller secant
//! slope otherwise). The interpolant is C1, passes through every node, never overshoots the
//! data (every extremum of the interpolant is a data node) and is local: a node influences
//! only the two intervals on either side of it and their neighbours.

use crate::error::LawError;

/// A Steffen (1990) interpolant y(x) through strictly increasing nodes.
///
/// ```
/// use contact_law::steffen::Steffen;
/// // a near-discontinuity: the interpolant stays within [0, 1] and monotone
/// let s = Steffen::new(&[0.0, 1.0, 1.001, 2.0], &[0.0, 0.0, 1.0, 1.0]).unwrap();
/// let (y, dy) = s.value_and_slope(1.0005);
/// assert!((0.0..=1.0).contains(&y) && dy >= 0.0);
/// assert_eq!(s.value_and_slope(0.5), (0.0, 0.0));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Steffen {
    x: Vec<f64>,
    /// Per interval i: y = c0 + c1 t + c2 t^2 + c3 t^3 with t = x - x_i.
    coef: Vec<[f64; 4]>,
    /// Value and slope at the last node (exact there, not the end of the last cubic).
    last: (f64, f64),
}

/// Sign with sign(0) = 0 (f64::signum gives +1 for +0).
fn sign(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// End-point slope of Steffen's eq. (26)-(27): the parabola through the first three nodes,
/// limited to [0, 2 s0] in the direction of the first secant `s0`.
fn end_slope(s0: f64, s1: f64, h0: f64, h1: f64) -> f64 {
    let p = s0 * (1.0 + h0 / (h0 + h1)) - s1 * h0 / (h0 + h1);
    if p * s0 <= 0.0 {
        0.0
    } else if p.abs() > 2.0 * s0.abs() {
        2.0 * s0
    } else {
        p
    }
}

impl Steffen {
    /// The interpolant through (x_i, y_i). Requires at least two nodes, equal lengths,
    /// finite values and strictly increasing x; fails if a secant slope overflows.
    pub fn new(x: &[f64], y: &[f64]) -> Result<Self, LawError> {
        let n = x.len();
        if n < 2 || y.len() != n {
            return Err(LawError::Invalid {
                name: "interpolation nodes",
                value: format!("{} abscissae, {} values", n, y.len()),
                allowed: "at least two nodes and as many values as abscissae",
            });
        }
        for i in 0..n {
            if !x[i].is_finite() || !y[i].is_finite() {
                return Err(LawError::invalid(
                    "interpolation node",
                    if x[i].is_finite() { y[i] } else { x[i] },
                    "finite",
                ));
            }
            if i > 0 && x[i] <= x[i - 1] {
                return Err(LawError::invalid(
                    "interpolation abscissa",
                    x[i],
                    "strictly increasing",
                ));
            }
        }
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let s: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
        let mut m = vec![0.0; n];
        if n == 2 {
            m[0] = s[0];
            m[1] = s[0];
        } else {
            for i in 1..n - 1 {
                let p = (s[i - 1] * h[i] + s[i] * h[i - 1]) / (h[i - 1] + h[i]);
                m[i] = (sign(s[i - 1]) + sign(s[i]))
                    * s[i - 1].abs().min(s[i].abs()).min(0.5 * p.abs());
            }
            m[0] = end_slope(s[0], s[1], h[0], h[1]);
            m[n - 1] = end_slope(s[n - 2], s[n - 3], h[n - 2], h[n - 3]);
        }
        let mut coef = Vec::with_capacity(n - 1);
        for i in 0..n - 1 {
            let c2 = (3.0 * s[i] - 2.0 * m[i] - m[i + 1]) / h[i];
            let c3 = (m[i] + m[i + 1] - 2.0 * s[i]) / (h[i] * h[i]);
            let c = [y[i], m[i], c2, c3];
            if c.iter().any(|v| !v.is_finite()) {
                return Err(LawError::invalid(
                    "interpolation node",
                    x[i],
                    "nodes whose secant slopes and cubic coefficients are finite (values too large or nodes too close)",
                ));
            }
            coef.push(c);
        }
        Ok(Steffen {
            x: x.to_vec(),
            coef,
            last: (y[n - 1], m[n - 1]),
        })
    }

    /// Value and derivative dy/dx at `t`. Inside [x_0, x_n] this is the interpolant (exactly
    /// the data and the node slope at every node); outside it the end cubic is continued
    /// (the caller decides what the law is there).
    #[inline]
    pub fn value_and_slope(&self, t: f64) -> (f64, f64) {
        let last = self.coef.len() - 1;
        if t == self.x[last + 1] {
            return self.last;
        }
        let i = self
            .x
            .partition_point(|&v| v <= t)
            .saturating_sub(1)
            .min(last);
        let [c0, c1, c2, c3] = self.coef[i];
        let u = t - self.x[i];
        (
            c0 + u * (c1 + u * (c2 + u * c3)),
            c1 + u * (2.0 * c2 + 3.0 * u * c3),
        )
    }

    /// The cubic of interval i: y = c0 + c1 t + c2 t^2 + c3 t^3 with t = x - x_i.
    pub(crate) fn coefficients(&self, i: usize) -> [f64; 4] {
        self.coef[i]
    }

    /// The node abscissae.
    pub fn nodes(&self) -> &[f64] {
        &self.x
    }

    /// First abscissa.
    pub fn start(&self) -> f64 {
        self.x[0]
    }

    /// Last abscissa.
    pub fn end(&self) -> f64 {
        self.x[self.x.len() - 1]
    }

    /// Value at the first node.
    pub fn first_value(&self) -> f64 {
        self.coef[0][0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_a_straight_line_exactly_enough() {
        let x = [0.0, 0.3, 1.0, 1.1, 2.5];
        let y: Vec<f64> = x.iter().map(|v| 2.0 * v - 1.0).collect();
        let s = Steffen::new(&x, &y).unwrap();
        for t in [0.0, 0.1, 0.7, 1.05, 2.0, 2.5] {
            let (v, d) = s.value_and_slope(t);
            assert!((v - (2.0 * t - 1.0)).abs() < 1e-14, "{t}: {v}");
            assert!((d - 2.0).abs() < 1e-13, "{t}: {d}");
        }
    }

    #[test]
    fn passes_through_the_nodes_and_is_c1() {
        let x = [0.0, 0.5, 0.7, 2.0, 3.0];
        let y = [1.0, -2.0, 0.5, 0.4, 3.0];
        let s = Steffen::new(&x, &y).unwrap();
        for i in 0..x.len() {
            assert_eq!(s.value_and_slope(x[i]).0, y[i]);
        }
        // derivative continuous across interior nodes
        for &xi in &x[1..4] {
            let e = 1e-9;
            let l = s.value_and_slope(xi - e).1;
            let r = s.value_and_slope(xi + e).1;
            assert!((l - r).abs() < 1e-6 * (1.0 + l.abs()), "{xi}: {l} {r}");
        }
    }

    #[test]
    fn slope_is_zero_at_a_data_extremum() {
        let s = Steffen::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.5]).unwrap();
        assert_eq!(s.value_and_slope(1.0).1, 0.0);
    }

    #[test]
    fn rejects_bad_nodes() {
        assert!(Steffen::new(&[0.0], &[1.0]).is_err());
        assert!(Steffen::new(&[0.0, 0.0], &[1.0, 2.0]).is_err());
        assert!(Steffen::new(&[0.0, 1.0], &[1.0, f64::NAN]).is_err());
        assert!(Steffen::new(&[0.0, 1.0], &[1.0]).is_err());
        assert!(Steffen::new(&[0.0, 1e-300], &[-1e300, 1e300]).is_err());
    }
}
