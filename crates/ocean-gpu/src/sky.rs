//! Stage `sky` (`shaders/sky.wgsl`): the environment behind everything, one full-screen
//! triangle into the HDR frame. The sky model is the technique `shaders/sky.wgsl` imports as
//! `technique/sky`: `preetham` (`shaders/sky/preetham.wgsl`), `preetham_clouds`
//! (`shaders/sky/preetham_clouds.wgsl`, seed 001 eq. 4), both over `shaders/shared/preetham.wgsl`,
//! `atmosphere` (`shaders/sky/atmosphere.wgsl`, seed 002, over `shaders/shared/sky_lut.wgsl`),
//! or `overcast` (`shaders/sky/overcast.wgsl`, the CIE standard overcast sky), assembled by [`crate::common::shader_module_with`] for the renderer's techniques (the
//! renderer assembles the stage again when a plan asks for the other). Bindings:
//! group 0 = `CameraUniforms`, group 1 = `SkyUniforms` and sky `atmosphere`'s `SkyLut`. CPU mirror: `ocean-cpu/src/shaders/sky.rs` (its `RASTER_STATE`: depth test
//! `Always`, no depth writes, no blending — the same here).

use crate::created::Counted;
use ocean_core::camera_uniforms::CameraUniforms;

use crate::common::{
    Load, begin_render_pass, depth_state, entry, label, pipeline_layout, primitive, replace_target,
    shader_module_with, uniform_entry,
};
use crate::device::Error;

/// The stage's pipeline.
pub struct SkyStage {
    pipeline: wgpu::RenderPipeline,
    camera_layout: wgpu::BindGroupLayout,
    sky_layout: wgpu::BindGroupLayout,
}

impl SkyStage {
    /// Creates the pipeline `"ocean.sky"` for the sky technique of `techniques`, drawing into
    /// a frame of `target` format.
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled.
    pub fn new(
        device: &wgpu::Device,
        techniques: &ocean_core::plan::Techniques,
        target: wgpu::TextureFormat,
    ) -> Result<Self, Error> {
        let name = label("sky");
        let module = shader_module_with(device, "sky", techniques)?;
        let layout = |l: &str, entries: &[wgpu::BindGroupLayoutEntry]| {
            device
                .new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(l), entries })
        };
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let camera_layout = layout("ocean.sky.camera", &[uniform_entry(0, fragment)]);
        let sky_layout =
            layout("ocean.sky.sky", &[uniform_entry(0, fragment), uniform_entry(1, fragment)]);
        let pipeline = device.new_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(&name),
            layout: Some(&pipeline_layout(device, &name, &[&camera_layout, &sky_layout])),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(entry("sky", "vs_main")?),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: primitive(),
            depth_stencil: Some(depth_state(wgpu::CompareFunction::Always, false)),
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(entry("sky", "fs_main")?),
                compilation_options: Default::default(),
                targets: &replace_target(target),
            }),
            multiview_mask: None,
            cache: None,
        });
        Ok(Self { pipeline, camera_layout, sky_layout })
    }

    /// Records the pass: clears the HDR frame to 0 and its depth to 0 (reversed Z), then draws
    /// the sky.
    #[expect(clippy::too_many_arguments, reason = "one argument per binding and attachment")]
    pub fn encode(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        camera: &CameraUniforms,
        sky: &wgpu::Buffer,
        sky_lut: &wgpu::Buffer,
        hdr: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let name = label("sky");
        let camera_group = kept.bind_group(
            "ocean.sky.camera",
            &self.camera_layout,
            &[kept.uniform("ocean.sky.camera", camera).as_entire_binding()],
        );
        let sky_group = kept.bind_group(
            "ocean.sky.sky",
            &self.sky_layout,
            &[sky.as_entire_binding(), sky_lut.as_entire_binding()],
        );
        let mut pass = begin_render_pass(
            encoder,
            &name,
            hdr,
            Load::Clear([0.0; 4]),
            Some((depth, Load::Clear(0.0))),
            timestamps,
        );
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &camera_group, &[]);
        pass.set_bind_group(1, &sky_group, &[]);
        pass.draw(0..3, 0..1);
    }
}
