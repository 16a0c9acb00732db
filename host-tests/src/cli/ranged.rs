//! Integer keys of scene files read wide (as TOML's `i64`) and checked against the range of the
//! field they fill, so that a value out of range is named with its range ("300 is outside
//! 0..=255") instead of serde's "invalid value: integer `300`, expected u8". Used with
//! `#[serde(deserialize_with = "...")]` on the `u8`, `u16`, `u32` and `usize` fields of
//! `render.rs`' sections: [`int()`], [`option()`], [`array()`] and [`arrays()`].

use serde::de::Error;
use serde::{Deserialize, Deserializer};

/// An integer field's type and its range.
pub trait Ranged: Sized {
    /// The smallest and largest value.
    const RANGE: (i64, i64);
    /// `v`, known to be within [`RANGE`](Self::RANGE).
    fn narrow(v: i64) -> Self;
}

macro_rules! ranged {
    ($($t:ty),*) => {$(
        impl Ranged for $t {
            const RANGE: (i64, i64) = (<$t>::MIN as i64, if <$t>::MAX as u64 > i64::MAX as u64 {
                i64::MAX
            } else {
                <$t>::MAX as i64
            });
            fn narrow(v: i64) -> Self {
                v as $t
            }
        }
    )*};
}
ranged!(u8, u16, u32, usize);

/// `v` as a `T`, or an error naming `v` and `T`'s range.
fn check<T: Ranged, E: Error>(v: i64) -> Result<T, E> {
    let (lo, hi) = T::RANGE;
    if (lo..=hi).contains(&v) {
        Ok(T::narrow(v))
    } else {
        Err(E::custom(format!("{v} is outside the range {lo}..={hi}")))
    }
}

/// One integer in `T`'s range.
pub fn int<'de, D: Deserializer<'de>, T: Ranged>(d: D) -> Result<T, D::Error> {
    check(i64::deserialize(d)?)
}

/// An optional integer in `T`'s range (with `#[serde(default)]` for an absent key).
pub fn option<'de, D: Deserializer<'de>, T: Ranged>(d: D) -> Result<Option<T>, D::Error> {
    Option::<i64>::deserialize(d)?.map(check).transpose()
}

/// `N` integers in `T`'s range, or an error naming how many were given.
fn exactly<T: Ranged, E: Error, const N: usize>(v: Vec<i64>) -> Result<[T; N], E> {
    if v.len() != N {
        return Err(E::custom(format!("expected {N} integers, got {}", v.len())));
    }
    let mut out = Vec::with_capacity(N);
    for x in v {
        out.push(check(x)?);
    }
    out.try_into()
        .map_err(|_| E::custom(format!("expected {N} integers")))
}

/// An array of `N` integers in `T`'s range.
pub fn array<'de, D: Deserializer<'de>, T: Ranged, const N: usize>(
    d: D,
) -> Result<[T; N], D::Error> {
    exactly(Vec::<i64>::deserialize(d)?)
}

/// A list of arrays of `N` integers in `T`'s range.
pub fn arrays<'de, D: Deserializer<'de>, T: Ranged, const N: usize>(
    d: D,
) -> Result<Vec<[T; N]>, D::Error> {
    Vec::<Vec<i64>>::deserialize(d)?
        .into_iter()
        .map(exactly)
        .collect()
}

/// A list of lists of integers in `T`'s range (polygons' vertex indices).
pub fn lists<'de, D: Deserializer<'de>, T: Ranged>(d: D) -> Result<Vec<Vec<T>>, D::Error> {
    Vec::<Vec<i64>>::deserialize(d)?
        .into_iter()
        .map(|l| l.into_iter().map(check).collect())
        .collect()
}
