//! The sea inside someone else's wgpu program: [`EmbeddedOcean`] records a frame of a scene's
//! sea into the caller's command encoder and composites it into the caller's colour target
//! and depth buffer, seen through the caller's camera matrices at the caller's clock.
//!
//! How it works: the frame graph (every pass the scene's plan runs: waves, Fresnel tables,
//! shadow, reflection and refraction maps, sky, the scene's own objects, water, foam, spray,
//! bloom, tonemap) runs in this crate's own targets at the caller's image size, with this
//! crate's reversed-Z infinite projection of the caller's eye, directions and field of view
//! (`ocean_core::camera::Camera::from_view_projection`). Its last pass, stage `composite`,
//! copies the picture into the caller's colour target and writes, per pixel, the depth the
//! same surface point has under the caller's projection, tested against the caller's depth
//! buffer (`ocean_core::composite`). So the caller's objects and the sea hide each other
//! correctly whether the caller draws them before or after the sea, in the same depth buffer.
//!
//! What the caller keeps in mind:
//! - the caller's objects are not in the sea's reflection and refraction maps or its shadow
//!   map (those hold the scene's own `[[objects]]`); put them in the scene to have them there;
//! - [`Output::Display`] writes the scene's tonemapped sRGB picture (on an `*Srgb` or float
//!   target its linear values, so an sRGB target stores the same bytes as `ocean render`);
//!   [`Output::Radiance`] writes linear HDR radiance (before exposure) for a caller that
//!   tonemaps everything itself;
//! - one [`EmbeddedOcean::encode`] per submitted encoder: the wave synthesis writes its maps
//!   through the queue, so two frames recorded into one encoder would show the second's sea;
//! - the frame allocates its intermediate targets each call (as `ocean view` does today).
//!
//! ```no_run
//! # fn main() -> Result<(), ocean_gpu::Error> {
//! use ocean_gpu::embed::{CameraView, DepthCompare, EmbeddedOcean, Output, Target};
//! use ocean_gpu::glam::{Mat4, Vec3};
//!
//! // The caller's own device, with the features the sea needs added to its own.
//! let instance = wgpu::Instance::default();
//! let adapter = pollster::block_on(instance.request_adapter(&Default::default()))
//!     .map_err(|e| ocean_gpu::Error::Unavailable(e.to_string()))?;
//! let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
//!     required_features: ocean_gpu::device::required_features(&adapter)?,
//!     ..Default::default()
//! }))
//! .map_err(|e| ocean_gpu::Error::Unavailable(e.to_string()))?;
//!
//! let target = Target {
//!     color_format: wgpu::TextureFormat::Rgba8UnormSrgb,
//!     depth_format: wgpu::TextureFormat::Depth32Float,
//!     depth_compare: DepthCompare::Less,
//!     sample_count: 1,
//!     output: Output::Display,
//! };
//! let scene = ocean_core::scene::Scene::builtin();
//! let mut ocean = EmbeddedOcean::new(&adapter, &device, &queue, scene, target)?;
//!
//! // Each frame: the caller's camera and clock, the caller's encoder and targets.
//! let (width, height) = (640, 360);
//! let camera = CameraView {
//!     view: glam::camera::rh::view::look_at_mat4(Vec3::new(0.0, 8.0, 0.0), Vec3::new(0.0, 2.0, -100.0), Vec3::Y),
//!     projection: glam::camera::rh::proj::directx::perspective(0.8, width as f32 / height as f32, 0.1, 5000.0),
//!     width,
//!     height,
//! };
//! # let texture = |format| device.create_texture(&wgpu::TextureDescriptor {
//! #     label: None,
//! #     size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
//! #     mip_level_count: 1,
//! #     sample_count: 1,
//! #     dimension: wgpu::TextureDimension::D2,
//! #     format,
//! #     usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
//! #     view_formats: &[],
//! # }).create_view(&Default::default());
//! # let color = texture(wgpu::TextureFormat::Rgba8UnormSrgb);
//! # let depth = texture(wgpu::TextureFormat::Depth32Float);
//! let mut encoder = device.create_command_encoder(&Default::default());
//! // … the caller clears `depth` to 1 and draws its own objects …
//! ocean.encode(&mut encoder, &camera, 12.5, &color, &depth)?;
//! // … and may draw more objects after the sea, in the same depth buffer …
//! queue.submit([encoder.finish()]);
//! # Ok(())
//! # }
//! ```

use glam::DMat4;
use ocean_core::camera::Camera;
use ocean_core::composite::CompositeUniforms;
use ocean_core::graph::FrameState;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::Scene;

use crate::composite::CompositeStage;
use crate::device::{Error, Gpu};
use crate::frame::Renderer;
use crate::timing::PassTimer;
use crate::wave_maps::WaveSynthesis;

/// How the caller's depth buffer orders depths.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DepthCompare {
    /// Near 0, far 1, cleared to 1, tested with `Less` (glam's `camera::rh::proj::directx::perspective`).
    #[default]
    Less,
    /// Reversed Z: near 1, far 0, cleared to 0, tested with `Greater`
    /// (`camera::rh::proj::directx::perspective_infinite_reverse` and the like).
    Greater,
}

/// What the sea writes into the caller's colour target.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Output {
    /// The scene's tonemapped picture (exposure, curve, vignette, bloom as the scene says),
    /// sRGB-encoded on an 8-bit non-sRGB target and linear on an sRGB or float target.
    #[default]
    Display,
    /// Linear HDR radiance before exposure and tonemapping (the plan's HDR frame), for a
    /// float target whose owner tonemaps.
    Radiance,
}

/// The caller's render targets, fixed for the life of an [`EmbeddedOcean`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Target {
    /// The colour target's format (a float-sampled format: unorm, unorm-sRGB or float).
    pub color_format: wgpu::TextureFormat,
    /// The depth buffer's format (any depth format, with or without stencil).
    pub depth_format: wgpu::TextureFormat,
    /// How the depth buffer orders depths.
    pub depth_compare: DepthCompare,
    /// Samples per pixel of both targets (1 or what the adapter supports for them); each
    /// sample of a pixel gets the pixel's colour and depth.
    pub sample_count: u32,
    /// What the sea writes.
    pub output: Output,
}

/// The caller's camera for one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraView {
    /// World → view: a rotation and a translation, right-handed, −z forward, y up
    /// (`glam::camera::rh::view::look_at_mat4`). The scene's world: y up, the mean sea level at y = 0, metres.
    pub view: glam::Mat4,
    /// A symmetric perspective projection with `w = −z_view`, any near and far plane, depth
    /// ordered as [`Target::depth_compare`] says.
    pub projection: glam::Mat4,
    /// The colour target's width, pixels.
    pub width: u32,
    /// Its height, pixels (the projection's aspect ratio must be width / height).
    pub height: u32,
}

/// What one [`EmbeddedOcean::encode`] recorded.
#[derive(Debug)]
pub struct EncodedFrame {
    /// The plan the frame ran (which passes, at which sizes).
    pub plan: FramePlan,
    /// The sea's time, s.
    pub time_s: f64,
}

/// A scene's sea, drawn into the caller's targets on the caller's device ([module
/// doc](self)).
pub struct EmbeddedOcean {
    renderer: Renderer,
    scene: Scene,
    state: FrameState,
    target: Target,
    composite: CompositeStage,
}

impl EmbeddedOcean {
    /// The sea of a validated `scene` (`Scene::load`, `Scene::from_toml`, `Scene::builtin`)
    /// on the caller's device, which must have been requested from `adapter` with
    /// [`crate::device::required_features`]; every pipeline is made here.
    ///
    /// # Errors
    /// [`Error::MissingFeature`] for a device without the features; [`Error::Unavailable`]
    /// for a colour format the sea cannot write (integer formats) or a depth format without
    /// depth; [`Error::Wgpu`] if a pipeline does not validate.
    pub fn new(
        adapter: &wgpu::Adapter,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: Scene,
        target: Target,
    ) -> Result<Self, Error> {
        let gpu = Gpu::from_device(adapter, device, queue)?;
        let float = matches!(
            target.color_format.sample_type(None, None),
            Some(wgpu::TextureSampleType::Float { .. })
        );
        if !float || target.color_format.is_depth_stencil_format() {
            return Err(Error::Unavailable(format!(
                "the sea writes float colours; colour target {:?} cannot take them",
                target.color_format
            )));
        }
        if !target.depth_format.has_depth_aspect() {
            return Err(Error::Unavailable(format!(
                "depth target {:?} has no depth to share with the sea",
                target.depth_format
            )));
        }
        let compare = match target.depth_compare {
            DepthCompare::Less => wgpu::CompareFunction::LessEqual,
            DepthCompare::Greater => wgpu::CompareFunction::GreaterEqual,
        };
        let composite = gpu.scoped("making the composite pipeline", || {
            CompositeStage::new(
                device,
                target.color_format,
                target.depth_format,
                compare,
                target.sample_count,
            )
        })??;
        let renderer = Renderer::with_gpu(gpu, WaveSynthesis::default())?;
        let state = FrameState::new(0.0).with_carried_boats();
        Ok(Self { renderer, scene, state, target, composite })
    }

    /// The scene whose sea is drawn (its camera is replaced by the caller's each frame).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Draws another validated scene from the next frame on (accumulated foam and spray
    /// start again).
    pub fn set_scene(&mut self, scene: Scene) {
        self.scene = scene;
        self.state = FrameState::new(0.0).with_carried_boats();
    }

    /// The renderer underneath (its device, adapter and wave source).
    pub fn renderer(&self) -> &Renderer {
        &self.renderer
    }

    /// The scene with the caller's camera and time, and its plan: what [`Self::encode`]
    /// draws, for a caller who wants the plan first or the height query of the same sea
    /// (`ocean_core::frame::SurfaceSource::new(&scene, &plan)`).
    ///
    /// # Errors
    /// As [`Self::encode`]'s camera and scene checks.
    pub fn frame_scene(
        &self,
        camera: &CameraView,
        time_s: f64,
    ) -> Result<(Scene, FramePlan, Camera), Error> {
        let view = camera.view.as_dmat4();
        let projection: DMat4 = camera.projection.as_dmat4();
        let c = Camera::from_view_projection(view, projection, camera.width, camera.height)?;
        let mut scene = self.scene.clone();
        scene.camera = c.to_scene(&scene.camera);
        scene.ocean.time_s = time_s;
        scene.validate().map_err(|(key, message)| {
            Error::Unavailable(format!("with this camera and time, `{key}`: {message}"))
        })?;
        let kind = match self.target.output {
            Output::Display => OutputKind::Ldr,
            Output::Radiance => OutputKind::Hdr,
        };
        let plan = FramePlan::new(&scene, kind);
        Ok((scene, plan, c))
    }

    /// Records the sea at `time_s` (the caller's clock, s; the scene's sea time is replaced)
    /// seen by `camera` into `encoder`: the frame's passes in this crate's targets, then the
    /// composite into `color` and `depth` (both loaded and kept; the caller clears them). The
    /// caller submits the encoder, once per frame: the frame's targets, buffers and bind
    /// groups are kept for the next ([`crate::pool`]), and its uniforms are written with
    /// `Queue::write_buffer`, which lands at the next submission, so two frames of one
    /// `EmbeddedOcean` recorded into one encoder would both see the second's uniforms.
    ///
    /// # Errors
    /// [`Error::Core`] for a camera whose matrices are not a rigid view and a symmetric
    /// perspective of the image's aspect ratio; [`Error::Unavailable`] for a scene the
    /// camera or time makes invalid, or a plan the pipelines cannot run; [`Error::TooLarge`]
    /// and [`Error::Wgpu`] from the device (targets of another size or format than
    /// [`Target`] and `camera` say are validation errors).
    pub fn encode(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        camera: &CameraView,
        time_s: f64,
        color: &wgpu::TextureView,
        depth: &wgpu::TextureView,
    ) -> Result<EncodedFrame, Error> {
        let (scene, plan, c) = self.frame_scene(camera, time_s)?;
        let inputs = self.renderer.prepare(&scene, &plan, &self.state, Some(c))?;
        let device = self.renderer.gpu().device.clone();
        let far = match self.target.depth_compare {
            DepthCompare::Less => 1.0,
            DepthCompare::Greater => 0.0,
        };
        let linear =
            self.target.output == Output::Display && linear_target(self.target.color_format);
        let uniforms = CompositeUniforms::new(camera.projection.as_dmat4(), far, linear);
        let state = &mut self.state;
        let renderer = &mut self.renderer;
        let composite = &self.composite;
        crate::device::scoped(
            &device,
            "recording the embedded frame",
            || -> Result<(), Error> {
                let recorded = renderer.record(&inputs, state, encoder, PassTimer::off())?;

                let kept = renderer.kept();
                let empty;
                let output = match recorded.output() {
                    Some(t) => t,
                    None => {
                        empty = kept.empty_map("ocean.composite.empty");
                        &empty
                    }
                };
                let frame_depth = match &recorded.depth {
                    Some(d) => d.clone(),
                    None => {
                        let usage = crate::texture::depth_usage();
                        let format = crate::texture::DEPTH_FORMAT;
                        kept.texture("ocean.composite.depth", 1, 1, format, usage).0
                    }
                };
                composite.encode(
                    kept,
                    encoder,
                    &uniforms,
                    &output.view,
                    &frame_depth.view,
                    color,
                    depth,
                );
                Ok(())
            },
        )??;
        drop(inputs);
        self.state.advance();
        Ok(EncodedFrame { plan, time_s })
    }
}

/// Whether a colour target stores linear values (sRGB-encoded on write, or float), so that
/// the display picture must be written with the sRGB curve inverted.
fn linear_target(format: wgpu::TextureFormat) -> bool {
    use wgpu::TextureFormat as F;
    format.is_srgb()
        || matches!(
            format,
            F::R16Float
                | F::Rg16Float
                | F::Rgba16Float
                | F::R32Float
                | F::Rg32Float
                | F::Rgba32Float
                | F::Rg11b10Ufloat
                | F::Rgb9e5Ufloat
        )
}
