//! Checked values of the scene file: numbers and vectors that must lie in a range, and arrays
//! that must hold exactly so many values. serde rejects a bad one while it reads it, so the TOML
//! reader points the error at the value's place in the file.

use std::fmt;
use std::marker::PhantomData;

use arrayvec::ArrayVec;
use glam::{Vec2, Vec3};
use serde::de::{Deserialize, Deserializer, Error, IgnoredAny, SeqAccess, Visitor};

use crate::color::Color;
use crate::limits::{MAX_COORDINATE, WHY, short_vector, within_range};

/// An array of exactly `N` values. serde's own `[T; N]` stops reading after `N` and the TOML
/// reader does not mind what is left, so `[0, 0, 0, 99]` would pass as three numbers; this
/// counts them all, and too many is the same error as too few.
#[derive(Clone, Copy, Debug)]
pub struct Exact<T, const N: usize>(pub [T; N]);

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_seq(ExactVisitor(PhantomData))
    }
}

struct ExactVisitor<T, const N: usize>(PhantomData<fn() -> T>);

impl<'de, T: Deserialize<'de>, const N: usize> Visitor<'de> for ExactVisitor<T, N> {
    type Value = Exact<T, N>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "an array of {N} values")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Exact<T, N>, A::Error> {
        let mut values = ArrayVec::<T, N>::new();
        while !values.is_full() {
            match seq.next_element()? {
                Some(value) => values.push(value),
                None => break,
            }
        }
        let mut count = values.len();
        if values.is_full() {
            while seq.next_element::<IgnoredAny>()?.is_some() {
                count += 1;
            }
        }
        match values.into_inner() {
            Ok(array) if count == N => Ok(Exact(array)),
            _ => Err(A::Error::custom(format!(
                "expected {N} values, got {count}"
            ))),
        }
    }
}

/// Implements `Deserialize` for a checked type by reading `$raw` and checking it with the type's
/// `TryFrom<$raw>`. The read goes through `deserialize_newtype_struct`, so that the TOML reader
/// attaches the value's own position to a failed check, even for an element of an array or the
/// value of a `{ scale = […] }` step, where it would otherwise attach the enclosing table's.
macro_rules! deserialize_checked {
    ($checked:ty, $raw:ty) => {
        impl<'de> Deserialize<'de> for $checked {
            fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                deserializer.deserialize_newtype_struct(
                    stringify!($checked),
                    CheckedVisitor::<$raw, $checked>(PhantomData),
                )
            }
        }
    };
}

/// Reads a `Raw` and checks it into a `T`.
struct CheckedVisitor<Raw, T>(PhantomData<fn(Raw) -> T>);

impl<'de, Raw, T> Visitor<'de> for CheckedVisitor<Raw, T>
where
    Raw: Deserialize<'de>,
    T: TryFrom<Raw, Error = String>,
{
    type Value = T;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(std::any::type_name::<Raw>())
    }

    fn visit_newtype_struct<D: Deserializer<'de>>(self, deserializer: D) -> Result<T, D::Error> {
        T::try_from(Raw::deserialize(deserializer)?).map_err(D::Error::custom)
    }
}

/// A point or offset: three numbers within ±[`MAX_COORDINATE`].
#[derive(Clone, Copy, Debug)]
pub struct Vector(pub Vec3);

deserialize_checked!(Vector, Exact<f32, 3>);

impl TryFrom<Exact<f32, 3>> for Vector {
    type Error = String;

    fn try_from(Exact(v): Exact<f32, 3>) -> Result<Self, String> {
        let v = Vec3::from_array(v);
        if within_range(v) {
            Ok(Vector(v))
        } else if v.is_finite() {
            Err(format!(
                "expected numbers within ±{MAX_COORDINATE:e}, got {}: {WHY}",
                short_vector(v)
            ))
        } else {
            Err(format!("expected three finite numbers, got {v}"))
        }
    }
}

/// A direction: three finite numbers, not all zero, kept as a unit vector.
#[derive(Clone, Copy, Debug)]
pub struct Direction(pub Vec3);

deserialize_checked!(Direction, Exact<f32, 3>);

impl TryFrom<Exact<f32, 3>> for Direction {
    type Error = String;

    fn try_from(Exact(v): Exact<f32, 3>) -> Result<Self, String> {
        let v = Vec3::from_array(v);
        // `try_normalize` also refuses vectors too long or too short to normalise.
        match v.try_normalize() {
            Some(unit) if v.is_finite() => Ok(Direction(unit)),
            _ => Err(format!(
                "expected a direction (three finite numbers, not all zero), got {v}"
            )),
        }
    }
}

/// A linear RGB colour: three finite, non-negative numbers.
#[derive(Clone, Copy, Debug)]
pub struct ColorValue(pub Color);

deserialize_checked!(ColorValue, Exact<f32, 3>);

impl TryFrom<Exact<f32, 3>> for ColorValue {
    type Error = String;

    fn try_from(Exact(c): Exact<f32, 3>) -> Result<Self, String> {
        let c = Color::from_array(c);
        if c.is_finite() && c.min_element() >= 0.0 {
            Ok(ColorValue(c))
        } else {
            Err(format!(
                "expected a colour [r, g, b] of finite, non-negative numbers, got {c}"
            ))
        }
    }
}

/// Scale factors along x, y and z: finite and non-zero (negative mirrors).
#[derive(Clone, Copy, Debug)]
pub struct ScaleFactors(pub Vec3);

deserialize_checked!(ScaleFactors, Exact<f32, 3>);

impl TryFrom<Exact<f32, 3>> for ScaleFactors {
    type Error = String;

    fn try_from(Exact(s): Exact<f32, 3>) -> Result<Self, String> {
        let s = Vec3::from_array(s);
        if s.is_finite() && !s.cmpeq(Vec3::ZERO).any() {
            Ok(ScaleFactors(s))
        } else {
            Err(format!(
                "expected scale factors that are finite and non-zero, got {s}"
            ))
        }
    }
}

/// Texture coordinates `[u, v]`: two finite numbers.
#[derive(Clone, Copy, Debug)]
pub struct TexCoord(pub Vec2);

deserialize_checked!(TexCoord, Exact<f32, 2>);

impl TryFrom<Exact<f32, 2>> for TexCoord {
    type Error = String;

    fn try_from(Exact(uv): Exact<f32, 2>) -> Result<Self, String> {
        let uv = Vec2::from_array(uv);
        if uv.is_finite() {
            Ok(TexCoord(uv))
        } else {
            Err(format!("expected two finite numbers, got {uv}"))
        }
    }
}

/// A finite number.
#[derive(Clone, Copy, Debug)]
pub struct Finite(pub f32);

deserialize_checked!(Finite, f32);

impl TryFrom<f32> for Finite {
    type Error = String;

    fn try_from(x: f32) -> Result<Self, String> {
        if x.is_finite() {
            Ok(Finite(x))
        } else {
            Err(format!("expected a finite number, got {x}"))
        }
    }
}

/// A finite number greater than zero.
#[derive(Clone, Copy, Debug)]
pub struct Positive(pub f32);

deserialize_checked!(Positive, f32);

impl TryFrom<f32> for Positive {
    type Error = String;

    fn try_from(x: f32) -> Result<Self, String> {
        if x.is_finite() && x > 0.0 {
            Ok(Positive(x))
        } else {
            Err(format!("expected a positive number, got {x}"))
        }
    }
}

/// A number greater than zero, `inf` included.
#[derive(Clone, Copy, Debug)]
pub struct PositiveOrInfinite(pub f32);

deserialize_checked!(PositiveOrInfinite, f32);

impl TryFrom<f32> for PositiveOrInfinite {
    type Error = String;

    fn try_from(x: f32) -> Result<Self, String> {
        if x > 0.0 {
            Ok(PositiveOrInfinite(x))
        } else {
            Err(format!("expected a positive number or inf, got {x}"))
        }
    }
}

/// A finite number, zero or more.
#[derive(Clone, Copy, Debug)]
pub struct NonNegative(pub f32);

deserialize_checked!(NonNegative, f32);

impl TryFrom<f32> for NonNegative {
    type Error = String;

    fn try_from(x: f32) -> Result<Self, String> {
        if x.is_finite() && x >= 0.0 {
            Ok(NonNegative(x))
        } else {
            Err(format!("expected a number of zero or more, got {x}"))
        }
    }
}

/// A number from 0 to 1.
#[derive(Clone, Copy, Debug)]
pub struct Fraction(pub f32);

deserialize_checked!(Fraction, f32);

impl TryFrom<f32> for Fraction {
    type Error = String;

    fn try_from(x: f32) -> Result<Self, String> {
        if (0.0..=1.0).contains(&x) {
            Ok(Fraction(x))
        } else {
            Err(format!("expected a number from 0 to 1, got {x}"))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_enforced() {
        assert!(Positive::try_from(0.0).is_err());
        assert!(Positive::try_from(f32::NAN).is_err());
        assert!(NonNegative::try_from(0.0).is_ok());
        assert!(NonNegative::try_from(-0.5).is_err());
        assert!(Fraction::try_from(1.0).is_ok());
        assert!(Fraction::try_from(1.5).is_err());
        assert!(Finite::try_from(f32::INFINITY).is_err());
    }

    #[test]
    fn vectors_reject_what_they_cannot_be() {
        assert!(Vector::try_from(Exact([0.0, f32::NAN, 0.0])).is_err());
        assert!(Vector::try_from(Exact([0.0, 0.0, 3e38])).is_err());
        assert!(Vector::try_from(Exact([0.0, 0.0, -1e15])).is_ok());
        assert!(Direction::try_from(Exact([0.0; 3])).is_err());
        assert!(Direction::try_from(Exact([1e30, 0.0, 0.0])).is_err());
        assert_eq!(
            Direction::try_from(Exact([0.0, 0.0, 2.0])).unwrap().0,
            Vec3::Z
        );
        assert!(ColorValue::try_from(Exact([1.0, -0.1, 0.0])).is_err());
        assert!(ScaleFactors::try_from(Exact([1.0, 0.0, 1.0])).is_err());
        assert!(ScaleFactors::try_from(Exact([-1.0, 2.0, 1.0])).is_ok());
        assert!(TexCoord::try_from(Exact([f32::INFINITY, 0.0])).is_err());
    }
}
