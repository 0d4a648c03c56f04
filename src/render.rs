//! `ocean render`: the frame of Hu et al. 2004 on the CPU oracle or the GPU.

use std::path::PathBuf;

use anyhow::bail;

/// Arguments of `ocean render`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML); the built-in default scene when omitted.
    scene: Option<PathBuf>,
    /// Which renderer.
    #[arg(long, value_enum, default_value_t = Backend::Cpu)]
    backend: Backend,
    /// Output file, .png (8-bit sRGB) or .exr (linear HDR).
    #[arg(short, long, default_value = "ocean.png")]
    output: PathBuf,
    /// Time of the frame in seconds (overrides the scene's `ocean.time_s`).
    #[arg(long)]
    time: Option<f64>,
    /// Image size WIDTHxHEIGHT (overrides the scene's camera).
    #[arg(long)]
    size: Option<String>,
}

/// Render back ends.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum Backend {
    /// The deterministic software renderer (the correctness oracle).
    Cpu,
    /// The wgpu real-time path.
    Gpu,
}

/// Runs `ocean render`.
pub fn run(args: Args) -> anyhow::Result<()> {
    // Validate what can be validated now, so the command's contract is already honest.
    let _scene = crate::load_scene(args.scene.as_ref())?;
    bail!(
        "`ocean render` is not implemented yet (the CPU renderer is issue 3, the GPU path issue 4); \
         `ocean heightfield -o h.exr` and `ocean fresnel --eta 1.333` work today \
         (requested backend {:?}, output {})",
        args.backend,
        args.output.display()
    )
}
