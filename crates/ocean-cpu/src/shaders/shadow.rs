//! CPU mirror of `shaders/shadow.wgsl`: depth of the objects seen from the sun.

use ocean_core::frame::FrameUniforms;

use super::shared::frame::transform_point;
use super::wgsl::{Vec4, vec4};

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
