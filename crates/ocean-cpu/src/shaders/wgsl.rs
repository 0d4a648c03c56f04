//! WGSL built-ins in f32, with the order of operations the CPU mirrors commit to.
//!
//! A GPU may evaluate a `dot` or a matrix product in another order or with fused
//! multiply-adds; those differences are what the CPU ↔ GPU tolerances of `DESIGN.md` cover.

/// `vec3<f32>`.
pub type Vec3 = [f32; 3];
/// `vec4<f32>`.
pub type Vec4 = [f32; 4];
/// `mat4x4<f32>`: four columns.
pub type Mat4 = [[f32; 4]; 4];

/// `dot(a, b)` = (a.x b.x + a.y b.y) + a.z b.z.
#[inline]
pub fn dot(a: Vec3, b: Vec3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `cross(a, b)`.
#[inline]
pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `length(a)` = sqrt(dot(a, a)).
#[inline]
pub fn length(a: Vec3) -> f32 {
    dot(a, a).sqrt()
}

/// `normalize(a)` = a / length(a), component by component.
#[inline]
pub fn normalize(a: Vec3) -> Vec3 {
    let len = length(a);
    a.map(|c| c / len)
}

/// `m * v` = `((m[0] v.x + m[1] v.y) + m[2] v.z) + m[3] v.w`, per row.
#[inline]
pub fn mat4_mul_vec4(m: &Mat4, v: Vec4) -> Vec4 {
    std::array::from_fn(|r| m[0][r] * v[0] + m[1][r] * v[1] + m[2][r] * v[2] + m[3][r] * v[3])
}

/// `clamp(e, low, high)` = min(max(e, low), high). With IEEE `maxNum`/`minNum` semantics a NaN
/// `e` gives `low` (Rust's `f32::max` returns the non-NaN argument; `f32::clamp` would return
/// NaN).
#[inline]
pub fn clamp(e: f32, low: f32, high: f32) -> f32 {
    e.max(low).min(high)
}

/// `select(f, t, cond)`: `t` if `cond`, else `f`.
#[inline]
pub fn select<T>(f: T, t: T, cond: bool) -> T {
    if cond { t } else { f }
}

/// `v.xyz`.
#[inline]
pub fn xyz(v: Vec4) -> Vec3 {
    [v[0], v[1], v[2]]
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
    }

    #[test]
    fn matrix_columns_multiply_vector_components() {
        let m = [
            [1.0, 2.0, 3.0, 4.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [5.0, 0.0, 0.0, 1.0],
        ];
        assert_eq!(mat4_mul_vec4(&m, [1.0, 1.0, 1.0, 1.0]), [6.0, 3.0, 4.0, 5.0]);
        assert_eq!(normalize([3.0, 0.0, 4.0]), [0.6, 0.0, 0.8]);
        assert_eq!(cross([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]);
    }
}
