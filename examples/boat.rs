//! A boat on a scene's sea, as CSV: the library API of floating objects
//! (`ocean_core::floating`, seed 004's boat) driven by the height query of the scene's waves.
//!
//! ```text
//! cargo run --release --example boat -- [scene.toml] [frames] > boat.csv
//! ```
//!
//! Defaults: `reference/scenes/welch_calm_day.toml` (Gerstner waves) and 600 frames (10 s at
//! 60 Hz). The boat starts at rest at its draft below the water at the origin, heading along
//! the scene's wind, with the engine at full throttle; for the first half of the run the helm
//! is centred, then turned to port. One row per frame: the time (s), the keel centre (m), the
//! pitch, roll and yaw (rad, `BoatPose`'s conventions) and the water's height above the keel
//! centre (m).
//!
//! Gerstner scenes run in a fraction of a second; under waves `fft` every height query sums
//! all of the scene's modes, so a 256² scene takes several milliseconds a frame. A scene's
//! own boats (`[[objects]] kind = "boat"`) are drawn at poses settled the same way
//! (`ocean_core::frame::ObjectPoses`).

use std::path::PathBuf;

use anyhow::Context;
use glam::DVec3;
use ocean_core::floating::{Boat, BoatControls, BoatParams, BoatPose, WaterHeight};
use ocean_core::frame::SurfaceSource;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::Scene;

/// The frame step, s: a 60 Hz display.
const FRAME_S: f64 = 1.0 / 60.0;

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let path = args.next().map(PathBuf::from).unwrap_or_else(|| {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reference/scenes/welch_calm_day.toml")
    });
    let frames: usize = match args.next() {
        Some(n) => n.parse().with_context(|| format!("frames: `{n}` is not a count"))?,
        None => 600,
    };
    let scene = Scene::load(&path).with_context(|| format!("loading {}", path.display()))?;
    let plan = FramePlan::new(&scene, OutputKind::Ldr);
    let t0 = scene.ocean.time_s;

    let params = BoatParams::default();
    // Heading along the wind (the scene's degrees, measured like the waves' directions from
    // +x towards +z, i.e. clockwise seen from above, which is minus the boat's yaw).
    let yaw = -scene.ocean.wind_direction_deg.to_radians();
    // The sea's modes made once; each frame's surface from them.
    let sea = SurfaceSource::new(&scene, &plan)?;
    let eta0 = sea.at(t0)?.water_height(0.0, 0.0);
    let keel = DVec3::new(0.0, eta0 - params.still_water_draft_m(), 0.0);
    let mut boat = Boat::new(params, &BoatPose::from_angles(keel, yaw, 0.0, 0.0), t0)?;

    println!("t_s,x_m,y_m,z_m,pitch_rad,roll_rad,yaw_rad,water_m");
    // The surface at the frame's start time drives the frame; the one at its end is reported
    // with the frame and drives the next, so each time's surface is built once.
    let mut water = sea.at(boat.time_s())?;
    for frame in 0..frames {
        let steer_rad = if frame < frames / 2 { 0.0 } else { 0.3 };
        boat.controls = BoatControls { throttle: 1.0, steer_rad };
        boat.step(&water, FRAME_S);
        water = sea.at(boat.time_s())?;
        let pose = boat.pose();
        let p = pose.position;
        let here = water.water_height(p.x, p.z);
        println!(
            "{:.4},{:.4},{:.4},{:.4},{:.5},{:.5},{:.5},{:.4}",
            boat.time_s(),
            p.x,
            p.y,
            p.z,
            pose.pitch_rad(),
            pose.roll_rad(),
            pose.yaw_rad(),
            here
        );
    }
    Ok(())
}
