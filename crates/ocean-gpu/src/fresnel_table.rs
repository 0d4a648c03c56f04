//! Stage `fresnel_table` (`shaders/fresnel_table.wgsl`): the 2D Fresnel texture, one compute
//! invocation per texel, written to an `Rgba32Float` storage texture.
//! CPU mirror: `ocean-cpu/src/shaders/fresnel_table.rs`.

use crate::created::Counted;
use ocean_core::frame::FresnelTableUniforms;

use crate::common::{entry, label, pipeline_layout, shader_module};
use crate::device::Error;
use crate::texture::GpuTexture;

/// `@workgroup_size(8, 8, 1)` of the WGSL.
pub const WORKGROUP_SIZE: u32 = 8;

/// The stage's pipeline and bindings: group 0, binding 0 = `FresnelTableUniforms`, binding 1
/// = `texture_storage_2d<rgba32float, write>`.
pub struct FresnelTableStage {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl FresnelTableStage {
    /// Creates the pipeline `"ocean.fresnel_table"`.
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled.
    pub fn new(device: &wgpu::Device) -> Result<Self, Error> {
        let name = label("fresnel_table");
        let module = shader_module(device, "fresnel_table")?;
        let layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&name),
            entries: &[
                crate::common::uniform_entry(0, wgpu::ShaderStages::COMPUTE),
                crate::common::storage_map_entry(1),
            ],
        });
        let pipeline = device.new_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(&name),
            layout: Some(&pipeline_layout(device, &name, &[&layout])),
            module: &module,
            entry_point: Some(entry("fresnel_table", "main")?),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
        Ok(Self { pipeline, layout })
    }

    /// Records one dispatch filling `table` (`params.size` texels a side, created with
    /// storage usage) into `encoder`.
    pub fn encode(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        params: &FresnelTableUniforms,
        table: &GpuTexture,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let name = label("fresnel_table");
        let uniforms = kept.uniform(&name, params);
        let group = kept.bind_group(
            &name,
            &self.layout,
            &[uniforms.as_entire_binding(), wgpu::BindingResource::TextureView(&table.view)],
        );
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&name),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &group, &[]);
        let groups = params.size.div_ceil(WORKGROUP_SIZE);
        pass.dispatch_workgroups(groups, groups, 1);
    }
}
