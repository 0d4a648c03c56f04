// The camera, shared by the render stages. Rust: ocean_core::camera_uniforms::CameraUniforms;
// CPU mirror: ocean-cpu/src/shaders/shared/camera.rs.
//
// Camera-relative: the eye is at the origin of view_proj (the renderer subtracts the eye in
// f64 before casting to f32). Clip space is wgpu's: x right, y up, z in [0, 1], reversed Z.

struct CameraUniforms {
    // Projection x view of the camera-relative world.
    view_proj: mat4x4<f32>,
    // The inverse of view_proj (inverted in f64).
    inv_view_proj: mat4x4<f32>,
    // World position of the eye (x, y, z, 1); imprecise far from the origin.
    eye: vec4<f32>,
    // (width, height, 1 / width, 1 / height) in pixels.
    viewport: vec4<f32>,
}

// The unit view ray (camera-relative world space) through framebuffer position frag_xy
// (@builtin(position).xy: pixel centres at +0.5, y down).
//
//   ndc = (2 x / W - 1, 1 - 2 y / H)
//   h   = inv_view_proj * (ndc, 0.5, 1)
//   ray = normalize(h.xyz / h.w)
//
// Since the eye is at the origin, any point of the pixel's ray is a direction along it; NDC
// depth 0.5 lies strictly between the near plane and the far plane (or infinity) for reversed
// and standard Z alike, so h.w > 0 and finite for a perspective camera.
fn view_ray(camera: CameraUniforms, frag_xy: vec2<f32>) -> vec3<f32> {
    let ndc_x = frag_xy.x * camera.viewport.z * 2.0 - 1.0;
    let ndc_y = 1.0 - frag_xy.y * camera.viewport.w * 2.0;
    let h = camera.inv_view_proj * vec4<f32>(ndc_x, ndc_y, 0.5, 1.0);
    return normalize(h.xyz / h.w);
}
