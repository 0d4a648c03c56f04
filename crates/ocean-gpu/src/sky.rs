//! Stage `sky` (`shaders/sky.wgsl`): the environment behind everything, one compute dispatch
//! of 8×8 workgroups storing into the HDR frame (a full-screen pass in compute: on GPUs whose
//! fragment work runs on a few units it uses the whole chip), after a depth-only pass that
//! clears the frame's depth to 0 (reversed Z). The sky model is the technique
//! `shaders/sky.wgsl` imports as `technique/sky`: `preetham` (`shaders/sky/preetham.wgsl`),
//! `preetham_clouds` (`shaders/sky/preetham_clouds.wgsl`, seed 001 eq. 4), both over
//! `shaders/shared/preetham.wgsl`, `atmosphere` (`shaders/sky/atmosphere.wgsl`, seed 002, over
//! `shaders/shared/sky_lut.wgsl`), or `overcast` (`shaders/sky/overcast.wgsl`, the CIE
//! standard overcast sky), assembled for the renderer's techniques (the renderer assembles the
//! stage again when a plan asks for another). Bindings: group 0 = `CameraUniforms` and the
//! HDR frame (storage, write, in the frame's format), group 1 = `SkyUniforms` and sky
//! `atmosphere`'s `SkyLut`. CPU mirror: `ocean-cpu/src/shaders/sky.rs`.

use crate::created::Counted;
use ocean_core::camera_uniforms::CameraUniforms;

use crate::common::{
    entry, frame_storage_module, label, pipeline_layout, storage_entry_of, uniform_entry,
};
use crate::device::Error;

/// `@workgroup_size(8, 8, 1)` of the WGSL.
const WORKGROUP_SIZE: u32 = 8;

/// The stage's pipeline.
pub struct SkyStage {
    pipeline: wgpu::ComputePipeline,
    camera_layout: wgpu::BindGroupLayout,
    sky_layout: wgpu::BindGroupLayout,
}

impl SkyStage {
    /// Creates the pipeline `"ocean.sky"` for the sky technique of `techniques`, storing into
    /// a frame of `target` format (`Rgba32Float` or `Rgba16Float`).
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled; [`Error::Unavailable`] if its storage
    /// declaration cannot be made the frame's format.
    pub fn new(
        device: &wgpu::Device,
        techniques: &ocean_core::plan::Techniques,
        target: wgpu::TextureFormat,
    ) -> Result<Self, Error> {
        let name = label("sky");
        let module = frame_storage_module(device, "sky", techniques, target)?;
        let layout = |l: &str, entries: &[wgpu::BindGroupLayoutEntry]| {
            device
                .new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(l), entries })
        };
        let compute = wgpu::ShaderStages::COMPUTE;
        let camera_layout =
            layout("ocean.sky.camera", &[uniform_entry(0, compute), storage_entry_of(1, target)]);
        let sky_layout =
            layout("ocean.sky.sky", &[uniform_entry(0, compute), uniform_entry(1, compute)]);
        let pipeline = device.new_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(&name),
            layout: Some(&pipeline_layout(device, &name, &[&camera_layout, &sky_layout])),
            module: &module,
            entry_point: Some(entry("sky", "cs_main")?),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
        Ok(Self { pipeline, camera_layout, sky_layout })
    }

    /// Records the pass: stores the sky into every texel of the HDR frame (`width × height`,
    /// made with storage usage). The frame's depth is cleared by the next pass that draws
    /// into it (the frame's `take_depth_load`), not by a pass of its own here.
    pub fn encode(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        camera: &CameraUniforms,
        (sky, sky_lut): (&wgpu::Buffer, &wgpu::Buffer),
        (hdr, [width, height]): (&wgpu::TextureView, [u32; 2]),
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let name = label("sky");
        let camera_group = kept.bind_group(
            "ocean.sky.camera",
            &self.camera_layout,
            &[
                kept.uniform("ocean.sky.camera", camera).as_entire_binding(),
                wgpu::BindingResource::TextureView(hdr),
            ],
        );
        let sky_group = kept.bind_group(
            "ocean.sky.sky",
            &self.sky_layout,
            &[sky.as_entire_binding(), sky_lut.as_entire_binding()],
        );
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&name),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &camera_group, &[]);
        pass.set_bind_group(1, &sky_group, &[]);
        pass.dispatch_workgroups(
            width.div_ceil(WORKGROUP_SIZE),
            height.div_ceil(WORKGROUP_SIZE),
            1,
        );
    }
}
