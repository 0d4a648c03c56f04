//! One frame in the window: the window's next image acquired, the frame rendered and
//! composed with the panel over it, the screenshot read back, the image presented.

use std::sync::Arc;
use std::time::Instant;

use anyhow::bail;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::Scene;
use ocean_gpu::Readback;
use ocean_gpu::readback::{Readbacks, TexelData};
use winit::dpi::PhysicalSize;
use winit::event_loop::ActiveEventLoop;
use winit::window::Window;

use super::{App, Graphics};
use crate::view::ui::{self, Action, Overlay};

/// What egui drew this frame, ready to paint.
struct UiPaint {
    jobs: Vec<egui::ClippedPrimitive>,
    textures: egui::TexturesDelta,
    screen: egui_wgpu::ScreenDescriptor,
}

impl Drop for UiPaint {
    // `present` applies the deltas (or the frame was lost with them, as a release build would
    // lose them too); epaint's debug assertion asks that what is dropped be cleared first.
    fn drop(&mut self) {
        self.textures.clear();
    }
}

/// The window's next image, acquired for a frame.
struct Acquired {
    texture: wgpu::SurfaceTexture,
    /// Suboptimal: used for this frame, the surface configured again after presenting it.
    reconfigure: bool,
}

/// What composing a frame onto a target reads: the frame's output and the panel's paint.
struct Compose<'f> {
    device: &'f wgpu::Device,
    queue: &'f wgpu::Queue,
    /// The frame's output, which the present stage draws from.
    output: &'f wgpu::TextureView,
    paint: Option<&'f UiPaint>,
}

impl Compose<'_> {
    /// The frame's output, and the panel over it, drawn into `target` (egui's buffer
    /// uploads go to `extra`, submitted before the encoder).
    fn onto(
        &self,
        gfx: &mut Graphics,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        extra: &mut Vec<wgpu::CommandBuffer>,
    ) {
        let (device, queue) = (self.device, self.queue);
        gfx.present.encode(device, encoder, self.output, target);
        if let Some(p) = self.paint {
            extra.extend(gfx.egui.update_buffers(device, queue, encoder, &p.jobs, &p.screen));
            let mut pass = encoder
                .begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("ocean.view.egui"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: target,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Load,
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    depth_stencil_attachment: None,
                    timestamp_writes: None,
                    occlusion_query_set: None,
                    multiview_mask: None,
                })
                .forget_lifetime();
            gfx.egui.render(&mut pass, &p.jobs, &p.screen);
        }
    }

    /// The screenshot's copy into `readbacks`: of the window's image `shown` itself where the
    /// surface can be copied from, else of the frame composed again into a texture that can
    /// (returned: it must live until the copy is submitted).
    fn screenshot(
        &self,
        gfx: &mut Graphics,
        encoder: &mut wgpu::CommandEncoder,
        shown: &wgpu::Texture,
        readbacks: &mut Readbacks<()>,
        extra: &mut Vec<wgpu::CommandBuffer>,
    ) -> Option<wgpu::Texture> {
        let device = self.device;
        if gfx.copy_src {
            readbacks.copy_texture(device, encoder, (), "screenshot", shown, gfx.view_format);
            return None;
        }
        let shot_target = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("ocean.view.screenshot"),
            size: shown.size(),
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: gfx.view_format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let shot_view = shot_target.create_view(&Default::default());
        self.onto(gfx, encoder, &shot_view, extra);
        readbacks.copy_texture(device, encoder, (), "screenshot", &shot_target, gfx.view_format);
        Some(shot_target)
    }
}

impl App {
    /// One frame on `gfx` (taken out of `self` for the frame).
    pub(super) fn draw(
        &mut self,
        event_loop: &ActiveEventLoop,
        window: &Arc<Window>,
        gfx: &mut Graphics,
        size: PhysicalSize<u32>,
        dt: f64,
    ) -> anyhow::Result<()> {
        gfx.resize(size)?;
        let last = self.args.frames.is_some_and(|n| self.frame_index + 1 >= n);
        self.sync_waves(gfx, last)?;

        let Some(image) = self.acquire(window, gfx)? else { return Ok(()) };
        let scene = self.frame_scene(gfx);
        let plan = FramePlan::new(&scene, OutputKind::Ldr);
        let cpu_start = Instant::now();
        let frame =
            match gfx.renderer.run_frame(&scene, &plan, &mut self.frame_state, Readback::None) {
                Ok(f) => f,
                Err(e) if gfx.device_lost() => {
                    eprintln!("view: frame {} failed on a lost device ({e})", self.frame_index);
                    return Ok(());
                }
                Err(e) => return Err(e.into()),
            };

        let view = image.texture.texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(gfx.view_format),
            ..Default::default()
        });

        let paint = if self.ui_visible {
            let Some(paint) = self.ui_pass(window, gfx) else { return Ok(()) };
            Some(paint)
        } else {
            None
        };

        let device = gfx.gpu().device.clone();
        let queue = gfx.gpu().queue.clone();
        let compose = Compose {
            device: &device,
            queue: &queue,
            output: &frame.output.view,
            paint: paint.as_ref(),
        };
        if !self.present(window, gfx, image, &view, &compose, last)? {
            return Ok(());
        }

        self.stats.record(dt, cpu_start.elapsed().as_secs_f64(), frame.waves_cpu, self.frame_index);
        if let Some(p) = frame.pending_timings {
            self.timings.push_back((self.frame_index, p));
        }
        self.collect_timings();
        self.wave_source = frame.wave_source;
        self.last_plan = Some(plan);
        self.frame_index += 1;
        if last {
            event_loop.exit();
        }
        Ok(())
    }

    /// The window's next image, acquired before the frame is rendered so that a hidden window
    /// costs nothing; `None` where there is none to draw into this time (hidden: idle;
    /// outdated or lost: configured or made anew for the next frame).
    fn acquire(
        &mut self,
        window: &Arc<Window>,
        gfx: &mut Graphics,
    ) -> anyhow::Result<Option<Acquired>> {
        let mut reconfigure = false;
        let texture = match gfx.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t) => t,
            wgpu::CurrentSurfaceTexture::Suboptimal(t) => {
                // Used this once; configured again after presenting.
                reconfigure = true;
                t
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                self.go_idle();
                return Ok(None);
            }
            wgpu::CurrentSurfaceTexture::Outdated => {
                eprintln!("view: surface outdated; configuring it again");
                gfx.configure()?;
                return Ok(None);
            }
            wgpu::CurrentSurfaceTexture::Lost => {
                eprintln!("view: surface lost; making a new one");
                gfx.recreate_surface(window)?;
                eprintln!("view: recovered: new surface");
                return Ok(None);
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                if gfx.device_lost() {
                    return Ok(None);
                }
                gfx.check_uncaptured("acquiring the window's next image")?;
                bail!("GPU validation error while acquiring the window's next image");
            }
        };
        Ok(Some(Acquired { texture, reconfigure }))
    }

    /// This frame's scene: the sea whose modes the GPU holds, seen from the controller's
    /// camera at the window's size, at the simulation's time.
    fn frame_scene(&self, gfx: &Graphics) -> Scene {
        let mut scene = self.scene.clone();
        if let Some(sea) = &self.shown_sea {
            scene.ocean = sea.clone();
        }
        self.controller.apply(&mut scene.camera);
        (scene.camera.width, scene.camera.height) = (gfx.config.width, gfx.config.height);
        scene.ocean.time_s = self.sim_time;
        scene
    }

    /// The panel's pass: egui's input taken, the panel drawn and its actions applied, its
    /// shapes tessellated; `None` where the window has no egui state.
    fn ui_pass(&mut self, window: &Arc<Window>, gfx: &Graphics) -> Option<UiPaint> {
        let overlay = Overlay {
            stats: &self.stats,
            plan: self.last_plan.as_ref(),
            adapter: &gfx.gpu().report.name,
            controller: &self.controller,
            time_s: self.sim_time,
            size: (gfx.config.width, gfx.config.height),
            error: self.param_error.as_deref(),
            wave_source: self.wave_source,
        };
        let state = self.egui_state.as_mut()?;
        let raw = state.take_egui_input(window);
        let mut actions = Vec::new();
        let ctx = self.egui_ctx.clone();
        let out = ctx.run_pass(raw, |ctx| {
            ui::draw(ctx, &mut self.params, &overlay, &mut actions);
        });
        state.handle_platform_output(window, out.platform_output);
        for a in actions {
            match a {
                Action::JumpHome => self.controller.jump_home(),
                Action::Horizon => self.controller.look_at_horizon(),
            }
        }
        Some(UiPaint {
            jobs: ctx.tessellate(out.shapes, out.pixels_per_point),
            textures: out.textures_delta,
            screen: egui_wgpu::ScreenDescriptor {
                size_in_pixels: [gfx.config.width, gfx.config.height],
                pixels_per_point: out.pixels_per_point,
            },
        })
    }

    /// Composes the frame into the window's `image` (through its `view`), reads the picture
    /// back on the last frame when `--screenshot` asks for it, and presents the image.
    /// `Ok(false)`: the device was lost meanwhile.
    fn present(
        &mut self,
        window: &Arc<Window>,
        gfx: &mut Graphics,
        image: Acquired,
        view: &wgpu::TextureView,
        compose: &Compose<'_>,
        last: bool,
    ) -> anyhow::Result<bool> {
        let (device, queue) = (compose.device, compose.queue);
        if let Some(p) = compose.paint {
            for (id, deltas) in &p.textures.set {
                for delta in deltas {
                    gfx.egui.update_texture(device, queue, *id, delta);
                }
            }
        }
        let mut encoder = device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("ocean.view") });
        let mut extra = Vec::new();
        compose.onto(gfx, &mut encoder, view, &mut extra);
        let mut readbacks: Readbacks<()> = Readbacks::default();
        // Held until the frame is presented, as the copy's source.
        let _shot_target = if last && self.args.screenshot.is_some() {
            compose.screenshot(
                gfx,
                &mut encoder,
                &image.texture.texture,
                &mut readbacks,
                &mut extra,
            )
        } else {
            None
        };
        queue.submit(extra.into_iter().chain([encoder.finish()]));
        if last && self.args.screenshot.is_some() {
            let data = readbacks.finish(gfx.gpu())?;
            if let Some(((), TexelData::Rgba8(rgba))) = data.into_iter().next() {
                let s = image.texture.texture.size();
                self.screenshot = Some((s.width, s.height, rgba));
            }
        }
        if let Some(p) = compose.paint {
            for id in &p.textures.free {
                gfx.egui.free_texture(id);
            }
        }
        window.pre_present_notify();
        queue.present(image.texture);
        if image.reconfigure {
            gfx.configure()?;
        }
        if gfx.device_lost() {
            return Ok(false);
        }
        gfx.check_uncaptured("presenting the frame")?;
        Ok(true)
    }
}
