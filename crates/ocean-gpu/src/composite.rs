//! Stage `composite` (`shaders/composite.wgsl`): the last pass of a sea drawn inside someone
//! else's wgpu program ([`crate::embed`]), not a pass of the frame plan. One full-screen
//! triangle copies the frame's output into the caller's colour target and writes the caller's
//! depth of each pixel's surface point (`ocean_core::composite`), tested against the caller's
//! depth buffer with `LessEqual` (or `GreaterEqual` for a reversed-Z buffer), so sky pixels,
//! at the caller's far depth, fill only what the caller left clear.
//! Bindings: group 0 — 0 the uniforms, 1 the output, 2 the frame's depth (`textureLoad`
//! only). CPU mirror: `ocean-cpu/src/shaders/composite.rs`.

use crate::created::Counted;
use ocean_core::composite::CompositeUniforms;

use crate::common::{
    Load, begin_render_pass, entry, label, pipeline_layout, primitive, shader_module,
    texture_entry, uniform_entry,
};
use crate::device::Error;

/// The stage's pipeline for one caller's target.
pub struct CompositeStage {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
}

impl CompositeStage {
    /// Creates the pipeline `"ocean.composite"` drawing into `color` with `depth`, compared
    /// by `compare` (written), `samples` samples per pixel.
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled; [`Error::Wgpu`] if the pipeline does
    /// not validate for these formats.
    pub fn new(
        device: &wgpu::Device,
        color: wgpu::TextureFormat,
        depth: wgpu::TextureFormat,
        compare: wgpu::CompareFunction,
        samples: u32,
    ) -> Result<Self, Error> {
        let name = label("composite");
        let module = shader_module(device, "composite")?;
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&name),
            entries: &[
                uniform_entry(0, fragment),
                texture_entry(1, fragment, false),
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: fragment,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
            ],
        });
        let pipeline = device.new_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(&name),
            layout: Some(&pipeline_layout(device, &name, &[&layout])),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(entry("composite", "vs_main")?),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: primitive(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: depth,
                depth_write_enabled: Some(true),
                depth_compare: Some(compare),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            multisample: wgpu::MultisampleState { count: samples, ..Default::default() },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(entry("composite", "fs_main")?),
                compilation_options: Default::default(),
                targets: &crate::common::replace_target(color),
            }),
            multiview_mask: None,
            cache: None,
        });
        Ok(Self { pipeline, layout })
    }

    /// Records the composite of `output` (the frame's output, the size of `color`) and
    /// `frame_depth` (its reversed-Z depth) into the caller's `color` and `depth`, both kept.
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        uniforms: &CompositeUniforms,
        output: &wgpu::TextureView,
        frame_depth: &wgpu::TextureView,
        color: &wgpu::TextureView,
        depth: &wgpu::TextureView,
    ) {
        let name = label("composite");
        let buffer = kept.uniform(&name, uniforms);
        let group = kept.bind_group(
            &name,
            &self.layout,
            &[
                buffer.as_entire_binding(),
                wgpu::BindingResource::TextureView(output),
                wgpu::BindingResource::TextureView(frame_depth),
            ],
        );
        let mut pass =
            begin_render_pass(encoder, &name, color, Load::Keep, Some((depth, Load::Keep)), None);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.draw(0..3, 0..1);
    }
}
