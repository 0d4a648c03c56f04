//! The CPU renderer's entry points: a scene in, the frame's maps and picture out. Wires the
//! Preetham sky (stage `sky`), the near/far patch mesh and the tonemap into [`frame::render`].

use ocean_core::camera::Camera;
use ocean_core::camera_uniforms::CameraUniforms;
use ocean_core::frame::{FrameUniforms, scene_sky, sky_ambient};
use ocean_core::plan::{FramePlan, OutputKind, Pass};
use ocean_core::scene::Scene;
use ocean_core::tonemap::TonemapUniforms;

use crate::frame::{self, Error, FrameBuffers, WaterMesh};
use crate::shaders::shared::preetham;
use crate::shaders::{sky, tonemap};

/// A rendered frame.
pub struct Rendered {
    /// The plan it ran.
    pub plan: FramePlan,
    /// Every map and the HDR picture.
    pub buffers: FrameBuffers,
    /// The 8-bit sRGB RGBA picture, when the plan tonemaps.
    pub ldr: Option<Vec<u8>>,
}

/// The near/far patch mesh of a view (seed 000 §3), for the scene's displacement grid and
/// `[quality]`, without the far patch where the plan leaves it out.
pub fn water_mesh(scene: &Scene, plan: &FramePlan, camera: &Camera) -> Result<WaterMesh, Error> {
    Ok(plan.water_mesh(scene, camera)?.into())
}

/// Renders a validated scene by its single-frame plan; `on_pass` is called as each pass
/// starts.
pub fn render_scene(
    scene: &Scene,
    output: OutputKind,
    on_pass: &mut dyn FnMut(Pass),
) -> Result<Rendered, Error> {
    render_scene_with_plan(scene, FramePlan::new(scene, output), on_pass)
}

/// Renders a validated scene by a given plan (e.g. [`FramePlan::full`], to compare with the
/// pruned one).
pub fn render_scene_with_plan(
    scene: &Scene,
    plan: FramePlan,
    on_pass: &mut dyn FnMut(Pass),
) -> Result<Rendered, Error> {
    let camera = Camera::from_scene(&scene.camera)?;
    let preetham_sky = scene_sky(scene)?;
    let sky_u = preetham_sky.uniforms();
    let camera_u = CameraUniforms::new(
        camera.view_proj().to_cols_array_2d(),
        [0.0; 3],
        camera.width,
        camera.height,
    )?;
    let ambient = sky_ambient(&preetham_sky);
    let sky_radiance = |d: [f32; 3]| preetham::sky_radiance(&sky_u, d);
    let draw_sky = |t: &mut crate::raster::RenderTarget| sky::render_sky(t, &camera_u, &sky_u);
    let mesh = |c: &Camera| water_mesh(scene, &plan, c);
    let customise = |u: &mut FrameUniforms| u.sky_ambient = ambient;
    let buffers =
        frame::render_with(scene, &plan, &sky_radiance, &draw_sky, &mesh, &customise, on_pass)?;
    let ldr = if plan.runs(Pass::Tonemap) {
        on_pass(Pass::Tonemap);
        let t = TonemapUniforms::new(scene.camera.exposure)?;
        Some(tonemap::tonemap_to_rgba8(&buffers.hdr.color, camera.width, camera.height, &t))
    } else {
        None
    };
    Ok(Rendered { plan, buffers, ldr })
}

/// The 8-bit sRGB RGBA picture of a scene (row-major, top row first).
pub fn render_ldr(scene: &Scene) -> Result<Vec<u8>, Error> {
    let r = render_scene(scene, OutputKind::Ldr, &mut |_| {})?;
    Ok(r.ldr.unwrap_or_default())
}
