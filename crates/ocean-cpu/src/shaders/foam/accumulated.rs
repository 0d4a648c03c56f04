//! CPU mirror of `shaders/foam/accumulated.wgsl`: the accumulated foam field, sampled.

use crate::shaders::shared::foam::{foam_mix, foam_texture_at};
use crate::shaders::water::{Bindings, SurfacePoint, VertexOut, WRAP_LINEAR};
use crate::shaders::wgsl::{Vec2, clamp, sqrt, texture_sample_level};

/// `foam_coverage(in, p)`.
pub fn foam_coverage(input: &VertexOut, _p: &SurfacePoint, b: &Bindings<'_>) -> f32 {
    let f = &b.frame.foam;
    let uv = (input.pos + Vec2::from(f.field_origin)) * f.inv_field_size + f.field_half_texel;
    let mut t = clamp(texture_sample_level(b.foam_field, &WRAP_LINEAR, uv, 0.0).x, 0.0, 1.0);
    if f.window_outer > 0.0 {
        let d = sqrt(input.rel.x * input.rel.x + input.rel.z * input.rel.z);
        t *= clamp((f.window_outer - d) * f.inv_window_band, 0.0, 1.0);
    }
    foam_mix(t, foam_texture_at(input.pos, b.frame), b.frame)
}
