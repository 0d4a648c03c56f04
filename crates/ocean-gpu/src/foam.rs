//! Stage `foam` (`shaders/foam.wgsl`): the fixed steps of foam `accumulated`'s field, one
//! compute dispatch (`accumulate`) per step in one timed compute pass, each reading the field
//! from one texture and writing the other (ping-pong). The field stays on the device across
//! frames ([`GpuFoam`], kept by the renderer as the spray's pool is). Bindings (group 0): 0
//! `FoamStepUniforms`, 1 `FrameUniforms` (waves `gerstner`'s block), 2 `displacement`, 3
//! `src`, 4 `dst` (storage). The water stage samples the result (binding 13 of
//! `shaders/water.wgsl`, through `shaders/foam/accumulated.wgsl`).
//! CPU mirror: `ocean-cpu/src/shaders/foam.rs`.

use crate::created::Counted;
use ocean_core::foam::{FieldGrid, FoamStepUniforms};

use crate::common::{entry, label, pipeline_layout, shader_module};
use crate::device::Error;
use crate::texture::{GpuTexture, MAP_FORMAT, map_usage};

/// `@workgroup_size(8, 8, 1)` of the WGSL.
pub const WORKGROUP_SIZE: u32 = 8;

/// The field on the device: two textures of the grid's size, `current` the latest.
pub struct GpuFoam {
    /// Where the field lives.
    pub grid: FieldGrid,
    /// Steps run.
    pub steps: u64,
    /// The field after the last step.
    pub current: GpuTexture,
    /// The other texture (the next step writes it).
    pub spare: GpuTexture,
}

impl GpuFoam {
    /// An empty field of `grid` (zeros) that has run `steps` steps.
    pub fn new(gpu: &crate::Gpu, grid: FieldGrid, steps: u64) -> Self {
        let n = grid.size;
        let zeros = vec![[0.0f32; 4]; (n as usize) * (n as usize)];
        let current = GpuTexture::upload_map(gpu, "ocean.foam_field", n, n, &zeros);
        let spare =
            GpuTexture::new(&gpu.device, "ocean.foam_field.spare", n, n, MAP_FORMAT, map_usage());
        Self { grid, steps, current, spare }
    }
}

/// The stage's pipeline and its bind group layout.
pub struct FoamStage {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl FoamStage {
    /// Creates the pipeline `"ocean.foam"`.
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled or the entry point is not registered.
    pub fn new(device: &wgpu::Device) -> Result<Self, Error> {
        let name = label("foam");
        let module = shader_module(device, "foam")?;
        let compute = wgpu::ShaderStages::COMPUTE;
        let layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&name),
            entries: &[
                crate::common::uniform_entry(0, compute),
                crate::common::uniform_entry(1, compute),
                crate::common::texture_entry(2, compute, false),
                crate::common::texture_entry(3, compute, false),
                crate::common::storage_map_entry(4),
            ],
        });
        let pipeline_layout = pipeline_layout(device, &name, &[&layout]);
        let pipeline = device.new_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(&name),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some(entry("foam", "accumulate")?),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
        Ok(Self { pipeline, layout })
    }

    /// Records `steps` of `field` in one compute pass, one dispatch per step, each reading
    /// the field's current texture and writing the other (the textures swap after each).
    #[expect(clippy::too_many_arguments, reason = "one argument per binding and the timer")]
    pub fn encode_steps(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        field: &mut GpuFoam,
        steps: &[FoamStepUniforms],
        frame: &wgpu::Buffer,
        displacement: &wgpu::TextureView,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let name = label("foam");
        let groups: Vec<wgpu::BindGroup> = steps
            .iter()
            .enumerate()
            .map(|(k, params)| {
                let uniforms = kept.uniform(&name, params);
                // Step k reads what step k − 1 wrote.
                let (src, dst) = if k % 2 == 0 {
                    (&field.current, &field.spare)
                } else {
                    (&field.spare, &field.current)
                };
                kept.bind_group(
                    &name,
                    &self.layout,
                    &[
                        uniforms.as_entire_binding(),
                        frame.as_entire_binding(),
                        wgpu::BindingResource::TextureView(displacement),
                        wgpu::BindingResource::TextureView(&src.view),
                        wgpu::BindingResource::TextureView(&dst.view),
                    ],
                )
            })
            .collect();
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(&name),
                timestamp_writes: timestamps,
            });
            pass.set_pipeline(&self.pipeline);
            for (params, group) in steps.iter().zip(&groups) {
                pass.set_bind_group(0, group, &[]);
                let n = params.size.div_ceil(WORKGROUP_SIZE);
                pass.dispatch_workgroups(n, n, 1);
            }
        }
        if steps.len() % 2 == 1 {
            std::mem::swap(&mut field.current, &mut field.spare);
        }
    }
}
