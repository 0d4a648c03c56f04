//! Stage `bloom` (`shaders/bloom.wgsl`, post technique `bloom`): the bright pass of the HDR
//! frame and its blur pyramid, one compute dispatch per level (`bright_down` for the down
//! chain's level 0, `downsample` for each level after, then `upsample` from the coarsest level
//! back to level 0 of the up chain), each reading a one-level view and writing another. The up
//! chain's coarsest level is a copy of the down chain's. CPU mirror:
//! `ocean-cpu/src/shaders/bloom.rs`; what each step does and why: `ocean_core::bloom`.

use crate::created::Counted;
use ocean_core::frame_format::FrameFormat;
use ocean_core::graph::BloomInputs;

use crate::common::{entry, label, pipeline_layout, shader_module};
use crate::device::Error;
use crate::wave_mips::GpuMipChain;

/// `@workgroup_size(8, 8, 1)` of the WGSL.
pub const WORKGROUP_SIZE: u32 = 8;

/// The stage's three pipelines and their bindings: group 0, binding 0 = `BloomUniforms`,
/// 1 = the level (or frame) read, 2 = the level written (storage), 3 = `upsample`'s detail
/// level (the others bind their source there again, unused).
pub struct BloomStage {
    bright_down: wgpu::ComputePipeline,
    downsample: wgpu::ComputePipeline,
    upsample: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl BloomStage {
    /// Creates the pipelines `"ocean.bloom"`, writing chains of `format` (the frame's).
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled or an entry point is not registered.
    pub fn new(device: &wgpu::Device, format: FrameFormat) -> Result<Self, Error> {
        let name = label("bloom");
        // WGSL has no preprocessor: the `rgba16float` module is the stage's source with its
        // one storage declaration's format replaced (the line says so in bloom.wgsl).
        let module = match format {
            FrameFormat::Rgba32Float => shader_module(device, "bloom")?,
            FrameFormat::Rgba16Float => {
                let source = ocean_core::shader_source::stage_source("bloom")?;
                let declared = "texture_storage_2d<rgba32float, write>";
                if source.matches(declared).count() != 1 {
                    return Err(Error::Unavailable(format!(
                        "bloom.wgsl must declare exactly one `{declared}` to make its \
                         rgba16float variant"
                    )));
                }
                let source = source.replace(declared, "texture_storage_2d<rgba16float, write>");
                device.new_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(&name),
                    source: wgpu::ShaderSource::Wgsl(source.into()),
                })
            }
        };
        let layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&name),
            entries: &[
                crate::common::uniform_entry(0, wgpu::ShaderStages::COMPUTE),
                crate::common::texture_entry(1, wgpu::ShaderStages::COMPUTE, false),
                crate::common::storage_entry_of(2, crate::texture::frame_format(format)),
                crate::common::texture_entry(3, wgpu::ShaderStages::COMPUTE, false),
            ],
        });
        let pipeline_layout = pipeline_layout(device, &name, &[&layout]);
        let make = |entry_point: &str| -> Result<wgpu::ComputePipeline, Error> {
            Ok(device.new_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&name),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry("bloom", entry_point)?),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                cache: None,
            }))
        };
        Ok(Self {
            bright_down: make("bright_down")?,
            downsample: make("downsample")?,
            upsample: make("upsample")?,
            layout,
        })
    }

    /// Records the pass: the chains (`down`, `up`, both with `inputs.levels` levels) from the
    /// HDR frame `hdr`, in two compute passes (the down chain, then the up chain; between
    /// them the copy of the coarsest level), timed by `timestamps` (down, up).
    pub fn encode(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        hdr: &wgpu::TextureView,
        inputs: &BloomInputs,
        (down, up): (&GpuMipChain, &GpuMipChain),
        timestamps: [Option<wgpu::ComputePassTimestampWrites<'_>>; 2],
    ) {
        let name = label("bloom");
        let [down_writes, up_writes] = timestamps;
        // Each dispatch: (pipeline, uniforms, read, written, detail).
        let group = |params: &ocean_core::bloom::BloomUniforms,
                     src: &wgpu::TextureView,
                     dst: &wgpu::TextureView,
                     detail: &wgpu::TextureView| {
            let uniforms = kept.uniform(&name, params);
            kept.bind_group(
                &name,
                &self.layout,
                &[
                    uniforms.as_entire_binding(),
                    wgpu::BindingResource::TextureView(src),
                    wgpu::BindingResource::TextureView(dst),
                    wgpu::BindingResource::TextureView(detail),
                ],
            )
        };
        let groups = |params: &ocean_core::bloom::BloomUniforms| {
            [params.width.div_ceil(WORKGROUP_SIZE), params.height.div_ceil(WORKGROUP_SIZE)]
        };
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(&name),
                timestamp_writes: down_writes,
            });
            for (k, params) in inputs.down.iter().enumerate() {
                let (pipeline, src) = if k == 0 {
                    (&self.bright_down, hdr)
                } else {
                    (&self.downsample, &down.levels[k - 1])
                };
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &group(params, src, &down.levels[k], src), &[]);
                let [x, y] = groups(params);
                pass.dispatch_workgroups(x, y, 1);
            }
        }
        let last = inputs.levels.len() - 1;
        let [w, h] = inputs.levels[last];
        encoder.copy_texture_to_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &down.texture,
                mip_level: last as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyTextureInfo {
                texture: &up.texture,
                mip_level: last as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        );
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&name),
            timestamp_writes: up_writes,
        });
        pass.set_pipeline(&self.upsample);
        for k in (0..last).rev() {
            let params = inputs.up(k);
            let g = group(&params, &up.levels[k + 1], &up.levels[k], &down.levels[k]);
            pass.set_bind_group(0, &g, &[]);
            let [x, y] = groups(&params);
            pass.dispatch_workgroups(x, y, 1);
        }
    }
}
