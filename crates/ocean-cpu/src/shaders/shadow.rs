//! CPU mirror of `shaders/shadow.wgsl`: depth of the objects seen from the sun.

use ocean_core::frame::FrameUniforms;

use super::shared::frame::transform_point;
use super::wgsl::{Vec4, vec4};
use crate::envelope::raster::{self, ScreenIv};
use crate::envelope::{Iv, JitterRules, Real, mat4_mul_vec4};

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
/// interval, and whether its coverage is ambiguous (envelope `raster`).
pub fn envelope(
    triangles: &[[[f32; 3]; 3]],
    frame: &FrameUniforms,
    size: [u32; 2],
) -> (Vec<Iv>, Vec<bool>) {
    let screen: Option<Vec<[ScreenIv; 3]>> = triangles
        .iter()
        .map(|t| {
            let v = t.map(|p| raster::to_screen(vs_main_r::<Iv>(p, frame), size[0], size[1]));
            Some([v[0]?, v[1]?, v[2]?])
        })
        .collect();
    match screen {
        Some(screen) => raster::depth_pass(&screen, size[0], size[1], 1.0),
        // A vertex whose w may be ≤ 0 needs the clipper, which the envelope does not carry
        // (the sun's view is orthographic, w = 1): anything, everywhere.
        None => {
            let n = (size[0] as usize) * (size[1] as usize);
            (vec![Iv::FULL; n], vec![true; n])
        }
    }
}

/// The shadow map as one random conformant GPU draws it (`rules.scale` times the rules).
pub fn jitter(
    triangles: &[[[f32; 3]; 3]],
    frame: &FrameUniforms,
    size: [u32; 2],
    rules: JitterRules,
) -> Vec<f32> {
    let clip: Vec<[[f32; 4]; 3]> = triangles.iter().map(|t| t.map(|p| vs_main(p, frame))).collect();
    raster::jitter_depth_pass(&clip, size[0], size[1], 1.0, rules)
}
