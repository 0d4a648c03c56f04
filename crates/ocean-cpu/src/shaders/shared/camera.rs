//! Mirror of `shaders/shared/camera.wgsl`.

pub use ocean_core::camera_uniforms::CameraUniforms;

use crate::shaders::wgsl::{Vec3, mat4_mul_vec4, normalize};

/// The unit view ray through framebuffer position `frag_xy` (`@builtin(position).xy`); the
/// formula and why NDC depth 0.5 is in `camera.wgsl`.
pub fn view_ray(camera: &CameraUniforms, frag_xy: [f32; 2]) -> Vec3 {
    let ndc_x = frag_xy[0] * camera.viewport[2] * 2.0 - 1.0;
    let ndc_y = 1.0 - frag_xy[1] * camera.viewport[3] * 2.0;
    let h = mat4_mul_vec4(&camera.inv_view_proj, [ndc_x, ndc_y, 0.5, 1.0]);
    normalize([h[0] / h[3], h[1] / h[3], h[2] / h[3]])
}
