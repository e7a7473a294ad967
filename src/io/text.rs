//! Line and token scanning for the text formats, with fast number parsing.
//!
//! Numbers are parsed from bytes without building strings. Decimal numbers
//! of at most 19 significant digits and a small exponent take an exact fast
//! path: when the mantissa fits 53 bits, it and the power of ten are both
//! exact `f64`, so one correctly rounded division or multiplication gives
//! the correctly rounded result; a longer mantissa (the 17 digits of a
//! shortest round-trip float) over a power of ten is divided in 128-bit
//! integers and rounded once. Anything else goes to the standard library's
//! parser. Tests compare every path with it.

use super::error::{Error, Location};

/// Lines of a byte buffer, numbered from 1, without their `\n` or `\r\n`.
pub(crate) struct Lines<'a> {
    data: &'a [u8],
    pos: usize,
    /// Number of the line last returned.
    pub(crate) line: u64,
}

impl<'a> Lines<'a> {
    pub(crate) fn new(data: &'a [u8]) -> Lines<'a> {
        Lines {
            data,
            pos: 0,
            line: 0,
        }
    }

    /// Bytes not yet returned.
    pub(crate) fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }

    /// Byte offset of the next line.
    pub(crate) fn offset(&self) -> usize {
        self.pos
    }

    /// The location of the line last returned.
    pub(crate) fn here(&self) -> Location {
        Location::line(self.line.max(1))
    }

    /// The location just after the last line (for "unexpected end").
    pub(crate) fn end(&self) -> Location {
        Location::line(self.line + 1)
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = &'a [u8];

    #[inline]
    fn next(&mut self) -> Option<&'a [u8]> {
        if self.pos >= self.data.len() {
            return None;
        }
        let rest = &self.data[self.pos..];
        let len = find_newline(rest);
        let (line, step) = match len {
            Some(n) => (&rest[..n], n + 1),
            None => (rest, rest.len()),
        };
        self.pos += step;
        self.line += 1;
        Some(line.strip_suffix(b"\r").unwrap_or(line))
    }
}

/// The index of the first `\n`, eight bytes at a time.
#[inline]
fn find_newline(s: &[u8]) -> Option<usize> {
    const ONES: u64 = 0x0101_0101_0101_0101;
    const HIGHS: u64 = 0x8080_8080_8080_8080;
    const NL: u64 = ONES * b'\n' as u64;
    let mut chunks = s.chunks_exact(8);
    let mut base = 0;
    for chunk in chunks.by_ref() {
        let mut w = [0u8; 8];
        w.copy_from_slice(chunk);
        let x = u64::from_le_bytes(w) ^ NL;
        if (x.wrapping_sub(ONES) & !x & HIGHS) != 0 {
            return chunk.iter().position(|&b| b == b'\n').map(|i| base + i);
        }
        base += 8;
    }
    chunks
        .remainder()
        .iter()
        .position(|&b| b == b'\n')
        .map(|i| base + i)
}

#[inline]
pub(crate) fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\r' | b'\x0b' | b'\x0c')
}

/// Whitespace-separated tokens of one line.
#[derive(Clone)]
pub(crate) struct Tokens<'a> {
    s: &'a [u8],
    i: usize,
}

impl<'a> Tokens<'a> {
    pub(crate) fn new(s: &'a [u8]) -> Tokens<'a> {
        Tokens { s, i: 0 }
    }
}

impl<'a> Iterator for Tokens<'a> {
    type Item = &'a [u8];

    #[inline]
    fn next(&mut self) -> Option<&'a [u8]> {
        let s = self.s;
        let mut i = self.i;
        while i < s.len() && is_space(s[i]) {
            i += 1;
        }
        if i == s.len() {
            self.i = i;
            return None;
        }
        let start = i;
        while i < s.len() && !is_space(s[i]) {
            i += 1;
        }
        self.i = i;
        Some(&s[start..i])
    }
}

/// The line without a `#` comment and surrounding whitespace.
#[inline]
pub(crate) fn strip_comment(line: &[u8]) -> &[u8] {
    let line = match line.iter().position(|&b| b == b'#') {
        Some(i) => &line[..i],
        None => line,
    };
    line.trim_ascii()
}

const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Skip an optional sign at `s[*i]`; whether it was a minus.
#[inline(always)]
fn take_sign(s: &[u8], i: &mut usize) -> bool {
    match s.get(*i) {
        Some(b'-') => {
            *i += 1;
            true
        }
        Some(b'+') => {
            *i += 1;
            false
        }
        _ => false,
    }
}

/// Parse the number that starts at `s[*i]` and ends at whitespace, a line
/// end or the end of `s`; on success `*i` moves past it. One pass over its
/// bytes in the common case (the exact fast path); otherwise the token is
/// cut out and parsed like [`parse_f64`].
#[inline]
pub(crate) fn parse_f64_at(s: &[u8], i: &mut usize) -> Option<f64> {
    let start = *i;
    let mut j = start;
    let neg = take_sign(s, &mut j);
    let mut mant: u64 = 0;
    let mut digits = 0u32;
    let mut any = false;
    let mut exp: i64 = 0;
    while let Some(&b) = s.get(j) {
        let d = b.wrapping_sub(b'0');
        if d > 9 {
            break;
        }
        digits += u32::from(digits > 0 || d != 0);
        mant = mant.wrapping_mul(10).wrapping_add(u64::from(d));
        any = true;
        j += 1;
    }
    if s.get(j) == Some(&b'.') {
        j += 1;
        while let Some(&b) = s.get(j) {
            let d = b.wrapping_sub(b'0');
            if d > 9 {
                break;
            }
            digits += u32::from(digits > 0 || d != 0);
            mant = mant.wrapping_mul(10).wrapping_add(u64::from(d));
            exp -= 1;
            any = true;
            j += 1;
        }
    }
    let ends = |j: usize| s.get(j).is_none_or(|&b| is_space(b) || b == b'\n');
    if any && digits <= 19 && (-22..=0).contains(&exp) && ends(j) {
        let v = if mant <= (1u64 << 53) {
            let m = mant as f64;
            if exp == 0 {
                m
            } else {
                m / POW10[(-exp) as usize]
            }
        } else if (-21..0).contains(&exp) {
            div_pow10(mant, (-exp) as u32)
        } else {
            f64::NAN
        };
        if !v.is_nan() {
            *i = j;
            return Some(if neg { -v } else { v });
        }
    }
    // Anything else (exponents, more digits): cut the token out.
    let mut end = j;
    while end < s.len() && !is_space(s[end]) && s[end] != b'\n' {
        end += 1;
    }
    let v = slow_f64(&s[start..end])?;
    *i = end;
    Some(v)
}

/// `mant / 10^k`, correctly rounded, for `2^53 < mant < 2^64` and
/// `1 <= k <= 21`: the quotient is taken in 128-bit integers with 54 to 56
/// significant bits and rounded to 53 (to nearest, ties to even, the
/// remainder deciding near ties). The result is that integer times a power
/// of two, exact and normal for these inputs.
fn div_pow10(mant: u64, k: u32) -> f64 {
    let d = 10u128.pow(k);
    let bits = |x: u128| 128 - x.leading_zeros() as i32;
    let s = (55 + bits(d) - bits(u128::from(mant))).max(0);
    let n = u128::from(mant) << s;
    let (q, r) = (n / d, n % d);
    let shift = bits(q) - 53;
    let mut m = q >> shift;
    let rest = q & ((1u128 << shift) - 1);
    let half = 1u128 << (shift - 1);
    if rest > half || (rest == half && (r != 0 || m & 1 == 1)) {
        m += 1;
    }
    // m <= 2^53 and the exponent is well inside the normal range here.
    let scale = f64::from_bits(((1023 + shift - s) as u64) << 52);
    (m as u64 as f64) * scale
}

/// Parse a decimal floating-point number; `None` if `tok` is not one.
#[inline]
pub(crate) fn parse_f64(tok: &[u8]) -> Option<f64> {
    fast_f64(tok).or_else(|| slow_f64(tok))
}

/// The exact fast path: `[+-]digits[.digits][(e|E)[+-]digits]` with at most
/// 19 significant digits and a power of ten that is exact in `f64`.
#[inline]
fn fast_f64(tok: &[u8]) -> Option<f64> {
    let (neg, mut i) = match tok.first()? {
        b'-' => (true, 1),
        b'+' => (false, 1),
        _ => (false, 0),
    };
    let mut mant: u64 = 0;
    let mut digits = 0u32;
    let mut any = false;
    while i < tok.len() && tok[i].is_ascii_digit() {
        if digits > 0 || tok[i] != b'0' {
            digits += 1;
        }
        mant = mant.wrapping_mul(10).wrapping_add(u64::from(tok[i] - b'0'));
        i += 1;
        any = true;
    }
    let mut exp: i64 = 0;
    if i < tok.len() && tok[i] == b'.' {
        i += 1;
        while i < tok.len() && tok[i].is_ascii_digit() {
            if digits > 0 || tok[i] != b'0' {
                digits += 1;
            }
            mant = mant.wrapping_mul(10).wrapping_add(u64::from(tok[i] - b'0'));
            exp -= 1;
            i += 1;
            any = true;
        }
    }
    if !any || digits > 19 {
        return None;
    }
    if i < tok.len() && (tok[i] == b'e' || tok[i] == b'E') {
        i += 1;
        let eneg = take_sign(tok, &mut i);
        let start = i;
        let mut e: i64 = 0;
        while i < tok.len() && tok[i].is_ascii_digit() && i - start < 6 {
            e = e * 10 + i64::from(tok[i] - b'0');
            i += 1;
        }
        if i == start {
            return None;
        }
        exp += if eneg { -e } else { e };
    }
    if i != tok.len() {
        return None;
    }
    if mant > (1u64 << 53) {
        let v = (-21..0)
            .contains(&exp)
            .then(|| div_pow10(mant, (-exp) as u32))?;
        return Some(if neg { -v } else { v });
    }
    let m = mant as f64;
    let v = if exp == 0 {
        m
    } else if (-22..0).contains(&exp) {
        m / POW10[(-exp) as usize]
    } else if (1..=22).contains(&exp) {
        m * POW10[exp as usize]
    } else {
        return None;
    };
    Some(if neg { -v } else { v })
}

#[cold]
fn slow_f64(tok: &[u8]) -> Option<f64> {
    let s = std::str::from_utf8(tok).ok()?;
    // Rust also accepts "inf", "nan" and "infinity": pass them through, the
    // builder refuses non-finite positions with the vertex named.
    s.parse::<f64>().ok()
}

/// Parse a decimal integer (optional sign); `None` on anything else or
/// overflow.
#[inline]
pub(crate) fn parse_i64(tok: &[u8]) -> Option<i64> {
    let (neg, digits) = match tok.first()? {
        b'-' => (true, &tok[1..]),
        b'+' => (false, &tok[1..]),
        _ => (false, tok),
    };
    if digits.is_empty() {
        return None;
    }
    let mut v: i64 = 0;
    for &b in digits {
        if !b.is_ascii_digit() {
            return None;
        }
        v = v.checked_mul(10)?.checked_add(i64::from(b - b'0'))?;
    }
    Some(if neg { -v } else { v })
}

/// The next token as `f64`, or a syntax or truncation error.
#[inline]
pub(crate) fn next_f64(
    tokens: &mut Tokens<'_>,
    at: impl Fn() -> Location,
    what: &str,
) -> Result<f64, Error> {
    match tokens.next() {
        Some(t) => parse_f64(t).ok_or_else(|| Error::syntax(at(), what, t)),
        None => Err(Error::syntax(at(), what, b"")),
    }
}

/// The next token as a non-negative count, or a header error.
pub(crate) fn next_count(
    tokens: &mut Tokens<'_>,
    at: impl Fn() -> Location,
    what: &str,
) -> Result<usize, Error> {
    match tokens.next() {
        Some(t) => parse_i64(t)
            .and_then(|v| usize::try_from(v).ok())
            .ok_or_else(|| Error::syntax(at(), what, t)),
        None => Err(Error::syntax(at(), what, b"")),
    }
}

/// A capacity for `count` records of at least `min_bytes` each that the
/// remaining `bytes` could hold: never more than the input can supply.
#[inline]
pub(crate) fn capped(count: usize, bytes: usize, min_bytes: usize) -> usize {
    count.min(bytes / min_bytes.max(1) + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_match_std() {
        for s in [
            "0",
            "-0",
            "1",
            "-1.5",
            "3.14159",
            "0.1",
            "1e10",
            "1.5E-3",
            "-2.5e+2",
            ".5",
            "5.",
            "123456789012345678",
            "0.000001",
            "1e22",
            "1e23",
            "9007199254740993",
            "2.000000e+01",
            "-.1",
            "1e-30",
            "12345678901234567890123",
        ] {
            let want: f64 = s.parse().unwrap();
            assert_eq!(parse_f64(s.as_bytes()), Some(want), "{s}");
        }
        for s in ["", "-", ".", "e5", "1e", "1x", "--1", "\x10"] {
            assert_eq!(parse_f64(s.as_bytes()), None, "{s:?}");
        }
    }

    #[test]
    fn newlines() {
        for s in [
            "",
            "a",
            "\n",
            "abcdefgh\n",
            "abcdefghijklmnop",
            "abcdefghijk\nlm",
            "\u{80}\u{80}\n",
        ] {
            assert_eq!(
                find_newline(s.as_bytes()),
                s.bytes().position(|b| b == b'\n'),
                "{s:?}"
            );
        }
    }

    #[test]
    fn long_mantissas_round_like_std() {
        // A small deterministic generator: many 17- to 19-digit decimals.
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let digits = 17 + (x % 3) as usize;
            let text = format!("{:019}", x % 10_000_000_000_000_000_000)[..digits].to_string();
            let point = 1 + (x >> 40) as usize % (digits - 1);
            for s in [
                format!("{}.{}", &text[..point], &text[point..]),
                format!("{}.{}e-2", &text[..point], &text[point..]),
                format!("0.{}", &text[..digits.min(18)]),
                format!("-0.000{}", &text[..digits.min(18)]),
            ] {
                let mut i = 0;
                assert_eq!(
                    parse_f64_at(s.as_bytes(), &mut i),
                    s.parse::<f64>().ok(),
                    "{s}"
                );
                assert_eq!(parse_f64(s.as_bytes()), s.parse::<f64>().ok(), "{s}");
            }
        }
        // Ties and near ties at the 53-bit boundary.
        for s in [
            "9007199254740993.0",
            "9007199254740995.0",
            "18014398509481986.5",
            "0.0014027596028405353",
            "1844674407370955161.5",
        ] {
            let mut i = 0;
            assert_eq!(
                parse_f64_at(s.as_bytes(), &mut i),
                s.parse::<f64>().ok(),
                "{s}"
            );
        }
    }

    #[test]
    fn floats_in_place() {
        let line = b"  1.5 -2 3e2 0.002004008016032064 x\n";
        let mut i = 2;
        let mut got = Vec::new();
        while let Some(v) = parse_f64_at(line, &mut i) {
            got.push(v);
            while line[i] == b' ' {
                i += 1;
            }
        }
        assert_eq!(got, [1.5, -2.0, 300.0, 0.002004008016032064]);
        assert_eq!(line[i], b'x');
    }

    #[test]
    fn ints() {
        assert_eq!(parse_i64(b"-12"), Some(-12));
        assert_eq!(parse_i64(b"99999999999999999999"), None);
        assert_eq!(parse_i64(b"1.0"), None);
    }

    #[test]
    fn lines_and_tokens() {
        let mut l = Lines::new(b"a b\r\n\n  c\td ");
        assert_eq!(l.next(), Some(&b"a b"[..]));
        assert_eq!(l.next(), Some(&b""[..]));
        let t: Vec<_> = Tokens::new(l.next().unwrap()).collect();
        assert_eq!(t, vec![&b"c"[..], &b"d"[..]]);
        assert_eq!(l.line, 3);
        assert_eq!(l.next(), None);
    }
}
