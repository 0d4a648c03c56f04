//! Stage `tonemap` (`shaders/tonemap.wgsl`): HDR frame → 8-bit sRGB, one compute dispatch of
//! 8×8 workgroups storing into an `Rgba8Unorm` storage texture (a full-screen pass in compute:
//! on GPUs whose fragment work runs on a few units it uses the whole chip). Bindings: group 0
//! — 0 `TonemapUniforms`, 1 the HDR frame, 2 post `bloom`'s up chain, level 0 (`textureLoad`
//! only), 3 the 8-bit picture (storage, write). CPU mirror: `ocean-cpu/src/shaders/tonemap.rs`.

use crate::created::Counted;
use ocean_core::tonemap::TonemapUniforms;

use crate::common::{
    entry, label, pipeline_layout, shader_module, storage_entry_of, texture_entry, uniform_entry,
};
use crate::device::Error;
use crate::texture::LDR_FORMAT;

/// `@workgroup_size(8, 8, 1)` of the WGSL.
const WORKGROUP_SIZE: u32 = 8;

/// The stage's pipeline.
pub struct TonemapStage {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl TonemapStage {
    /// Creates the pipeline `"ocean.tonemap"`.
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled.
    pub fn new(device: &wgpu::Device) -> Result<Self, Error> {
        let name = label("tonemap");
        let module = shader_module(device, "tonemap")?;
        let layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&name),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::COMPUTE),
                texture_entry(1, wgpu::ShaderStages::COMPUTE, false),
                texture_entry(2, wgpu::ShaderStages::COMPUTE, false),
                storage_entry_of(3, LDR_FORMAT),
            ],
        });
        let pipeline = device.new_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(&name),
            layout: Some(&pipeline_layout(device, &name, &[&layout])),
            module: &module,
            entry_point: Some(entry("tonemap", "cs_main")?),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
        Ok(Self { pipeline, layout })
    }

    /// Records the pass from `hdr` (and `bloom`, the up chain's level 0 or a 1×1 zero
    /// texture) into `ldr` (`width × height`, made with storage usage).
    pub fn encode(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        uniforms: &TonemapUniforms,
        (hdr, bloom): (&wgpu::TextureView, &wgpu::TextureView),
        (ldr, [width, height]): (&wgpu::TextureView, [u32; 2]),
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let name = label("tonemap");
        let group = kept.bind_group(
            &name,
            &self.layout,
            &[
                kept.uniform(&name, uniforms).as_entire_binding(),
                wgpu::BindingResource::TextureView(hdr),
                wgpu::BindingResource::TextureView(bloom),
                wgpu::BindingResource::TextureView(ldr),
            ],
        );
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&name),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(
            width.div_ceil(WORKGROUP_SIZE),
            height.div_ceil(WORKGROUP_SIZE),
            1,
        );
    }
}
