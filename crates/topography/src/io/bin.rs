//! Bounded reads of fixed-size fields from a byte slice: every accessor returns `None`
//! past the end (no panic, no slicing beyond the data, no overflow of the offset).

/// The bytes of a file, read field by field at absolute offsets.
#[derive(Clone, Copy)]
pub(crate) struct Bin<'a>(pub &'a [u8]);

macro_rules! getter {
    ($name:ident, $t:ty, $n:expr, $from:ident) => {
        pub fn $name(&self, at: usize) -> Option<$t> {
            let s = self.slice(at, $n)?;
            let mut b = [0u8; $n];
            b.copy_from_slice(s);
            Some(<$t>::$from(b))
        }
    };
}

impl<'a> Bin<'a> {
    /// `len` bytes from `at`, if they exist.
    pub fn slice(&self, at: usize, len: usize) -> Option<&'a [u8]> {
        self.0.get(at..at.checked_add(len)?)
    }

    /// Number of bytes.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// A fixed-size text field: bytes up to the first NUL, Latin-1 decoded, trimmed.
    pub fn text(&self, at: usize, len: usize) -> Option<String> {
        let s = self.slice(at, len)?;
        let end = s.iter().position(|&b| b == 0).unwrap_or(s.len());
        Some(latin1(&s[..end]).trim().to_string())
    }

    pub fn u8(&self, at: usize) -> Option<u8> {
        self.0.get(at).copied()
    }

    getter!(u16_le, u16, 2, from_le_bytes);
    getter!(i16_le, i16, 2, from_le_bytes);
    getter!(u32_le, u32, 4, from_le_bytes);
    getter!(i32_le, i32, 4, from_le_bytes);
    getter!(f32_le, f32, 4, from_le_bytes);
    getter!(f64_le, f64, 8, from_le_bytes);
    getter!(u16_be, u16, 2, from_be_bytes);
    getter!(i16_be, i16, 2, from_be_bytes);
    getter!(u32_be, u32, 4, from_be_bytes);
    getter!(f32_be, f32, 4, from_be_bytes);
}

/// Latin-1 bytes as text (every byte is the code point of the same value).
pub(crate) fn latin1(b: &[u8]) -> String {
    b.iter().map(|&c| c as char).collect()
}

/// `a * b * c` as a byte or point count, `None` on overflow.
pub(crate) fn product(factors: &[u64]) -> Option<u64> {
    factors.iter().try_fold(1u64, |acc, &f| acc.checked_mul(f))
}

/// The first position of `needle` in `hay`.
pub(crate) fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    if needle.is_empty() || hay.len() < needle.len() {
        return None;
    }
    hay.windows(needle.len()).position(|w| w == needle)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_past_the_end_are_none() {
        let b = Bin(&[1, 0, 0, 0, 0xff]);
        assert_eq!(b.u32_le(0), Some(1));
        assert_eq!(b.u32_le(2), None);
        assert_eq!(b.u16_le(usize::MAX), None);
        assert_eq!(b.slice(usize::MAX - 1, 4), None);
        assert_eq!(b.u8(4), Some(0xff));
        assert_eq!(product(&[u64::MAX, 2]), None);
        assert_eq!(Bin(b"ab\0cd").text(0, 5).as_deref(), Some("ab"));
        assert_eq!(find(b"xxabc", b"abc"), Some(2));
    }
}
