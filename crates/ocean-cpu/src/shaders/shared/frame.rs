//! Mirror of `shaders/shared/frame.wgsl`: the helpers every frame stage uses.

use crate::shaders::wgsl::{Mat4, Vec3, Vec4};

/// `transform_point(m, p)` = m\[0\]·p.x + m\[1\]·p.y + m\[2\]·p.z + m\[3\], summed left to right.
#[inline]
pub fn transform_point(m: &Mat4, p: Vec3) -> Vec4 {
    let m = m.map(Vec4::from);
    m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3]
}

/// `unit(v)` = v / sqrt(v.x·v.x + v.y·v.y + v.z·v.z) (a vector divided by a scalar divides
/// each component).
#[inline]
pub fn unit(v: Vec3) -> Vec3 {
    v / (v.x * v.x + v.y * v.y + v.z * v.z).sqrt()
}

/// `dot3(a, b)` = a.x·b.x + a.y·b.y + a.z·b.z.
#[inline]
pub fn dot3(a: Vec3, b: Vec3) -> f32 {
    a.x * b.x + a.y * b.y + a.z * b.z
}
