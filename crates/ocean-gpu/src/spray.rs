//! Stage `spray` (`shaders/spray.wgsl`, spray technique `particles`): the `step` compute
//! pipeline that advances the particle pool in place in a storage buffer that stays on the
//! device (nothing per frame is uploaded but the step's uniforms), and the sprite pipeline
//! that adds the active particles to the HDR frame. Group 0 has two layouts: `step`'s
//! (0 `SprayUniforms`, 1 the pool read-write, 2 the emitters, 3 `displacement`,
//! 4 `wrap_linear`) and the draw's (5 `FrameUniforms`, 6 the pool read-only, 7
//! `SprayUniforms`). Draw state: reversed-Z `Greater` against the frame's depth, no depth
//! write, blend One + One, no culling. CPU mirror: `ocean-cpu/src/shaders/spray.rs`.

use crate::created::Counted;
use ocean_core::spray::{Emitter, Particle, SprayUniforms};

use crate::common::{
    Load, begin_render_pass, depth_state, entry, label, pipeline_layout, primitive, sampler_entry,
    shader_module, texture_entry, uniform_entry,
};
use crate::device::Error;
use crate::texture::MAP_FORMAT;

/// Invocations per workgroup of `step` (the WGSL's `@workgroup_size`).
pub const WORKGROUP_SIZE: u32 = 64;

fn storage_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    read_only: bool,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// The stage's pipelines.
pub struct SprayStage {
    step: wgpu::ComputePipeline,
    /// `None` without `FLOAT32_BLENDABLE` when the frame is `Rgba32Float`.
    draw: Option<wgpu::RenderPipeline>,
    step_layout: wgpu::BindGroupLayout,
    draw_layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
}

/// A particle pool on the device: the slots, the emitters, and the steps run.
pub struct GpuSpray {
    /// What it was made for.
    pub key: ocean_core::spray::PoolKey,
    /// The slots (`Particle`, storage, copy source for read-back).
    pub particles: wgpu::Buffer,
    /// The emitters (at least one element: a buffer cannot be empty).
    pub emitters: wgpu::Buffer,
    /// Slots.
    pub count: u32,
    /// Steps run.
    pub steps: u64,
}

impl GpuSpray {
    /// A pool of free slots for `key` (zeroed once, at creation).
    pub fn new(device: &wgpu::Device, key: ocean_core::spray::PoolKey) -> Self {
        let count = key.spray.particles;
        let particles = device.new_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("ocean.spray.particles"),
            contents: bytemuck::cast_slice(&vec![Particle::default(); count as usize]),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        });
        let placeholder = [Emitter::default()];
        let e: &[Emitter] = if key.emitters.is_empty() { &placeholder } else { &key.emitters };
        let emitter_buffer = device.new_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("ocean.spray.emitters"),
            contents: bytemuck::cast_slice(e),
            usage: wgpu::BufferUsages::STORAGE,
        });
        Self { key, particles, emitters: emitter_buffer, count, steps: 0 }
    }
}

impl SprayStage {
    /// Creates the pipelines `"ocean.spray"`, the sprites blending into a frame of `target`
    /// format.
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled or an entry point is not registered.
    pub fn new(device: &wgpu::Device, target: wgpu::TextureFormat) -> Result<Self, Error> {
        let name = label("spray");
        let module = shader_module(device, "spray")?;
        let compute = wgpu::ShaderStages::COMPUTE;
        let step_layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ocean.spray.step"),
            entries: &[
                uniform_entry(0, compute),
                storage_entry(1, compute, false),
                storage_entry(2, compute, true),
                texture_entry(3, compute, true),
                sampler_entry(4, compute),
            ],
        });
        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let draw_layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ocean.spray.draw"),
            entries: &[
                uniform_entry(5, vf),
                storage_entry(6, wgpu::ShaderStages::VERTEX, true),
                uniform_entry(7, vf),
            ],
        });
        let step = device.new_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(&name),
            layout: Some(&pipeline_layout(device, "ocean.spray.step", &[&step_layout])),
            module: &module,
            entry_point: Some(entry("spray", "step")?),
            compilation_options: Default::default(),
            cache: None,
        });
        // An f16 target is always blendable; an f32 one only with the feature.
        let blendable =
            target != MAP_FORMAT || device.features().contains(wgpu::Features::FLOAT32_BLENDABLE);
        let (vs, fs) = (entry("spray", "vs_main")?, entry("spray", "fs_main")?);
        let draw = blendable.then(|| {
            device.new_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&name),
                layout: Some(&pipeline_layout(device, "ocean.spray.draw", &[&draw_layout])),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: primitive(),
                depth_stencil: Some(depth_state(wgpu::CompareFunction::Greater, false)),
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(fs),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: target,
                        blend: Some(wgpu::BlendState {
                            color: wgpu::BlendComponent {
                                src_factor: wgpu::BlendFactor::One,
                                dst_factor: wgpu::BlendFactor::One,
                                operation: wgpu::BlendOperation::Add,
                            },
                            alpha: wgpu::BlendComponent {
                                src_factor: wgpu::BlendFactor::One,
                                dst_factor: wgpu::BlendFactor::One,
                                operation: wgpu::BlendOperation::Add,
                            },
                        }),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        });
        // The CPU mirror's WRAP_LINEAR.
        let sampler = crate::common::linear_sampler(
            device,
            "ocean.spray.wrap_linear",
            wgpu::AddressMode::Repeat,
        );
        Ok(Self { step, draw, step_layout, draw_layout, sampler })
    }

    /// Records one `step` dispatch of `pool` with `params` (the step's uniforms), reading the
    /// sea's height from `displacement`.
    pub fn encode_step(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        pool: &GpuSpray,
        params: &SprayUniforms,
        displacement: &wgpu::TextureView,
    ) {
        let name = label("spray");
        let u = kept.uniform(&name, params);
        let group = kept.bind_group(
            &name,
            &self.step_layout,
            &[
                u.as_entire_binding(),
                pool.particles.as_entire_binding(),
                pool.emitters.as_entire_binding(),
                wgpu::BindingResource::TextureView(displacement),
                wgpu::BindingResource::Sampler(&self.sampler),
            ],
        );
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&name),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.step);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(pool.count.div_ceil(WORKGROUP_SIZE), 1, 1);
    }

    /// One `step` of a pool holding `before` (`pool`'s emitters, the step's uniforms
    /// `params`), reading the sea's height from `displacement`, recorded as a frame records
    /// it ([`Self::encode_step`]) on a slot buffer of its own: the slots as the device writes
    /// them. For the envelope's verdict on the step from the device's own inputs (`ocean
    /// compare`); `pool` is left as it was.
    ///
    /// # Errors
    /// A device error while reading the slots back.
    pub fn probe_step(
        &self,
        gpu: &crate::device::Gpu,
        kept: &crate::pool::FramePool,
        before: &[Particle],
        pool: &GpuSpray,
        params: &SprayUniforms,
        displacement: &wgpu::TextureView,
    ) -> Result<Vec<Particle>, Error> {
        // A buffer cannot be empty: one free slot stands in for none.
        let slots = if before.is_empty() { &[Particle::default()][..] } else { before };
        let probe = GpuSpray {
            key: pool.key.clone(),
            particles: gpu.device.new_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("ocean.spray.probe.particles"),
                contents: bytemuck::cast_slice(slots),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            }),
            emitters: pool.emitters.clone(),
            count: slots.len() as u32,
            steps: pool.steps,
        };
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.encode_step(kept, &mut encoder, &probe, params, displacement);
        gpu.queue.submit([encoder.finish()]);
        let mut after = read_particles(gpu, &probe.particles)?;
        after.truncate(before.len());
        Ok(after)
    }

    /// Whether the device can draw the sprites (an `Rgba16Float` frame, or `FLOAT32_BLENDABLE`).
    pub fn can_draw(&self) -> bool {
        self.draw.is_some()
    }

    /// Records the sprites of `pool` added to `target` behind `depth` (nothing without
    /// [`Self::can_draw`]).
    #[expect(clippy::too_many_arguments, reason = "one argument per binding and attachment")]
    pub fn encode_draw(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        frame: &wgpu::Buffer,
        pool: &GpuSpray,
        params: &SprayUniforms,
        target: &wgpu::TextureView,
        (depth, depth_load): (&wgpu::TextureView, Load<f32>),
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let Some(draw) = &self.draw else { return };
        let name = label("spray");
        let u = kept.uniform(&name, params);
        // Bindings 5–7: the draw's layout of group 0.
        let group = kept.bind_group_numbered(
            &name,
            &self.draw_layout,
            &[
                (5, frame.as_entire_binding()),
                (6, pool.particles.as_entire_binding()),
                (7, u.as_entire_binding()),
            ],
        );
        let mut pass = begin_render_pass(
            encoder,
            &name,
            target,
            Load::Keep,
            Some((depth, depth_load)),
            timestamps,
        );
        pass.set_pipeline(draw);
        pass.set_bind_group(0, &group, &[]);
        pass.draw(0..6 * pool.count, 0..1);
    }
}

/// The slots `buffer` holds, read back from the device (blocks until it is done).
///
/// # Errors
/// A device error while mapping the copy.
pub fn read_particles(
    gpu: &crate::device::Gpu,
    buffer: &wgpu::Buffer,
) -> Result<Vec<Particle>, Error> {
    let device = &gpu.device;
    let staging = device.new_buffer(&wgpu::BufferDescriptor {
        label: Some("ocean.spray.readback"),
        size: buffer.size(),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, buffer.size());
    gpu.queue.submit([encoder.finish()]);
    let bytes = crate::readback::map_read_bytes(device, &staging)
        .map_err(|e| Error::Unavailable(format!("reading the spray back: {e}")))?;
    Ok(bytemuck::cast_slice(&bytes).to_vec())
}
