//! The viewer's window: winit's event loop, the wgpu surface, egui, and what a real-time
//! program must survive (resizing, minimising, a lost surface, a lost device).
//!
//! Recovery, in the words of wgpu's `CurrentSurfaceTexture`: `Outdated` or `Suboptimal` →
//! configure the surface again; `Lost` → make a new surface for the same window; `Timeout`
//! or `Occluded` → skip the frame; a device lost (the callback fires, or a frame fails after
//! it) → a new device, renderer, surface and egui renderer, keeping camera, parameters and
//! time. A zero-sized (minimised) window renders nothing and wakes ten times a second.

use std::collections::VecDeque;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, mpsc};
use std::time::{Duration, Instant};

use anyhow::{Context, anyhow, bail};
use ocean_core::graph::FrameState;
use ocean_core::plan::FramePlan;
use ocean_core::scene::{Ocean, Scene};
use ocean_core::waves::OceanSurface;
use ocean_gpu::frame::wave_key;
use ocean_gpu::present::PresentStage;
use ocean_gpu::timing::PendingTimings;
use ocean_gpu::{Gpu, Renderer, WaveSynthesis};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop, OwnedDisplayHandle};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

use super::controller::{CameraController, Motion};
use super::params::ViewParams;
use super::ui::Stats;
use super::{Args, Vsync, fixed_step_time};

mod frame;

/// How long a minimised or occluded window sleeps between checks.
const IDLE_WAIT: Duration = Duration::from_millis(100);

/// winit's OS errors start with the place in winit's source that raised them (`os error at
/// …/winit-0.30.13/src/platform_impl/linux/mod.rs:765: `), a path in the cargo registry that
/// means nothing to a user: keep what follows it.
fn without_source_location(message: &str) -> &str {
    let Some(rest) = message.strip_prefix("os error at ") else { return message };
    rest.find(".rs:")
        .and_then(|i| rest[i..].find(": ").map(|j| &rest[i + j + 2..]))
        .map_or(message, |m| m.trim_end_matches('.'))
}

/// Opens the window and runs the event loop until the window closes or `--frames` are done.
pub(super) fn run(args: Args, scene: Scene) -> anyhow::Result<()> {
    let event_loop = EventLoop::new().map_err(|e| {
        anyhow!(
            "cannot open a window: {}. `ocean view` needs a display (X11 or Wayland: DISPLAY \
             or WAYLAND_DISPLAY); without one, run it under Xvfb (`xvfb-run ocean view …`) or \
             use `ocean render`",
            without_source_location(&e.to_string())
        )
    })?;
    event_loop.set_control_flow(ControlFlow::Poll);
    let mut app = App::new(args, scene, event_loop.owned_display_handle());
    event_loop.run_app(&mut app).context("the window's event loop failed")?;
    app.finish()
}

/// Everything on the GPU side of the window; dropped and made anew when the device is lost.
struct Graphics {
    instance: wgpu::Instance,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    /// The non-sRGB view of the surface's format that the present stage and egui draw into.
    view_format: wgpu::TextureFormat,
    /// Whether the surface texture can be copied from (the screenshot reads the window
    /// itself; otherwise the same passes are drawn again into a texture that can).
    copy_src: bool,
    renderer: Renderer,
    present: PresentStage,
    egui: egui_wgpu::Renderer,
    lost: Arc<AtomicBool>,
    uncaptured: Arc<Mutex<Option<String>>>,
}

impl Graphics {
    fn new(
        display: &OwnedDisplayHandle,
        window: &Arc<Window>,
        vsync: Vsync,
    ) -> anyhow::Result<Self> {
        let instance = wgpu::Instance::new(
            wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(display.clone())),
        );
        let surface = instance
            .create_surface(Arc::clone(window))
            .context("cannot make a GPU surface for the window")?;
        let gpu = Gpu::for_surface(&instance, &surface)?;
        let lost = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&lost);
        gpu.device.set_device_lost_callback(move |reason, message| {
            eprintln!("view: the GPU device was lost ({reason:?}: {message})");
            flag.store(true, Ordering::SeqCst);
        });
        // Errors outside the renderer's error scopes (surface, present, egui) would panic in
        // wgpu's default handler; they are kept and turned into an error or a recovery.
        let uncaptured = Arc::new(Mutex::new(None));
        let slot = Arc::clone(&uncaptured);
        gpu.device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            if let Ok(mut s) = slot.lock() {
                s.get_or_insert_with(|| e.to_string());
            }
        }));
        let caps = surface.get_capabilities(&gpu.adapter);
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f.remove_srgb_suffix(),
                    wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
                )
            })
            .with_context(|| {
                format!(
                    "the window's surface offers no 8-bit RGBA/BGRA format on {} (it offers \
                     {:?})",
                    gpu.report, caps.formats
                )
            })?;
        let view_format = format.remove_srgb_suffix();
        let copy_src = caps.usages.contains(wgpu::TextureUsages::COPY_SRC);
        let mut usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
        if copy_src {
            usage |= wgpu::TextureUsages::COPY_SRC;
        }
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage,
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode: match vsync {
                Vsync::On => wgpu::PresentMode::AutoVsync,
                Vsync::Off => wgpu::PresentMode::AutoNoVsync,
            },
            desired_maximum_frame_latency: 2,
            alpha_mode: caps.alpha_modes.first().copied().unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: if format == view_format { vec![] } else { vec![view_format] },
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        let present = PresentStage::new(&gpu.device, view_format)?;
        let egui = egui_wgpu::Renderer::new(
            &gpu.device,
            view_format,
            egui_wgpu::RendererOptions::default(),
        );
        let renderer = Renderer::with_gpu(gpu, WaveSynthesis::default())?;
        let mut g = Self {
            instance,
            surface,
            config,
            view_format,
            copy_src,
            renderer,
            present,
            egui,
            lost,
            uncaptured,
        };
        if size.width > 0 && size.height > 0 {
            g.configure()?;
        }
        Ok(g)
    }

    fn gpu(&self) -> &Gpu {
        self.renderer.gpu()
    }

    /// Configures the surface at the current size.
    fn configure(&mut self) -> anyhow::Result<()> {
        self.surface.configure(&self.gpu().device, &self.config);
        self.check_uncaptured("configuring the window's surface")
    }

    /// Follows the window's size; a zero side (minimised) leaves the surface as it is.
    fn resize(&mut self, size: PhysicalSize<u32>) -> anyhow::Result<()> {
        if size.width == 0 || size.height == 0 {
            return Ok(());
        }
        if (self.config.width, self.config.height) == (size.width, size.height) {
            return Ok(());
        }
        self.config.width = size.width;
        self.config.height = size.height;
        self.configure()
    }

    /// A new surface for the same window (the old one was lost).
    fn recreate_surface(&mut self, window: &Arc<Window>) -> anyhow::Result<()> {
        self.surface = self
            .instance
            .create_surface(Arc::clone(window))
            .context("cannot make a new GPU surface for the window")?;
        self.configure()
    }

    fn device_lost(&self) -> bool {
        // Lets the device report a loss that happened since the last frame.
        let _ = self.gpu().device.poll(wgpu::PollType::Poll);
        self.lost.load(Ordering::SeqCst)
    }

    fn check_uncaptured(&self, what: &str) -> anyhow::Result<()> {
        let message = self.uncaptured.lock().ok().and_then(|mut s| s.take());
        match message {
            Some(m) => bail!("GPU error while {what}: {m}"),
            None => Ok(()),
        }
    }
}

/// Draws a sea's wave modes (`Ocean::surface`, ~10–20 ms at N = 256 here) on a thread of its
/// own, so that moving a slider never stalls a frame: frames keep the sea whose modes are on
/// the GPU until the new ones are ready, then switch.
struct ModeWorker {
    requests: mpsc::Sender<Ocean>,
    results: mpsc::Receiver<(Ocean, Result<OceanSurface, String>)>,
    /// The last sea asked for, while it is being drawn.
    pending: Option<Ocean>,
    /// Results still to come that were asked for before a lost device: dropped.
    stale: usize,
    /// A sea whose modes could not be drawn (not asked for again).
    failed: Option<Ocean>,
}

impl ModeWorker {
    fn new() -> Self {
        let (requests, inbox) = mpsc::channel::<Ocean>();
        let (outbox, results) = mpsc::channel();
        std::thread::spawn(move || {
            for ocean in inbox {
                let surface = ocean.surface().map_err(|e| e.to_string());
                if outbox.send((ocean, surface)).is_err() {
                    break;
                }
            }
        });
        Self { requests, results, pending: None, stale: 0, failed: None }
    }
}

struct App {
    args: Args,
    display: OwnedDisplayHandle,
    /// The scene as loaded (and sized by `--size`); the panel's values apply on top of it.
    base: Scene,
    params: ViewParams,
    /// The parameters `scene` was made from, and why the panel's latest values were refused.
    applied: ViewParams,
    scene: Scene,
    param_error: Option<String>,
    controller: CameraController,
    window: Option<Arc<Window>>,
    gfx: Option<Graphics>,
    egui_ctx: egui::Context,
    egui_state: Option<egui_winit::State>,
    ui_visible: bool,
    t0: f64,
    sim_time: f64,
    frame_index: u64,
    /// What lives across the viewer's frames (the spray's particle pool's step count): the
    /// sea's time is the scene's, set each frame, so the state's own step is 0.
    frame_state: FrameState,
    last_frame: Option<Instant>,
    stats: Stats,
    last_plan: Option<FramePlan>,
    wave_source: Option<&'static str>,
    looking: bool,
    cursor: Option<(f64, f64)>,
    screenshot: Option<(u32, u32, Vec<u8>)>,
    error: Option<anyhow::Error>,
    /// The window size at start, which the recovery exercise returns to.
    start_size: PhysicalSize<u32>,
    worker: ModeWorker,
    /// GPU time per pass of frames still on the GPU, oldest first.
    timings: VecDeque<(u64, PendingTimings)>,
    /// Set while the window has nothing to draw: no redraw is asked for before then.
    idle_until: Option<Instant>,
    /// The sea whose modes the renderer holds ([`wave_key`]); `None` after a new device.
    shown_sea: Option<Ocean>,
}

impl App {
    fn new(args: Args, scene: Scene, display: OwnedDisplayHandle) -> Self {
        let params = ViewParams::from_scene(&scene);
        let t0 = scene.ocean.time_s;
        let start_size = PhysicalSize::new(scene.camera.width, scene.camera.height);
        Self {
            ui_visible: !args.no_ui,
            args,
            display,
            controller: CameraController::new(&scene.camera),
            applied: params.clone(),
            params,
            base: scene.clone(),
            scene,
            param_error: None,
            window: None,
            gfx: None,
            egui_ctx: egui::Context::default(),
            egui_state: None,
            t0,
            sim_time: t0,
            frame_index: 0,
            frame_state: FrameState::new(0.0).with_carried_boats(),
            last_frame: None,
            stats: Stats::default(),
            last_plan: None,
            wave_source: None,
            looking: false,
            cursor: None,
            screenshot: None,
            error: None,
            start_size,
            worker: ModeWorker::new(),
            timings: VecDeque::new(),
            idle_until: None,
            shown_sea: None,
        }
    }

    /// After the event loop: the screenshot, the timing summary, or the error that ended it.
    fn finish(mut self) -> anyhow::Result<()> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        if let Some(n) = self.args.frames
            && self.frame_index < n
        {
            bail!("the window closed after {} of {n} frames", self.frame_index);
        }
        if let Some(g) = &self.gfx
            && g.gpu().wait().is_ok()
        {
            self.collect_timings();
        }
        let adapter = self.gfx.as_ref().map_or_else(String::new, |g| g.gpu().report.to_string());
        eprintln!("{}", self.stats.summary(self.frame_index, &adapter));
        let c = &self.controller;
        eprintln!(
            "view: camera at ({:.3}, {:.3}, {:.3}) m, yaw {:.3}°, pitch {:.3}°, speed {:.2} m/s",
            c.position.x,
            c.position.y,
            c.position.z,
            c.yaw.to_degrees(),
            c.pitch.to_degrees(),
            c.speed
        );
        if let Some(path) = &self.args.screenshot {
            let (w, h, rgba) = self
                .screenshot
                .take()
                .with_context(|| format!("no screenshot was taken for {}", path.display()))?;
            crate::output::write_atomic(path, &crate::output::encode_png(rgba, w, h)?)?;
            eprintln!("view: wrote {} ({w}×{h})", path.display());
        }
        Ok(())
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: anyhow::Error) {
        self.error.get_or_insert(e);
        event_loop.exit();
    }

    /// Opens the window, the device and egui (first `resumed`, or after a lost device).
    fn open(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<()> {
        let window = match &self.window {
            Some(w) => Arc::clone(w),
            None => {
                let attrs = Window::default_attributes()
                    .with_title("ocean view")
                    .with_inner_size(self.start_size);
                let w = Arc::new(event_loop.create_window(attrs).context("cannot open a window")?);
                self.window = Some(Arc::clone(&w));
                w
            }
        };
        // The old surface and device go before the new ones come (one swapchain a window).
        self.gfx = None;
        let gfx = Graphics::new(&self.display, &window, self.args.vsync)?;
        eprintln!(
            "view: {}×{} on {} ({:?}, {})",
            window.inner_size().width,
            window.inner_size().height,
            gfx.gpu().report,
            gfx.config.format,
            if gfx.copy_src { "screenshots read the window" } else { "screenshots redraw" }
        );
        // A fresh egui context re-sends its font atlas to the new egui renderer.
        self.egui_ctx = egui::Context::default();
        self.egui_state = Some(egui_winit::State::new(
            self.egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(gfx.gpu().device.limits().max_texture_dimension_2d as usize),
        ));
        self.gfx = Some(gfx);
        self.shown_sea = None;
        if self.worker.pending.take().is_some() {
            self.worker.stale += 1;
        }
        self.timings.clear();
        Ok(())
    }

    /// Takes the GPU times of the frames the GPU has finished (the device was polled this
    /// frame).
    fn collect_timings(&mut self) {
        while let Some((index, pending)) = self.timings.front() {
            match pending.try_take() {
                None => break,
                Some(Ok(passes)) => self.stats.record_passes(&passes, *index),
                Some(Err(e)) => eprintln!("view: GPU timings of frame {index} lost: {e}"),
            }
            self.timings.pop_front();
        }
    }

    /// Brings the renderer's wave modes towards the panel's sea: takes a finished drawing,
    /// asks for the next one. With `wait` (the last frame of a `--frames` run) it returns
    /// only once the renderer holds the panel's sea, so screenshots are reproducible. The
    /// first frame on a device draws the modes itself, in `Renderer::run_with`.
    fn sync_waves(&mut self, gfx: &mut Graphics, wait: bool) -> anyhow::Result<()> {
        let target = wave_key(&self.scene.ocean);
        loop {
            let received = if wait && self.worker.pending.is_some() {
                Some(self.worker.results.recv().context("the wave-mode worker stopped")?)
            } else {
                self.worker.results.try_recv().ok()
            };
            if let Some((sea, surface)) = received {
                if self.worker.stale > 0 {
                    // Asked for before the device was lost: the new renderer has moved on.
                    self.worker.stale -= 1;
                    continue;
                }
                self.worker.pending = None;
                match surface {
                    Ok(surface) => {
                        gfx.renderer.set_waves(&sea, surface)?;
                        self.shown_sea = Some(sea);
                    }
                    Err(e) => {
                        self.param_error = Some(format!("wave modes: {e}"));
                        self.worker.failed = Some(sea);
                    }
                }
                continue;
            }
            if self.shown_sea.as_ref() == Some(&target) {
                return Ok(());
            }
            if self.shown_sea.is_none() && self.worker.pending.is_none() {
                // Nothing on the GPU yet: the frame draws the modes itself.
                self.shown_sea = Some(target);
                return Ok(());
            }
            if self.worker.failed.as_ref() == Some(&target) {
                // Not asked again: the last good sea stays, the panel says why.
                if wait {
                    bail!(
                        "the wave modes of the panel's sea cannot be drawn: {}",
                        self.param_error.as_deref().unwrap_or("unknown error")
                    );
                }
                return Ok(());
            }
            if self.worker.pending.is_none() {
                self.worker
                    .requests
                    .send(target.clone())
                    .context("the wave-mode worker stopped")?;
                self.worker.pending = Some(target.clone());
            }
            if !wait {
                return Ok(());
            }
        }
    }

    /// Turns changed panel values into the scene; refused values keep the last good scene.
    fn refresh_scene(&mut self) {
        if self.params == self.applied {
            return;
        }
        match self.params.apply(&self.base) {
            Ok(scene) => {
                self.scene = scene;
                self.param_error = None;
            }
            Err(e) => self.param_error = Some(e),
        }
        self.applied = self.params.clone();
    }

    fn advance_time(&mut self, dt: f64) {
        if self.args.frames.is_some() {
            self.sim_time = fixed_step_time(self.t0, self.frame_index);
        } else if !self.params.paused {
            self.sim_time += dt * self.params.time_scale;
        }
    }

    /// The testing aid behind `--exercise-recovery`: at fixed frames, what a user's desktop
    /// and driver can do to a window, each followed by the normal recovery path.
    fn exercise(&mut self, window: &Arc<Window>) -> anyhow::Result<()> {
        let Some(gfx) = self.gfx.as_mut() else { return Ok(()) };
        let (w, h) = (self.start_size.width, self.start_size.height);
        match self.frame_index {
            5 => {
                eprintln!("view: exercise: resize to {}×{}", w / 2, h / 2);
                let _ =
                    window.request_inner_size(PhysicalSize::new((w / 2).max(1), (h / 2).max(1)));
            }
            10 => {
                eprintln!("view: exercise: resize back to {w}×{h}");
                let _ = window.request_inner_size(self.start_size);
            }
            20 => {
                eprintln!("view: exercise: surface lost");
                gfx.recreate_surface(window)?;
                eprintln!("view: recovered: new surface");
            }
            30 => {
                eprintln!("view: exercise: device destroyed");
                gfx.gpu().device.destroy();
            }
            _ => {}
        }
        Ok(())
    }

    /// Nothing to draw (minimised, occluded): sleep [`IDLE_WAIT`] before trying again, and do
    /// not count the time away as a frame step (the sea and the camera carry on from here).
    fn go_idle(&mut self) {
        self.idle_until = Some(Instant::now() + IDLE_WAIT);
        self.last_frame = None;
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<()> {
        let Some(window) = self.window.clone() else { return Ok(()) };
        let size = window.inner_size();
        if size.width == 0 || size.height == 0 {
            self.go_idle();
            return Ok(());
        }
        let now = Instant::now();
        let dt = self.last_frame.map_or(0.0, |t| (now - t).as_secs_f64());
        self.last_frame = Some(now);
        self.controller.update(dt);
        self.advance_time(dt);
        if self.args.exercise_recovery {
            self.exercise(&window)?;
        }
        if self.gfx.as_ref().is_none_or(Graphics::device_lost) {
            self.open(event_loop)?;
            eprintln!("view: recovered: new device at frame {}", self.frame_index);
        }
        if let (true, Some(n)) = (self.args.exercise_wind_sweep, self.args.frames) {
            self.params.wind_speed = super::swept_wind(self.frame_index, n);
        }
        self.refresh_scene();
        let Some(mut gfx) = self.gfx.take() else { return Ok(()) };
        let result = self.draw(event_loop, &window, &mut gfx, size, dt);
        self.gfx = Some(gfx);
        if let Some(ms) = self.args.min_frame_ms {
            std::thread::sleep(Duration::from_millis(ms).saturating_sub(now.elapsed()));
        }
        result
    }

    fn key(&mut self, event_loop: &ActiveEventLoop, code: KeyCode, pressed: bool, repeat: bool) {
        let motion = match code {
            KeyCode::KeyW | KeyCode::ArrowUp => Some(Motion::Forward),
            KeyCode::KeyS | KeyCode::ArrowDown => Some(Motion::Back),
            KeyCode::KeyA | KeyCode::ArrowLeft => Some(Motion::Left),
            KeyCode::KeyD | KeyCode::ArrowRight => Some(Motion::Right),
            KeyCode::KeyE | KeyCode::PageUp => Some(Motion::Up),
            KeyCode::KeyQ | KeyCode::PageDown => Some(Motion::Down),
            _ => None,
        };
        if let Some(m) = motion {
            self.controller.set_held(m, pressed);
            return;
        }
        if !pressed || repeat {
            return;
        }
        match code {
            KeyCode::KeyR | KeyCode::Home => self.controller.jump_home(),
            KeyCode::KeyH => self.controller.look_at_horizon(),
            KeyCode::Space => self.params.paused = !self.params.paused,
            KeyCode::F1 => self.ui_visible = !self.ui_visible,
            KeyCode::Escape => event_loop.exit(),
            _ => {}
        }
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gfx.is_none()
            && let Err(e) = self.open(event_loop)
        {
            self.fail(event_loop, e);
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(window) = self.window.clone() else { return };
        let consumed = match (&mut self.egui_state, self.ui_visible) {
            (Some(state), true) => state.on_window_event(&window, &event).consumed,
            _ => false,
        };
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if size.width > 0 && size.height > 0 {
                    eprintln!("view: window resized to {}×{}", size.width, size.height);
                }
                if let Some(gfx) = self.gfx.as_mut()
                    && let Err(e) = gfx.resize(size)
                {
                    self.fail(event_loop, e);
                }
                window.request_redraw();
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.redraw(event_loop) {
                    self.fail(event_loop, e);
                }
            }
            WindowEvent::Focused(false) => {
                self.controller.release_all();
                self.looking = false;
            }
            WindowEvent::ModifiersChanged(m) => self.controller.boost = m.state().shift_key(),
            WindowEvent::KeyboardInput { event, .. } => {
                let pressed = event.state == ElementState::Pressed;
                // Releases always reach the camera, so no key stays held behind the panel.
                // F1 too: it must work while a panel field has the focus.
                if let PhysicalKey::Code(code) = event.physical_key
                    && (!consumed || !pressed || code == KeyCode::F1)
                {
                    self.key(event_loop, code, pressed, event.repeat);
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                // Hit-test the cursor now: egui's own idea of the pointer is a frame old, and a
                // frame is 100 ms on lavapipe.
                let ppp = window.scale_factor() as f32;
                let over_ui = self.ui_visible
                    && self.cursor.is_some_and(|(x, y)| {
                        let p = egui::pos2(x as f32 / ppp, y as f32 / ppp);
                        self.egui_ctx.layer_id_at(p).is_some()
                    });
                match (button, state) {
                    (MouseButton::Right, ElementState::Pressed) if !over_ui => self.looking = true,
                    (MouseButton::Left, ElementState::Pressed) if !consumed && !over_ui => {
                        self.looking = true;
                    }
                    (MouseButton::Left | MouseButton::Right, ElementState::Released) => {
                        self.looking = false;
                    }
                    _ => {}
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                let p = (position.x, position.y);
                if self.looking
                    && let Some(last) = self.cursor
                {
                    self.controller.look(p.0 - last.0, p.1 - last.1);
                }
                self.cursor = Some(p);
            }
            WindowEvent::CursorLeft { .. } => self.cursor = None,
            WindowEvent::MouseWheel { delta, .. } if !consumed => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                self.controller.scroll(steps);
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        // A redraw request makes winit poll without sleeping, so an idle window (minimised,
        // occluded) asks for none until its wake-up time.
        if let Some(t) = self.idle_until
            && Instant::now() < t
        {
            event_loop.set_control_flow(ControlFlow::WaitUntil(t));
            return;
        }
        self.idle_until = None;
        event_loop.set_control_flow(ControlFlow::Poll);
        if let Some(w) = &self.window {
            w.request_redraw();
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn winit_source_locations_are_left_out() {
        let m = "os error at /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/\
                 winit-0.30.13/src/platform_impl/linux/mod.rs:765: neither WAYLAND_DISPLAY nor \
                 WAYLAND_SOCKET nor DISPLAY is set.";
        assert_eq!(
            super::without_source_location(m),
            "neither WAYLAND_DISPLAY nor WAYLAND_SOCKET nor DISPLAY is set"
        );
        assert_eq!(super::without_source_location("no adapter"), "no adapter");
    }
}
