//! Stage `present` (`shaders/present.wgsl`): the real-time viewer's copy of the frame's 8-bit
//! output into a window's surface texture, texel for texel. Not a pass of the frame plan.
//! Bindings: group 0 — 0 the output (`textureLoad` only). CPU mirror:
//! `ocean-cpu/src/shaders/present.rs`.
//!
//! The target must be a non-sRGB view (`Bgra8Unorm` or `Rgba8Unorm`; a surface whose format
//! is sRGB is viewed through its non-sRGB twin): the output is already sRGB-encoded, and a
//! unorm store of k/255 gives back the byte k exactly.

use crate::common::{
    Load, begin_render_pass, bind_group, fullscreen_pipeline, label, shader_module, texture_entry,
};
use crate::created::Counted;
use crate::device::Error;

/// The stage's pipeline for one target format.
pub struct PresentStage {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    format: wgpu::TextureFormat,
    /// The bind group of the output view last presented: the renderer keeps its output
    /// texture across frames, so a steady viewer makes no bind group per frame.
    group: std::sync::Mutex<Option<(wgpu::TextureView, wgpu::BindGroup)>>,
}

impl PresentStage {
    /// Creates the pipeline `"ocean.present"` drawing into `format`.
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled; [`Error::Unavailable`] for an sRGB
    /// `format` (it would encode the output a second time).
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Result<Self, Error> {
        if format.is_srgb() {
            return Err(Error::Unavailable(format!(
                "the present stage needs a non-sRGB target, got {format:?} (view the surface \
                 as {:?})",
                format.remove_srgb_suffix()
            )));
        }
        let name = label("present");
        let module = shader_module(device, "present")?;
        let layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&name),
            entries: &[texture_entry(0, wgpu::ShaderStages::FRAGMENT, false)],
        });
        let pipeline = fullscreen_pipeline(device, "present", &module, &layout, format)?;
        Ok(Self { pipeline, layout, format, group: std::sync::Mutex::new(None) })
    }

    /// The target format the pipeline was made for.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.format
    }

    /// Records the copy of `output` (an `Rgba8Unorm` view the size of `target`) into
    /// `target`.
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        output: &wgpu::TextureView,
        target: &wgpu::TextureView,
    ) {
        let name = label("present");
        let group = {
            let mut kept = self.group.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            match &*kept {
                Some((view, group)) if view == output => group.clone(),
                _ => {
                    let group = bind_group(
                        device,
                        &name,
                        &self.layout,
                        &[wgpu::BindingResource::TextureView(output)],
                    );
                    *kept = Some((output.clone(), group.clone()));
                    group
                }
            }
        };
        let mut pass = begin_render_pass(
            encoder,
            &name,
            target,
            Load::Clear([0.0, 0.0, 0.0, 1.0]),
            None,
            None,
        );
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.draw(0..3, 0..1);
    }
}
