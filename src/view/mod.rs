//! `ocean view`: the wgpu frame in a window, at the display's refresh rate where the machine
//! allows, with a fly camera and a parameter panel that changes the sea while it runs.
//!
//! - [`controller`]: the fly camera (mouse-look, WASD/QE, scroll for speed, jumps).
//! - [`params`]: the panel's values, presets and their mapping onto a scene.
//! - `app`: the winit event loop, the surface, egui, and recovery from a lost surface or
//!   device; `ui`: the panel and the overlay.
//!
//! Each frame runs the same [`ocean_gpu::Renderer`] and [`ocean_core::plan::FramePlan`] as
//! `ocean render --backend gpu`, then the `present` stage copies the 8-bit output texel for
//! texel into the window, and egui draws on top. The waves are synthesised on the GPU every
//! frame, so a slider that changes the sea costs one h0 upload (N² modes), not a stall.
//!
//! With `--frames N`, time advances exactly 1/60 s per frame (frame i shows
//! `t0 + i/60`), whatever the wall clock does, and the last frame waits for the panel's sea,
//! so `--screenshot --no-ui` is reproducible and matches
//! `ocean render --backend gpu --time t0+(N−1)/60` of the same scene and size (with the panel,
//! the overlay's timings are in the picture).

mod app;
pub mod controller;
pub mod params;
mod ui;

use std::path::PathBuf;

use anyhow::bail;

/// Simulated seconds per frame with `--frames` (a 60 Hz display).
pub const FIXED_STEP_S: f64 = 1.0 / 60.0;

/// Arguments of `ocean view`.
#[derive(clap::Args, Debug, Clone)]
pub struct Args {
    /// Scene file (TOML); the built-in default scene when omitted.
    pub scene: Option<PathBuf>,
    /// `--system`.
    #[command(flatten)]
    pub system: crate::scene_arg::SystemArg,
    /// Window size WIDTHxHEIGHT in physical pixels (default: the scene's camera size).
    #[arg(long, allow_hyphen_values = true)]
    pub size: Option<String>,
    /// Render this many frames, then exit (time advances 1/60 s per frame).
    #[arg(long)]
    pub frames: Option<u64>,
    /// With --frames: save the last frame's window contents here (.png).
    #[arg(long, requires = "frames")]
    pub screenshot: Option<PathBuf>,
    /// Wait for the display's refresh (on) or present as fast as the GPU renders (off, for
    /// benchmarks).
    #[arg(long, value_enum, default_value_t = Vsync::On)]
    pub vsync: Vsync,
    /// Start time in seconds (overrides the scene's `ocean.time_s`).
    #[arg(long, allow_negative_numbers = true)]
    pub time: Option<f64>,
    /// Start with the panel and overlay hidden (F1 shows them).
    #[arg(long)]
    pub no_ui: bool,
    /// Testing aid: during a --frames run, resize the window, lose the surface and destroy
    /// the device at fixed frames, and recover from each.
    #[arg(long, hide = true, requires = "frames")]
    pub exercise_recovery: bool,
    /// Testing aid: during a --frames run, move the wind slider from 0 to its top
    /// ([`params::range::WIND_SPEED`]) one step a frame, through the panel's mapping.
    #[arg(long, hide = true, requires = "frames")]
    pub exercise_wind_sweep: bool,
    /// Testing aid: make each frame last at least this many milliseconds (a slow display), so
    /// that scripted input lands within a --frames run on any machine.
    #[arg(long, hide = true)]
    pub min_frame_ms: Option<u64>,
}

/// Whether presentation waits for the display.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Vsync {
    /// `PresentMode::AutoVsync`.
    On,
    /// `PresentMode::AutoNoVsync` (falls back to vsync where the surface has nothing else).
    Off,
}

/// Runs `ocean view`: opens the window and returns when it is closed (or after `--frames`).
///
/// # Errors
/// A bad argument or scene; no display or no GPU adapter that can present to the window
/// (the message says what to install); a GPU error that is not a lost device.
pub fn run(args: Args) -> anyhow::Result<()> {
    if args.frames == Some(0) {
        bail!("--frames must be at least 1");
    }
    if let Some(path) = &args.screenshot {
        crate::output::require_extension(path, "png")?;
        // Fail now, not after the frames: the folder must exist.
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty());
        if let Some(dir) = dir.filter(|d| !d.is_dir()) {
            bail!("cannot write {}: folder {} does not exist", path.display(), dir.display());
        }
    }
    let mut scene = crate::scene_arg::load_scene(args.scene.as_ref(), &args.system)?;
    if let Some(s) = &args.size {
        (scene.camera.width, scene.camera.height) = crate::output::parse_size(s)?;
    }
    if let Some(t) = args.time {
        scene.ocean.time_s = t;
    }
    crate::scene_arg::revalidate(&scene, "--size/--time")?;
    app::run(args, scene)
}

/// The wind speed of frame `index` of `frames` in a `--exercise-wind-sweep` run: 0 at the
/// first frame, the top of the slider (exactly) at the last.
pub fn swept_wind(index: u64, frames: u64) -> f64 {
    let top = params::range::WIND_SPEED.1;
    if frames <= 1 { top } else { top * index as f64 / (frames - 1) as f64 }
}

/// The simulated time of frame `index` of a `--frames` run that starts at `t0`.
pub fn fixed_step_time(t0: f64, index: u64) -> f64 {
    t0 + index as f64 * FIXED_STEP_S
}
