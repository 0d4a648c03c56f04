//! `ocean plan`: which passes a scene's frame runs and why each is in or out (DESIGN.md:
//! `--json` prints `{"passes": [{"name", "reason"}…], "skipped": […]}`).

use std::path::PathBuf;

use ocean_core::plan::{FramePlan, OutputKind};

/// Arguments of `ocean plan`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scene file (TOML); the built-in default scene when omitted.
    scene: Option<PathBuf>,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
    /// Plan for EXR (linear HDR) output: no tonemap pass.
    #[arg(long)]
    hdr: bool,
}

/// Runs `ocean plan`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let scene = crate::load_scene(args.scene.as_ref())?;
    let output = if args.hdr { OutputKind::Hdr } else { OutputKind::Ldr };
    let plan = FramePlan::new(&scene, output);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&plan)?);
    } else {
        print!("{plan}");
    }
    Ok(())
}
