//! The frame of Hu et al. 2004 on wgpu: runs a [`FramePlan`] with the same passes, in the same
//! order, with the same uniforms as ocean-cpu's frame (`ocean-cpu/src/frame.rs`), and reads
//! back every intermediate map for the cross-check.
//!
//! | pass | target (clear) | depth (clear, test) |
//! |---|---|---|
//! | waves | N_d², N_d², N_b² `Rgba32Float` ([`crate::wave_maps`]) | — |
//! | fresnel_table | 2 × 256² `Rgba32Float` (η, 1/η), compute | — |
//! | shadow_map | 1024² `R32Float` (1, 0, 0, 0) | 1, `Less` |
//! | reflection_map, refraction_map | viewport `Rgba32Float` (0) | 0, `Greater` |
//! | sky (or, camera under water, a clear to the water colour) | HDR viewport `Rgba32Float` (0) | 0, `Always` without writes |
//! | objects | HDR (kept) | kept, `Greater` |
//! | water | HDR (kept) | kept, `Greater` |
//! | tonemap | viewport `Rgba8Unorm` | — |
//!
//! A skipped pass leaves a 1×1 zero texture where its map would be, as on the CPU. Everything
//! is recorded into one command encoder and submitted once.

use std::time::{Duration, Instant};

use ocean_core::camera::Camera;
use ocean_core::camera_uniforms::CameraUniforms;
use ocean_core::frame::{
    FrameUniforms, FresnelTableUniforms, ObjectVertex, object_triangles, scene_sky, sky_ambient,
};
use ocean_core::plan::{FramePlan, Pass};
use ocean_core::scene::{Object, Ocean, Scene};
use ocean_core::tonemap::TonemapUniforms;
use ocean_core::waves::OceanSurface;
use wgpu::util::DeviceExt;

use crate::common::{Load, begin_render_pass, bind_group, uniform_buffer};
use crate::device::{AdapterReport, Error, Gpu};
use crate::fresnel_table::FresnelTableStage;
use crate::objects::{ObjectsEntry, ObjectsStage};
use crate::shadow::ShadowStage;
use crate::sky::SkyStage;
use crate::texture::{
    FloatMap, GpuTexture, LDR_FORMAT, MAP_FORMAT, Readbacks, SHADOW_FORMAT, TexelData, map_usage,
};
use crate::timing::{PassTimer, PendingTimings};
use crate::tonemap::TonemapStage;
use crate::water::{WaterMeshBuffers, WaterStage, WaterTextures};
use crate::wave_maps::{WaveMapSource, WaveSynthesis, make_source_from};

/// What identifies an ocean's wave modes: everything but the time.
pub fn wave_key(ocean: &Ocean) -> Ocean {
    Ocean { time_s: 0.0, ..ocean.clone() }
}

/// Side of the 2D Fresnel textures (ocean-cpu's `FRESNEL_TABLE_SIZE`).
pub const FRESNEL_TABLE_SIZE: u32 = 256;
/// Side of the sun's shadow map (ocean-cpu's `SHADOW_MAP_SIZE`).
pub const SHADOW_MAP_SIZE: u32 = 1024;

/// A map of the frame that is read back, named as ocean-cpu's `FrameBuffers` fields.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FrameMap {
    /// (disp_x, height, disp_z, jacobian).
    Displacement,
    /// (slope_x, slope_z, 0, 0).
    DisplacementSlopes,
    /// (slope_x, slope_z, height, jacobian).
    Bump,
    /// Fresnel texture for η.
    FresnelAbove,
    /// Fresnel texture for 1/η.
    FresnelBelow,
    /// Depth from the sun in red.
    ShadowMap,
    /// Mirrored objects, alpha = coverage.
    ReflectionMap,
    /// Fogged objects under the water, alpha = coverage.
    RefractionMap,
    /// The linear HDR frame after the water pass.
    Hdr,
}

impl FrameMap {
    /// Every map, in the order the frame makes them.
    pub const ALL: [FrameMap; 9] = [
        FrameMap::Displacement,
        FrameMap::DisplacementSlopes,
        FrameMap::Bump,
        FrameMap::FresnelAbove,
        FrameMap::FresnelBelow,
        FrameMap::ShadowMap,
        FrameMap::ReflectionMap,
        FrameMap::RefractionMap,
        FrameMap::Hdr,
    ];

    /// The field name (`displacement`, …, `hdr`).
    pub fn name(self) -> &'static str {
        match self {
            FrameMap::Displacement => "displacement",
            FrameMap::DisplacementSlopes => "displacement_slopes",
            FrameMap::Bump => "bump",
            FrameMap::FresnelAbove => "fresnel_above",
            FrameMap::FresnelBelow => "fresnel_below",
            FrameMap::ShadowMap => "shadow_map",
            FrameMap::ReflectionMap => "reflection_map",
            FrameMap::RefractionMap => "refraction_map",
            FrameMap::Hdr => "hdr",
        }
    }

    /// The pass that writes it last.
    pub fn pass(self) -> Pass {
        match self {
            FrameMap::Displacement | FrameMap::DisplacementSlopes | FrameMap::Bump => Pass::Waves,
            FrameMap::FresnelAbove | FrameMap::FresnelBelow => Pass::FresnelTable,
            FrameMap::ShadowMap => Pass::ShadowMap,
            FrameMap::ReflectionMap => Pass::ReflectionMap,
            FrameMap::RefractionMap => Pass::RefractionMap,
            FrameMap::Hdr => Pass::Water,
        }
    }
}

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
    /// The plan it ran.
    pub plan: FramePlan,
    /// The maps read back, in [`FrameMap::ALL`] order (skipped passes: their 1×1 zero map).
    pub maps: Vec<(FrameMap, FloatMap)>,
    /// The 8-bit sRGB RGBA picture, when the plan tonemaps and it was read back.
    pub ldr: Option<Vec<u8>>,
    /// The output texture on the GPU: the 8-bit picture (`Rgba8Unorm`) when the plan
    /// tonemaps, else the HDR frame (`Rgba32Float`).
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
}

impl GpuFrame {
    /// A map, if it was read back.
    pub fn map(&self, which: FrameMap) -> Option<&FloatMap> {
        self.maps.iter().find(|(m, _)| *m == which).map(|(_, t)| t)
    }
}

/// The GPU renderer: the device and every stage's pipelines, made once; a wave-map source
/// kept while the ocean stays the same (its modes are drawn once, as the GPU FFT will upload
/// h0 once).
pub struct Renderer {
    gpu: Gpu,
    fresnel_table: FresnelTableStage,
    sky: SkyStage,
    objects: ObjectsStage,
    shadow: ShadowStage,
    water: WaterStage,
    tonemap: TonemapStage,
    wave_synthesis: WaveSynthesis,
    waves: Option<(Ocean, Box<dyn WaveMapSource>)>,
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
        let stages = gpu.scoped("creating the pipelines", || -> Result<_, Error> {
            Ok((
                FresnelTableStage::new(d)?,
                SkyStage::new(d)?,
                ObjectsStage::new(d)?,
                ShadowStage::new(d)?,
                WaterStage::new(d)?,
                TonemapStage::new(d)?,
            ))
        })??;
        let (fresnel_table, sky, objects, shadow, water, tonemap) = stages;
        Ok(Self {
            gpu,
            fresnel_table,
            sky,
            objects,
            shadow,
            water,
            tonemap,
            wave_synthesis,
            waves: None,
        })
    }

    /// The device.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
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
        if let Some((k, source)) = &mut self.waves
            && source.update(&self.gpu, &surface)?
        {
            *k = key;
            return Ok(());
        }
        self.waves = None;
        self.waves = Some((key, make_source_from(&self.gpu, self.wave_synthesis, surface)?));
        Ok(())
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
        let start = Instant::now();
        let camera = Camera::from_scene(&scene.camera)?;
        let (w, h) = (camera.width, camera.height);
        let max = self.gpu.device.limits().max_texture_dimension_2d;
        if w > max || h > max {
            return Err(Error::TooLarge { width: w, height: h, max });
        }
        // The same ocean-core calls as ocean-cpu's `render_scene`.
        let mesh = plan.water_mesh(scene, &camera)?;
        let preetham = scene_sky(scene)?;
        let sky_u = preetham.uniforms();
        let mut u = FrameUniforms::new(scene, &camera, plan, mesh.origin);
        u.sky_ambient = sky_ambient(&preetham);
        let camera_u = CameraUniforms::new(camera.view_proj().to_cols_array_2d(), [0.0; 3], w, h)?;
        let tonemap_u = plan
            .runs(Pass::Tonemap)
            .then(|| TonemapUniforms::new(scene.camera.exposure))
            .transpose()?;

        // The wave-map source for this ocean (kept across frames while the ocean is the same).
        let mut waves_cpu = None;
        let mut wave_source = None;
        if plan.runs(Pass::Waves)
            && self.waves.as_ref().is_none_or(|(k, _)| *k != wave_key(&scene.ocean))
        {
            self.set_waves(&scene.ocean, scene.ocean.surface()?)?;
        }

        let gpu = &self.gpu;
        let device = &gpu.device;
        let frame = gpu.scoped("rendering the frame", || -> Result<_, Error> {
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("ocean.frame"),
            });
            let mut timer = PassTimer::new(gpu);
            let mut readbacks: Readbacks<Option<FrameMap>> = Readbacks::default();
            let all = readback == Readback::All;

            // waves
            let empty = |label: &str| GpuTexture::empty_map(gpu, label);
            let owned_waves;
            let (displacement, displacement_slopes, bump) = match &mut self.waves {
                Some((_, source)) if plan.runs(Pass::Waves) => {
                    let t0 = Instant::now();
                    wave_source = Some(source.name());
                    let slot =
                        if source.records_gpu_passes() { timer.slot(Pass::Waves) } else { None };
                    let maps = source.encode(
                        gpu,
                        &mut encoder,
                        scene.ocean.time_s,
                        scene.ocean.choppiness,
                        timer.compute_writes(slot),
                    )?;
                    waves_cpu = Some(t0.elapsed());
                    (&maps.displacement, &maps.displacement_slopes, &maps.bump)
                }
                _ => {
                    owned_waves = [
                        empty("ocean.waves.displacement"),
                        empty("ocean.waves.displacement_slopes"),
                        empty("ocean.waves.bump"),
                    ];
                    (&owned_waves[0], &owned_waves[1], &owned_waves[2])
                }
            };

            // fresnel_table
            let table = |label: &str| {
                GpuTexture::new(
                    device,
                    label,
                    FRESNEL_TABLE_SIZE,
                    FRESNEL_TABLE_SIZE,
                    MAP_FORMAT,
                    map_usage(),
                )
            };
            let fresnel_above = table("ocean.fresnel_table.above");
            let fresnel_below = table("ocean.fresnel_table.below");
            let eta = u.water_params[0];
            for (target, eta) in [(&fresnel_above, eta), (&fresnel_below, 1.0 / eta)] {
                let params =
                    FresnelTableUniforms { eta, size: FRESNEL_TABLE_SIZE, mapping: 0, pad: 0 };
                let slot = timer.slot(Pass::FresnelTable);
                self.fresnel_table.encode(
                    device,
                    &mut encoder,
                    &params,
                    target,
                    timer.compute_writes(slot),
                );
            }

            // The objects each pass draws (the plan culls per pass, as on the CPU): their
            // triangles, camera-relative, in ocean-core's order; one zero vertex keeps a buffer
            // non-empty.
            let objects_of = |pass: Pass| -> (wgpu::Buffer, u32) {
                let objects: Vec<Object> =
                    plan.objects.of(pass).iter().map(|&i| scene.objects[i].clone()).collect();
                let tris = object_triangles(&objects, camera.eye);
                let mut vertices: Vec<ObjectVertex> = tris.iter().flatten().copied().collect();
                let count = vertices.len() as u32;
                if vertices.is_empty() {
                    vertices.push(bytemuck::Zeroable::zeroed());
                }
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("ocean.objects.vertices"),
                    contents: bytemuck::cast_slice(&vertices),
                    usage: wgpu::BufferUsages::VERTEX,
                });
                (buffer, count)
            };
            let frame_buffer = uniform_buffer(device, "ocean.frame.uniforms", &u);
            let frame_group = |layout: &wgpu::BindGroupLayout, label: &str| {
                bind_group(device, label, layout, &[frame_buffer.as_entire_binding()])
            };

            // shadow_map
            let shadow_map = if plan.runs(Pass::ShadowMap) {
                let target = GpuTexture::target(
                    device,
                    "ocean.shadow.map",
                    SHADOW_MAP_SIZE,
                    SHADOW_MAP_SIZE,
                    SHADOW_FORMAT,
                );
                let depth = GpuTexture::depth(
                    device,
                    "ocean.shadow.depth",
                    SHADOW_MAP_SIZE,
                    SHADOW_MAP_SIZE,
                );
                let slot = timer.slot(Pass::ShadowMap);
                let (object_vertices, vertex_count) = objects_of(Pass::ShadowMap);
                self.shadow.encode(
                    &mut encoder,
                    &frame_group(&self.shadow.frame_layout, "ocean.shadow"),
                    &object_vertices,
                    vertex_count,
                    &target.view,
                    &depth.view,
                    timer.render_writes(slot),
                );
                (target, SHADOW_FORMAT)
            } else {
                (empty("ocean.shadow.map"), MAP_FORMAT)
            };

            // reflection_map, refraction_map
            let objects_group = frame_group(&self.objects.frame_layout, "ocean.objects");
            let mut object_map = |pass: Pass, entry: ObjectsEntry, label: &str| {
                if !plan.runs(pass) {
                    return empty(label);
                }
                let target = GpuTexture::target(device, label, w, h, MAP_FORMAT);
                let depth = GpuTexture::depth(device, label, w, h);
                let slot = timer.slot(pass);
                let (object_vertices, vertex_count) = objects_of(pass);
                self.objects.encode(
                    &mut encoder,
                    entry,
                    &objects_group,
                    &object_vertices,
                    vertex_count,
                    &target.view,
                    &depth.view,
                    (Load::Clear([0.0; 4]), Load::Clear(0.0)),
                    timer.render_writes(slot),
                );
                target
            };
            let reflection_map = object_map(
                Pass::ReflectionMap,
                ObjectsEntry::Reflect,
                "ocean.objects.reflection_map",
            );
            let refraction_map = object_map(
                Pass::RefractionMap,
                ObjectsEntry::Refract,
                "ocean.objects.refraction_map",
            );

            // sky (or the water volume as the background)
            let hdr = GpuTexture::target(device, "ocean.hdr", w, h, MAP_FORMAT);
            let depth = GpuTexture::depth(device, "ocean.hdr.depth", w, h);
            if plan.runs(Pass::Sky) {
                let slot = timer.slot(Pass::Sky);
                self.sky.encode(
                    device,
                    &mut encoder,
                    &camera_u,
                    &sky_u,
                    &hdr.view,
                    &depth.view,
                    timer.render_writes(slot),
                );
            } else {
                let c = u.water_color;
                drop(begin_render_pass(
                    &mut encoder,
                    "ocean.background",
                    &hdr.view,
                    Load::Clear([c[0], c[1], c[2], 1.0]),
                    Some((&depth.view, Load::Clear(0.0))),
                    None,
                ));
            }

            // objects
            if plan.runs(Pass::Objects) {
                let slot = timer.slot(Pass::Objects);
                let (object_vertices, vertex_count) = objects_of(Pass::Objects);
                self.objects.encode(
                    &mut encoder,
                    ObjectsEntry::Main,
                    &objects_group,
                    &object_vertices,
                    vertex_count,
                    &hdr.view,
                    &depth.view,
                    (Load::Keep, Load::Keep),
                    timer.render_writes(slot),
                );
            }

            // water
            let water_vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("ocean.water.vertices"),
                contents: bytemuck::cast_slice(&mesh.vertices),
                usage: wgpu::BufferUsages::VERTEX,
            });
            let water_indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("ocean.water.indices"),
                contents: bytemuck::cast_slice(&mesh.indices),
                usage: wgpu::BufferUsages::INDEX,
            });
            let sky_buffer = uniform_buffer(device, "ocean.water.sky", &sky_u);
            let slot = timer.slot(Pass::Water);
            self.water.encode(
                device,
                &mut encoder,
                &frame_buffer,
                &sky_buffer,
                &WaterTextures {
                    displacement: &displacement.view,
                    displacement_slopes: &displacement_slopes.view,
                    bump: &bump.view,
                    fresnel_above: &fresnel_above.view,
                    fresnel_below: &fresnel_below.view,
                    reflection_map: &reflection_map.view,
                    refraction_map: &refraction_map.view,
                    shadow_map: &shadow_map.0.view,
                },
                &WaterMeshBuffers {
                    vertices: &water_vertices,
                    indices: &water_indices,
                    index_count: 3 * mesh.indices.len() as u32,
                },
                &hdr.view,
                &depth.view,
                timer.render_writes(slot),
            );

            // tonemap
            let ldr = tonemap_u.map(|t| {
                let ldr = GpuTexture::target(device, "ocean.ldr", w, h, LDR_FORMAT);
                let slot = timer.slot(Pass::Tonemap);
                self.tonemap.encode(
                    device,
                    &mut encoder,
                    &t,
                    &hdr.view,
                    &ldr.view,
                    timer.render_writes(slot),
                );
                ldr
            });
            timer.resolve(&mut encoder);

            // readback
            let mut copy = |key: Option<FrameMap>, texture: &GpuTexture, format| {
                let label = key.map_or("ldr", FrameMap::name);
                readbacks.copy(device, &mut encoder, key, label, texture, format);
            };
            if all {
                copy(Some(FrameMap::Displacement), displacement, MAP_FORMAT);
                copy(Some(FrameMap::DisplacementSlopes), displacement_slopes, MAP_FORMAT);
                copy(Some(FrameMap::Bump), bump, MAP_FORMAT);
                copy(Some(FrameMap::FresnelAbove), &fresnel_above, MAP_FORMAT);
                copy(Some(FrameMap::FresnelBelow), &fresnel_below, MAP_FORMAT);
                copy(Some(FrameMap::ShadowMap), &shadow_map.0, shadow_map.1);
                copy(Some(FrameMap::ReflectionMap), &reflection_map, MAP_FORMAT);
                copy(Some(FrameMap::RefractionMap), &refraction_map, MAP_FORMAT);
            }
            let output = readback != Readback::None;
            if all || (output && ldr.is_none()) {
                copy(Some(FrameMap::Hdr), &hdr, MAP_FORMAT);
            }
            if let Some(ldr) = ldr.as_ref().filter(|_| output) {
                copy(None, ldr, LDR_FORMAT);
            }
            gpu.queue.submit([encoder.finish()]);
            let data = readbacks.finish(gpu)?;
            // Reading nothing back, the frame does not wait for the GPU: its timestamps come
            // later (`GpuFrame::pending_timings`).
            let (timings, pending) = if output {
                (timer.finish(gpu)?, None)
            } else {
                (Vec::new(), timer.finish_later())
            };
            Ok((data, timings, pending, ldr.unwrap_or(hdr)))
        })??;

        let (data, gpu_timings, pending_timings, output) = frame;
        let mut maps = Vec::new();
        let mut ldr = None;
        for (key, texels) in data {
            match (key, texels) {
                (Some(m), TexelData::Float(t)) => maps.push((m, t)),
                (None, TexelData::Rgba8(bytes)) => ldr = Some(bytes),
                (key, _) => {
                    return Err(Error::Readback {
                        what: key.map_or("ldr", FrameMap::name).into(),
                        message: "unexpected texel format".into(),
                    });
                }
            }
        }
        Ok(GpuFrame {
            plan: plan.clone(),
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
        })
    }
}
