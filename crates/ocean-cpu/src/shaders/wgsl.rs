//! WGSL's `vec2<f32>`, `vec3<f32>`, `vec4<f32>` and the built-ins the CPU mirrors use, in f32,
//! with the order of operations the mirrors commit to.
//!
//! Every operator is the plain f32 operation on each component, in WGSL's evaluation order:
//! no `mul_add`, no fused or reordered operations. `a * b + c` rounds the product and then the
//! sum; `dot(a, b)` is `(a.x * b.x + a.y * b.y) + a.z * b.z`, left to right. A GPU may
//! evaluate a `dot` or a matrix product in another order or with fused multiply-adds; those
//! differences are what the CPU ↔ GPU tolerances of `docs/design.md` cover.
//!
//! At the mirrors' boundaries (ocean-core's uniforms and vertex formats, the sampler's
//! textures, the rasterizer's positions and outputs) vectors are `[f32; N]`; `From`/`Into`
//! convert both ways.

use std::ops::{Add, Div, Mul, Neg, Sub};

use crate::sampler::{self, Sampler, Texture2D};

/// `vec2<f32>`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vec2 {
    /// `.x`.
    pub x: f32,
    /// `.y`.
    pub y: f32,
}

/// `vec3<f32>`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vec3 {
    /// `.x`.
    pub x: f32,
    /// `.y`.
    pub y: f32,
    /// `.z`.
    pub z: f32,
}

/// `vec4<f32>`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vec4 {
    /// `.x`.
    pub x: f32,
    /// `.y`.
    pub y: f32,
    /// `.z`.
    pub z: f32,
    /// `.w`.
    pub w: f32,
}

/// `vec2<bool>`, e.g. of a component-wise comparison.
pub type BVec2 = [bool; 2];
/// `vec3<bool>`.
pub type BVec3 = [bool; 3];
/// `vec4<bool>`.
pub type BVec4 = [bool; 4];

/// `mat4x4<f32>`: four columns (the uniforms' layout).
pub type Mat4 = [[f32; 4]; 4];

/// `vec2<f32>(x, y)`.
#[inline]
pub const fn vec2(x: f32, y: f32) -> Vec2 {
    Vec2 { x, y }
}

/// `vec3<f32>(x, y, z)`.
#[inline]
pub const fn vec3(x: f32, y: f32, z: f32) -> Vec3 {
    Vec3 { x, y, z }
}

/// `vec4<f32>(x, y, z, w)`.
#[inline]
pub const fn vec4(x: f32, y: f32, z: f32, w: f32) -> Vec4 {
    Vec4 { x, y, z, w }
}

impl Vec2 {
    /// `vec2<f32>(v)`: every component `v`.
    #[inline]
    pub const fn splat(v: f32) -> Self {
        vec2(v, v)
    }
}

impl Vec3 {
    /// `vec3<f32>(v)`: every component `v`.
    #[inline]
    pub const fn splat(v: f32) -> Self {
        vec3(v, v, v)
    }

    /// `vec4<f32>(self, w)`.
    #[inline]
    pub const fn extend(self, w: f32) -> Vec4 {
        vec4(self.x, self.y, self.z, w)
    }

    /// `self <= other` per component.
    #[inline]
    pub fn le(self, other: Self) -> BVec3 {
        [self.x <= other.x, self.y <= other.y, self.z <= other.z]
    }
}

impl Vec4 {
    /// `vec4<f32>(v)`: every component `v`.
    #[inline]
    pub const fn splat(v: f32) -> Self {
        vec4(v, v, v, v)
    }

    /// `.xy`.
    #[inline]
    pub const fn xy(self) -> Vec2 {
        vec2(self.x, self.y)
    }

    /// `.xyz` (also `.rgb`).
    #[inline]
    pub const fn xyz(self) -> Vec3 {
        vec3(self.x, self.y, self.z)
    }
}

/// f32 and the f32 vectors: what WGSL's component-wise built-ins take.
pub trait Components: Copy {
    /// The boolean of the same shape (`bool`, [`BVec2`], [`BVec3`], [`BVec4`]).
    type Bool: Copy;
    /// `f` of each component.
    fn map(self, f: impl Fn(f32) -> f32) -> Self;
    /// `f` of each pair of components.
    fn zip(self, other: Self, f: impl Fn(f32, f32) -> f32) -> Self;
    /// Each component of `t` where `cond` holds, else of `f`.
    fn select(f: Self, t: Self, cond: Self::Bool) -> Self;
}

impl Components for f32 {
    type Bool = bool;
    #[inline]
    fn map(self, f: impl Fn(f32) -> f32) -> Self {
        f(self)
    }
    #[inline]
    fn zip(self, other: Self, f: impl Fn(f32, f32) -> f32) -> Self {
        f(self, other)
    }
    #[inline]
    fn select(f: Self, t: Self, cond: bool) -> Self {
        if cond { t } else { f }
    }
}

/// The vector type's definitions: conversions, [`Components`], and the operators, each on
/// every component, one plain f32 operation.
macro_rules! vector {
    ($V:ident, $N:literal, $B:ty, $($c:ident $i:literal),+) => {
        impl From<[f32; $N]> for $V {
            #[inline]
            fn from(a: [f32; $N]) -> Self {
                Self { $($c: a[$i]),+ }
            }
        }

        impl From<$V> for [f32; $N] {
            #[inline]
            fn from(v: $V) -> Self {
                [$(v.$c),+]
            }
        }

        impl Components for $V {
            type Bool = $B;
            #[inline]
            fn map(self, f: impl Fn(f32) -> f32) -> Self {
                Self { $($c: f(self.$c)),+ }
            }
            #[inline]
            fn zip(self, other: Self, f: impl Fn(f32, f32) -> f32) -> Self {
                Self { $($c: f(self.$c, other.$c)),+ }
            }
            #[inline]
            fn select(f: Self, t: Self, cond: $B) -> Self {
                Self { $($c: if cond[$i] { t.$c } else { f.$c }),+ }
            }
        }

        impl Neg for $V {
            type Output = Self;
            #[inline]
            fn neg(self) -> Self {
                Self { $($c: -self.$c),+ }
            }
        }

        vector!(@op $V, Add, add, +, $($c),+);
        vector!(@op $V, Sub, sub, -, $($c),+);
        vector!(@op $V, Mul, mul, *, $($c),+);
        vector!(@op $V, Div, div, /, $($c),+);
    };
    (@op $V:ident, $Op:ident, $op:ident, $sym:tt, $($c:ident),+) => {
        impl $Op for $V {
            type Output = Self;
            #[inline]
            fn $op(self, b: Self) -> Self {
                Self { $($c: self.$c $sym b.$c),+ }
            }
        }

        impl $Op<f32> for $V {
            type Output = Self;
            #[inline]
            fn $op(self, b: f32) -> Self {
                Self { $($c: self.$c $sym b),+ }
            }
        }

        impl $Op<$V> for f32 {
            type Output = $V;
            #[inline]
            fn $op(self, b: $V) -> $V {
                $V { $($c: self $sym b.$c),+ }
            }
        }
    };
}

vector!(Vec2, 2, BVec2, x 0, y 1);
vector!(Vec3, 3, BVec3, x 0, y 1, z 2);
vector!(Vec4, 4, BVec4, x 0, y 1, z 2, w 3);

/// `dot(a, b)` = (a.x b.x + a.y b.y) + a.z b.z.
#[inline]
pub fn dot(a: Vec3, b: Vec3) -> f32 {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// `cross(a, b)`.
#[inline]
pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x)
}

/// `length(a)` = sqrt(dot(a, a)).
#[inline]
pub fn length(a: Vec3) -> f32 {
    dot(a, a).sqrt()
}

/// `normalize(a)` = a / length(a), component by component.
#[inline]
pub fn normalize(a: Vec3) -> Vec3 {
    a / length(a)
}

/// `m * v` = `((m[0] v.x + m[1] v.y) + m[2] v.z) + m[3] v.w`, per row.
#[inline]
pub fn mat4_mul_vec4(m: &Mat4, v: Vec4) -> Vec4 {
    let [c0, c1, c2, c3] = m.map(Vec4::from);
    c0 * v.x + c1 * v.y + c2 * v.z + c3 * v.w
}

/// `max(a, b)`, per component, with IEEE `maxNum` semantics (Rust's `f32::max`: a NaN
/// argument gives the other).
#[inline]
pub fn max<T: Components>(a: T, b: T) -> T {
    a.zip(b, f32::max)
}

/// `min(a, b)`, per component, with IEEE `minNum` semantics (Rust's `f32::min`).
#[inline]
pub fn min<T: Components>(a: T, b: T) -> T {
    a.zip(b, f32::min)
}

/// `clamp(e, low, high)` = min(max(e, low), high). With IEEE `maxNum`/`minNum` semantics a NaN
/// `e` gives `low` (Rust's `f32::max` returns the non-NaN argument; `f32::clamp` would return
/// NaN).
#[inline]
pub fn clamp<T: Components>(e: T, low: T, high: T) -> T {
    min(max(e, low), high)
}

/// `select(f, t, cond)`: `t` where `cond`, else `f` (per component for vectors).
#[inline]
pub fn select<T: Components>(f: T, t: T, cond: T::Bool) -> T {
    T::select(f, t, cond)
}

/// `sqrt(e)`, per component.
#[inline]
pub fn sqrt<T: Components>(e: T) -> T {
    e.map(f32::sqrt)
}

/// `exp(e)`, per component.
#[inline]
pub fn exp<T: Components>(e: T) -> T {
    e.map(f32::exp)
}

pub use crate::float::{frexp, ldexp};

/// `abs(e)`, per component.
#[inline]
pub fn abs<T: Components>(e: T) -> T {
    e.map(f32::abs)
}

/// `pow(e1, e2)`, per component.
#[inline]
pub fn pow<T: Components>(e1: T, e2: T) -> T {
    e1.zip(e2, f32::powf)
}

/// `round(e)`, per component: to the nearest integer, halves to even (exact).
#[inline]
pub fn round<T: Components>(e: T) -> T {
    e.map(f32::round_ties_even)
}

/// `textureSample(t, s, coords)`.
#[inline]
pub fn texture_sample(t: &Texture2D, s: &Sampler, coords: Vec2) -> Vec4 {
    sampler::texture_sample(t, s, coords.into()).into()
}

/// `textureSampleLevel(t, s, coords, level)`.
#[inline]
pub fn texture_sample_level(t: &Texture2D, s: &Sampler, coords: Vec2, level: f32) -> Vec4 {
    sampler::texture_sample_level(t, s, coords.into(), level).into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamp_maps_nan_to_low_and_keeps_order() {
        assert_eq!(clamp(f32::NAN, 0.0, 1.0), 0.0);
        assert_eq!(clamp(f32::INFINITY, 0.0, 1.0), 1.0);
        assert_eq!(clamp(-2.0, 0.0, 1.0), 0.0);
        assert_eq!(clamp(0.25, 0.0, 1.0), 0.25);
        let v = clamp(vec3(f32::NAN, 2.0, 0.5), Vec3::splat(0.0), Vec3::splat(1.0));
        assert_eq!(v, vec3(0.0, 1.0, 0.5));
    }

    #[test]
    fn matrix_columns_multiply_vector_components() {
        let m = [
            [1.0, 2.0, 3.0, 4.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [5.0, 0.0, 0.0, 1.0],
        ];
        assert_eq!(mat4_mul_vec4(&m, Vec4::splat(1.0)), vec4(6.0, 3.0, 4.0, 5.0));
        assert_eq!(normalize(vec3(3.0, 0.0, 4.0)), vec3(0.6, 0.0, 0.8));
        assert_eq!(cross(vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0)), vec3(0.0, 0.0, 1.0));
    }

    /// a, b, c with a·b + c rounded twice (product, then sum) ≠ fma(a, b, c) rounded once.
    fn unfused_inputs() -> (f32, f32, f32) {
        // a = b = 1 + 2⁻¹²: a·b = 1 + 2⁻¹¹ + 2⁻²⁴ rounds (a tie, to even) to 1 + 2⁻¹¹, so
        // a·b + c with c = −(1 + 2⁻¹¹) gives 0; fused, the sum is exact: 2⁻²⁴.
        let a = 1.0 + 2.0_f32.powi(-12);
        let b = a;
        let c = -(a * b);
        assert_ne!(a * b + c, a.mul_add(b, c), "inputs must tell a fused sum apart");
        (a, b, c)
    }

    #[test]
    fn operators_are_unfused_and_ordered() {
        let (a, b, c) = unfused_inputs();
        let twice = a * b + c;
        let fused = a.mul_add(b, c);
        assert_ne!(twice.to_bits(), fused.to_bits());
        // Vector times scalar plus vector, vector times vector plus scalar, scalar forms.
        let v = Vec3::splat(a) * b + Vec3::splat(c);
        let w = Vec4::splat(a) * Vec4::splat(b) + c;
        let s = a * Vec2::splat(b) + c;
        for got in [v.x, v.y, v.z, w.x, w.y, w.z, w.w, s.x, s.y] {
            assert_eq!(got.to_bits(), twice.to_bits());
        }
        // The matrix product is unfused and summed left to right.
        let m = [[a, a, a, a], [0.0; 4], [0.0; 4], [c; 4]];
        let h = mat4_mul_vec4(&m, vec4(b, 0.0, 0.0, 1.0));
        assert_eq!(h.x.to_bits(), (a * b + 0.0 * 0.0 + 0.0 * 0.0 + c * 1.0).to_bits());
        assert_eq!(h.x.to_bits(), twice.to_bits());
    }

    #[test]
    fn dot_is_the_left_to_right_sum() {
        let (a, b, c) = unfused_inputs();
        let x = vec3(a, 1.0, 1.0);
        let y = vec3(b, c, 0.0);
        assert_eq!(dot(x, y).to_bits(), (a * b + 1.0 * c + 1.0 * 0.0).to_bits());
        assert_ne!(dot(x, y).to_bits(), a.mul_add(b, c).to_bits());
        // Cancellation tells the orders apart: (1e8 + 1) − 1e8 = 0 in f32, 1 + (1e8 − 1e8) = 1.
        let p = vec3(1e8, 1.0, -1e8);
        let one = Vec3::splat(1.0);
        assert_eq!(dot(p, one), (1e8_f32 + 1.0) + -1e8);
        assert_eq!(dot(p, one), 0.0);
        assert_eq!(length(vec3(3.0, 4.0, 12.0)), 13.0);
    }

    #[test]
    fn select_and_swizzles() {
        let lo = vec3(1.0, 2.0, 3.0);
        let hi = Vec3::splat(9.0);
        assert_eq!(select(hi, lo, lo.le(Vec3::splat(2.0))), vec3(1.0, 2.0, 9.0));
        assert_eq!(select(0.0, 1.0, true), 1.0);
        let v = vec4(1.0, 2.0, 3.0, 4.0);
        assert_eq!(v.xyz().extend(v.w), v);
        assert_eq!(v.xy(), vec2(1.0, 2.0));
        assert_eq!(<[f32; 4]>::from(v), [1.0, 2.0, 3.0, 4.0]);
        assert_eq!(Vec3::from([1.0, 2.0, 3.0]), lo);
        assert_eq!(-lo, vec3(-1.0, -2.0, -3.0));
        assert_eq!(1.0 - lo, vec3(0.0, -1.0, -2.0));
        assert_eq!(lo / 2.0, vec3(0.5, 1.0, 1.5));
    }
}
