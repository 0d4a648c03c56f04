//! `ocean heightfield`: the displacement map of a scene's ocean at a time, as EXR.
//! TO BE WRITTEN once the waves module lands.

use std::path::PathBuf;

/// Arguments of `ocean heightfield`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML); the built-in default scene when omitted.
    scene: Option<PathBuf>,
    /// Time in seconds (overrides the scene's `ocean.time_s`).
    #[arg(long)]
    time: Option<f64>,
    /// Seed of the random amplitudes (overrides the scene's `ocean.seed`).
    #[arg(long)]
    seed: Option<u64>,
    /// Output EXR file.
    #[arg(short, long)]
    output: PathBuf,
}

/// Runs `ocean heightfield`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("not yet")
}
