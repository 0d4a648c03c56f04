//! The frame of Hu et al. 2004 on the CPU: runs a [`FramePlan`] pass by pass with the shader
//! mirrors and the rasterizer, keeping every intermediate map for the tests and the GPU
//! cross-check.

use std::time::{Duration, Instant};

use ocean_core::camera::Camera;
use ocean_core::frame::{
    FrameUniforms, FresnelTableUniforms, ObjectVertex, bump_texels, displacement_slope_texels,
    displacement_texels, object_triangles,
};
use ocean_core::plan::{FramePlan, Pass};
use ocean_core::scene::{Object, Scene};
use ocean_core::waves::{FrameCycle, Synthesizer, WaveMaps};

use crate::raster::{self, BlendMode, CompareFunction, RasterState, RenderTarget, Vertex};
use crate::sampler::Texture2D;
use crate::shaders::{fresnel_table, objects, shadow, water};

/// Default side of the 2D Fresnel textures (the error table in the README: 256² is within 2e-3
/// of eq. 2 up to 76° from the normal); a scene's `[quality] fresnel_table_size` and the plan
/// choose the size a frame uses.
pub const FRESNEL_TABLE_SIZE: u32 = ocean_core::scene::DEFAULT_FRESNEL_TABLE_SIZE;
/// Side of the sun's shadow map.
pub const SHADOW_MAP_SIZE: u32 = 1024;

/// Errors of the CPU renderer.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The scene's physics could not be set up.
    #[error(transparent)]
    Core(#[from] ocean_core::Error),
    /// The image is larger than a render target may be.
    #[error("image {width}×{height} exceeds the largest render target ({max}² pixels)")]
    TooLarge {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
        /// The limit.
        max: u32,
    },
}

/// Every map a frame produced: the final HDR image and each intermediate.
pub struct FrameBuffers {
    /// (disp_x, height, disp_z, jacobian) of the displacement map.
    pub displacement: Texture2D,
    /// (slope_x, slope_z, 0, 0) of the displacement map.
    pub displacement_slopes: Texture2D,
    /// (slope_x, slope_z, height, jacobian) of the bump map.
    pub bump: Texture2D,
    /// Fresnel texture for η (surface seen from above).
    pub fresnel_above: Texture2D,
    /// Fresnel texture for 1/η (seen from below).
    pub fresnel_below: Texture2D,
    /// Depth of the objects from the sun (R channel).
    pub shadow_map: Texture2D,
    /// Mirrored objects above the water, alpha = coverage.
    pub reflection_map: Texture2D,
    /// Fogged objects under the water, alpha = coverage.
    pub refraction_map: Texture2D,
    /// The frame, linear HDR RGBA.
    pub hdr: RenderTarget,
    /// The frame's uniforms.
    pub uniforms: FrameUniforms,
    /// Wall time of each pass that ran, in order.
    pub timings: Vec<(Pass, Duration)>,
}

/// An empty 1×1 texture bound where a skipped pass would have left its map: the shaders
/// multiply what they read from it by 0 (the plan's pass flags).
fn empty() -> Texture2D {
    Texture2D::new(1, 1, vec![[0.0; 4]])
}

fn target_texture(t: RenderTarget) -> Texture2D {
    Texture2D::new(t.width, t.height, t.color)
}

/// The displacement map packed as the water stage binds it: (disp_x, height, disp_z,
/// jacobian) and (slope_x, slope_z, 0, 0).
fn wave_textures(maps: &WaveMaps<f32>) -> (Texture2D, Texture2D) {
    let n = maps.resolution() as u32;
    (
        Texture2D::new(n, n, displacement_texels(maps)),
        Texture2D::new(n, n, displacement_slope_texels(maps)),
    )
}

/// The water mesh of a view: vertices relative to `origin` (world x, z; see
/// `ocean_core::geometry::WaterMesh`), triangles counter-clockwise seen from above.
#[derive(Clone, Debug, PartialEq)]
pub struct WaterMesh {
    /// The vertices.
    pub vertices: Vec<water::WaterVertex>,
    /// The triangles.
    pub indices: Vec<[u32; 3]>,
    /// The mesh's reference point (world x, z), m.
    pub origin: [f64; 2],
}

impl From<ocean_core::geometry::WaterMesh> for WaterMesh {
    fn from(m: ocean_core::geometry::WaterMesh) -> Self {
        Self { vertices: m.vertices, indices: m.indices, origin: m.origin }
    }
}

/// Draws the objects' triangles with one of the objects stage's entry-point pairs.
fn draw_objects(
    target: &mut RenderTarget,
    state: &RasterState,
    tris: &[[ObjectVertex; 3]],
    u: &FrameUniforms,
    vs: fn(&ObjectVertex, &FrameUniforms) -> objects::VertexOut,
    fs: fn(&objects::VertexOut, &FrameUniforms) -> Option<[f32; 4]>,
) {
    let verts: Vec<[Vertex<{ objects::VARYINGS }>; 3]> = tris
        .iter()
        .map(|t| {
            t.map(|v| {
                let o = vs(&v, u);
                Vertex::new(o.clip, o.varyings())
            })
        })
        .collect();
    raster::draw(target, state, &verts, |frag| {
        fs(&objects::VertexOut::from_varyings(&frag.varyings), u)
    });
}

/// Reversed-Z depth state of the views from the eye: `Greater`, cleared to 0.
fn eye_state() -> RasterState {
    RasterState { depth_compare: CompareFunction::Greater, ..RasterState::default() }
}

/// Renders a frame of a validated scene by its plan. `sky_radiance` is the sky stage's
/// radiance of a world direction; `water_mesh` gives the near/far patch mesh of the view (it
/// should leave the far patch out where the plan does: `ocean_core::plan::water_mesh`);
/// `on_pass` is called as each pass starts (progress reporting).
pub fn render(
    scene: &Scene,
    plan: &FramePlan,
    sky_radiance: &(dyn Fn([f32; 3]) -> [f32; 3] + Sync),
    draw_sky: &dyn Fn(&mut RenderTarget),
    water_mesh: &dyn Fn(&Camera) -> Result<WaterMesh, Error>,
    on_pass: &mut dyn FnMut(Pass),
) -> Result<FrameBuffers, Error> {
    render_with(scene, plan, sky_radiance, draw_sky, water_mesh, &|_| {}, on_pass)
}

/// [`render`], with `customise` applied to the frame's uniforms before any pass (the sky's
/// ambient term, which depends on the sky model the caller chose).
pub fn render_with(
    scene: &Scene,
    plan: &FramePlan,
    sky_radiance: &(dyn Fn([f32; 3]) -> [f32; 3] + Sync),
    draw_sky: &dyn Fn(&mut RenderTarget),
    water_mesh: &dyn Fn(&Camera) -> Result<WaterMesh, Error>,
    customise: &dyn Fn(&mut FrameUniforms),
    on_pass: &mut dyn FnMut(Pass),
) -> Result<FrameBuffers, Error> {
    let camera = Camera::from_scene(&scene.camera)?;
    let (w, h) = (camera.width, camera.height);
    if w > RenderTarget::MAX_SIZE || h > RenderTarget::MAX_SIZE {
        return Err(Error::TooLarge { width: w, height: h, max: RenderTarget::MAX_SIZE });
    }
    let mesh_start = Instant::now();
    let mesh = water_mesh(&camera)?;
    let mesh_time = mesh_start.elapsed();
    let mut u = FrameUniforms::new(scene, &camera, plan, mesh.origin);
    customise(&mut u);
    let u = u;
    let mut timings = Vec::new();
    let mut timed = |pass: Pass, start: Instant| timings.push((pass, start.elapsed()));

    // cycle, waves
    let (mut displacement, mut displacement_slopes, mut bump) = (empty(), empty(), empty());
    if plan.runs(Pass::Waves) {
        let mut t0 = Instant::now();
        let surface = scene.ocean.surface()?;
        let t = scene.ocean.time_s;
        let chop = scene.ocean.choppiness;
        let mut synth_d = Synthesizer::<f32>::new(surface.displacement.resolution())?;
        let mut synth_b = Synthesizer::<f32>::new(surface.bump.resolution())?;
        let (d, b) = if plan.runs(Pass::Cycle) {
            // Cyclic playback: the loop's maps at F instants, the one nearest t shown.
            on_pass(Pass::Cycle);
            let d = FrameCycle::new(&surface.displacement, &mut synth_d, chop)?;
            let b = FrameCycle::new(&surface.bump, &mut synth_b, chop)?;
            timed(Pass::Cycle, t0);
            t0 = Instant::now();
            on_pass(Pass::Waves);
            (d.frame_at(t).clone(), b.frame_at(t).clone())
        } else {
            on_pass(Pass::Waves);
            (
                synth_d.synthesize(&surface.displacement, t, chop)?,
                synth_b.synthesize(&surface.bump, t, chop)?,
            )
        };
        (displacement, displacement_slopes) = wave_textures(&d);
        let n = b.resolution() as u32;
        bump = Texture2D::new(n, n, bump_texels(&b));
        timed(Pass::Waves, t0);
    }

    // fresnel_table
    on_pass(Pass::FresnelTable);
    let t0 = Instant::now();
    let table = |eta: f32| {
        fresnel_table::dispatch(&FresnelTableUniforms {
            eta,
            size: plan.fresnel_table_size,
            mapping: 0,
            pad: 0,
        })
    };
    let fresnel_above = table(u.water_params[0]);
    let fresnel_below = table(1.0 / u.water_params[0]);
    timed(Pass::FresnelTable, t0);

    // The objects each pass draws (the plan culls per pass).
    let tris_of = |pass: Pass| {
        let objects: Vec<Object> =
            plan.objects.of(pass).iter().map(|&i| scene.objects[i].clone()).collect();
        object_triangles(&objects, camera.eye)
    };

    // shadow_map
    let mut shadow_map = empty();
    if plan.runs(Pass::ShadowMap) {
        on_pass(Pass::ShadowMap);
        let t0 = Instant::now();
        let mut target = RenderTarget::new(SHADOW_MAP_SIZE, SHADOW_MAP_SIZE);
        target.clear_color([1.0, 0.0, 0.0, 0.0]);
        target.clear_depth(1.0);
        let verts: Vec<[Vertex<0>; 3]> = tris_of(Pass::ShadowMap)
            .iter()
            .map(|t| t.map(|v| Vertex::new(shadow::vs_main(v.position, &u), [])))
            .collect();
        raster::draw(&mut target, &RasterState::default(), &verts, |f| {
            Some(shadow::fs_main(f.frag_coord))
        });
        shadow_map = target_texture(target);
        timed(Pass::ShadowMap, t0);
    }

    // reflection_map, refraction_map
    // Both are looked up at normalised screen coordinates, so they may be smaller than the
    // viewport (the plan's reflection_map_size).
    let mut object_map = |pass: Pass, size: [u32; 2], vs, fs| {
        on_pass(pass);
        let mut target = RenderTarget::new(size[0], size[1]);
        target.clear_depth(0.0);
        draw_objects(&mut target, &eye_state(), &tris_of(pass), &u, vs, fs);
        target_texture(target)
    };
    let mut reflection_map = empty();
    if plan.runs(Pass::ReflectionMap) {
        let t0 = Instant::now();
        reflection_map = object_map(
            Pass::ReflectionMap,
            plan.reflection_map_size,
            objects::vs_reflect,
            objects::fs_reflect,
        );
        timed(Pass::ReflectionMap, t0);
    }
    let mut refraction_map = empty();
    if plan.runs(Pass::RefractionMap) {
        let t0 = Instant::now();
        refraction_map =
            object_map(Pass::RefractionMap, [w, h], objects::vs_refract, objects::fs_refract);
        timed(Pass::RefractionMap, t0);
    }

    // sky
    let mut hdr = RenderTarget::new(w, h);
    hdr.clear_depth(0.0);
    if plan.runs(Pass::Sky) {
        on_pass(Pass::Sky);
        let t0 = Instant::now();
        draw_sky(&mut hdr);
        timed(Pass::Sky, t0);
    } else {
        // Under the water: the water volume is the background.
        hdr.clear_color([u.water_color[0], u.water_color[1], u.water_color[2], 1.0]);
    }

    // objects
    if plan.runs(Pass::Objects) {
        on_pass(Pass::Objects);
        let t0 = Instant::now();
        draw_objects(
            &mut hdr,
            &eye_state(),
            &tris_of(Pass::Objects),
            &u,
            objects::vs_main,
            |o, u| Some(objects::fs_main(o, u)),
        );
        timed(Pass::Objects, t0);
    }

    // water
    on_pass(Pass::Water);
    let t0 = Instant::now();
    let bindings = water::Bindings {
        frame: &u,
        displacement: &displacement,
        displacement_slopes: &displacement_slopes,
        bump: &bump,
        fresnel_above: &fresnel_above,
        fresnel_below: &fresnel_below,
        reflection_map: &reflection_map,
        refraction_map: &refraction_map,
        shadow_map: &shadow_map,
        sky_radiance,
    };
    let verts: Vec<Vertex<{ water::VARYINGS }>> = mesh
        .vertices
        .iter()
        .map(|v| {
            let o = water::vs_main(v, &bindings);
            Vertex::new(o.clip, o.varyings())
        })
        .collect();
    let state = RasterState { blend: BlendMode::Replace, ..eye_state() };
    raster::draw_indexed(&mut hdr, &state, &verts, &mesh.indices, |frag| {
        Some(water::fs_main(
            &water::VertexOut::from_fragment(frag.frag_coord, &frag.varyings),
            &bindings,
        ))
    });
    // The water pass's time includes building its mesh (near patch, and far patch if planned).
    timings.push((Pass::Water, t0.elapsed() + mesh_time));

    Ok(FrameBuffers {
        displacement,
        displacement_slopes,
        bump,
        fresnel_above,
        fresnel_below,
        shadow_map,
        reflection_map,
        refraction_map,
        hdr,
        uniforms: u,
        timings,
    })
}
