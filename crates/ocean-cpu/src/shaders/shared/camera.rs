//! Mirror of `shaders/shared/camera.wgsl`.

pub use ocean_core::camera_uniforms::CameraUniforms;

use crate::shaders::wgsl::{Vec2, Vec3, Vec4, mat4_mul_vec4, normalize, vec4};

/// The unit view ray through framebuffer position `frag_xy` (`@builtin(position).xy`); the
/// formula and why NDC depth 0.5 is in `camera.wgsl`.
pub fn view_ray(camera: &CameraUniforms, frag_xy: Vec2) -> Vec3 {
    let viewport = Vec4::from(camera.viewport);
    let ndc_x = frag_xy.x * viewport.z * 2.0 - 1.0;
    let ndc_y = 1.0 - frag_xy.y * viewport.w * 2.0;
    let h = mat4_mul_vec4(&camera.inv_view_proj, vec4(ndc_x, ndc_y, 0.5, 1.0));
    normalize(h.xyz() / h.w)
}
