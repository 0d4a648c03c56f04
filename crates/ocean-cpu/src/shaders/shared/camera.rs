//! Mirror of `shaders/shared/camera.wgsl`.

pub use ocean_core::camera_uniforms::CameraUniforms;

use crate::envelope::{self, Real};
use crate::shaders::wgsl::{Vec2, Vec3};

/// The unit view ray through framebuffer position `frag_xy` (`@builtin(position).xy`); the
/// formula and why NDC depth 0.5 is in `camera.wgsl`.
pub fn view_ray(camera: &CameraUniforms, frag_xy: Vec2) -> Vec3 {
    Vec3::from(view_ray_r(camera, [frag_xy.x, frag_xy.y]))
}

/// [`view_ray`] over any [`Real`].
pub fn view_ray_r<R: Real>(camera: &CameraUniforms, frag_xy: [R; 2]) -> [R; 3] {
    let l = R::lit;
    let [_, _, vz, vw] = camera.viewport;
    let ndc_x = frag_xy[0] * l(vz) * l(2.0) - l(1.0);
    let ndc_y = l(1.0) - frag_xy[1] * l(vw) * l(2.0);
    let h = envelope::mat4_mul_vec4(&camera.inv_view_proj, [ndc_x, ndc_y, l(0.5), l(1.0)]);
    envelope::normalize3([h[0] / h[3], h[1] / h[3], h[2] / h[3]])
}
