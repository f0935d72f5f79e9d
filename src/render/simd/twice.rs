//! Sixteen lanes as two of eight: [`Twice`] does each operation on both halves, so work written
//! over sixteen lanes runs on any [`Lanes8`](super::Lanes8) and gives the bits it gives on eight.

use std::ops::{Add, BitAnd, Div, Mul, Neg, Sub};

use super::lanes::Lanes;

/// Two sets of lanes side by side: the low half, then the high half.
#[derive(Debug, Clone, Copy)]
pub struct Twice<L>(pub L, pub L);

/// A lane-by-lane binary operator, on each half.
macro_rules! on_halves {
    ($trait:ident, $method:ident) => {
        impl<L: $trait<Output = L>> $trait for Twice<L> {
            type Output = Twice<L>;
            #[inline(always)]
            fn $method(self, other: Twice<L>) -> Twice<L> {
                Twice(self.0.$method(other.0), self.1.$method(other.1))
            }
        }
    };
}

on_halves!(Add, add);
on_halves!(Sub, sub);
on_halves!(Mul, mul);
on_halves!(Div, div);
on_halves!(BitAnd, bitand);

impl<L: Neg<Output = L>> Neg for Twice<L> {
    type Output = Twice<L>;
    #[inline(always)]
    fn neg(self) -> Twice<L> {
        Twice(-self.0, -self.1)
    }
}

impl<L: Lanes> Lanes for Twice<L> {
    type Mask = Twice<L::Mask>;

    #[inline(always)]
    fn splat(value: f32) -> Self {
        Twice(L::splat(value), L::splat(value))
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        Twice(self.0.sqrt(), self.1.sqrt())
    }

    #[inline(always)]
    fn max(self, other: Self) -> Self {
        Twice(self.0.max(other.0), self.1.max(other.1))
    }

    #[inline(always)]
    fn min(self, other: Self) -> Self {
        Twice(self.0.min(other.0), self.1.min(other.1))
    }

    #[inline(always)]
    fn gt(self, other: Self) -> Self::Mask {
        Twice(self.0.gt(other.0), self.1.gt(other.1))
    }

    #[inline(always)]
    fn lt(self, other: Self) -> Self::Mask {
        Twice(self.0.lt(other.0), self.1.lt(other.1))
    }

    #[inline(always)]
    fn keep(mask: Self::Mask, value: Self) -> Self {
        Twice(L::keep(mask.0, value.0), L::keep(mask.1, value.1))
    }

    #[inline(always)]
    fn select(mask: Self::Mask, yes: Self, no: Self) -> Self {
        Twice(
            L::select(mask.0, yes.0, no.0),
            L::select(mask.1, yes.1, no.1),
        )
    }

    #[inline(always)]
    fn negate_where(mask: Self::Mask, value: Self) -> Self {
        Twice(
            L::negate_where(mask.0, value.0),
            L::negate_where(mask.1, value.1),
        )
    }

    #[inline(always)]
    fn any(mask: Self::Mask) -> bool {
        L::any(mask.0) || L::any(mask.1)
    }

    #[inline(always)]
    fn split_exponent(self) -> (Self, Self) {
        let ((e0, m0), (e1, m1)) = (self.0.split_exponent(), self.1.split_exponent());
        (Twice(e0, e1), Twice(m0, m1))
    }

    #[inline(always)]
    fn scale_by_pow2(self, n: Self) -> Self {
        Twice(self.0.scale_by_pow2(n.0), self.1.scale_by_pow2(n.1))
    }
}
