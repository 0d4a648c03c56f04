//! Mirror of `shaders/shared/frame.wgsl`: the helpers every frame stage uses, with WGSL's
//! vector arithmetic written out component by component in the same order.

/// `transform_point(m, p)` = m[0]·p.x + m[1]·p.y + m[2]·p.z + m[3], summed left to right.
#[inline]
pub fn transform_point(m: &[[f32; 4]; 4], p: [f32; 3]) -> [f32; 4] {
    std::array::from_fn(|i| m[0][i] * p[0] + m[1][i] * p[1] + m[2][i] * p[2] + m[3][i])
}

/// `dot3(a, b)` = a.x·b.x + a.y·b.y + a.z·b.z.
#[inline]
pub fn dot3(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `unit(v)` = v / sqrt(v.x·v.x + v.y·v.y + v.z·v.z) (a vector divided by a scalar divides
/// each component).
#[inline]
pub fn unit(v: [f32; 3]) -> [f32; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

/// `a * s` for a vec3.
#[inline]
pub fn scale3(a: [f32; 3], s: f32) -> [f32; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// `a + b` for a vec3.
#[inline]
pub fn add3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a * b` (component-wise) for a vec3.
#[inline]
pub fn mul3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] * b[0], a[1] * b[1], a[2] * b[2]]
}

/// The xyz of a vec4.
#[inline]
pub fn xyz(v: [f32; 4]) -> [f32; 3] {
    [v[0], v[1], v[2]]
}
