//! Mirror of `shaders/shared/shadow.wgsl`: the sun's shadow map looked up at a point.

use ocean_core::frame::FrameUniforms;
use ocean_core::switch::SWITCH_OFF;

use crate::envelope::{Cond, Real, choose, mat4_mul_vec4, on_floor};
use crate::sampler::Texture2D;
use crate::shaders::wgsl::Vec3;

/// `SHADOW_BIAS`: bias of the shadow-map depth comparison.
pub const SHADOW_BIAS: f32 = 0.002;

/// `sun_visibility(rel)`; `shadow_map` is the importing stage's `shadow_map` binding.
pub fn sun_visibility(rel: Vec3, frame: &FrameUniforms, shadow_map: &Texture2D) -> f32 {
    let dims = [shadow_map.width, shadow_map.height];
    sun_visibility_r([rel.x, rel.y, rel.z], frame, dims, &|x, y| shadow_map.texel(x, y)[0])
}

/// [`sun_visibility`] over any [`Real`], the map `dims` texels wide and high, its texel (x, y)
/// read by `occluder` (for an envelope, the interval the GPU's map may hold there).
pub fn sun_visibility_r<R: Real>(
    rel: [R; 3],
    frame: &FrameUniforms,
    dims: [u32; 2],
    occluder: &dyn Fn(u32, u32) -> R,
) -> R {
    let l = R::lit;
    if frame.passes.shadow_map == SWITCH_OFF {
        return l(1.0);
    }
    let s = mat4_mul_vec4(&frame.sun.shadow_view_proj, [rel[0], rel[1], rel[2], l(1.0)]);
    let u = s[0] * l(0.5) + l(0.5);
    let v = l(0.5) - s[1] * l(0.5);
    let outside = u.lt(l(0.0)).or(l(1.0).le(u)).or(v.lt(l(0.0))).or(l(1.0).le(v));
    choose(
        outside,
        || l(1.0),
        || {
            let (w, h) = (dims[0] as f32, dims[1] as f32);
            // Past two texels a side, whichever the GPU reads: lit or not.
            let either = l(0.0).hull(l(1.0));
            let [lit] = on_floor(u * l(w), [either], |fx, _| {
                on_floor(v * l(h), [either], |fy, _| {
                    // u < 1 can still round to u·size = size: clamp to the last texel.
                    let tx = (fx.max(0.0) as u32).min(dims[0] - 1);
                    let ty = (fy.max(0.0) as u32).min(dims[1] - 1);
                    let o = occluder(tx, ty);
                    // The clear value 1: no caster (also beyond the map's far plane).
                    let shadowed = o.lt(l(1.0)).and(o.lt(s[2] - l(SHADOW_BIAS)));
                    [choose(shadowed, || l(0.0), || l(1.0))]
                })
            });
            lit
        },
    )
}
