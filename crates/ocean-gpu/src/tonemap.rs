//! Stage `tonemap` (`shaders/tonemap.wgsl`): HDR frame → 8-bit sRGB, one full-screen triangle
//! into an `Rgba8Unorm` target. Bindings: group 0 — 0 `TonemapUniforms`, 1 the HDR frame,
//! 2 post `bloom`'s up chain, level 0 (`textureLoad` only). CPU mirror: `ocean-cpu/src/shaders/tonemap.rs`.

use crate::created::Counted;
use ocean_core::tonemap::TonemapUniforms;

use crate::common::{
    Load, begin_render_pass, fullscreen_pipeline, label, shader_module, texture_entry,
    uniform_entry,
};
use crate::device::Error;
use crate::texture::LDR_FORMAT;

/// The stage's pipeline.
pub struct TonemapStage {
    pipeline: wgpu::RenderPipeline,
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
                uniform_entry(0, wgpu::ShaderStages::FRAGMENT),
                texture_entry(1, wgpu::ShaderStages::FRAGMENT, false),
                texture_entry(2, wgpu::ShaderStages::FRAGMENT, false),
            ],
        });
        let pipeline = fullscreen_pipeline(device, "tonemap", &module, &layout, LDR_FORMAT)?;
        Ok(Self { pipeline, layout })
    }

    /// Records the pass from `hdr` (and `bloom`, the up chain's level 0 or a 1×1 zero
    /// texture) into `ldr`.
    pub fn encode(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        uniforms: &TonemapUniforms,
        (hdr, bloom): (&wgpu::TextureView, &wgpu::TextureView),
        ldr: &wgpu::TextureView,
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let name = label("tonemap");
        let group = kept.bind_group(
            &name,
            &self.layout,
            &[
                kept.uniform(&name, uniforms).as_entire_binding(),
                wgpu::BindingResource::TextureView(hdr),
                wgpu::BindingResource::TextureView(bloom),
            ],
        );
        let mut pass =
            begin_render_pass(encoder, &name, ldr, Load::Clear([0.0; 4]), None, timestamps);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.draw(0..3, 0..1);
    }
}
