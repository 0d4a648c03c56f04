//! Mirror of `shaders/shared/shadow.wgsl`: the sun's shadow map looked up at a point.

use ocean_core::frame::FrameUniforms;

use super::frame::transform_point;
use crate::sampler::Texture2D;
use crate::shaders::wgsl::Vec3;

/// `SHADOW_BIAS`: bias of the shadow-map depth comparison.
pub const SHADOW_BIAS: f32 = 0.002;

/// `sun_visibility(rel)`; `shadow_map` is the importing stage's `shadow_map` binding.
#[expect(clippy::manual_range_contains, reason = "the WGSL's comparisons, NaN included")]
pub fn sun_visibility(rel: Vec3, frame: &FrameUniforms, shadow_map: &Texture2D) -> f32 {
    if frame.passes.shadow_map == 0.0 {
        return 1.0;
    }
    let s = transform_point(&frame.sun.shadow_view_proj, rel);
    let u = s.x * 0.5 + 0.5;
    let v = 0.5 - s.y * 0.5;
    if u < 0.0 || u >= 1.0 || v < 0.0 || v >= 1.0 {
        return 1.0;
    }
    let dims = [shadow_map.width as i32, shadow_map.height as i32];
    let texel = [
        ((u * dims[0] as f32).floor() as i32).min(dims[0] - 1),
        ((v * dims[1] as f32).floor() as i32).min(dims[1] - 1),
    ];
    let occluder = shadow_map.texel(texel[0] as u32, texel[1] as u32)[0];
    // The clear value 1: no caster (also beyond the map's far plane).
    if occluder < 1.0 && occluder < s.z - SHADOW_BIAS {
        return 0.0;
    }
    1.0
}
