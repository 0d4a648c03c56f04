//! Stage `shadow` (`shaders/shadow.wgsl`): the depth of the objects seen from the sun, into
//! an `R32Float` map (cleared to 1) with a standard-Z depth buffer (`Less`, cleared to 1).
//! Bindings: group 0, binding 0 = `FrameUniforms`. Vertices: the objects' `ObjectVertex`
//! buffer, position only. CPU mirror: `ocean-cpu/src/shaders/shadow.rs`.

use crate::common::{
    Load, begin_render_pass, depth_state, entry, label, pipeline_layout, primitive, replace_target,
    shader_module, uniform_entry,
};
use crate::created::Counted;
use crate::device::Error;
use crate::objects::OBJECT_VERTEX_LAYOUT;
use crate::texture::SHADOW_FORMAT;

/// The stage's pipeline.
pub struct ShadowStage {
    pipeline: wgpu::RenderPipeline,
    /// Group 0: the frame's uniforms.
    pub frame_layout: wgpu::BindGroupLayout,
}

impl ShadowStage {
    /// Creates the pipeline `"ocean.shadow"`.
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled.
    pub fn new(device: &wgpu::Device) -> Result<Self, Error> {
        let name = label("shadow");
        let module = shader_module(device, "shadow")?;
        let frame_layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&name),
            entries: &[uniform_entry(0, wgpu::ShaderStages::VERTEX)],
        });
        let position_only = wgpu::VertexBufferLayout {
            array_stride: OBJECT_VERTEX_LAYOUT.array_stride,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &OBJECT_VERTEX_LAYOUT.attributes[..1],
        };
        let pipeline = device.new_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(&name),
            layout: Some(&pipeline_layout(device, &name, &[&frame_layout])),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(entry("shadow", "vs_main")?),
                compilation_options: Default::default(),
                buffers: &[Some(position_only)],
            },
            primitive: primitive(),
            depth_stencil: Some(depth_state(wgpu::CompareFunction::Less, true)),
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(entry("shadow", "fs_main")?),
                compilation_options: Default::default(),
                targets: &replace_target(SHADOW_FORMAT),
            }),
            multiview_mask: None,
            cache: None,
        });
        Ok(Self { pipeline, frame_layout })
    }

    /// Records the pass: clears the map to 1 (red) and depth to 1, draws the objects.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &wgpu::BindGroup,
        vertices: &[crate::objects::VertexChunk],
        target: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let name = label("shadow");
        let mut pass = begin_render_pass(
            encoder,
            &name,
            target,
            Load::Clear([1.0, 0.0, 0.0, 0.0]),
            Some((depth, Load::Clear(1.0))),
            timestamps,
        );
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, frame, &[]);
        for chunk in vertices {
            pass.set_vertex_buffer(0, chunk.buffer.slice(..));
            pass.draw(0..chunk.count, 0..1);
        }
    }
}
