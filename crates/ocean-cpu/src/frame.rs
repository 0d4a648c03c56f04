//! The CPU back end of the frame graph: [`CpuBackend`] executes one planned pass at a time
//! with the shader mirrors and the rasterizer, at the sizes the plan gives
//! (`ocean_core::graph::run_frame` walks the passes), keeping every intermediate map for the
//! tests and the GPU cross-check.

use std::time::Duration;

use ocean_core::camera::Camera;
use ocean_core::frame::{
    FrameUniforms, FresnelTableUniforms, ObjectVertex, bump_texels, displacement_slope_texels,
    displacement_texels, pass_triangles,
};
use ocean_core::graph::{Backend, FoamField, FoamWork, FrameInputs, FrameState, run_frame};
use ocean_core::plan::{Format, FramePlan, Pass, PlannedPass, ResourceId, WavesKernel};
use ocean_core::scene::Scene;
use ocean_core::spray::{SprayFrame, SprayState};
use ocean_core::waves::{Synthesizer, WaveMaps};

use crate::mip::MipChain;
use crate::raster::{self, BlendMode, CompareFunction, RasterState, RenderTarget, Vertex};
use crate::sampler::Texture2D;
use crate::shaders::shared::floor::FloorMaps;
use crate::shaders::waves::WavesMirror;
use crate::shaders::{
    bloom, fresnel_table, objects, shadow, sky, spray, tonemap, water, wave_mips,
};

/// Default side of the 2D Fresnel textures (docs/design.md's tolerance table: 256² is within 2e-3
/// of eq. 2 up to 76° from the normal); a scene's `[quality] fresnel_table_size` and the plan
/// choose the size a frame uses.
pub const FRESNEL_TABLE_SIZE: u32 = ocean_core::scene::DEFAULT_FRESNEL_TABLE_SIZE;
/// Side of the sun's shadow map (the plan's).
pub const SHADOW_MAP_SIZE: u32 = ocean_core::plan::SHADOW_MAP_SIZE;

/// The water mesh of a view (ocean-core's [`ocean_core::graph::DrawMesh`]).
pub type WaterMesh = ocean_core::graph::DrawMesh;

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
    /// The displacement map's slope chain (far fields `mip`, `variance`; else 1×1 zero).
    pub displacement_slope_mips: MipChain,
    /// The bump map's.
    pub bump_mips: MipChain,
    /// The filtered Fresnel table (far field `variance`; else 1×1 zero).
    pub fresnel_filter: Texture2D,
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
    /// The sea floor's relief as the stages bound it (one zero texel without one).
    pub floor_map: Texture2D,
    /// Foam `accumulated`'s field after this frame's steps (else one zero texel).
    pub foam_field: Texture2D,
    /// The frame, linear HDR RGBA.
    pub hdr: RenderTarget,
    /// Post `bloom`: the bright pass's down chain (else 1×1 zero).
    pub bloom_down: MipChain,
    /// Post `bloom`: the up chain, level 0 what the tonemap adds (else 1×1 zero).
    pub bloom_up: MipChain,
    /// The 8-bit sRGB RGBA picture, when the plan tonemaps.
    pub ldr: Option<Vec<u8>>,
    /// The frame's uniforms.
    pub uniforms: FrameUniforms,
    /// Wall time of each pass that ran, in order.
    pub timings: Vec<(Pass, Duration)>,
}

impl FrameBuffers {
    /// The slope maps as the water pass bound them: the chains when `wave_mips` ran, else
    /// the maps themselves as one level.
    pub fn water_slopes(&self, plan: &FramePlan) -> (MipChain, MipChain) {
        if plan.runs(Pass::WaveMips) {
            (self.displacement_slope_mips.clone(), self.bump_mips.clone())
        } else {
            (
                MipChain::single(self.displacement_slopes.clone()),
                MipChain::single(self.bump.clone()),
            )
        }
    }

    /// The water pass's bindings over these buffers, with the slope chains of
    /// [`Self::water_slopes`], the plan's foam and a given sky and shading (tools that rerun
    /// parts of the pass).
    pub fn water_bindings<'a>(
        &'a self,
        plan: &FramePlan,
        (slopes, bump): (&'a MipChain, &'a MipChain),
        sky_radiance: &'a (dyn Fn([f32; 3]) -> [f32; 3] + Sync),
        shade_above: crate::shaders::shading::ShadeAbove,
    ) -> water::Bindings<'a> {
        water::Bindings {
            frame: &self.uniforms,
            displacement: &self.displacement,
            displacement_slopes: slopes,
            bump,
            fresnel_filter: &self.fresnel_filter,
            fresnel_above: &self.fresnel_above,
            fresnel_below: &self.fresnel_below,
            reflection_map: &self.reflection_map,
            refraction_map: &self.refraction_map,
            shadow_map: &self.shadow_map,
            floor_map: &self.floor_map,
            foam_field: &self.foam_field,
            sky_radiance,
            shade_above,
            foam_coverage: crate::shaders::foam::foam_coverage(plan.techniques.foam()),
        }
    }

    /// A float map by its resource id (`ldr` is not a float map: `None`).
    pub fn map(&self, id: ResourceId) -> Option<(u32, u32, &[[f32; 4]])> {
        let t = match id {
            ResourceId::Displacement => &self.displacement,
            ResourceId::DisplacementSlopes => &self.displacement_slopes,
            ResourceId::Bump => &self.bump,
            ResourceId::DisplacementSlopeMips => &self.displacement_slope_mips.atlas,
            ResourceId::BumpMips => &self.bump_mips.atlas,
            ResourceId::FresnelFilter => &self.fresnel_filter,
            ResourceId::FresnelAbove => &self.fresnel_above,
            ResourceId::FresnelBelow => &self.fresnel_below,
            ResourceId::ShadowMap => &self.shadow_map,
            ResourceId::ReflectionMap => &self.reflection_map,
            ResourceId::RefractionMap => &self.refraction_map,
            ResourceId::Hdr => return Some((self.hdr.width, self.hdr.height, &self.hdr.color)),
            ResourceId::BloomDown => &self.bloom_down.atlas,
            ResourceId::BloomUp => &self.bloom_up.atlas,
            ResourceId::FoamField => &self.foam_field,
            ResourceId::Ldr | ResourceId::Environment => return None,
        };
        Some((t.width, t.height, &t.texels))
    }
}

/// The environment the frame reflects and draws behind everything: the plan's sky technique,
/// or (tests of the water pass) a given radiance function and background.
#[derive(Clone, Copy)]
pub enum Environment<'a> {
    /// The sky technique the plan chose, from [`FrameInputs::environment`].
    Planned,
    /// A given radiance of a world direction, and what the `sky` pass draws.
    Given {
        /// Radiance of a world direction.
        radiance: &'a (dyn Fn([f32; 3]) -> [f32; 3] + Sync),
        /// The `sky` pass.
        draw: &'a dyn Fn(&mut RenderTarget),
    },
}

/// The CPU back end: executes passes, holding the resources they write.
pub struct CpuBackend<'e> {
    environment: Environment<'e>,
    maps: Vec<(ResourceId, Texture2D)>,
    chains: Vec<(ResourceId, MipChain)>,
    hdr: Option<RenderTarget>,
    ldr: Option<Vec<u8>>,
    /// The sea floor's relief (`floor_map`), made on first use: the object passes, the water
    /// pass and the frame's buffers share one copy.
    floor: Option<Texture2D>,
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

/// Draws the objects' triangles with one of the objects stage's entry-point pairs.
fn draw_objects(
    target: &mut RenderTarget,
    state: &RasterState,
    tris: &[[ObjectVertex; 3]],
    u: &FrameUniforms,
    vs: fn(&ObjectVertex, &FrameUniforms) -> objects::VertexOut,
    fs: &(dyn Fn(&objects::VertexOut, &FrameUniforms) -> Option<[f32; 4]> + Sync),
) {
    let verts: Vec<[Vertex<{ objects::VARYINGS }>; 3]> = tris
        .iter()
        .map(|t| {
            t.map(|v| {
                let o = vs(&v, u);
                Vertex::new(o.clip.into(), o.varyings())
            })
        })
        .collect();
    raster::draw(target, state, &verts, |frag| {
        fs(&objects::VertexOut::from_varyings(&frag.varyings), u)
    });
}

/// The water pass's draw: `water::vs_main` on every vertex of `mesh` (surface
/// `projected_grid`: `water::vs_projected_grid` on every vertex index, `clipmap`
/// `water::vs_clipmap`), then `fragment` on
/// every covered pixel, reversed-Z with `Greater`, no blending. The frame's water pass runs it
/// with `water::fs_main`; a probe (`ocean report`'s Fresnel lookups) runs it with another
/// fragment function of the same mirror.
pub fn draw_water(
    target: &mut RenderTarget,
    mesh: &WaterMesh,
    bindings: &water::Bindings<'_>,
    fragment: &(dyn Fn(&water::VertexOut, &water::Bindings<'_>) -> Option<[f32; 4]> + Sync),
) {
    let (verts, indices) = water_vertices(mesh, bindings);
    let state = RasterState { blend: BlendMode::Replace, ..eye_state() };
    raster::draw_indexed(target, &state, &verts, &indices, |frag| {
        fragment(&water::VertexOut::from_fragment(frag.frag_coord, &frag.varyings), bindings)
    });
}

/// [`draw_water`] of the frame's `water::fs_main`, which never discards: each pixel is shaded
/// once, for the water fragment that stays ([`raster::draw_indexed_visible`]); the same
/// target bit for bit, without shading what the nearer water hides.
fn draw_water_visible(target: &mut RenderTarget, mesh: &WaterMesh, bindings: &water::Bindings<'_>) {
    let (verts, indices) = water_vertices(mesh, bindings);
    let state = RasterState { blend: BlendMode::Replace, ..eye_state() };
    raster::draw_indexed_visible(target, &state, &verts, &indices, |frag| {
        water::fs_main(&water::VertexOut::from_fragment(frag.frag_coord, &frag.varyings), bindings)
    });
}

/// The water's vertices, shaded, and its triangles.
#[allow(clippy::type_complexity, reason = "a vertex list and its index triples")]
fn water_vertices(
    mesh: &WaterMesh,
    bindings: &water::Bindings<'_>,
) -> (Vec<Vertex<{ water::VARYINGS }>>, Vec<[u32; 3]>) {
    let vertex = |o: water::VertexOut| Vertex::new(o.clip.into(), o.varyings());
    let grid = bindings.frame.grid.vertex_count();
    let clipmap = bindings.frame.clip.vertex_count();
    if clipmap > 0 {
        // Surface `clipmap`: the vertex-index draw of its levels' triangle lists; every vertex
        // is a pure function of its index, so they are shaded in parallel.
        use rayon::prelude::*;
        let verts =
            (0..clipmap).into_par_iter().map(|k| vertex(water::vs_clipmap(k, bindings))).collect();
        (verts, (0..clipmap / 3).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect())
    } else if grid > 0 {
        // Surface `projected_grid`: the vertex-index draw of a triangle list.
        let verts = (0..grid).map(|k| vertex(water::vs_projected_grid(k, bindings))).collect();
        (verts, (0..grid / 3).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect())
    } else {
        let verts = mesh.vertices.iter().map(|v| vertex(water::vs_main(v, bindings))).collect();
        (verts, mesh.indices.to_vec())
    }
}

/// Reversed-Z depth state of the views from the eye: `Greater`, cleared to 0.
fn eye_state() -> RasterState {
    RasterState { depth_compare: CompareFunction::Greater, ..RasterState::default() }
}

/// What a stage reads for a map whose pass did not run: one zero texel.
static EMPTY_MAP: std::sync::LazyLock<Texture2D> =
    std::sync::LazyLock::new(|| Texture2D::new(1, 1, vec![[0.0; 4]]));

/// The sea floor's relief as the stages bind it (`floor_map`).
fn floor_texture(scene: &Scene) -> Texture2D {
    let (w, h, texels) = ocean_core::terrain::relief_texels(scene.terrain.as_ref());
    Texture2D::new(w, h, texels)
}

fn target_texture(t: RenderTarget) -> Texture2D {
    Texture2D::new(t.width, t.height, t.color)
}

/// The HDR frame at the plan's size and clear colour, reversed-Z depth cleared to 0.
fn new_hdr(plan: &FramePlan) -> RenderTarget {
    let mut t = planned_target(plan, ResourceId::Hdr);
    t.clear_depth(0.0);
    t
}

/// A render target of the plan's size for `id`, cleared to the plan's colour.
fn planned_target(plan: &FramePlan, id: ResourceId) -> RenderTarget {
    let (size, clear, format) = plan
        .resource(id)
        .map_or(([1, 1], [0.0; 4], Format::Rgba32Float), |r| (r.size, r.clear, r.format));
    let mut t = RenderTarget::with_format(size[0], size[1], format.storage());
    t.clear_color(clear);
    t
}

impl<'e> CpuBackend<'e> {
    /// A back end for one frame with the given environment.
    pub fn new(environment: Environment<'e>) -> Self {
        Self {
            environment,
            maps: Vec::new(),
            chains: Vec::new(),
            hdr: None,
            ldr: None,
            floor: None,
        }
    }

    /// Makes the frame's `floor_map` if no pass has yet.
    fn ensure_floor(&mut self, scene: &Scene) {
        if self.floor.is_none() {
            self.floor = Some(floor_texture(scene));
        }
    }

    /// The frame's `floor_map` ([`Self::ensure_floor`] first).
    fn floor_map(&self) -> &Texture2D {
        self.floor.as_ref().unwrap_or(&EMPTY_MAP)
    }

    fn put(&mut self, id: ResourceId, t: Texture2D) {
        self.maps.retain(|(m, _)| *m != id);
        self.maps.push((id, t));
    }

    /// A map a pass wrote, or the plan's 1×1 zero texture in place of a skipped pass's.
    fn take(&mut self, id: ResourceId) -> Texture2D {
        match self.maps.iter().position(|(m, _)| *m == id) {
            Some(i) => self.maps.swap_remove(i).1,
            None => EMPTY_MAP.clone(),
        }
    }

    /// A chain `wave_mips` wrote, or a 1×1 zero chain.
    fn take_chain(&mut self, id: ResourceId) -> MipChain {
        match self.chains.iter().position(|(m, _)| *m == id) {
            Some(i) => self.chains.swap_remove(i).1,
            None => MipChain::single(EMPTY_MAP.clone()),
        }
    }

    /// `wave_mips`: the two chains from the slope maps, and the filtered Fresnel table when
    /// the plan sizes it.
    fn mip_chains(&mut self, frame: &FrameInputs<'_>) {
        for (src, dst) in ResourceId::SLOPE_CHAINS {
            let chain = wave_mips::dispatch(self.map_or_empty(src));
            self.chains.retain(|(m, _)| *m != dst);
            self.chains.push((dst, chain));
        }
        if let Some(table) = frame.plan.fresnel_filter(frame.scene) {
            let (w, h) =
                (ocean_core::far_field::FILTER_RADII, ocean_core::far_field::FILTER_SIGMAS);
            self.put(ResourceId::FresnelFilter, Texture2D::new(w, h, table.texels.clone()));
        }
    }

    /// The HDR frame, made at the plan's size and clear colour by its first writer.
    fn hdr(&mut self, plan: &FramePlan) -> &mut RenderTarget {
        self.hdr.get_or_insert_with(|| new_hdr(plan))
    }

    /// The frame's buffers once every pass has run.
    pub fn finish(
        mut self,
        frame: &FrameInputs<'_>,
        timings: Vec<(Pass, Duration)>,
    ) -> FrameBuffers {
        let hdr = self.hdr.take().unwrap_or_else(|| planned_target(frame.plan, ResourceId::Hdr));
        FrameBuffers {
            displacement: self.take(ResourceId::Displacement),
            displacement_slopes: self.take(ResourceId::DisplacementSlopes),
            bump: self.take(ResourceId::Bump),
            displacement_slope_mips: self.take_chain(ResourceId::DisplacementSlopeMips),
            bump_mips: self.take_chain(ResourceId::BumpMips),
            fresnel_filter: self.take(ResourceId::FresnelFilter),
            fresnel_above: self.take(ResourceId::FresnelAbove),
            fresnel_below: self.take(ResourceId::FresnelBelow),
            shadow_map: self.take(ResourceId::ShadowMap),
            reflection_map: self.take(ResourceId::ReflectionMap),
            refraction_map: self.take(ResourceId::RefractionMap),
            floor_map: self.floor.take().unwrap_or_else(|| floor_texture(frame.scene)),
            foam_field: self.take(ResourceId::FoamField),
            hdr,
            bloom_down: self.take_chain(ResourceId::BloomDown),
            bloom_up: self.take_chain(ResourceId::BloomUp),
            ldr: self.ldr.take(),
            uniforms: frame.uniforms,
            timings,
        }
    }

    fn wave_maps(&mut self, frame: &FrameInputs<'_>, state: &FrameState) -> Result<(), Error> {
        let ocean = &frame.scene.ocean;
        let t = frame.time_s;
        let owned;
        let (d, b) = if frame.plan.runs(Pass::Cycle) {
            // Cyclic playback: the loop's maps at F instants, the one nearest t shown.
            state.cycle_at(ocean, t).ok_or_else(|| {
                Error::Core(ocean_core::Error::InvalidParameter {
                    name: "loop_period_s",
                    value: ocean.loop_period_s,
                    reason: "the plan plays a cycle that was not precomputed".into(),
                })
            })?
        } else if frame.plan.waves_kernel == WavesKernel::Shader {
            // The oracle runs waves.wgsl's own mirror, as the GPU runs the WGSL.
            let surface = ocean.surface()?;
            let chop = ocean.choppiness;
            let d = WavesMirror::new(&surface.displacement)?.run(t, chop)?;
            let b = WavesMirror::new(&surface.bump)?.run(t, chop)?;
            self.put(ResourceId::Displacement, d.displacement);
            self.put(ResourceId::DisplacementSlopes, d.displacement_slopes);
            self.put(ResourceId::Bump, b.bump);
            return Ok(());
        } else {
            let surface = ocean.surface()?;
            let chop = ocean.choppiness;
            let mut synth_d = Synthesizer::<f32>::new(surface.displacement.resolution())?;
            let mut synth_b = Synthesizer::<f32>::new(surface.bump.resolution())?;
            owned = (
                synth_d.synthesize(&surface.displacement, t, chop)?,
                synth_b.synthesize(&surface.bump, t, chop)?,
            );
            (&owned.0, &owned.1)
        };
        let (displacement, slopes) = wave_textures(d);
        let n = b.resolution() as u32;
        self.put(ResourceId::Displacement, displacement);
        self.put(ResourceId::DisplacementSlopes, slopes);
        self.put(ResourceId::Bump, Texture2D::new(n, n, bump_texels(b)));
        Ok(())
    }

    fn fresnel_textures(&mut self, frame: &FrameInputs<'_>) {
        let eta = frame.uniforms.water.eta;
        for (id, eta) in [(ResourceId::FresnelAbove, eta), (ResourceId::FresnelBelow, 1.0 / eta)] {
            let size = frame.plan.resource(id).map_or(1, |r| r.size[0]);
            let t = fresnel_table::dispatch(&FresnelTableUniforms::new(
                eta,
                size,
                frame.plan.fresnel_mapping,
            ));
            self.put(id, t);
        }
    }

    /// A map the frame made so far, or one zero texel before its pass ran.
    fn map_or_empty(&self, id: ResourceId) -> &Texture2D {
        self.maps.iter().find(|(m, _)| *m == id).map_or(&EMPTY_MAP, |(_, t)| t)
    }

    /// The objects stage's maps (bindings 1, 3, 4).
    fn object_maps<'a>(&'a self, floor_map: &'a Texture2D) -> objects::Maps<'a> {
        objects::Maps {
            displacement: self.map_or_empty(ResourceId::Displacement),
            floor: FloorMaps { shadow_map: self.map_or_empty(ResourceId::ShadowMap), floor_map },
        }
    }

    fn object_pass(&mut self, pass: &PlannedPass, frame: &FrameInputs<'_>) {
        let scene = frame.scene;
        let tris = pass_triangles(scene, &frame.poses, pass, frame.camera.eye);
        let u = &frame.uniforms;
        match pass.name {
            Pass::ShadowMap => {
                let mut target = planned_target(frame.plan, ResourceId::ShadowMap);
                target.clear_color([1.0, 0.0, 0.0, 0.0]);
                target.clear_depth(1.0);
                let verts: Vec<[Vertex<0>; 3]> = tris
                    .iter()
                    .map(|t| t.map(|v| Vertex::new(shadow::vs_main(v.position, u), [])))
                    .collect();
                raster::draw(&mut target, &RasterState::default(), &verts, |f| {
                    Some(shadow::fs_main(f.frag_coord))
                });
                self.put(ResourceId::ShadowMap, target_texture(target));
            }
            // Both maps are looked up at normalised screen coordinates, so they may be
            // smaller than the viewport (the plan's sizes).
            Pass::ReflectionMap | Pass::RefractionMap => {
                let (id, vs, fs): (_, objects::VertexEntry, objects::MapFragmentEntry) =
                    if pass.name == Pass::ReflectionMap {
                        (ResourceId::ReflectionMap, objects::vs_reflect, objects::fs_reflect)
                    } else {
                        (ResourceId::RefractionMap, objects::vs_refract, objects::fs_refract)
                    };
                let mut target = planned_target(frame.plan, id);
                target.clear_depth(0.0);
                self.ensure_floor(scene);
                let maps = self.object_maps(self.floor_map());
                draw_objects(&mut target, &eye_state(), &tris, u, vs, &|o, u| fs(o, u, maps));
                self.put(id, target_texture(target));
            }
            _ => {
                self.ensure_floor(scene);
                // Taken out while the maps are borrowed, put back after the draw.
                let mut hdr = self.hdr.take().unwrap_or_else(|| new_hdr(frame.plan));
                let maps = self.object_maps(self.floor_map());
                draw_objects(&mut hdr, &eye_state(), &tris, u, objects::vs_main, &|o, u| {
                    Some(objects::fs_main(o, u, maps))
                });
                self.hdr = Some(hdr);
            }
        }
    }

    fn water_pass(&mut self, frame: &FrameInputs<'_>) -> Result<(), Error> {
        self.ensure_floor(frame.scene);
        let env = frame.environment;
        let t = &frame.plan.techniques;
        let radiance = sky::environment_radiance(t.sky());
        let shade_above = crate::shaders::shading::shade_above(t.shading());
        let foam_coverage = crate::shaders::foam::foam_coverage(t.foam());
        let lut = &*frame.sky_lut;
        let planned_sky = move |d: [f32; 3]| radiance(&env, lut, d);
        let sky_radiance: &(dyn Fn([f32; 3]) -> [f32; 3] + Sync) = match self.environment {
            Environment::Planned => &planned_sky,
            Environment::Given { radiance, .. } => radiance,
        };
        // Taken out while the bindings borrow the other maps, put back after the draw.
        let mut hdr = self.hdr.take().unwrap_or_else(|| new_hdr(frame.plan));
        let map = |id| self.map_or_empty(id);
        // The chains when `wave_mips` made them, else the maps themselves as one level.
        let chain = |mips: ResourceId, plain: ResourceId| {
            self.chains
                .iter()
                .find(|(m, _)| *m == mips)
                .map_or_else(|| MipChain::single(map(plain).clone()), |(_, c)| c.clone())
        };
        let slope_chain = chain(ResourceId::DisplacementSlopeMips, ResourceId::DisplacementSlopes);
        let bump_chain = chain(ResourceId::BumpMips, ResourceId::Bump);
        let bindings = water::Bindings {
            frame: &frame.uniforms,
            displacement: map(ResourceId::Displacement),
            displacement_slopes: &slope_chain,
            bump: &bump_chain,
            fresnel_filter: map(ResourceId::FresnelFilter),
            fresnel_above: map(ResourceId::FresnelAbove),
            fresnel_below: map(ResourceId::FresnelBelow),
            reflection_map: map(ResourceId::ReflectionMap),
            refraction_map: map(ResourceId::RefractionMap),
            shadow_map: map(ResourceId::ShadowMap),
            floor_map: self.floor_map(),
            foam_field: map(ResourceId::FoamField),
            sky_radiance,
            shade_above,
            foam_coverage,
        };
        draw_water_visible(&mut hdr, &frame.mesh, &bindings);
        self.hdr = Some(hdr);
        Ok(())
    }
}

impl Backend for CpuBackend<'_> {
    type Error = Error;

    fn waves(&mut self, frame: &FrameInputs<'_>, state: &FrameState) -> Result<(), Error> {
        self.wave_maps(frame, state)
    }

    fn wave_mips(&mut self, frame: &FrameInputs<'_>) -> Result<(), Error> {
        self.mip_chains(frame);
        Ok(())
    }

    fn fresnel_tables(&mut self, frame: &FrameInputs<'_>) -> Result<(), Error> {
        self.fresnel_textures(frame);
        Ok(())
    }

    fn objects(&mut self, pass: &PlannedPass, frame: &FrameInputs<'_>) -> Result<(), Error> {
        self.object_pass(pass, frame);
        Ok(())
    }

    fn sky(&mut self, frame: &FrameInputs<'_>) -> Result<(), Error> {
        let environment = self.environment;
        let hdr = self.hdr(frame.plan);
        match environment {
            Environment::Planned => {
                let technique = sky::technique(frame.plan.techniques.sky());
                let (camera, sky) = (&frame.camera_uniforms, &frame.environment);
                sky::render_sky(hdr, camera, sky, &frame.sky_lut, &technique);
            }
            Environment::Given { draw, .. } => draw(hdr),
        }
        Ok(())
    }

    fn water(&mut self, frame: &FrameInputs<'_>) -> Result<(), Error> {
        self.water_pass(frame)
    }

    fn spray(
        &mut self,
        frame: &FrameInputs<'_>,
        state: &mut FrameState,
        steps: u64,
    ) -> Result<(), Error> {
        let work =
            SprayFrame::new(frame.scene, frame.plan, &frame.camera, state.spray_steps, steps);
        // Another scene's pool, or a state the GPU advanced, starts again from free slots.
        let pool = match state.spray.take() {
            Some(p) if work.continues(&p.key, p.steps) => p,
            _ => SprayState::fresh(work.key.clone(), state.spray_steps),
        };
        let pool = state.spray.insert(pool);
        let displacement = self.map_or_empty(ResourceId::Displacement);
        for u in &work.steps {
            spray::step(&mut pool.particles, u, &work.key.emitters, displacement);
        }
        pool.steps = state.spray_steps + steps;
        let hdr = self.hdr.get_or_insert_with(|| new_hdr(frame.plan));
        spray::draw_sprites(hdr, &pool.particles, &frame.uniforms, &work.draw);
        Ok(())
    }

    fn foam(
        &mut self,
        frame: &FrameInputs<'_>,
        state: &mut FrameState,
        work: &FoamWork,
    ) -> Result<(), Error> {
        // Another scene's field, or a state the GPU advanced, starts again from empty.
        let texels = (work.grid.size as usize).pow(2);
        let field = match state.foam.take() {
            Some(f) if work.continues(&f.grid, f.steps, state) => f,
            _ => FoamField {
                grid: work.grid,
                steps: state.foam_steps,
                texels: vec![[0.0; 4]; texels],
            },
        };
        let field = state.foam.insert(field);
        let displacement = self.map_or_empty(ResourceId::Displacement);
        for u in &work.steps {
            field.texels =
                crate::shaders::foam::accumulate(u, &frame.uniforms, displacement, &field.texels);
        }
        field.steps += work.steps.len() as u64;
        let n = work.grid.size;
        self.put(ResourceId::FoamField, Texture2D::new(n, n, field.texels.clone()));
        Ok(())
    }

    fn bloom(&mut self, frame: &FrameInputs<'_>) -> Result<(), Error> {
        if let Some(inputs) = &frame.bloom {
            let hdr = self.hdr(frame.plan);
            let texture = Texture2D::new(hdr.width, hdr.height, hdr.color.clone());
            let (down, up) = bloom::dispatch(&texture, inputs);
            for (id, chain) in [(ResourceId::BloomDown, down), (ResourceId::BloomUp, up)] {
                self.chains.retain(|(m, _)| *m != id);
                self.chains.push((id, chain));
            }
        }
        Ok(())
    }

    fn tonemap(&mut self, frame: &FrameInputs<'_>) -> Result<(), Error> {
        if let Some(t) = &frame.tonemap {
            // The up chain's level 0 where pass `bloom` ran, else one zero texel.
            let glow = self
                .chains
                .iter()
                .find(|(m, _)| *m == ResourceId::BloomUp)
                .map_or_else(|| EMPTY_MAP.clone(), |(_, c)| bloom::level0(c));
            let hdr = self.hdr(frame.plan);
            let (w, h) = (hdr.width, hdr.height);
            self.ldr = Some(tonemap::tonemap_to_rgba8_with_bloom(&hdr.color, w, h, t, &glow));
        }
        Ok(())
    }
}

/// Checks the image size against the rasterizer's limit.
fn check_size(camera: &Camera) -> Result<(), Error> {
    let (w, h) = (camera.width, camera.height);
    if w > RenderTarget::MAX_SIZE || h > RenderTarget::MAX_SIZE {
        return Err(Error::TooLarge { width: w, height: h, max: RenderTarget::MAX_SIZE });
    }
    Ok(())
}

/// Runs one frame of `plan` on the CPU: [`FrameInputs`] for `state`'s frame, then every
/// pass through [`run_frame`]. `on_pass` is called as each pass starts (progress).
///
/// # Errors
/// [`Error::TooLarge`] for an image beyond the rasterizer's targets; [`Error::Core`] for
/// physics that cannot be set up.
pub fn render_frame(
    frame: &FrameInputs<'_>,
    environment: Environment<'_>,
    state: &mut FrameState,
    on_pass: &mut dyn FnMut(Pass),
) -> Result<FrameBuffers, Error> {
    check_size(&frame.camera)?;
    let mut backend = CpuBackend::new(environment);
    let timings = run_frame(&mut backend, frame, state, on_pass)?;
    Ok(backend.finish(frame, timings))
}

/// One frame of a validated scene with a given environment and water mesh (the tests of the
/// water pass: a uniform sky, a plain grid); everything else as the plan says.
///
/// # Errors
/// As [`render_frame`], and whatever `water_mesh` returns.
pub fn render(
    scene: &Scene,
    plan: &FramePlan,
    sky_radiance: &(dyn Fn([f32; 3]) -> [f32; 3] + Sync),
    draw_sky: &dyn Fn(&mut RenderTarget),
    water_mesh: &dyn Fn(&Camera) -> Result<WaterMesh, Error>,
    on_pass: &mut dyn FnMut(Pass),
) -> Result<FrameBuffers, Error> {
    let camera = Camera::from_scene(&scene.camera)?;
    check_size(&camera)?;
    let start = std::time::Instant::now();
    let mesh = water_mesh(&camera)?;
    let mut state = FrameState::default();
    let frame = FrameInputs::with_mesh(scene, plan, &state, camera, mesh, start.elapsed())?;
    let environment = Environment::Given { radiance: sky_radiance, draw: draw_sky };
    render_frame(&frame, environment, &mut state, on_pass)
}
