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

use ocean_core::frame::{FrameUniforms, FresnelTableUniforms, ObjectVertex};
use ocean_core::graph::{FrameInputs, FrameState, run_frame};
use ocean_core::plan::{Format, FramePlan, Pass, ResourceId, WavesKernel};
use ocean_core::scene::{Ocean, Scene};
use ocean_core::terrain::{Relief, relief_texels};
use ocean_core::waves::OceanSurface;

use crate::bloom::BloomStage;
use crate::device::{AdapterReport, Error, Gpu};
use crate::foam::{FoamStage, GpuFoam};
use crate::fresnel_table::FresnelTableStage;
use crate::objects::{KeptObjects, ObjectsStage, VertexChunk};
use crate::pool::FramePool;
use crate::readback::{FloatMap, Readbacks, TexelData};
use crate::shading_path::ShadingPath;
use crate::shadow::ShadowStage;
use crate::sky::SkyStage;
use crate::spray::{GpuSpray, SprayStage};
use crate::texture::{GpuTexture, LDR_FORMAT, MAP_FORMAT, SHADOW_FORMAT};
use crate::timing::{PassTimer, PendingTimings, TimerPool};
use crate::tonemap::TonemapStage;
use crate::water::WaterStage;
use crate::wave_maps::{WaveMapSource, WaveSynthesis, make_source_from};
use crate::wave_mips::{GpuMipChain, WaveMipsStage};

mod backend;
pub use backend::GpuBackend;

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
