//! The height map: a regular grid of heights in metres.

use serde::Serialize;

use crate::error::{Result, TopographyError};

/// A measured (or generated) surface: `nx` x `ny` heights on a regular grid of spacing
/// `dx`, `dy` (m), row-major: the height at x = i dx, y = j dy is `z[j * nx + i]` (m).
///
/// Construction validates once (sizes, finite positive spacings, finite heights); every
/// analysis then assumes a valid map.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HeightMap {
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    z: Vec<f64>,
}

impl HeightMap {
    /// The smallest grid any analysis accepts in each direction (a summit needs its 8
    /// neighbours, a curvature its two).
    pub const MIN_SIDE: usize = 3;
    /// The finest grid spacing a measured map may have (m): a picometre, below any
    /// instrument's ([`crate::io::read_path`] refuses a file's map outside this range and
    /// [`Self::MAX_SPACING`]; maps built in memory, nondimensional ones included, are free).
    pub const MIN_SPACING: f64 = 1e-12;
    /// The coarsest grid spacing a measured map may have (m): a metre (at 1e308 m the
    /// slopes underflow and the map would read as flat).
    pub const MAX_SPACING: f64 = 1.0;

    /// A map of `nx` x `ny` heights `z` (m, row-major, x fastest) with spacings `dx`, `dy` (m).
    ///
    /// Errors: `nx` or `ny` below [`Self::MIN_SIDE`], `z.len() != nx * ny`, a spacing that is
    /// not finite and positive, or a height that is not finite (the first one is named).
    pub fn new(nx: usize, ny: usize, dx: f64, dy: f64, z: Vec<f64>) -> Result<Self> {
        if nx < Self::MIN_SIDE || ny < Self::MIN_SIDE {
            return Err(TopographyError::param(
                "grid",
                format!("{nx} x {ny}"),
                format!("needs at least {0} x {0} points", Self::MIN_SIDE),
            ));
        }
        let n = nx.checked_mul(ny).ok_or_else(|| {
            TopographyError::param("grid", format!("{nx} x {ny}"), "too many points")
        })?;
        if z.len() != n {
            return Err(TopographyError::param(
                "heights",
                format!("{} values", z.len()),
                format!("a {nx} x {ny} grid needs {n}"),
            ));
        }
        for (name, v) in [("dx", dx), ("dy", dy)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(TopographyError::param(
                    name,
                    format!("{v:e}"),
                    "a grid spacing must be finite and > 0 (m)",
                ));
            }
        }
        if let Some(k) = z.iter().position(|v| !v.is_finite()) {
            let bad = z.iter().filter(|v| !v.is_finite()).count();
            return Err(TopographyError::param(
                "heights",
                z[k],
                format!(
                    "{bad} height(s) are not finite, the first at column {} row {} (0-based); \
                     fill or crop invalid points first",
                    k % nx,
                    k / nx
                ),
            ));
        }
        Ok(HeightMap { nx, ny, dx, dy, z })
    }

    /// Number of points along x (columns).
    pub fn nx(&self) -> usize {
        self.nx
    }
    /// Number of points along y (rows).
    pub fn ny(&self) -> usize {
        self.ny
    }
    /// Grid spacing along x (m).
    pub fn dx(&self) -> f64 {
        self.dx
    }
    /// Grid spacing along y (m).
    pub fn dy(&self) -> f64 {
        self.dy
    }
    /// Heights (m), row-major, x fastest.
    pub fn heights(&self) -> &[f64] {
        &self.z
    }
    /// The heights, consuming the map.
    pub fn into_heights(self) -> Vec<f64> {
        self.z
    }
    /// Height at column `i`, row `j` (m). Panics outside the grid, like slice indexing.
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.z[j * self.nx + i]
    }
    /// Scan size along x, `nx dx` (m): the period of the map seen as periodic.
    pub fn scan_x(&self) -> f64 {
        self.nx as f64 * self.dx
    }
    /// Scan size along y, `ny dy` (m).
    pub fn scan_y(&self) -> f64 {
        self.ny as f64 * self.dy
    }

    /// The same surface with new heights (same grid); used by detrending.
    pub(crate) fn with_heights(&self, z: Vec<f64>) -> Self {
        debug_assert_eq!(z.len(), self.z.len());
        HeightMap {
            nx: self.nx,
            ny: self.ny,
            dx: self.dx,
            dy: self.dy,
            z,
        }
    }

    /// The map coarsened by `factor` by **block averaging**: each `factor` x `factor` block
    /// becomes one point at spacing `factor dx`, `factor dy` (incomplete blocks at the far
    /// edges are dropped). Block averaging models a coarser instrument whose pixel averages
    /// over its area and does not alias wavelengths shorter than the new spacing into the
    /// band (decimation would). `None` if the result would be smaller than
    /// [`Self::MIN_SIDE`] in a direction, or `factor` is 0.
    pub fn coarsen(&self, factor: usize) -> Option<HeightMap> {
        if factor == 0 {
            return None;
        }
        let (mx, my) = (self.nx / factor, self.ny / factor);
        if mx < Self::MIN_SIDE || my < Self::MIN_SIDE {
            return None;
        }
        let mut z = vec![0.0; mx * my];
        let w = 1.0 / (factor * factor) as f64;
        for (jj, out_row) in z.chunks_mut(mx).enumerate() {
            for j in jj * factor..(jj + 1) * factor {
                let row = &self.z[j * self.nx..j * self.nx + mx * factor];
                for (ii, o) in out_row.iter_mut().enumerate() {
                    *o += row[ii * factor..(ii + 1) * factor].iter().sum::<f64>();
                }
            }
            out_row.iter_mut().for_each(|v| *v *= w);
        }
        Some(HeightMap {
            nx: mx,
            ny: my,
            dx: self.dx * factor as f64,
            dy: self.dy * factor as f64,
            z,
        })
    }

    /// The window of `wx` x `wy` points starting at column `i0`, row `j0` (same spacing):
    /// a smaller scan of the same surface. `None` if it does not fit or is below
    /// [`Self::MIN_SIDE`].
    pub fn crop(&self, i0: usize, j0: usize, wx: usize, wy: usize) -> Option<HeightMap> {
        if wx < Self::MIN_SIDE
            || wy < Self::MIN_SIDE
            || i0.checked_add(wx)? > self.nx
            || j0.checked_add(wy)? > self.ny
        {
            return None;
        }
        let mut z = Vec::with_capacity(wx * wy);
        for j in j0..j0 + wy {
            z.extend_from_slice(&self.z[j * self.nx + i0..j * self.nx + i0 + wx]);
        }
        Some(HeightMap {
            nx: wx,
            ny: wy,
            dx: self.dx,
            dy: self.dy,
            z,
        })
    }

    /// Sum surface of two maps on the same grid, `z = z1 + z2` (m).
    ///
    /// For two rough surfaces facing each other, each measured upwards from its own body,
    /// the gap between them is the gap between a flat and this sum surface, so the contact
    /// of the pair is the contact of the sum surface with a flat (the equivalence the GW
    /// model of two rough surfaces rests on). Errors if the grids differ (sizes, or
    /// spacings by more than 1e-9 relative).
    pub fn sum_surface(&self, other: &HeightMap) -> Result<HeightMap> {
        let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
        if self.nx != other.nx
            || self.ny != other.ny
            || !same(self.dx, other.dx)
            || !same(self.dy, other.dy)
        {
            return Err(TopographyError::param(
                "sum surface",
                format!(
                    "{} x {} at {:e} x {:e} m and {} x {} at {:e} x {:e} m",
                    self.nx, self.ny, self.dx, self.dy, other.nx, other.ny, other.dx, other.dy
                ),
                "the two maps must share a grid; otherwise combine their moments (sum_moments)",
            ));
        }
        let z = self.z.iter().zip(&other.z).map(|(a, b)| a + b).collect();
        Ok(self.with_heights(z))
    }

    /// A picture-sized copy, at most `max_side` points on its longer side, by block
    /// averaging (for plots; `max_side` >= 3).
    pub fn downsample(&self, max_side: usize) -> HeightMap {
        let longest = self.nx.max(self.ny);
        let max_side = max_side.max(Self::MIN_SIDE);
        if longest <= max_side {
            return self.clone();
        }
        let factor = longest.div_ceil(max_side);
        self.coarsen(factor).unwrap_or_else(|| self.clone())
    }
}

/// A length unit, as a factor to metres. Parsed from `m`, `mm`, `um` (`µm`, `μm`,
/// `micron`), `nm`, `pm`, `angstrom` (`Å`), or a positive number (the factor itself, e.g.
/// `1e-9`). `A` alone is refused: in Gwyddion files it is the ampere.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LengthUnit {
    /// Metres per unit.
    pub to_metres: f64,
}

impl LengthUnit {
    /// Metres.
    pub const METRE: LengthUnit = LengthUnit { to_metres: 1.0 };

    /// Parses a unit string (case-sensitive for the SI prefixes, surrounding spaces ignored).
    pub fn parse(s: &str) -> Result<Self> {
        let t = s.trim();
        let f = match t {
            "m" | "metre" | "meter" | "metres" | "meters" => 1.0,
            "mm" => 1e-3,
            "um" | "µm" | "μm" | "micron" | "microns" => 1e-6,
            "nm" => 1e-9,
            "pm" => 1e-12,
            "Å" | "angstrom" | "Angstrom" | "ang" => 1e-10,
            _ => match t.parse::<f64>() {
                Ok(v) if v.is_finite() && v > 0.0 => v,
                _ => {
                    return Err(TopographyError::Unit {
                        unit: s.to_string(),
                    });
                }
            },
        };
        Ok(LengthUnit { to_metres: f })
    }

    /// A unit of `to_metres` metres (finite, > 0).
    pub fn factor(to_metres: f64) -> Result<Self> {
        if to_metres.is_finite() && to_metres > 0.0 {
            Ok(LengthUnit { to_metres })
        } else {
            Err(TopographyError::param(
                "unit factor",
                to_metres,
                "must be finite and > 0 (metres per unit)",
            ))
        }
    }
}

/// Parses "1e-8", "1e-8 m", "10 nm", "10nm" into metres.
pub(crate) fn parse_length(s: &str) -> Result<f64> {
    let t = s.trim();
    // The unit is the trailing run of letters (an exponent such as 1e-8 ends in a digit).
    let is_unit_char = |c: char| c.is_alphabetic() || matches!(c, 'µ' | 'μ' | 'Å');
    let split = t
        .char_indices()
        .rev()
        .take_while(|&(_, c)| is_unit_char(c))
        .last()
        .map(|(k, _)| k)
        .unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let v: f64 = num.trim().parse().map_err(|_| {
        TopographyError::param(
            "length",
            s,
            "expected a number with an optional unit, e.g. 1e-8 m or 10 nm",
        )
    })?;
    let u = if unit.trim().is_empty() {
        LengthUnit::METRE
    } else {
        LengthUnit::parse(unit)?
    };
    let m = v * u.to_metres;
    if !(m.is_finite() && m > 0.0) {
        return Err(TopographyError::param(
            "length",
            s,
            "must be finite and > 0",
        ));
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constructor_refuses_bad_maps() {
        assert!(HeightMap::new(2, 5, 1.0, 1.0, vec![0.0; 10]).is_err());
        assert!(HeightMap::new(3, 3, 1.0, 1.0, vec![0.0; 8]).is_err());
        assert!(HeightMap::new(3, 3, 0.0, 1.0, vec![0.0; 9]).is_err());
        assert!(HeightMap::new(3, 3, 1.0, f64::NAN, vec![0.0; 9]).is_err());
        let mut z = vec![0.0; 9];
        z[4] = f64::NAN;
        let e = HeightMap::new(3, 3, 1.0, 1.0, z).unwrap_err().to_string();
        assert!(e.contains("column 1 row 1"), "{e}");
        assert!(HeightMap::new(3, 3, 1.0, 1.0, vec![0.0; 9]).is_ok());
    }

    #[test]
    fn coarsening_averages_blocks_and_scales_spacing() {
        let z: Vec<f64> = (0..8 * 6).map(|k| k as f64).collect();
        let m = HeightMap::new(8, 6, 1.0, 2.0, z).unwrap();
        let c = m.coarsen(2).unwrap();
        assert_eq!((c.nx(), c.ny(), c.dx(), c.dy()), (4, 3, 2.0, 4.0));
        // block (0,0): values 0,1,8,9
        assert_eq!(c.at(0, 0), 4.5);
        assert_eq!(c.at(3, 2), (38.0 + 39.0 + 46.0 + 47.0) / 4.0);
        assert!(m.coarsen(3).is_none()); // 2 x 2 would be too small
    }

    #[test]
    fn units_parse_and_refuse_the_ampere() {
        assert_eq!(LengthUnit::parse("nm").unwrap().to_metres, 1e-9);
        assert_eq!(LengthUnit::parse(" µm ").unwrap().to_metres, 1e-6);
        assert_eq!(LengthUnit::parse("1e-9").unwrap().to_metres, 1e-9);
        assert!(LengthUnit::parse("A").is_err());
        assert!(LengthUnit::parse("V").is_err());
        assert!(LengthUnit::parse("-1").is_err());
        assert_eq!(parse_length("10 nm").unwrap(), 10e-9);
        assert_eq!(parse_length("1e-8").unwrap(), 1e-8);
        assert!((parse_length("2.5um").unwrap() / 2.5e-6 - 1.0).abs() < 1e-15);
        assert_eq!(parse_length("1e-8 m").unwrap(), 1e-8);
        assert!(parse_length("ten nm").is_err());
    }
}
