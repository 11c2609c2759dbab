//! The stiction boundary (pull-out ratio = 1) of a map: crossing points of a 1-D map, the
//! contour of a 2-D map (marching squares on log10 ratio), and the crossings along the
//! numeric axis for each word of a map over a categorical and a numeric axis.

use crate::grid::Axis;
use crate::map::Map;
use crate::threshold::{CrossingKind, FreeSide};
use serde::Serialize;
use std::collections::HashMap;

/// Where a 1-D map crosses ratio = 1 between two neighbouring evaluated points.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BoundaryPoint {
    /// Estimated critical value: log10 ratio interpolated linearly in the plotted
    /// coordinate (log10 of the value on a log axis); the midpoint next to a point of
    /// ratio 0.
    pub value: f64,
    /// The side (of increasing value) where the ratio is below 1.
    pub free_side: FreeSide,
    /// The two grid values the crossing lies between, ascending.
    pub between: [f64; 2],
    /// `jump` next to a closing point of ratio 0, else `continuous` (a grid cannot tell a
    /// steep crossing from a jump: use a threshold search for that). Between a point that
    /// does not close and one that does there is no crossing: that is a closure boundary,
    /// and the stiction boundary may lie at it or beyond it, which the grid cannot tell.
    pub kind: CrossingKind,
}

/// log10 of the ratio of grid point `i`: `-inf` for ratio 0, `None` if absent or failed.
fn level(map: &Map, i: usize) -> Option<f64> {
    map.point(i).and_then(|p| p.ratio()).map(f64::log10)
}

/// [`level`] along one numeric axis: NaN where the switch does not close (no stiction
/// boundary runs through it or ends on it).
fn level_along(map: &Map, i: usize) -> Option<f64> {
    match map.point(i)?.status {
        crate::point::Status::DoesNotClose => Some(f64::NAN),
        _ => level(map, i),
    }
}

/// Fraction along a -> b where the level crosses 0 (midpoint if either end is infinite).
fn crossing_fraction(la: f64, lb: f64) -> f64 {
    if la.is_finite() && lb.is_finite() {
        la / (la - lb)
    } else {
        0.5
    }
}

/// The crossings of a word of a categorical axis: where the ratio crosses 1 along the
/// numeric axis of a map over a categorical and a numeric axis, with that word fixed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WordBoundary {
    /// The categorical field.
    pub field: String,
    /// Its word.
    pub word: String,
    /// The crossings along the numeric axis, ascending value.
    pub crossings: Vec<BoundaryPoint>,
}

impl Map {
    /// The crossings of ratio = 1 of a 1-D numeric map, ascending value (empty for a 2-D
    /// map, and for a categorical axis: its words have no order to cross along). Failed
    /// points are skipped: a crossing may then span them. A point that does not close
    /// ends the stretch: no crossing spans it or ends on it.
    pub fn boundary_1d(&self) -> Vec<BoundaryPoint> {
        if self.grid().dim() != 1 || self.grid().has_categorical() {
            return Vec::new();
        }
        let axis = &self.grid().axes()[0];
        crossings(
            axis,
            (0..axis.n).filter_map(|i| level_along(self, i).map(|l| (axis.values[i], l))),
        )
    }

    /// For a 2-D map over one categorical and one numeric axis, the crossings of ratio = 1
    /// along the numeric axis for each word, in the order of the words (the boundary of
    /// each law, say); empty for any other map. Computed as [`Map::boundary_1d`] on the
    /// points of each word.
    pub fn boundary_by_word(&self) -> Vec<WordBoundary> {
        let g = self.grid();
        if g.dim() != 2 {
            return Vec::new();
        }
        let (c, x) = match (g.axes()[0].is_categorical(), g.axes()[1].is_categorical()) {
            (true, false) => (0, 1),
            (false, true) => (1, 0),
            _ => return Vec::new(),
        };
        let (cat, num) = (&g.axes()[c], &g.axes()[x]);
        cat.words
            .iter()
            .enumerate()
            .map(|(w, word)| {
                let known = (0..num.n).filter_map(|j| {
                    let mut idx = [0; 2];
                    idx[c] = w;
                    idx[x] = j;
                    level_along(self, g.index(&idx)).map(|l| (num.values[j], l))
                });
                WordBoundary {
                    field: cat.field.clone(),
                    word: word.clone(),
                    crossings: crossings(num, known),
                }
            })
            .collect()
    }
}

/// The crossings of ratio = 1 between neighbouring `(value, log10 ratio)` of a numeric
/// axis, ascending value.
fn crossings(axis: &Axis, known: impl Iterator<Item = (f64, f64)>) -> Vec<BoundaryPoint> {
    let known: Vec<(f64, f64)> = known.collect();
    let mut out: Vec<BoundaryPoint> = known
        .windows(2)
        .filter(|w| !w[0].1.is_nan() && !w[1].1.is_nan())
        .filter(|w| (w[0].1 < 0.0) != (w[1].1 < 0.0))
        .map(|w| {
            let ((xa, la), (xb, lb)) = (w[0], w[1]);
            let (ta, tb) = (axis.plotted(xa), axis.plotted(xb));
            let t = ta + crossing_fraction(la, lb) * (tb - ta);
            let lower_free = if xa < xb { la < 0.0 } else { lb < 0.0 };
            BoundaryPoint {
                value: axis.unplotted(t),
                free_side: if lower_free {
                    FreeSide::Below
                } else {
                    FreeSide::Above
                },
                between: [xa.min(xb), xa.max(xb)],
                kind: if la.is_finite() && lb.is_finite() {
                    CrossingKind::Continuous
                } else {
                    CrossingKind::Jump
                },
            }
        })
        .collect();
    out.sort_by(|a, b| a.value.total_cmp(&b.value));
    out
}

impl Map {
    /// The contour ratio = 1 of a 2-D map as polylines of (first field, second field)
    /// values (empty for a 1-D map, and for a categorical axis: see
    /// [`Map::boundary_by_word`]). Computed by marching squares on log10 ratio with
    /// linear interpolation along cell edges in the plotted coordinates; cells with a
    /// failed or absent corner are skipped; next to a point that does not close the
    /// crossing is put at the edge midpoint.
    pub fn boundary_2d(&self) -> Vec<Vec<(f64, f64)>> {
        if self.grid().dim() != 2 || self.grid().has_categorical() {
            return Vec::new();
        }
        let [ax, ay] = [&self.grid().axes()[0], &self.grid().axes()[1]];
        contour_plotted(self)
            .into_iter()
            .map(|line| {
                line.into_iter()
                    .map(|(tx, ty)| (ax.unplotted(tx), ay.unplotted(ty)))
                    .collect()
            })
            .collect()
    }
}

/// The stiction boundary (ratio = 1) of a 2-D map as polylines, by marching squares in
/// plotted coordinates ([`crate::Axis::plotted`]: log10 for log axes); none over a
/// categorical axis (neighbouring words are not neighbouring values).
pub fn contour_plotted(map: &Map) -> Vec<Vec<(f64, f64)>> {
    let g = map.grid();
    if g.dim() != 2 || g.has_categorical() {
        return Vec::new();
    }
    let [ax, ay] = [&g.axes()[0], &g.axes()[1]];
    let (nx, ny) = (ax.n, ay.n);
    let node = |i: usize, j: usize| g.index(&[i, j]);
    let lv: Vec<Option<f64>> = (0..g.len()).map(|k| level(map, k)).collect();
    let pos = |k: usize| {
        let idx = g.indices(k);
        (ax.plotted(ax.values[idx[0]]), ay.plotted(ay.values[idx[1]]))
    };
    // the crossing point of an edge, always computed from its lower-index node
    let edge_point = |(a, b): (usize, usize)| {
        let (la, lb) = (lv[a].unwrap_or(0.0), lv[b].unwrap_or(0.0));
        let f = crossing_fraction(la, lb);
        let ((xa, ya), (xb, yb)) = (pos(a), pos(b));
        (xa + f * (xb - xa), ya + f * (yb - ya))
    };
    let edge = |a: usize, b: usize| (a.min(b), a.max(b));
    let mut segments: Vec<[(usize, usize); 2]> = Vec::new();
    for i in 0..nx.saturating_sub(1) {
        for j in 0..ny.saturating_sub(1) {
            // corners counter-clockwise: bl, br, tr, tl (x = first axis, y = second)
            let c = [
                node(i, j),
                node(i + 1, j),
                node(i + 1, j + 1),
                node(i, j + 1),
            ];
            let Some(l) = c.iter().map(|&k| lv[k]).collect::<Option<Vec<f64>>>() else {
                continue;
            };
            let inside: Vec<bool> = l.iter().map(|&v| v >= 0.0).collect();
            // edge e connects corner e and corner e+1
            let crossed: Vec<usize> = (0..4)
                .filter(|&e| inside[e] != inside[(e + 1) % 4])
                .collect();
            let e = |k: usize| edge(c[k], c[(k + 1) % 4]);
            match crossed.len() {
                2 => segments.push([e(crossed[0]), e(crossed[1])]),
                4 => {
                    // saddle: the centre (mean level) decides which corners are cut off
                    let centre = l.iter().sum::<f64>() / 4.0 >= 0.0;
                    for (k, &corner) in inside.iter().enumerate() {
                        if corner != centre {
                            // corner k touches edges k-1 and k
                            segments.push([e((k + 3) % 4), e(k)]);
                        }
                    }
                }
                _ => {}
            }
        }
    }
    // chain segments that share an edge into polylines
    let mut at: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for (s, seg) in segments.iter().enumerate() {
        for e in seg {
            at.entry(*e).or_default().push(s);
        }
    }
    let mut used = vec![false; segments.len()];
    let mut lines = Vec::new();
    for s0 in 0..segments.len() {
        if used[s0] {
            continue;
        }
        used[s0] = true;
        let mut chain = std::collections::VecDeque::from(segments[s0].to_vec());
        for forward in [true, false] {
            loop {
                let end = if forward {
                    *chain.back().expect("non-empty")
                } else {
                    *chain.front().expect("non-empty")
                };
                let next = at[&end].iter().copied().find(|&s| !used[s]);
                let Some(s) = next else { break };
                used[s] = true;
                let other = if segments[s][0] == end {
                    segments[s][1]
                } else {
                    segments[s][0]
                };
                if forward {
                    chain.push_back(other);
                } else {
                    chain.push_front(other);
                }
            }
        }
        lines.push(chain.into_iter().map(edge_point).collect());
    }
    lines
}
