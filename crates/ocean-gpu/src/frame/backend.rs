//! [`GpuBackend`]: one frame's passes recorded into one command encoder, pass by pass as
//! `ocean_core::graph::run_frame` walks the plan (the table in [`super`] lists each pass's
//! targets); [`super::Renderer`] makes it, submits what it recorded and reads back.

use std::sync::Arc;
use std::time::{Duration, Instant};

use ocean_core::far_field::mip_level_count;
use ocean_core::frame::{
    FresnelTableUniforms, ObjectVertex, bump_texels, displacement_slope_texels,
    displacement_texels, pass_floor_triangles,
};
use ocean_core::graph::{Backend, FoamWork, FrameInputs, FrameState};
use ocean_core::plan::{FramePlan, Pass, PlannedPass, ResourceId};

use crate::common::{Load, begin_render_pass};
use crate::device::{Error, Gpu};
use crate::foam::GpuFoam;
use crate::objects::{
    KeptObjects, ObjectsEntry, ObjectsSource, VertexChunk, labelled_vertex_chunks,
};
use crate::pool::FramePool;
use crate::spray::GpuSpray;
use crate::texture::{DEPTH_FORMAT, GpuTexture, MAP_FORMAT, depth_usage, map_usage, target_usage};
use crate::timing::PassTimer;
use crate::water::{WaterDraw, WaterMeshBuffers, WaterTextures};
use crate::wave_mips::GpuMipChain;

use super::{KeptFloor, KeptTables, KeptWaterMesh, Stages, WaveSlot, wave_key, wgpu_format};

/// The GPU back end of one frame: records each pass into `encoder`, with the textures at the
/// plan's sizes.
pub struct GpuBackend<'r> {
    pub(super) gpu: &'r Gpu,
    pub(super) stages: &'r Stages,
    pub(super) waves: &'r mut WaveSlot,
    pub(super) spray: &'r mut Option<GpuSpray>,
    pub(super) foam: &'r mut Option<GpuFoam>,
    pub(super) floor_map: &'r GpuTexture,
    pub(super) kept: &'r FramePool,
    pub(super) fresnel: &'r mut KeptTables,
    pub(super) floor_vertices: &'r mut KeptFloor,
    pub(super) object_vertices: &'r mut KeptObjects,
    pub(super) water_mesh: &'r mut KeptWaterMesh,
    pub(super) filter: &'r mut Option<(Arc<ocean_core::far_field::FresnelFilterTable>, GpuTexture)>,
    pub(super) reused: Vec<Pass>,
    pub(super) encoder: &'r mut wgpu::CommandEncoder,
    pub(super) timer: PassTimer,
    pub(super) maps: Vec<(ResourceId, GpuTexture)>,
    pub(super) chains: Vec<(ResourceId, GpuMipChain)>,
    pub(super) depth: Option<GpuTexture>,
    pub(super) hdr_started: bool,
    /// Whether the HDR frame's depth still waits for its clear: the sky pass (compute) leaves
    /// it to the next pass that draws into it, which clears it as it begins (one render pass
    /// fewer than a clear of its own).
    pub(super) depth_uncleared: bool,
    pub(super) frame_buffer: wgpu::Buffer,
    pub(super) waves_cpu: Option<Duration>,
    pub(super) wave_source: Option<&'static str>,
    pub(super) max_vertex_buffer_bytes: u64,
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
    pub(super) fn finish_depth(&mut self) {
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
