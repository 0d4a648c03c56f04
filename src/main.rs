//! `ocean`: the command-line program. One module per subcommand; each returns an
//! `anyhow::Result` whose message a user can act on, printed without a backtrace.

mod backend;
mod bench;
mod compare;
mod frames;
mod fresnel;
mod heightfield;
mod plan;
mod render;
mod report;
mod selftest;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Ocean renderer of four published systems (Hu et al. 2004, Chiu & Chang, Welch 2019, a coastal
/// shader): a deterministic CPU oracle and a wgpu real-time path that is checked against it.
#[derive(Parser, Debug)]
#[command(name = "ocean", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render a scene to PNG (8-bit sRGB) or EXR (linear HDR).
    Render(render::Args),
    /// Print the exact Fresnel term (eq. 2) as CSV, or write the 2D Fresnel texture as EXR.
    Fresnel(fresnel::Args),
    /// Write the displacement map of a scene's ocean at a time as EXR.
    Heightfield(heightfield::Args),
    /// Print the passes a scene's frame runs, and why each is in or out.
    Plan(plan::Args),
    /// Measure each quality knob's error against its run time, what the planner saves, and
    /// the numerical-stability table (CSV, SVG plot, report.md).
    Report(report::Args),
    /// Render a scene on the CPU oracle and on the GPU and compare every pass.
    Compare(compare::Args),
    /// Fly over the ocean in a window (GPU path), changing the sea while it runs.
    View(ocean::view::Args),
    /// Hold the GPU to the envelope of any conformant GPU on every reference scene, and check
    /// that every planted bug leaves it (`--quick`: small frames, about a minute on lavapipe).
    Selftest(selftest::Args),
    /// Time every system's frame at 720p/1080p/2160p and the wave synthesis at N = 128…1024
    /// on both back ends (`--quick`: a small set for CI), as a table or JSON.
    Bench(bench::Args),
}

/// Loads a scene file, or the built-in default scene when none is given (commands without
/// `--system`).
pub(crate) fn load_scene(path: Option<&PathBuf>) -> anyhow::Result<ocean_core::scene::Scene> {
    ocean::scene_arg::load_scene(path, &ocean::scene_arg::SystemArg::default())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if let Err(e) = ocean::output::remove_temporaries_on_interrupt() {
        eprintln!("warning: {e:#}");
    }
    let result = match cli.command {
        Command::Render(a) => render::run(a),
        Command::Fresnel(a) => fresnel::run(a),
        Command::Heightfield(a) => heightfield::run(a),
        Command::Plan(a) => plan::run(a),
        Command::Report(a) => report::run(a),
        Command::Compare(a) => compare::run(a),
        Command::View(a) => ocean::view::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Selftest(a) => selftest::run(a),
    };
    // What a refused input cost (tests/hostile_files.rs holds it under 100 MB).
    if std::env::var_os("OCEAN_PRINT_PEAK_MEMORY").is_some()
        && let Some(mib) = ocean::memory_arg::peak_rss_mib()
    {
        eprintln!("peak resident memory: {mib:.1} MiB");
    }
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
