//! The sea inside your own wgpu program: a minimal winit + wgpu application that opens its
//! own window, device, surface and depth buffer, draws its own objects (three pier posts
//! standing in the water, `support/boxes.rs`) with its own pipeline and camera, and has
//! `ocean_gpu::embed::EmbeddedOcean` draw a scene's sea into the same colour target and depth
//! buffer at the program's own clock. The posts hide the sea behind them; the sea hides their
//! feet.
//!
//! ```text
//! cargo run --release --example embed -- [scene.toml] [--frames N]
//! ```
//!
//! Default: the built-in scene. `--frames N` closes the window after N frames and prints the
//! mean frame time (the test under Xvfb runs it so). The camera circles the posts once a
//! minute. Everything the sea needs from the program is in `Graphics::new` (the device's
//! features, the targets' formats) and `Graphics::draw` (the camera, the clock, the encoder
//! and the two views).

#[path = "support/boxes.rs"]
#[allow(dead_code, reason = "the window shows its frames; it reads nothing back")]
mod boxes;

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{Context, anyhow};
use boxes::{BoxInstance, Boxes};
use glam::{Quat, Vec3};
use ocean_core::scene::Scene;
use ocean_gpu::embed::{CameraView, DepthCompare, EmbeddedOcean, Output, Target};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

fn main() -> anyhow::Result<()> {
    let mut scene_path = None;
    let mut frames = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--frames" => {
                let n = args.next().context("--frames needs a count")?;
                frames = Some(n.parse::<u64>().with_context(|| format!("--frames `{n}`"))?);
            }
            path => scene_path = Some(PathBuf::from(path)),
        }
    }
    let scene = match &scene_path {
        Some(p) => Scene::load(p).with_context(|| format!("loading {}", p.display()))?,
        None => Scene::builtin(),
    };
    let event_loop = EventLoop::new().map_err(|e| anyhow!("cannot open a window: {e}"))?;
    event_loop.set_control_flow(ControlFlow::Poll);
    let mut app =
        App { scene, frames, graphics: None, start: Instant::now(), drawn: 0, error: None };
    event_loop.run_app(&mut app)?;
    if let Some(e) = app.error {
        return Err(e);
    }
    Ok(())
}

struct App {
    scene: Scene,
    frames: Option<u64>,
    graphics: Option<Graphics>,
    start: Instant,
    drawn: u64,
    error: Option<anyhow::Error>,
}

/// The program's own GPU objects, and the sea among them.
struct Graphics {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    device: wgpu::Device,
    queue: wgpu::Queue,
    config: wgpu::SurfaceConfiguration,
    depth: wgpu::TextureView,
    boxes: Boxes,
    ocean: EmbeddedOcean,
    busy: Duration,
}

impl Graphics {
    fn new(event_loop: &ActiveEventLoop, scene: Scene) -> anyhow::Result<Self> {
        let attributes = Window::default_attributes()
            .with_title("ocean: the sea in your own wgpu program")
            .with_inner_size(winit::dpi::PhysicalSize::new(960, 540));
        let window = Arc::new(event_loop.create_window(attributes)?);
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle_from_env(
                Box::new(event_loop.owned_display_handle()),
            ));
        let surface = instance.create_surface(Arc::clone(&window))?;
        let adapter = pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(
            &instance,
            Some(&surface),
        ))?;
        // The program's own features (none here) plus what the sea needs.
        let (device, queue) =
            pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
                label: Some("embed example"),
                required_features: ocean_gpu::device::required_features(&adapter)?,
                ..Default::default()
            }))?;
        let size = window.inner_size();
        let config = surface
            .get_default_config(&adapter, size.width.max(1), size.height.max(1))
            .context("the window's surface cannot be drawn by this adapter")?;
        surface.configure(&device, &config);
        let depth = depth_view(&device, config.width, config.height);
        let boxes =
            Boxes::new(&device, config.format, DEPTH_FORMAT, wgpu::CompareFunction::Less, 1);
        let target = Target {
            color_format: config.format,
            depth_format: DEPTH_FORMAT,
            depth_compare: DepthCompare::Less,
            sample_count: 1,
            output: Output::Display,
        };
        let ocean = EmbeddedOcean::new(&adapter, &device, &queue, scene, target)?;
        eprintln!(
            "embed: {} on {:?}, surface {:?}",
            adapter.get_info().name,
            adapter.get_info().backend,
            config.format
        );
        Ok(Self {
            window,
            surface,
            device,
            queue,
            config,
            depth,
            boxes,
            ocean,
            busy: Duration::ZERO,
        })
    }

    fn resize(&mut self, width: u32, height: u32) {
        if width == 0 || height == 0 {
            return;
        }
        (self.config.width, self.config.height) = (width, height);
        self.surface.configure(&self.device, &self.config);
        self.depth = depth_view(&self.device, width, height);
    }

    /// One frame at `t` s of the program's clock.
    fn draw(&mut self, t: f64) -> anyhow::Result<()> {
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                return Ok(());
            }
            other => {
                eprintln!("embed: surface {other:?}; configuring it again");
                self.surface.configure(&self.device, &self.config);
                return Ok(());
            }
        };
        let started = Instant::now();
        let view = frame.texture.create_view(&Default::default());
        let (w, h) = (self.config.width, self.config.height);
        // The program's camera: circling the posts once a minute, 7 m above the sea.
        let angle = (t * std::f64::consts::TAU / 60.0) as f32;
        let eye = Vec3::new(40.0 * angle.sin(), 7.0, 40.0 * angle.cos());
        let camera = CameraView {
            view: glam::camera::rh::view::look_at_mat4(eye, Vec3::new(0.0, 1.0, 0.0), Vec3::Y),
            projection: glam::camera::rh::proj::directx::perspective(
                0.9,
                w as f32 / h as f32,
                0.1,
                5000.0,
            ),
            width: w,
            height: h,
        };
        let posts: Vec<BoxInstance> = (0..3)
            .map(|i| BoxInstance {
                center: Vec3::new(-6.0 + 6.0 * i as f32, 0.5, -2.0 * i as f32),
                half: Vec3::new(0.6, 5.0, 0.6),
                rotation: Quat::from_rotation_y(0.3 * i as f32),
                color: [0.35, 0.22, 0.12],
            })
            .collect();
        self.boxes.update(&self.device, &self.queue, &posts, camera.projection * camera.view);

        let mut encoder = self.device.create_command_encoder(&Default::default());
        // The program clears its targets and draws its own objects...
        self.boxes.pass(&mut encoder, &view, &self.depth, Some((wgpu::Color::BLACK, 1.0)));
        // ... and the sea goes into the same targets, at the program's clock.
        self.ocean.encode(&mut encoder, &camera, t, &view, &self.depth)?;
        self.queue.submit([encoder.finish()]);
        self.window.pre_present_notify();
        self.queue.present(frame);
        self.busy += started.elapsed();
        Ok(())
    }
}

fn depth_view(device: &wgpu::Device, width: u32, height: u32) -> wgpu::TextureView {
    device
        .create_texture(&wgpu::TextureDescriptor {
            label: Some("the program's depth buffer"),
            size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DEPTH_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        })
        .create_view(&Default::default())
}

impl App {
    fn fail(&mut self, event_loop: &ActiveEventLoop, e: anyhow::Error) {
        self.error = Some(e);
        event_loop.exit();
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.graphics.is_some() {
            return;
        }
        match Graphics::new(event_loop, self.scene.clone()) {
            Ok(g) => {
                self.graphics = Some(g);
                self.start = Instant::now();
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(g) = self.graphics.as_mut() else { return };
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => g.resize(size.width, size.height),
            WindowEvent::RedrawRequested => {
                let t = self.scene.ocean.time_s + self.start.elapsed().as_secs_f64();
                if let Err(e) = g.draw(t) {
                    return self.fail(event_loop, e);
                }
                self.drawn += 1;
                if self.frames.is_some_and(|n| self.drawn >= n) {
                    let mean = g.busy.as_secs_f64() * 1e3 / self.drawn as f64;
                    println!(
                        "embed: {} frames, {mean:.1} ms each from recording to presenting",
                        self.drawn
                    );
                    event_loop.exit();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        if let Some(g) = &self.graphics {
            g.window.request_redraw();
        }
    }
}
