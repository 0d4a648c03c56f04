//! CPU mirror of `shaders/shadow.wgsl`: depth of the objects seen from the sun.

use ocean_core::frame::FrameUniforms;

use super::shared::frame::transform_point;
use super::wgsl::{Vec4, vec4};
use crate::envelope::raster::{self, ScreenIv};
use crate::envelope::{Iv, Jitter, JitterRules, Precision, Real, mat4_mul_vec4};

/// `vs_main(position)`: the clip position in the sun's orthographic view (`position` and
/// the result are the rasterizer's arrays).
pub fn vs_main(position: [f32; 3], frame: &FrameUniforms) -> [f32; 4] {
    transform_point(&frame.sun.shadow_view_proj, position.into()).into()
}

/// `fs_main(frag)`: the fragment's depth in the red channel.
pub fn fs_main(frag_coord: [f32; 4]) -> [f32; 4] {
    let frag = Vec4::from(frag_coord);
    vec4(frag.z, 0.0, 0.0, 0.0).into()
}

/// [`vs_main`] over any [`Real`] (the matrix row a sum a GPU may reassociate).
pub fn vs_main_r<R: Real>(position: [f32; 3], frame: &FrameUniforms) -> [R; 4] {
    let [x, y, z] = position.map(R::lit);
    mat4_mul_vec4(&frame.sun.shadow_view_proj, [x, y, z, R::lit(1.0)])
}

/// The envelope of the shadow map a conformant GPU draws of `triangles` (object-space
/// positions, as the pass submits them) into a `size` map cleared to 1: per texel its
/// interval, and whether its coverage is ambiguous (envelope `raster`), on a device of
/// `precision` (its snap).
pub fn envelope(
    triangles: &[[[f32; 3]; 3]],
    frame: &FrameUniforms,
    size: [u32; 2],
    precision: Precision,
) -> (Vec<Iv>, Vec<bool>) {
    let mut screen: Vec<[ScreenIv; 3]> = Vec::with_capacity(triangles.len());
    let n = (size[0] as usize) * (size[1] as usize);
    for t in triangles {
        // Past the near or far plane (not today: the sun's view is fitted around the casters
        // with a margin), the clipper's parts; one it cannot bound, or a vertex whose w may be
        // ≤ 0: anything, everywhere.
        let clip = t.map(|p| vs_main_r::<Iv>(p, frame));
        let Some(parts) = raster::clip_near_far(clip) else {
            return (vec![Iv::FULL; n], vec![true; n]);
        };
        for part in parts {
            let Some(s) = raster::piece_to_screen(&part, &clip, size[0], size[1]) else {
                return (vec![Iv::FULL; n], vec![true; n]);
            };
            screen.push(s);
        }
    }
    raster::depth_pass(&screen, size[0], size[1], 1.0, precision.snap_px())
}

/// The shadow map as one random conformant GPU of `precision` draws it (`rules.scale` times
/// the rules).
pub fn jitter(
    triangles: &[[[f32; 3]; 3]],
    frame: &FrameUniforms,
    size: [u32; 2],
    rules: JitterRules,
    precision: Precision,
) -> Vec<f32> {
    // The vertex shader with random roundings too (a row of the matrix may be reassociated).
    let clip: Vec<[[f32; 4]; 3]> = triangles
        .iter()
        .enumerate()
        .map(|(k, t)| {
            Jitter::reseed(rules, (k as u64) << 32 | 0xffff_ffff);
            t.map(|p| vs_main_r::<Jitter>(p, frame).map(|c| c.0))
        })
        .collect();
    raster::jitter_depth_pass(&clip, size[0], size[1], 1.0, rules, precision.subpixel_bits)
}
