//! PLY's scalar types: their names (both spellings), sizes, and how a value of each is read
//! from binary data of either byte order.

use std::fmt;

/// A PLY scalar type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    /// The type a header names, in either spelling (`uchar` or `uint8`); `None` for others.
    pub fn from_name(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    /// Bytes a value takes in a binary body.
    pub fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    /// Whether values are whole numbers (a list's length must be).
    pub fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The largest value of an integer type, by which colour channels are scaled to [0, 1];
    /// 1 for the floating-point types.
    pub fn full_scale(self) -> f64 {
        match self {
            Scalar::I8 => i8::MAX as f64,
            Scalar::U8 => u8::MAX as f64,
            Scalar::I16 => i16::MAX as f64,
            Scalar::U16 => u16::MAX as f64,
            Scalar::I32 => i32::MAX as f64,
            Scalar::U32 => u32::MAX as f64,
            Scalar::F32 | Scalar::F64 => 1.0,
        }
    }

    /// The value at the start of `bytes` (at least [`Scalar::size`] of them), big-endian when
    /// `BIG`.
    #[inline(always)]
    pub fn read<const BIG: bool>(self, bytes: &[u8]) -> f64 {
        macro_rules! get {
            ($t:ty, $n:literal) => {{
                let b: [u8; $n] = bytes[..$n].try_into().expect("sliced to size");
                if BIG {
                    <$t>::from_be_bytes(b)
                } else {
                    <$t>::from_le_bytes(b)
                }
            }};
        }
        match self {
            Scalar::I8 => bytes[0] as i8 as f64,
            Scalar::U8 => bytes[0] as f64,
            Scalar::I16 => get!(i16, 2) as f64,
            Scalar::U16 => get!(u16, 2) as f64,
            Scalar::I32 => get!(i32, 4) as f64,
            Scalar::U32 => get!(u32, 4) as f64,
            Scalar::F32 => get!(f32, 4) as f64,
            Scalar::F64 => get!(f64, 8),
        }
    }
}

impl fmt::Display for Scalar {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Scalar::I8 => "char",
            Scalar::U8 => "uchar",
            Scalar::I16 => "short",
            Scalar::U16 => "ushort",
            Scalar::I32 => "int",
            Scalar::U32 => "uint",
            Scalar::F32 => "float",
            Scalar::F64 => "double",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_read_in_either_byte_order() {
        assert_eq!(Scalar::I16.read::<true>(&[0xff, 0xfe]), -2.0);
        assert_eq!(Scalar::I16.read::<false>(&[0xfe, 0xff]), -2.0);
        assert_eq!(Scalar::U32.read::<true>(&[0, 0, 1, 0]), 256.0);
        assert_eq!(Scalar::F64.read::<true>(&1.5f64.to_be_bytes()), 1.5);
        assert_eq!(Scalar::F32.read::<false>(&0.25f32.to_le_bytes()), 0.25);
        assert_eq!(Scalar::I8.read::<false>(&[0x80]), -128.0);
        assert_eq!(Scalar::from_name("uint8"), Some(Scalar::U8));
        assert_eq!(Scalar::from_name("float64"), Some(Scalar::F64));
        assert_eq!(Scalar::from_name("long"), None);
    }
}
