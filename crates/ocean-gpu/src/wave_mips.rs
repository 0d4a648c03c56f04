//! Stage `wave_mips` (`shaders/wave_mips.wgsl`): a slope map's mip chain with its second
//! moments, one compute dispatch per level and one compute pass for all chains (`moments`
//! for level 0, `downsample` for each level after), each reading the level below through a
//! one-level view and writing its own through another. CPU mirror:
//! `ocean-cpu/src/shaders/wave_mips.rs`.

use crate::created::Counted;
use ocean_core::far_field::mip_level_size;
use ocean_core::frame::WaveMipsUniforms;

use crate::common::{entry, label, pipeline_layout, shader_module};
use crate::device::Error;
pub use crate::texture::GpuMipChain;
use crate::texture::GpuTexture;

/// `@workgroup_size(8, 8, 1)` of the WGSL.
pub const WORKGROUP_SIZE: u32 = 8;

/// The stage's two pipelines and their bindings: group 0, binding 0 = `WaveMipsUniforms`,
/// 1 = the level read, 2 = the level written (storage).
pub struct WaveMipsStage {
    moments: wgpu::ComputePipeline,
    downsample: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl WaveMipsStage {
    /// Creates the pipelines `"ocean.wave_mips"`.
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled or an entry point is not registered.
    pub fn new(device: &wgpu::Device) -> Result<Self, Error> {
        let name = label("wave_mips");
        let module = shader_module(device, "wave_mips")?;
        let layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&name),
            entries: &[
                crate::common::uniform_entry(0, wgpu::ShaderStages::COMPUTE),
                crate::common::texture_entry(1, wgpu::ShaderStages::COMPUTE, false),
                crate::common::storage_map_entry(2),
            ],
        });
        let pipeline_layout = pipeline_layout(device, &name, &[&layout]);
        let make = |entry_point: &str| -> Result<wgpu::ComputePipeline, Error> {
            Ok(device.new_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&name),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry("wave_mips", entry_point)?),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                cache: None,
            }))
        };
        Ok(Self { moments: make("moments")?, downsample: make("downsample")?, layout })
    }

    /// Records the dispatches filling every level of each chain from its slope map (the same
    /// size as the chain's level 0), all in one compute pass: wgpu orders a dispatch after the
    /// one that wrote what it reads inside a pass as across passes, and a pass per level cost
    /// more CPU encode than the dispatch it held (18 passes a frame with two chains).
    pub fn encode(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        chains: &[(&GpuTexture, &GpuMipChain)],
    ) {
        let name = label("wave_mips");
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&name),
            timestamp_writes: None,
        });
        for (slopes, chain) in chains {
            let (w, h) = (chain.width, chain.height);
            for k in 0..chain.levels.len() as u32 {
                let dst = mip_level_size(w, h, k);
                let (pipeline, src_view, src) = if k == 0 {
                    (&self.moments, &slopes.view, dst)
                } else {
                    (&self.downsample, &chain.levels[k as usize - 1], mip_level_size(w, h, k - 1))
                };
                let uniforms = kept.uniform(&name, &WaveMipsUniforms::new(dst, src));
                let group = kept.bind_group(
                    &name,
                    &self.layout,
                    &[
                        uniforms.as_entire_binding(),
                        wgpu::BindingResource::TextureView(src_view),
                        wgpu::BindingResource::TextureView(&chain.levels[k as usize]),
                    ],
                );
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &group, &[]);
                pass.dispatch_workgroups(
                    dst[0].div_ceil(WORKGROUP_SIZE),
                    dst[1].div_ceil(WORKGROUP_SIZE),
                    1,
                );
            }
        }
    }
}
