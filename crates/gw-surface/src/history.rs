/// What a surface remembers: the largest interference delta_max(h) each asperity of
/// initial height h has reached.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum GwHistory {
    /// Loaded only by one flat: delta_max(h) = h - deepest. The whole history is one number.
    Flat {
        /// The deepest separation reached (m; +infinity if never loaded).
        deepest: f64,
    },
    /// Any delta_max(h), tabulated on a height grid.
    Table(HeightTable),
}

impl GwHistory {
    /// A surface never pressed.
    pub const VIRGIN: Self = GwHistory::Flat {
        deepest: f64::INFINITY,
    };

    /// delta_max(h) (m); at or below zero for an asperity never pressed.
    pub fn delta_max(&self, h: f64) -> f64 {
        match self {
            GwHistory::Flat { deepest } => h - deepest,
            GwHistory::Table(t) => t.delta_max(h),
        }
    }

    /// History after the flat reaches separation `d`: delta_max(h) <- max(delta_max(h), h - d).
    pub fn loaded(&self, d: f64) -> Self {
        match self {
            GwHistory::Flat { deepest } => GwHistory::Flat {
                deepest: deepest.min(d),
            },
            GwHistory::Table(t) => GwHistory::Table(t.loaded(d)),
        }
    }

    /// The deepest separation if the history is the one-number form.
    pub fn deepest(&self) -> Option<f64> {
        match self {
            GwHistory::Flat { deepest } => Some(*deepest),
            GwHistory::Table(_) => None,
        }
    }
}

/// delta_max(h) sampled on a uniform height grid, linear in between, and extended by
/// its end values' slopes outside (a straight line of slope 1 for a flat's history).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct HeightTable {
    h0: f64,
    dh: f64,
    values: Vec<f64>,
}

impl HeightTable {
    /// A never-loaded table on `n` (>= 2) heights from `h_lo` to `h_hi` (m).
    pub fn virgin(h_lo: f64, h_hi: f64, n: usize) -> Self {
        let n = n.max(2);
        Self {
            h0: h_lo,
            dh: (h_hi - h_lo) / (n - 1) as f64,
            values: vec![f64::NEG_INFINITY; n],
        }
    }

    /// Interpolated delta_max(h) (m).
    pub fn delta_max(&self, h: f64) -> f64 {
        let x = (h - self.h0) / self.dh;
        let n = self.values.len();
        let i = (x.floor().max(0.0) as usize).min(n - 2);
        let (a, b) = (self.values[i], self.values[i + 1]);
        if a == f64::NEG_INFINITY || b == f64::NEG_INFINITY {
            return if x - i as f64 >= 1.0 {
                b
            } else if x <= i as f64 {
                a
            } else {
                a.min(b)
            };
        }
        a + (b - a) * (x - i as f64)
    }

    /// The table after a flat reaches separation `d`.
    pub fn loaded(&self, d: f64) -> Self {
        let mut t = self.clone();
        for (i, v) in t.values.iter_mut().enumerate() {
            *v = v.max(self.h0 + self.dh * i as f64 - d);
        }
        t
    }
}
