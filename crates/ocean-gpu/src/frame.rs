//! The GPU back end of the frame graph: [`GpuBackend`] records one planned pass at a time
//! into one command encoder, with the textures at the sizes and formats of the plan's
//! resource table (`ocean_core::graph::run_frame` walks the passes, as it does for the CPU
//! oracle), and [`Renderer`] submits the frame and reads back every map for the cross-check.
//!
//! | pass | target (clear) | depth (clear, test) |
//! |---|---|---|
//! | waves (or the cycle's maps, uploaded) | the plan's sizes, `Rgba32Float` ([`crate::wave_maps`]) | — |
//! | fresnel_table | 2 × the plan's N² `Rgba32Float` (η, 1/η), compute | — |
//! | shadow_map | the plan's `R32Float` (1, 0, 0, 0) | 1, `Less` |
//! | reflection_map, refraction_map | the plan's sizes, the frame format (0) | 0, `Greater` |
//! | sky (or, camera under water, a clear to the plan's colour) | HDR viewport, the frame format, compute | 0 (a depth-only clear) |
//! | objects | HDR (kept) | kept, `Greater` |
//! | water | [`ShadingPath::Compute`]: the visibility buffer (3 × `Rgba32Float`, coverage 0), then HDR (kept), compute; [`ShadingPath::Fragment`]: HDR (kept) | kept, `Greater` |
//! | tonemap | viewport `Rgba8Unorm`, compute | — |
//!
//! The frame format is the plan's `frame_format` (`ocean_core::frame_format`): `Rgba32Float`,
//! or `Rgba16Float` (system `welch`), also for the bloom chains; the stages that draw or blur
//! into those buffers are made again when a plan asks for the other format.
//!
//! A skipped pass leaves the plan's 1×1 zero texture where its map would be, as on the CPU.

use std::sync::Arc;
use std::time::{Duration, Instant};

use ocean_core::frame::{
    FrameUniforms, FresnelTableUniforms, ObjectVertex, bump_texels, displacement_slope_texels,
    displacement_texels, pass_floor_triangles,
};
use ocean_core::graph::{Backend, FoamWork, FrameInputs, FrameState, run_frame};
use ocean_core::plan::{Format, FramePlan, Pass, PlannedPass, ResourceId, WavesKernel};
use ocean_core::scene::{Ocean, Scene};
use ocean_core::terrain::{Relief, relief_texels};
use ocean_core::waves::OceanSurface;

use crate::bloom::BloomStage;
use crate::common::{Load, begin_render_pass};
use crate::device::{AdapterReport, Error, Gpu};
use crate::foam::{FoamStage, GpuFoam};
use crate::fresnel_table::FresnelTableStage;
use crate::objects::{
    KeptObjects, ObjectsEntry, ObjectsSource, ObjectsStage, VertexChunk, labelled_vertex_chunks,
};
use crate::pool::FramePool;
use crate::readback::{FloatMap, Readbacks, TexelData};
use crate::shading_path::ShadingPath;
use crate::shadow::ShadowStage;
use crate::sky::SkyStage;
use crate::spray::{GpuSpray, SprayStage};
use crate::texture::{
    DEPTH_FORMAT, GpuTexture, LDR_FORMAT, MAP_FORMAT, SHADOW_FORMAT, depth_usage, map_usage,
    target_usage,
};
use crate::timing::{PassTimer, PendingTimings, TimerPool};
use crate::tonemap::TonemapStage;
use crate::water::{WaterDraw, WaterMeshBuffers, WaterStage, WaterTextures};
use crate::wave_maps::{WaveMapSource, WaveSynthesis, make_source_from};
use crate::wave_mips::{GpuMipChain, WaveMipsStage};
use ocean_core::far_field::mip_level_count;

/// What identifies an ocean's wave modes: everything but the time.
pub fn wave_key(ocean: &Ocean) -> Ocean {
    Ocean { time_s: 0.0, ..ocean.clone() }
}

/// A map of the frame that is read back: the plan's resource id
/// ([`ResourceId::MAPS`] lists the float maps, in the order the frame makes them).
pub type FrameMap = ResourceId;

/// What [`Renderer::run_with`] reads back.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Readback {
    /// Every [`FrameMap`] and the 8-bit output (the cross-check).
    #[default]
    All,
    /// Only the output: the 8-bit picture when the plan tonemaps, else the HDR frame.
    Output,
    /// Nothing: the output stays on the GPU in [`GpuFrame::output`] (the real-time viewer
    /// presents it), and the call returns after the submission without waiting for the GPU.
    None,
}

/// A frame rendered on the GPU.
pub struct GpuFrame {
    /// The plan it ran (shared with the renderer's frames that run an equal plan, so that a
    /// steady frame does not copy it).
    pub plan: Arc<FramePlan>,
    /// The maps read back, in [`ResourceId::MAPS`] order (skipped passes: their 1×1 zero map).
    pub maps: Vec<(FrameMap, FloatMap)>,
    /// The 8-bit sRGB RGBA picture, when the plan tonemaps and it was read back.
    pub ldr: Option<Vec<u8>>,
    /// The output texture on the GPU: the 8-bit picture (`Rgba8Unorm`) when the plan
    /// tonemaps, else the HDR frame (`Rgba32Float`). The renderer keeps its targets across
    /// frames ([`crate::pool`]): the texture holds this frame until the renderer's next frame
    /// is submitted, which draws into it again (copy it to keep it longer).
    pub output: GpuTexture,
    /// The frame's uniforms.
    pub uniforms: FrameUniforms,
    /// GPU time per pass from timestamp queries (empty without `TIMESTAMP_QUERY`, and with
    /// [`Readback::None`], which leaves them in [`Self::pending_timings`]).
    pub gpu_timings: Vec<(Pass, Duration)>,
    /// With [`Readback::None`]: the timestamps on their way back.
    pub pending_timings: Option<PendingTimings>,
    /// CPU time of the `waves` pass when its source runs on the CPU (synthesis and upload).
    pub waves_cpu: Option<Duration>,
    /// Wall time of the whole frame: setup, encoding, submission, GPU work and readback (with
    /// [`Readback::None`]: up to the submission, the GPU work goes on).
    pub wall: Duration,
    /// Which adapter rendered it.
    pub adapter: AdapterReport,
    /// Which wave-map source made the maps, when the waves pass ran.
    pub wave_source: Option<&'static str>,
    /// Passes whose results the renderer kept from an earlier frame because their inputs did
    /// not change (the Fresnel tables of the same η, size and mapping): not recorded again.
    pub reused: Vec<Pass>,
    /// Where the CPU's share of the frame went, up to its submission.
    pub encode: EncodeSplit,
}

/// The CPU's share of a frame up to its submission, in its four steps: what a real-time
/// frame's encode budget is spent on, so that a driver's cost (in `finish` and `submit`)
/// can be told from the renderer's own (in `prepare` and `record`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EncodeSplit {
    /// The frame's inputs on the CPU (uniforms, meshes, the boats' poses; pipelines when the
    /// plan's techniques changed).
    pub prepare: Duration,
    /// The passes recorded into the command encoder, and the uniforms written.
    pub record: Duration,
    /// `CommandEncoder::finish`: wgpu validates the recorded passes, tracks their resources'
    /// states and encodes them into the driver's command buffer.
    pub finish: Duration,
    /// `Queue::submit`.
    pub submit: Duration,
}

impl GpuFrame {
    /// A map, if it was read back.
    pub fn map(&self, which: FrameMap) -> Option<&FloatMap> {
        self.maps.iter().find(|(m, _)| *m == which).map(|(_, t)| t)
    }
}

/// Every stage's pipelines, made once.
struct Stages {
    wave_mips: WaveMipsStage,
    fresnel_table: FresnelTableStage,
    sky: SkyStage,
    objects: ObjectsStage,
    shadow: ShadowStage,
    water: WaterStage,
    spray: SprayStage,
    foam: FoamStage,
    bloom: BloomStage,
    tonemap: TonemapStage,
}

/// The wave-map source of the ocean whose modes it holds, and which kind it is.
type WaveSlot = Option<(Ocean, WaveSynthesis, Box<dyn WaveMapSource>)>;

/// The GPU renderer: the device and every stage's pipelines, made once; a wave-map source
/// kept while the ocean stays the same (its modes are drawn once, as the GPU FFT will upload
/// h0 once).
pub struct Renderer {
    gpu: Gpu,
    stages: Stages,
    wave_synthesis: WaveSynthesis,
    waves: WaveSlot,
    max_vertex_buffer_bytes: u64,
    /// The techniques the composing stages (`sky`, `water`) were assembled for.
    built: ocean_core::plan::Techniques,
    /// The frame format the stages that draw or blur into the frame's colour buffers (`sky`,
    /// `objects`, `water`, `spray`, `bloom`) were made for.
    built_format: ocean_core::frame_format::FrameFormat,
    /// The spray's particle pool, kept on the device across frames.
    spray: Option<GpuSpray>,
    /// Foam `accumulated`'s field, kept on the device across frames.
    foam: Option<GpuFoam>,
    /// The sea floor's relief as uploaded, and the relief it was made from (uploaded again
    /// only when the scene's relief changes).
    floor: Option<(Option<Arc<Relief>>, GpuTexture)>,
    /// The frame's targets, buffers and bind groups, kept across frames.
    kept: FramePool,
    /// Timestamp query sets, back from read frames.
    timers: TimerPool,
    /// The Fresnel tables as last computed, with the uniforms they were computed from.
    fresnel: KeptTables,
    /// The sea floor's triangles as last uploaded, and the list they were uploaded from.
    floor_vertices: KeptFloor,
    /// The object passes' vertex buffers and what they hold.
    object_vertices: KeptObjects,
    /// The water mesh's buffers and the lists they were uploaded from.
    water_mesh: KeptWaterMesh,
    /// The far field's Fresnel filter table as uploaded, and the table it was made from.
    filter: Option<(Arc<ocean_core::far_field::FresnelFilterTable>, GpuTexture)>,
    /// How the water and the objects are shaded.
    shading_path: ShadingPath,
    /// The plan the last frame ran, handed to the next frame that runs an equal one.
    last_plan: Option<Arc<FramePlan>>,
}

/// Each Fresnel table's texture and the uniforms it was computed from.
type KeptTables = Vec<(ResourceId, FresnelTableUniforms, GpuTexture)>;

/// The sea floor's vertex buffers, the kept triangle list they hold (ocean-core's
/// `terrain_triangles`: one list per floor and eye, told apart by its pointer) and the buffer
/// size they were cut to.
type KeptFloor = Option<(Arc<Vec<[ObjectVertex; 3]>>, u64, Vec<VertexChunk>)>;

/// The water mesh's vertex and index buffers and the kept lists they hold.
type KeptWaterMesh = Option<(
    Arc<Vec<ocean_core::geometry::WaterVertex>>,
    Arc<Vec<[u32; 3]>>,
    (wgpu::Buffer, wgpu::Buffer),
)>;

fn wgpu_format(f: Format) -> wgpu::TextureFormat {
    match f {
        Format::Rgba32Float => MAP_FORMAT,
        Format::Rgba16Float => crate::texture::HALF_FORMAT,
        Format::R32Float => SHADOW_FORMAT,
        Format::Rgba8Unorm => LDR_FORMAT,
        // No pass renders into or reads back the environment (a uniform buffer); a texture
        // is never made of it.
        Format::Uniform => MAP_FORMAT,
    }
}

/// The GPU back end of one frame: records each pass into `encoder`, with the textures at the
/// plan's sizes.
pub struct GpuBackend<'r> {
    gpu: &'r Gpu,
    stages: &'r Stages,
    waves: &'r mut WaveSlot,
    spray: &'r mut Option<GpuSpray>,
    foam: &'r mut Option<GpuFoam>,
    floor_map: &'r GpuTexture,
    kept: &'r FramePool,
    fresnel: &'r mut KeptTables,
    floor_vertices: &'r mut KeptFloor,
    object_vertices: &'r mut KeptObjects,
    water_mesh: &'r mut KeptWaterMesh,
    filter: &'r mut Option<(Arc<ocean_core::far_field::FresnelFilterTable>, GpuTexture)>,
    reused: Vec<Pass>,
    encoder: &'r mut wgpu::CommandEncoder,
    timer: PassTimer,
    maps: Vec<(ResourceId, GpuTexture)>,
    chains: Vec<(ResourceId, GpuMipChain)>,
    depth: Option<GpuTexture>,
    hdr_started: bool,
    /// Whether the HDR frame's depth still waits for its clear: the sky pass (compute) leaves
    /// it to the next pass that draws into it, which clears it as it begins (one render pass
    /// fewer than a clear of its own).
    depth_uncleared: bool,
    frame_buffer: wgpu::Buffer,
    waves_cpu: Option<Duration>,
    wave_source: Option<&'static str>,
    max_vertex_buffer_bytes: u64,
}

impl GpuBackend<'_> {
    fn put(&mut self, id: ResourceId, t: GpuTexture) {
        self.maps.retain(|(m, _)| *m != id);
        self.maps.push((id, t));
    }

    /// A written map, or the plan's 1×1 zero texture in place of a skipped pass's.
    fn map(&mut self, id: ResourceId) -> GpuTexture {
        if let Some((_, t)) = self.maps.iter().find(|(m, _)| *m == id) {
            return t.clone();
        }
        let t = self.kept.empty_map(&format!("ocean.{}", id.name()));
        self.put(id, t.clone());
        t
    }

    /// A render target of the plan's size and format for `id`; the ones compute passes store
    /// into (the HDR frame: sky, water and objects; the 8-bit picture: tonemap; the reflection
    /// and refraction maps: objects), storage textures as well.
    fn target(&self, plan: &FramePlan, id: ResourceId) -> GpuTexture {
        let (size, format) =
            plan.resource(id).map_or(([1, 1], MAP_FORMAT), |r| (r.size, wgpu_format(r.format)));
        let label = format!("ocean.{}", id.name());
        let usage = match id {
            ResourceId::Ldr
            | ResourceId::Hdr
            | ResourceId::ReflectionMap
            | ResourceId::RefractionMap => target_usage() | wgpu::TextureUsages::STORAGE_BINDING,
            _ => target_usage(),
        };
        self.kept.texture(&label, size[0], size[1], format, usage).0
    }

    /// A depth buffer of `width × height`, kept across frames.
    fn depth_buffer(&self, label: &str, width: u32, height: u32) -> GpuTexture {
        self.kept.texture(label, width, height, DEPTH_FORMAT, depth_usage()).0
    }

    /// The HDR frame and its depth, made by their first writer; with the sky skipped, that
    /// writer first clears the frame to the plan's background.
    fn hdr(&mut self, plan: &FramePlan) -> (GpuTexture, GpuTexture) {
        let hdr = match self.maps.iter().find(|(m, _)| *m == ResourceId::Hdr) {
            Some((_, t)) => t.clone(),
            None => {
                let t = self.target(plan, ResourceId::Hdr);
                self.put(ResourceId::Hdr, t.clone());
                t
            }
        };
        let depth = match &self.depth {
            Some(d) => d.clone(),
            None => {
                let d = self.depth_buffer("ocean.hdr.depth", hdr.width, hdr.height);
                self.depth = Some(d.clone());
                d
            }
        };
        (hdr, depth)
    }

    /// Clears the HDR frame to the plan's background before its first writer when the sky
    /// pass (which draws over every pixel) does not run.
    fn start_hdr(&mut self, plan: &FramePlan) -> (GpuTexture, GpuTexture) {
        let (hdr, depth) = self.hdr(plan);
        if !self.hdr_started {
            let c = plan.resource(ResourceId::Hdr).map_or([0.0; 4], |r| r.clear);
            drop(begin_render_pass(
                self.encoder,
                "ocean.background",
                &hdr.view,
                Load::Clear(c),
                Some((&depth.view, Load::Clear(0.0))),
                None,
            ));
            self.hdr_started = true;
        }
        (hdr, depth)
    }

    /// How the next pass that draws into the HDR frame's depth loads it: cleared to 0
    /// (reversed Z) if the sky pass left the clear to it, else as stored.
    fn take_depth_load(&mut self) -> Load<f32> {
        if std::mem::take(&mut self.depth_uncleared) { Load::Clear(0.0) } else { Load::Keep }
    }

    /// Clears the HDR frame's depth if no pass after the sky drew into it (a frame of the
    /// sky alone), so that the depth read back is the cleared one.
    fn finish_depth(&mut self) {
        if let (true, Some(depth)) = (self.depth_uncleared, &self.depth) {
            drop(self.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("ocean.hdr.depth_clear"),
                color_attachments: &[],
                depth_stencil_attachment: Some(crate::common::depth_attachment(
                    &depth.view,
                    Load::Clear(0.0),
                )),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            }));
            self.depth_uncleared = false;
        }
    }

    fn wave_maps(&mut self, frame: &FrameInputs<'_>, state: &FrameState) -> Result<(), Error> {
        let ocean = &frame.scene.ocean;
        if frame.plan.runs(Pass::Cycle) {
            // Cyclic playback: the cycle's maps nearest t, uploaded (the same maps the CPU
            // oracle binds).
            let t0 = Instant::now();
            let (d, b) = state.cycle_at(ocean, frame.time_s).ok_or_else(|| {
                Error::Core(ocean_core::Error::InvalidParameter {
                    name: "loop_period_s",
                    value: ocean.loop_period_s,
                    reason: "the plan plays a cycle that was not precomputed".into(),
                })
            })?;
            for (id, texels) in [
                (ResourceId::Displacement, displacement_texels(d)),
                (ResourceId::DisplacementSlopes, displacement_slope_texels(d)),
                (ResourceId::Bump, bump_texels(b)),
            ] {
                let r = frame.plan.resource(id);
                let size = r.map_or([1, 1], |r| r.size);
                let label = format!("ocean.waves.{}", id.name());
                let (t, _) = self.kept.texture(&label, size[0], size[1], MAP_FORMAT, map_usage());
                crate::wave_maps::write(self.gpu, &t, &texels);
                self.put(id, t);
            }
            self.waves_cpu = Some(t0.elapsed());
            self.wave_source = Some("cycle-upload");
            return Ok(());
        }
        if self.waves.as_ref().is_none_or(|(k, _, _)| *k != wave_key(ocean)) {
            return Err(Error::Unavailable(
                "stage `waves`: the renderer holds no wave source for this ocean".into(),
            ));
        }
        let Some((_, _, source)) = self.waves.as_mut() else { return Ok(()) };
        let t0 = Instant::now();
        self.wave_source = Some(source.name());
        let slot = if source.records_gpu_passes() { self.timer.slot(Pass::Waves) } else { None };
        let maps = source.encode(
            self.gpu,
            self.encoder,
            frame.time_s,
            ocean.choppiness,
            self.timer.compute_writes(slot),
        )?;
        let (d, s, b) =
            (maps.displacement.clone(), maps.displacement_slopes.clone(), maps.bump.clone());
        self.waves_cpu = Some(t0.elapsed());
        self.put(ResourceId::Displacement, d);
        self.put(ResourceId::DisplacementSlopes, s);
        self.put(ResourceId::Bump, b);
        Ok(())
    }

    /// `wave_mips`: the two chains from the slope maps, and the filtered Fresnel table when
    /// the plan sizes it (ocean-core's texels, uploaded: the CPU binds the same).
    fn mip_chains(&mut self, frame: &FrameInputs<'_>) {
        let made = ResourceId::SLOPE_CHAINS.map(|(src, dst)| {
            let slopes = self.map(src);
            let label = format!("ocean.{}", dst.name());
            let (w, h) = (slopes.width, slopes.height);
            (dst, slopes, self.kept.chain(&label, w, h, mip_level_count(w, h), MAP_FORMAT))
        });
        let pairs = made.each_ref().map(|(_, slopes, chain)| (slopes, chain));
        self.stages.wave_mips.encode(self.kept, self.encoder, &pairs);
        for (dst, _, chain) in made {
            self.chains.retain(|(m, _)| *m != dst);
            self.chains.push((dst, chain));
        }
        if let Some(table) = frame.plan.fresnel_filter(frame.scene) {
            // The table is ocean-core's cached one per η: uploaded again only when it changes.
            if !self.filter.as_ref().is_some_and(|(kept, _)| Arc::ptr_eq(kept, &table)) {
                let (w, h) =
                    (ocean_core::far_field::FILTER_RADII, ocean_core::far_field::FILTER_SIGMAS);
                let t =
                    GpuTexture::upload_map(self.gpu, "ocean.fresnel_filter", w, h, &table.texels);
                *self.filter = Some((table, t));
            }
            if let Some((_, t)) = self.filter.as_ref() {
                let t = t.clone();
                self.put(ResourceId::FresnelFilter, t);
            }
        }
    }

    fn fresnel_textures(&mut self, frame: &FrameInputs<'_>) {
        let eta = frame.uniforms.water.eta;
        let mut computed = false;
        for (id, eta) in [(ResourceId::FresnelAbove, eta), (ResourceId::FresnelBelow, 1.0 / eta)] {
            let size = frame.plan.resource(id).map_or(1, |r| r.size[0]);
            let params = FresnelTableUniforms::new(eta, size, frame.plan.fresnel_mapping);
            // A table depends on its uniforms alone: kept while they stay the same.
            if let Some((_, _, t)) = self.fresnel.iter().find(|(i, p, _)| *i == id && *p == params)
            {
                let t = t.clone();
                self.put(id, t);
                continue;
            }
            let label = format!("ocean.fresnel_table.{}", id.name());
            let target =
                GpuTexture::new(&self.gpu.device, &label, size, size, MAP_FORMAT, map_usage());
            let slot = self.timer.slot(Pass::FresnelTable);
            self.stages.fresnel_table.encode(
                self.kept,
                self.encoder,
                &params,
                &target,
                self.timer.compute_writes(slot),
            );
            self.fresnel.retain(|(i, _, _)| *i != id);
            self.fresnel.push((id, params, target.clone()));
            self.put(id, target);
            computed = true;
        }
        if !computed {
            self.reused.push(Pass::FresnelTable);
        }
    }

    /// The triangles of a pass's objects, camera-relative, in ocean-core's order (its
    /// objects', then the sea floor's); one zero vertex keeps a buffer non-empty. The floor's
    /// buffers are uploaded once per kept list: the passes of a frame, and the frames of a
    /// still camera, draw the same ones.
    fn object_vertices(&mut self, pass: &PlannedPass, frame: &FrameInputs<'_>) -> Vec<VertexChunk> {
        let eye = frame.camera.eye;
        let max = self.gpu.device.limits().max_buffer_size.min(self.max_vertex_buffer_bytes);
        let from = ObjectsSource { scene: frame.scene, poses: &frame.poses, eye };
        let mut chunks = self.object_vertices.chunks(self.kept, &from, pass, max);
        if let Some(floor) = pass_floor_triangles(frame.scene, pass, eye) {
            let kept = self
                .floor_vertices
                .as_ref()
                .filter(|(list, cut, _)| Arc::ptr_eq(list, &floor) && *cut == max);
            let floor_chunks = match kept {
                Some((_, _, c)) => c.clone(),
                None => {
                    let vertices: &[ObjectVertex] = bytemuck::cast_slice(&floor);
                    let c =
                        labelled_vertex_chunks(self.kept, "ocean.floor.vertices", vertices, max);
                    *self.floor_vertices = Some((floor, max, c.clone()));
                    c
                }
            };
            chunks.extend(floor_chunks);
        }
        chunks
    }

    fn objects_group(&mut self) -> wgpu::BindGroup {
        let displacement = self.map(ResourceId::Displacement);
        let shadow_map = self.map(ResourceId::ShadowMap);
        self.stages.objects.group(
            self.kept,
            &self.frame_buffer,
            &displacement.view,
            &shadow_map.view,
            &self.floor_map.view,
        )
    }

    fn frame_group(&self, layout: &wgpu::BindGroupLayout, label: &str) -> wgpu::BindGroup {
        self.kept.bind_group(label, layout, &[self.frame_buffer.as_entire_binding()])
    }

    fn object_pass(&mut self, pass: &PlannedPass, frame: &FrameInputs<'_>) {
        let vertices = self.object_vertices(pass, frame);
        match pass.name {
            Pass::ShadowMap => {
                let target = self.target(frame.plan, ResourceId::ShadowMap);
                let depth = self.depth_buffer("ocean.shadow.depth", target.width, target.height);
                let group = self.frame_group(&self.stages.shadow.frame_layout, "ocean.shadow");
                let slot = self.timer.slot(Pass::ShadowMap);
                self.stages.shadow.encode(
                    self.encoder,
                    &group,
                    &vertices,
                    &target.view,
                    &depth.view,
                    self.timer.render_writes(slot),
                );
                self.put(ResourceId::ShadowMap, target);
            }
            Pass::ReflectionMap | Pass::RefractionMap => {
                let (id, entry) = if pass.name == Pass::ReflectionMap {
                    (ResourceId::ReflectionMap, ObjectsEntry::Reflect)
                } else {
                    (ResourceId::RefractionMap, ObjectsEntry::Refract)
                };
                let target = self.target(frame.plan, id);
                let label = format!("ocean.objects.{}", id.name());
                let depth = self.depth_buffer(&label, target.width, target.height);
                let group = self.objects_group();
                let slot = self.timer.slot(pass.name);
                self.stages.objects.encode(
                    self.kept,
                    self.encoder,
                    entry,
                    &group,
                    &vertices,
                    (&target.view, [target.width, target.height]),
                    &depth.view,
                    (Load::Clear([0.0; 4]), Load::Clear(0.0)),
                    self.timer.render_writes(slot),
                );
                self.put(id, target);
            }
            _ => {
                let (hdr, depth) = self.start_hdr(frame.plan);
                let depth_load = self.take_depth_load();
                let group = self.objects_group();
                let slot = self.timer.slot(Pass::Objects);
                self.stages.objects.encode(
                    self.kept,
                    self.encoder,
                    ObjectsEntry::Main,
                    &group,
                    &vertices,
                    (&hdr.view, [hdr.width, hdr.height]),
                    &depth.view,
                    (Load::Keep, depth_load),
                    self.timer.render_writes(slot),
                );
            }
        }
    }

    fn water_pass(&mut self, frame: &FrameInputs<'_>) {
        let [
            displacement,
            displacement_slopes,
            bump,
            fresnel_above,
            fresnel_below,
            shadow_map,
            reflection_map,
            refraction_map,
        ] = [
            ResourceId::Displacement,
            ResourceId::DisplacementSlopes,
            ResourceId::Bump,
            ResourceId::FresnelAbove,
            ResourceId::FresnelBelow,
            ResourceId::ShadowMap,
            ResourceId::ReflectionMap,
            ResourceId::RefractionMap,
        ]
        .map(|id| self.map(id));
        let fresnel_filter = self.map(ResourceId::FresnelFilter);
        let foam_field = self.map(ResourceId::FoamField);
        // The chains when `wave_mips` made them, else the maps themselves (one level).
        let chain_view = |id: ResourceId| {
            self.chains.iter().find(|(m, _)| *m == id).map(|(_, c)| c.view.clone())
        };
        let slopes_view = chain_view(ResourceId::DisplacementSlopeMips)
            .unwrap_or_else(|| displacement_slopes.view.clone());
        let bump_view = chain_view(ResourceId::BumpMips).unwrap_or_else(|| bump.view.clone());
        let (hdr, depth) = self.start_hdr(frame.plan);
        let depth_load = self.take_depth_load();
        let mesh = &frame.mesh;
        let (water_vertices, water_indices) = self.water_buffers(mesh);
        let (sky_buffer, sky_lut) = self.sky_buffers(frame);
        let slot = self.timer.slot(Pass::Water);
        self.stages.water.encode(
            self.kept,
            self.encoder,
            &self.frame_buffer,
            &sky_buffer,
            &sky_lut,
            &WaterTextures {
                displacement: &displacement.view,
                displacement_slopes: &slopes_view,
                bump: &bump_view,
                fresnel_above: &fresnel_above.view,
                fresnel_below: &fresnel_below.view,
                reflection_map: &reflection_map.view,
                refraction_map: &refraction_map.view,
                shadow_map: &shadow_map.view,
                fresnel_filter: &fresnel_filter.view,
                floor_map: &self.floor_map.view,
                foam_field: &foam_field.view,
            },
            &match (frame.uniforms.grid.vertex_count(), frame.uniforms.clip.vertex_count()) {
                (_, n) if n > 0 => WaterDraw::Clipmap(n),
                (0, _) => WaterDraw::Mesh(WaterMeshBuffers {
                    vertices: &water_vertices,
                    indices: &water_indices,
                    index_count: 3 * mesh.indices.len() as u32,
                }),
                (n, _) => WaterDraw::Grid(n),
            },
            (&hdr.view, [hdr.width, hdr.height]),
            (&depth.view, depth_load),
            self.timer.render_writes(slot),
        );
    }
}

impl GpuBackend<'_> {
    /// The water mesh's vertex and index buffers: uploaded once per kept mesh (ocean-core's
    /// `DrawMesh::kept`, told apart by its lists' pointers), so the frames of a still camera
    /// draw one upload.
    fn water_buffers(
        &mut self,
        mesh: &ocean_core::graph::DrawMesh,
    ) -> (wgpu::Buffer, wgpu::Buffer) {
        if let Some((v, i, buffers)) = self.water_mesh.as_ref()
            && Arc::ptr_eq(v, &mesh.vertices)
            && Arc::ptr_eq(i, &mesh.indices)
        {
            return buffers.clone();
        }
        let buffers = (
            self.kept.data(
                "ocean.water.vertices",
                wgpu::BufferUsages::VERTEX,
                bytemuck::cast_slice(&mesh.vertices),
            ),
            self.kept.data(
                "ocean.water.indices",
                wgpu::BufferUsages::INDEX,
                bytemuck::cast_slice(&mesh.indices),
            ),
        );
        *self.water_mesh = Some((mesh.vertices.clone(), mesh.indices.clone(), buffers.clone()));
        buffers
    }

    /// The sky's uniform blocks, which passes `sky` and `water` both read: one buffer each,
    /// uploaded once a frame at most.
    fn sky_buffers(&self, frame: &FrameInputs<'_>) -> (wgpu::Buffer, wgpu::Buffer) {
        (
            self.kept.uniform("ocean.sky.sky", &frame.environment),
            self.kept.uniform("ocean.sky.sky_lut", &*frame.sky_lut),
        )
    }
}

impl Backend for GpuBackend<'_> {
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
        let (hdr, _) = self.hdr(frame.plan);
        let (sky, sky_lut) = self.sky_buffers(frame);
        let slot = self.timer.slot(Pass::Sky);
        self.stages.sky.encode(
            self.kept,
            self.encoder,
            &frame.camera_uniforms,
            (&sky, &sky_lut),
            (&hdr.view, [hdr.width, hdr.height]),
            self.timer.compute_writes(slot),
        );
        self.hdr_started = true;
        self.depth_uncleared = true;
        Ok(())
    }

    fn water(&mut self, frame: &FrameInputs<'_>) -> Result<(), Error> {
        self.water_pass(frame);
        Ok(())
    }

    fn spray(
        &mut self,
        frame: &FrameInputs<'_>,
        state: &mut FrameState,
        steps: u64,
    ) -> Result<(), Error> {
        if !self.stages.spray.can_draw() {
            return Err(Error::Unavailable(
                "spray technique `particles` adds its sprites into the Rgba32Float frame, which \
                 needs the adapter feature FLOAT32_BLENDABLE; this adapter lacks it (use \
                 [post] frame_format = \"rgba16float\", --backend cpu, or [techniques] spray = \
                 \"none\")"
                    .into(),
            ));
        }
        let scene = frame.scene;
        let work = ocean_core::spray::SprayFrame::new(
            scene,
            frame.plan,
            &frame.camera,
            state.spray_steps,
            steps,
        );
        let device = &self.gpu.device;
        // The pool stays on the device while the scene's spray and the animation's step count
        // agree with it; otherwise (another scene, a fresh state) it starts again from free
        // slots, as the CPU's does.
        if !self.spray.as_ref().is_some_and(|p| work.continues(&p.key, p.steps)) {
            let mut pool = GpuSpray::new(device, work.key.clone());
            pool.steps = state.spray_steps;
            *self.spray = Some(pool);
        }
        let displacement = self.map(ResourceId::Displacement);
        let Some(pool) = self.spray.as_mut() else { return Ok(()) };
        for u in &work.steps {
            self.stages.spray.encode_step(self.kept, self.encoder, pool, u, &displacement.view);
        }
        pool.steps += steps;
        let u = work.draw;
        let (hdr, depth) = self.hdr(frame.plan);
        let depth_load = self.take_depth_load();
        let slot = self.timer.slot(Pass::Spray);
        let Some(pool) = self.spray.as_ref() else { return Ok(()) };
        self.stages.spray.encode_draw(
            self.kept,
            self.encoder,
            &self.frame_buffer,
            pool,
            &u,
            &hdr.view,
            (&depth.view, depth_load),
            self.timer.render_writes(slot),
        );
        Ok(())
    }

    fn foam(
        &mut self,
        _frame: &FrameInputs<'_>,
        state: &mut FrameState,
        work: &FoamWork,
    ) -> Result<(), Error> {
        // The field stays on the device while the grid and the animation's step count agree
        // with it; otherwise (another scene, a fresh state) it starts again from empty, as
        // the CPU's does.
        if !self.foam.as_ref().is_some_and(|f| work.continues(&f.grid, f.steps, state)) {
            *self.foam = Some(GpuFoam::new(self.gpu, work.grid, state.foam_steps));
        }
        let displacement = self.map(ResourceId::Displacement);
        let Some(field) = self.foam.as_mut() else { return Ok(()) };
        let slot = self.timer.slot(Pass::Foam);
        self.stages.foam.encode_steps(
            self.kept,
            self.encoder,
            field,
            &work.steps,
            &self.frame_buffer,
            &displacement.view,
            self.timer.compute_writes(slot),
        );
        field.steps += work.steps.len() as u64;
        let current = field.current.clone();
        self.put(ResourceId::FoamField, current);
        Ok(())
    }

    fn bloom(&mut self, frame: &FrameInputs<'_>) -> Result<(), Error> {
        let Some(inputs) = &frame.bloom else { return Ok(()) };
        let (hdr, _) = self.hdr(frame.plan);
        let [w, h] = inputs.levels[0];
        let count = inputs.levels.len() as u32;
        let format = crate::texture::frame_format(inputs.format);
        let down = self.kept.chain("ocean.bloom_down", w, h, count, format);
        let up = self.kept.chain("ocean.bloom_up", w, h, count, format);
        let slots = [self.timer.slot(Pass::Bloom), self.timer.slot(Pass::Bloom)];
        self.stages.bloom.encode(
            self.kept,
            self.encoder,
            &hdr.view,
            inputs,
            (&down, &up),
            slots.map(|s| self.timer.compute_writes(s)),
        );
        for (id, chain) in [(ResourceId::BloomDown, down), (ResourceId::BloomUp, up)] {
            self.chains.retain(|(m, _)| *m != id);
            self.chains.push((id, chain));
        }
        Ok(())
    }

    fn tonemap(&mut self, frame: &FrameInputs<'_>) -> Result<(), Error> {
        if let Some(t) = &frame.tonemap {
            let (hdr, _) = self.hdr(frame.plan);
            let ldr = self.target(frame.plan, ResourceId::Ldr);
            // The up chain's level 0 where pass `bloom` ran, else the 1×1 zero map.
            let glow = match self.chains.iter().find(|(m, _)| *m == ResourceId::BloomUp) {
                Some((_, c)) => c.levels[0].clone(),
                None => self.map(ResourceId::BloomUp).view,
            };
            let slot = self.timer.slot(Pass::Tonemap);
            self.stages.tonemap.encode(
                self.kept,
                self.encoder,
                t,
                (&hdr.view, &glow),
                (&ldr.view, [ldr.width, ldr.height]),
                self.timer.compute_writes(slot),
            );
            self.put(ResourceId::Ldr, ldr);
        }
        Ok(())
    }
}

impl Renderer {
    /// Opens the adapter the environment selects ([`crate::device`]) and creates every
    /// pipeline; the wave maps come from the GPU FFT ([`WaveSynthesis::GpuFft`], the
    /// default).
    ///
    /// # Errors
    /// [`Error::NoAdapter`] and the other device errors; [`Error::Wgpu`] if a pipeline does
    /// not validate.
    pub fn new() -> Result<Self, Error> {
        Self::with_gpu(Gpu::new()?, WaveSynthesis::default())
    }

    /// The renderer on an open device with the given wave-map source.
    ///
    /// # Errors
    /// [`Error::Wgpu`] if a pipeline does not validate; [`Error::Core`] if a stage's WGSL
    /// cannot be assembled.
    pub fn with_gpu(gpu: Gpu, wave_synthesis: WaveSynthesis) -> Result<Self, Error> {
        let d = &gpu.device;
        let built = crate::common::pipeline_techniques();
        let built_format = ocean_core::frame_format::FrameFormat::default();
        let target = crate::texture::frame_format(built_format);
        let shading_path = ShadingPath::for_device(d);
        let stages = gpu.scoped("creating the pipelines", || -> Result<_, Error> {
            Ok(Stages {
                wave_mips: WaveMipsStage::new(d)?,
                fresnel_table: FresnelTableStage::new(d)?,
                sky: SkyStage::new(d, &built, target)?,
                objects: ObjectsStage::new(d, target, shading_path)?,
                shadow: ShadowStage::new(d)?,
                water: WaterStage::new(d, &built, target, shading_path)?,
                spray: SprayStage::new(d, target)?,
                foam: FoamStage::new(d)?,
                bloom: BloomStage::new(d, built_format)?,
                tonemap: TonemapStage::new(d)?,
            })
        })??;
        let kept = FramePool::new(&gpu.device, &gpu.queue);
        Ok(Self {
            gpu,
            stages,
            wave_synthesis,
            waves: None,
            max_vertex_buffer_bytes: u64::MAX,
            built,
            built_format,
            spray: None,
            foam: None,
            floor: None,
            kept,
            timers: TimerPool::default(),
            fresnel: Vec::new(),
            floor_vertices: None,
            object_vertices: KeptObjects::default(),
            water_mesh: None,
            filter: None,
            shading_path,
            last_plan: None,
        })
    }

    /// How the water and the objects are shaded ([`ShadingPath::for_device`] unless set).
    pub fn shading_path(&self) -> ShadingPath {
        self.shading_path
    }

    /// Shades the water and the objects on `path` from the next frame on (the same bits either way; a test
    /// compares them). [`ShadingPath::Compute`] on a device without room for the visibility
    /// buffer fails when the pipelines are made.
    ///
    /// # Errors
    /// [`Error::Wgpu`] if a pipeline does not validate; [`Error::Core`] if the WGSL cannot be
    /// assembled.
    pub fn set_shading_path(&mut self, path: ShadingPath) -> Result<(), Error> {
        let d = &self.gpu.device;
        let (t, target) = (self.built, crate::texture::frame_format(self.built_format));
        let (water, objects) = self.gpu.scoped("assembling the shading pipelines", || {
            Ok::<_, Error>((
                WaterStage::new(d, &t, target, path)?,
                ObjectsStage::new(d, target, path)?,
            ))
        })??;
        (self.stages.water, self.stages.objects) = (water, objects);
        self.shading_path = path;
        Ok(())
    }

    /// The spray's particle pool as the last frame left it (`None` before a frame with pass
    /// `spray`), read back from the device.
    ///
    /// # Errors
    /// A device error while mapping the copy.
    pub fn spray_particles(&self) -> Result<Option<Vec<ocean_core::spray::Particle>>, Error> {
        let Some(pool) = &self.spray else { return Ok(None) };
        crate::spray::read_particles(&self.gpu, &pool.particles).map(Some)
    }

    /// The steps the spray's particle pool has run (`None` before a frame with pass `spray`).
    pub fn spray_steps(&self) -> Option<u64> {
        self.spray.as_ref().map(|p| p.steps)
    }

    /// One `step` of the spray from the slots `before` with `params`, reading the sea's
    /// height from a map holding `displacement` (`width` × `height` texels), on buffers of
    /// its own: the slots as this device writes them (`None` before a frame with pass
    /// `spray`). The envelope's verdict on the step, from the device's own inputs; the
    /// frame's pool is not touched.
    ///
    /// # Errors
    /// A device error while reading the slots back.
    pub fn spray_probe(
        &self,
        before: &[ocean_core::spray::Particle],
        params: &ocean_core::spray::SprayUniforms,
        (width, height, displacement): (u32, u32, &[[f32; 4]]),
    ) -> Result<Option<Vec<ocean_core::spray::Particle>>, Error> {
        let Some(pool) = &self.spray else { return Ok(None) };
        let map = GpuTexture::upload_map(
            &self.gpu,
            "ocean.spray.probe.displacement",
            width,
            height,
            displacement,
        );
        let after =
            self.stages.spray.probe_step(&self.gpu, &self.kept, before, pool, params, &map.view)?;
        Ok(Some(after))
    }

    /// Caps each vertex buffer of the objects' triangles at `bytes` (below the device's own
    /// `max_buffer_size`, which always applies): the geometry is cut into more buffers, drawn
    /// in order, with the same picture. For tests of the cut with few objects.
    pub fn set_max_vertex_buffer_bytes(&mut self, bytes: u64) {
        self.max_vertex_buffer_bytes = bytes;
    }

    /// The device.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// The objects its frames keep (for the embedding's composite, recorded after the frame).
    pub(crate) fn kept(&self) -> &FramePool {
        &self.kept
    }

    /// The adapter, for reports.
    pub fn adapter(&self) -> &AdapterReport {
        &self.gpu.report
    }

    /// Installs the wave modes of `ocean`, drawn by the caller as `ocean.surface()` (the
    /// real-time viewer draws them on a worker thread, so that a slider never stalls a
    /// frame). At the same map sizes the running source takes them in place (one upload, no
    /// new pipeline); otherwise a new source is made. Frames of this ocean (any time) then
    /// use them; [`Self::run`] installs the modes itself when they are not there.
    ///
    /// # Errors
    /// As [`Self::run`]'s `waves` pass.
    pub fn set_waves(&mut self, ocean: &Ocean, surface: OceanSurface) -> Result<(), Error> {
        let key = wave_key(ocean);
        let kind = self.source_kind(WavesKernel::for_ocean(ocean));
        if let Some((k, kept, source)) = &mut self.waves
            && *kept == kind
            && source.update(&self.gpu, &surface)?
        {
            *k = key;
            return Ok(());
        }
        self.waves = None;
        self.waves = Some((key, kind, make_source_from(&self.gpu, kind, surface)?));
        Ok(())
    }

    /// The wave-map source for the plan's kernel: ocean-core's synthesis uploaded where the
    /// plan says so, else the renderer's own choice (the GPU FFT by default).
    fn source_kind(&self, kernel: WavesKernel) -> WaveSynthesis {
        match kernel {
            WavesKernel::Shader => self.wave_synthesis,
            WavesKernel::Synthesis => WaveSynthesis::CpuUpload,
        }
    }

    /// Renders a validated scene by its plan and reads back every map ([`Readback::All`]).
    ///
    /// # Errors
    /// [`Error::TooLarge`] for an image beyond the adapter's textures; [`Error::Core`] for
    /// physics that cannot be set up; [`Error::Wgpu`] or [`Error::Readback`] from the device.
    pub fn run(&mut self, scene: &Scene, plan: &FramePlan) -> Result<GpuFrame, Error> {
        self.run_with(scene, plan, Readback::All)
    }

    /// [`Self::run`], reading back what `readback` says.
    ///
    /// # Errors
    /// As [`Self::run`].
    pub fn run_with(
        &mut self,
        scene: &Scene,
        plan: &FramePlan,
        readback: Readback,
    ) -> Result<GpuFrame, Error> {
        self.run_frame(scene, plan, &mut FrameState::default(), readback)
    }

    /// Renders frame `state.frame` of an animation by `plan` (a plan for several frames plays
    /// a looping sea's cycle, precomputed in `state` by the first frame), reads back what
    /// `readback` says, and advances `state`.
    ///
    /// # Errors
    /// As [`Self::run`].
    pub fn run_frame(
        &mut self,
        scene: &Scene,
        plan: &FramePlan,
        state: &mut FrameState,
        readback: Readback,
    ) -> Result<GpuFrame, Error> {
        self.run_frame_with_camera(scene, plan, state, readback, None)
    }

    /// [`Self::run_frame`] seen by `camera` instead of the scene's (when given): an
    /// embedding program's camera, which may roll (`ocean_core::camera::Camera::
    /// from_view_projection`), at the plan's image size.
    ///
    /// # Errors
    /// As [`Self::run`].
    pub fn run_frame_with_camera(
        &mut self,
        scene: &Scene,
        plan: &FramePlan,
        state: &mut FrameState,
        readback: Readback,
        camera: Option<ocean_core::camera::Camera>,
    ) -> Result<GpuFrame, Error> {
        let start = Instant::now();
        let inputs = self.prepare(scene, plan, state, camera)?;
        let mut split = EncodeSplit { prepare: start.elapsed(), ..EncodeSplit::default() };
        let u: FrameUniforms = inputs.uniforms;
        let device = self.gpu.device.clone();
        let frame =
            crate::device::scoped(&device, "rendering the frame", || -> Result<_, Error> {
                let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("ocean.frame"),
                });
                let timer = PassTimer::from_pool(&self.gpu, &self.timers);
                let Recorded { maps, chains, timer, waves_cpu, wave_source, reused, .. } =
                    self.record(&inputs, state, &mut encoder, timer)?;
                timer.resolve(&mut encoder);
                let gpu = &self.gpu;
                let device = &gpu.device;

                // readback
                let mut readbacks: Readbacks<ResourceId> = Readbacks::kept(&self.kept);
                let all = readback == Readback::All;
                let output_back = readback != Readback::None;
                let find = |id: ResourceId| maps.iter().find(|(m, _)| *m == id).map(|(_, t)| t);
                let ldr = find(ResourceId::Ldr).cloned();
                let empty = self.kept.empty_map("ocean.empty");
                for id in ResourceId::MAPS {
                    let wanted = all || (id == ResourceId::Hdr && output_back && ldr.is_none());
                    if !wanted {
                        continue;
                    }
                    let format = plan.resource(id).map_or(MAP_FORMAT, |r| wgpu_format(r.format));
                    // A chain comes back packed, as ocean-cpu's MipChain holds it.
                    if let Some((_, chain)) = chains.iter().find(|(m, _)| *m == id) {
                        let atlas = chain.pack(device, &mut encoder);
                        readbacks.copy(device, &mut encoder, id, id.name(), &atlas, format);
                        continue;
                    }
                    let texture = find(id).unwrap_or(&empty);
                    readbacks.copy(device, &mut encoder, id, id.name(), texture, format);
                }
                if let Some(ldr) = ldr.as_ref().filter(|_| output_back) {
                    readbacks.copy(device, &mut encoder, ResourceId::Ldr, "ldr", ldr, LDR_FORMAT);
                }
                // The read-back copies count as recorded with the passes.
                split.record = start.elapsed().saturating_sub(split.prepare);
                let finishing = Instant::now();
                let commands = encoder.finish();
                split.finish = finishing.elapsed();
                let submitting = Instant::now();
                gpu.queue.submit([commands]);
                split.submit = submitting.elapsed();
                let data = readbacks.finish(gpu)?;
                // Reading nothing back, the frame does not wait for the GPU: its timestamps come
                // later (`GpuFrame::pending_timings`).
                let (timings, pending) = if output_back {
                    (timer.finish(gpu)?, None)
                } else {
                    (Vec::new(), timer.finish_later())
                };
                let output = match ldr {
                    Some(l) => l,
                    None => find(ResourceId::Hdr).cloned().unwrap_or(empty),
                };
                Ok((data, timings, pending, output, waves_cpu, wave_source, reused))
            })??;
        drop(inputs);
        state.advance();

        let (data, gpu_timings, pending_timings, output, waves_cpu, wave_source, reused) = frame;
        let mut maps = Vec::new();
        let mut ldr = None;
        for (key, texels) in data {
            match (key, texels) {
                (ResourceId::Ldr, TexelData::Rgba8(bytes)) => ldr = Some(bytes),
                (m, TexelData::Float(t)) if m != ResourceId::Ldr => maps.push((m, t)),
                (key, _) => {
                    return Err(Error::Readback {
                        what: key.name().into(),
                        message: "unexpected texel format".into(),
                    });
                }
            }
        }
        let plan = match &self.last_plan {
            Some(kept) if **kept == *plan => Arc::clone(kept),
            _ => Arc::new(plan.clone()),
        };
        self.last_plan = Some(Arc::clone(&plan));
        Ok(GpuFrame {
            plan,
            maps,
            ldr,
            output,
            pending_timings,
            uniforms: u,
            gpu_timings,
            waves_cpu,
            wall: start.elapsed(),
            adapter: self.gpu.report.clone(),
            wave_source,
            reused,
            encode: split,
        })
    }

    /// Everything a frame needs before its passes are recorded: the pipelines for the plan's
    /// techniques and frame format, the frame's inputs (with `camera` in place of the
    /// scene's, when given), the wave-map source for the scene's ocean and the floor's relief.
    pub(crate) fn prepare<'a>(
        &mut self,
        scene: &'a Scene,
        plan: &'a FramePlan,
        state: &FrameState,
        camera: Option<ocean_core::camera::Camera>,
    ) -> Result<FrameInputs<'a>, Error> {
        // Only the composed stages (`common::COMPOSED`: sky, shading, foam) change the WGSL
        // of the sky and water pipelines, which are assembled again for the plan's choice.
        // Every technique of every other stage is in the pipelines as built: the far field and
        // the waves `gerstner`/`coastal` are uniform branches of `water`, the surfaces its
        // vertex entry points, and waves `fft`, spray, foam `accumulated` and bloom passes of
        // their own stages that the plan runs or skips.
        let format = plan.frame_format;
        if format != self.built_format
            || crate::common::COMPOSED.iter().any(|s| plan.techniques.of(*s) != self.built.of(*s))
        {
            let t = plan.techniques;
            let d = &self.gpu.device;
            let target = crate::texture::frame_format(format);
            let (sky, water) = self.gpu.scoped("assembling the pipelines", || {
                Ok::<_, Error>((
                    SkyStage::new(d, &t, target)?,
                    WaterStage::new(d, &t, target, self.shading_path)?,
                ))
            })??;
            self.stages.sky = sky;
            self.stages.water = water;
            self.built = t;
        }
        if format != self.built_format {
            let d = &self.gpu.device;
            let target = crate::texture::frame_format(format);
            let (objects, spray, bloom) =
                self.gpu.scoped("making the pipelines for the frame format", || {
                    Ok::<_, Error>((
                        ObjectsStage::new(d, target, self.shading_path)?,
                        SprayStage::new(d, target)?,
                        BloomStage::new(d, format)?,
                    ))
                })??;
            self.stages.objects = objects;
            self.stages.spray = spray;
            self.stages.bloom = bloom;
            self.built_format = format;
        }
        let inputs = match camera {
            Some(c) => FrameInputs::with_camera(scene, plan, state, c)?,
            None => FrameInputs::new(scene, plan, state)?,
        };
        let (w, h) = (inputs.camera.width, inputs.camera.height);
        let max = self.gpu.device.limits().max_texture_dimension_2d;
        if w > max || h > max {
            return Err(Error::TooLarge { width: w, height: h, max });
        }
        // The wave-map source for this ocean (kept across frames while the ocean is the same;
        // `make_source_from` follows the plan's `WavesKernel` rule).
        let kind = self.source_kind(plan.waves_kernel);
        if plan.runs(Pass::Waves)
            && !plan.runs(Pass::Cycle)
            && self
                .waves
                .as_ref()
                .is_none_or(|(k, kept, _)| *k != wave_key(&scene.ocean) || *kept != kind)
        {
            self.set_waves(&scene.ocean, scene.ocean.surface()?)?;
        }
        let relief = scene.terrain.as_ref().and_then(|t| t.relief.clone());
        let same = |kept: &Option<Arc<Relief>>| match (kept, &relief) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (None, None) => true,
            _ => false,
        };
        if !self.floor.as_ref().is_some_and(|(kept, _)| same(kept)) {
            let (w, h, texels) = relief_texels(scene.terrain.as_ref());
            let map = GpuTexture::upload_map(&self.gpu, "ocean.floor_map", w, h, &texels);
            self.floor = Some((relief, map));
        }
        Ok(inputs)
    }

    /// Records the plan's passes into `encoder` (nothing is submitted) and hands back the
    /// frame's textures.
    pub(crate) fn record(
        &mut self,
        inputs: &FrameInputs<'_>,
        state: &mut FrameState,
        encoder: &mut wgpu::CommandEncoder,
        timer: PassTimer,
    ) -> Result<Recorded, Error> {
        let empty_floor;
        let floor_map = match &self.floor {
            Some((_, map)) => map,
            None => {
                empty_floor = GpuTexture::empty_map(&self.gpu, "ocean.floor_map");
                &empty_floor
            }
        };
        self.kept.begin_frame();
        let frame_buffer = self.kept.uniform("ocean.frame.uniforms", &inputs.uniforms);
        let mut backend = GpuBackend {
            gpu: &self.gpu,
            stages: &self.stages,
            waves: &mut self.waves,
            spray: &mut self.spray,
            foam: &mut self.foam,
            floor_map,
            kept: &self.kept,
            fresnel: &mut self.fresnel,
            floor_vertices: &mut self.floor_vertices,
            object_vertices: &mut self.object_vertices,
            water_mesh: &mut self.water_mesh,
            filter: &mut self.filter,
            reused: Vec::new(),
            encoder,
            timer,
            maps: Vec::new(),
            chains: Vec::new(),
            depth: None,
            hdr_started: false,
            depth_uncleared: false,
            frame_buffer,
            waves_cpu: None,
            max_vertex_buffer_bytes: self.max_vertex_buffer_bytes,
            wave_source: None,
        };
        run_frame(&mut backend, inputs, state, &mut |_| {})?;
        backend.finish_depth();
        let GpuBackend { timer, waves_cpu, wave_source, maps, chains, depth, reused, .. } = backend;
        Ok(Recorded { maps, chains, depth, timer, waves_cpu, wave_source, reused })
    }
}

/// The textures of a recorded frame.
pub(crate) struct Recorded {
    /// Every map a pass wrote.
    pub maps: Vec<(ResourceId, GpuTexture)>,
    /// The mip chains (`wave_mips`, `bloom`).
    pub chains: Vec<(ResourceId, GpuMipChain)>,
    /// The HDR frame's depth (reversed-Z), made by its first writer.
    pub depth: Option<GpuTexture>,
    /// The frame's timestamp queries.
    pub timer: PassTimer,
    /// As [`GpuFrame::waves_cpu`].
    pub waves_cpu: Option<Duration>,
    /// As [`GpuFrame::wave_source`].
    pub wave_source: Option<&'static str>,
    /// As [`GpuFrame::reused`].
    pub reused: Vec<Pass>,
}

impl Recorded {
    /// The frame's output: the 8-bit picture when the plan tonemaps, else the HDR frame.
    pub fn output(&self) -> Option<&GpuTexture> {
        let find = |id: ResourceId| self.maps.iter().find(|(m, _)| *m == id).map(|(_, t)| t);
        find(ResourceId::Ldr).or_else(|| find(ResourceId::Hdr))
    }
}
