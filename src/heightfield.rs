//! `ocean heightfield`: the displacement map of a scene's ocean at a time, as EXR
//! (docs/design.md: N×N, pixel (i, j) at x = i·L/N, z = j·L/N, channels `height`, `disp_x`,
//! `disp_z`, `slope_x`, `slope_z`, `jacobian`). Under waves `fft` the maps the FFT makes;
//! under waves `gerstner` the sum of the waves evaluated at the same N×N points of the window
//! [0, L)² (the waves are not periodic, so the window is only where the samples lie).

use std::path::PathBuf;

use ocean::output::{Channel, encode_exr, require_extension};

/// Arguments of `ocean heightfield`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML); the built-in default scene when omitted.
    scene: Option<PathBuf>,
    /// Time in seconds (overrides the scene's `ocean.time_s`).
    #[arg(long, allow_negative_numbers = true)]
    time: Option<f64>,
    /// Seed of the random amplitudes (overrides the scene's `ocean.seed`), 0 or more.
    #[arg(long, allow_negative_numbers = true, value_parser = ocean::output::parse_seed)]
    seed: Option<u64>,
    /// Output EXR file.
    #[arg(short, long)]
    output: PathBuf,
}

/// Runs `ocean heightfield`.
pub fn run(args: Args) -> anyhow::Result<()> {
    require_extension(&args.output, "exr")?;
    let out = ocean::output::OutputFile::reserve(&args.output)?;
    let mut scene = crate::load_scene(args.scene.as_ref())?;
    if let Some(t) = args.time {
        scene.ocean.time_s = t;
    }
    if let Some(s) = args.seed {
        scene.ocean.seed = s;
    }
    ocean::scene_arg::revalidate(&scene, "--time/--seed")?;
    let ocean = &scene.ocean;
    let (n, fields) = ocean_core::heightfield::channels(&scene)?;
    let channels = fields.into_iter().map(|(name, data)| Channel { name, data }).collect();
    out.commit(&encode_exr(n, n, channels)?)?;
    eprintln!(
        "wrote {} ({n}×{n}, L = {} m, t = {} s, seed {})",
        args.output.display(),
        ocean.patch_size_m,
        ocean.time_s,
        ocean.seed
    );
    Ok(())
}
