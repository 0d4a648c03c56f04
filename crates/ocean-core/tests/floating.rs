//! The floating boat (`ocean_core::floating`, issue 15 item 6): Archimedes on still water,
//! rigidity, damping, determinism, riding a swell, the engine, hostile inputs and the real
//! height query of a scene.

use std::f64::consts::TAU;
use std::path::Path;

use glam::DVec3;
use ocean_core::GRAVITY;
use ocean_core::floating::{Boat, BoatControls, BoatParams, BoatPose, MAX_SUBSTEPS, WaterHeight};
use ocean_core::frame::surface_query;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::Scene;

/// The frame step every test runs at, s (a 60 Hz display).
const FRAME_S: f64 = 1.0 / 60.0;

fn boat_at(params: BoatParams, keel: DVec3) -> Boat {
    Boat::new(params, &BoatPose::from_angles(keel, 0.0, 0.0, 0.0), 0.0).expect("valid boat")
}

fn flat(_: f64, _: f64) -> f64 {
    0.0
}

/// Runs `frames` frames on the still sea y = 0 and returns the boat.
fn settle(mut boat: Boat, frames: usize) -> Boat {
    boat.simulate(frames, FRAME_S, |_| flat);
    boat
}

/// The mean depth of the four corners below y = 0, m: the keel's mean draft.
fn draft(boat: &Boat) -> f64 {
    -boat.points()[..4].iter().map(|p| p.y).sum::<f64>() / 4.0
}

fn assert_finite(boat: &Boat) {
    for p in boat.points().iter().chain(boat.velocities().iter()) {
        assert!(p.is_finite(), "non-finite state: {boat:?}");
    }
}

/// Pearson correlation and the ratio of standard deviations (b over a).
fn correlation_and_ratio(a: &[f64], b: &[f64]) -> (f64, f64) {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        sab += (x - ma) * (y - mb);
        saa += (x - ma) * (x - ma);
        sbb += (y - mb) * (y - mb);
    }
    (sab / (saa * sbb).sqrt(), (sbb / saa).sqrt())
}

/// On still water the boat settles where Σ buoyancy = weight. The model makes this exact: at a
/// fixed point of the step, momentum conservation of the projections leaves ΣF = 0, i.e.
/// ρ g (L B/4) Σ d_i = M g, so the corners' mean depth is M/(ρ L B) whatever the trim the
/// stern-heavy engine gives. What remains after 60 s is the heave oscillation, which decays as
/// exp(−ζ ω t) with ζ ω = c_v (d/H)/2 ≈ 1.95/s, i.e. by e^−117: nothing; so the tolerance is
/// round-off: 1e-9 m (positions ~0.2 m carry 1e-17 m of resolution; the constraint solves and
/// a few thousand frames of sums stay far below a nanometre).
#[test]
fn settles_at_the_archimedes_draft() {
    let params = BoatParams::default();
    let boat = settle(boat_at(params, DVec3::ZERO), 3600);
    let analytic = params.still_water_draft_m();
    let measured = draft(&boat);
    eprintln!("draft: measured {measured:.12} m, analytic {analytic:.12} m");
    assert!((measured - analytic).abs() < 1e-9, "draft {measured} vs {analytic}");
    assert!(boat.velocities().iter().all(|v| v.length() < 1e-9), "{:?}", boat.velocities());

    // Negative control: 20 % more mass is 20 % more draft, which the tolerance sees.
    let heavy = BoatParams { mass_kg: params.mass_kg * 1.2, ..params };
    let heavy_boat = settle(boat_at(heavy, DVec3::ZERO), 3600);
    let heavy_draft = draft(&heavy_boat);
    eprintln!(
        "heavy draft: measured {heavy_draft:.12} m, analytic {:.12} m",
        heavy.still_water_draft_m()
    );
    assert!((heavy_draft - heavy.still_water_draft_m()).abs() < 1e-9);
    assert!((heavy_draft - analytic).abs() > 0.03, "{heavy_draft} vs {analytic}");
}

/// A sea of three crossing swells, 1 m each, with the engine on and the helm over: the nine
/// distances stay at their rest lengths. The projection solves the constraints together and
/// every step ends with it, so the error does not accumulate: it is the round-off of a
/// Newton step on ~6 m lengths, 1e-15 relative (6e-15 measured). Bound 1e-12.
#[test]
fn constraints_hold_in_waves() {
    let sea = |t: f64| {
        move |x: f64, z: f64| {
            let swell = |amp: f64, wavelength: f64, dir: f64| {
                let k = TAU / wavelength;
                let omega = (GRAVITY * k).sqrt();
                amp * (k * (x * dir.cos() + z * dir.sin()) - omega * t).sin()
            };
            swell(1.0, 20.0, 0.0) + swell(1.0, 35.0, 1.0) + swell(1.0, 60.0, -2.0)
        }
    };
    let mut boat = boat_at(BoatParams::default(), DVec3::new(0.0, -0.2, 0.0));
    boat.controls = BoatControls { throttle: 1.0, steer_rad: 0.3 };
    let mut worst: f64 = 0.0;
    for _ in 0..60 {
        boat.simulate(100, FRAME_S, sea);
        for (rest, now) in boat.constraint_lengths() {
            worst = worst.max((now - rest).abs() / rest);
        }
    }
    eprintln!("worst relative constraint error over 100 s: {worst:e}");
    assert_finite(&boat);
    assert!(worst < 1e-12, "{worst}");
}

/// The peak of the mechanical energy over each heave period (0.89 s, 54 frames) falls from one
/// period to the next, released from a tilted pose 0.4 m above the draft, until it is within
/// 1e-6 J of its final value (round-off on ~10⁵ J of potential). Negative control: without
/// damping the energy does not decay: above 95 % is kept after 20 s (98.6 % measured; the
/// velocity projection of each step's impulse loses a little to the discrete step).
#[test]
fn damping_drains_the_energy() {
    let run = |params: BoatParams| {
        let pose = BoatPose::from_angles(DVec3::new(0.0, 0.2, 0.0), 0.3, 0.1, 0.15);
        let mut boat = Boat::new(params, &pose, 0.0).unwrap();
        let energy: Vec<f64> = (0..1200)
            .map(|_| {
                boat.step(&flat, FRAME_S);
                boat.mechanical_energy(0.0)
            })
            .collect();
        energy
    };
    let energy = run(BoatParams::default());
    let last = energy[energy.len() - 1];
    let peaks: Vec<f64> =
        energy.chunks(54).map(|w| w.iter().copied().fold(f64::MIN, f64::max)).collect();
    eprintln!(
        "energy above the final value, peak per period (J): {:?}",
        peaks.iter().map(|p| p - last).collect::<Vec<_>>()
    );
    let mut checked = 0;
    for pair in peaks.windows(2) {
        if pair[0] - last < 1e-6 {
            break;
        }
        assert!(pair[1] < pair[0], "peak energy rose: {peaks:?}");
        checked += 1;
    }
    assert!(checked >= 3, "the energy settled too soon to see a decay: {peaks:?}");
    assert!(
        energy[0] - last > 1000.0,
        "the release stored too little energy: {}",
        energy[0] - last
    );

    let undamped =
        run(BoatParams { heave_damping_per_s: 0.0, drag_per_s: 0.0, ..BoatParams::default() });
    let kept = (undamped[undamped.len() - 1] - last) / (undamped[0] - last);
    eprintln!("undamped: share of the released energy kept after 20 s: {kept}");
    assert!(kept > 0.95, "{kept}");
}

fn swell_sea(t: f64) -> impl Fn(f64, f64) -> f64 {
    move |x: f64, z: f64| {
        let k = TAU / 30.0;
        0.4 * (k * (x + 0.3 * z) - (GRAVITY * k).sqrt() * t).sin()
    }
}

/// Two runs are bit-identical, and n frames from the start equal k frames, a clone, and n − k
/// more.
#[test]
fn trajectories_are_bit_identical_and_restartable() {
    let start = || {
        let mut b = boat_at(BoatParams::default(), DVec3::new(1.0, -0.1, 2.0));
        b.controls = BoatControls { throttle: 0.7, steer_rad: -0.2 };
        b
    };
    let bits = |b: &Boat| {
        b.points()
            .iter()
            .chain(b.velocities().iter())
            .flat_map(|v| v.to_array())
            .map(f64::to_bits)
            .collect::<Vec<_>>()
    };
    let (mut a, mut b) = (start(), start());
    a.simulate(500, FRAME_S, swell_sea);
    b.simulate(500, FRAME_S, swell_sea);
    assert_eq!(bits(&a), bits(&b));

    let mut c = start();
    c.simulate(200, FRAME_S, swell_sea);
    let mut d = c.clone();
    d.simulate(300, FRAME_S, swell_sea);
    assert_eq!(bits(&a), bits(&d));
    assert_eq!(a.time_s().to_bits(), d.time_s().to_bits());
    // Not vacuous: the state after 200 frames differs from the state after 500.
    assert_ne!(bits(&c), bits(&a));
}

/// A long swell (λ = 100 m, A = 0.5 m, period 8 s) against the boat's 0.89 s heave and pitch
/// periods: the boat follows the water quasi-statically. Predicted heave ratio: the
/// oscillator's 1/|1 − r² + 2iζr| with r = 0.11, ζ ≈ 0.27 (1.01) times the corners' average
/// of the wave over the hull, cos(k L/2) (0.98): 0.99, lagging by 3.5° (+0.75° for the surface
/// taken at the frame's start), so correlation cos 4.3° = 0.997. Pitch likewise follows the
/// slope, atan(∂η/∂x), averaged over the hull (sin(kL/2)/(kL/2) = 0.994). Bounds: ratio within
/// 0.05 of 1, correlation above 0.99.
#[test]
fn rides_a_long_swell() {
    let (amp, wavelength) = (0.5, 100.0);
    let k = TAU / wavelength;
    let omega = (GRAVITY * k).sqrt();
    let eta = move |t: f64| move |x: f64, _z: f64| amp * (k * x - omega * t).sin();
    let slope = |x: f64, t: f64| amp * k * (k * x - omega * t).cos();
    let params = BoatParams::default();
    let mut boat = boat_at(params, DVec3::new(0.0, -params.still_water_draft_m(), 0.0));
    let com_start = boat.centre_of_mass().x;
    boat.simulate(960, FRAME_S, eta); // two periods settle the start
    let (mut water, mut heave, mut slope_angle, mut pitch) = (vec![], vec![], vec![], vec![]);
    for _ in 0..3840 {
        boat.simulate(1, FRAME_S, eta);
        let pose = boat.pose();
        let t = boat.time_s();
        water.push(eta(t)(pose.position.x, pose.position.z));
        heave.push(pose.position.y);
        slope_angle.push(slope(pose.position.x, t).atan());
        pitch.push(pose.pitch_rad());
    }
    let (heave_corr, heave_ratio) = correlation_and_ratio(&water, &heave);
    let (pitch_corr, pitch_ratio) = correlation_and_ratio(&slope_angle, &pitch);
    eprintln!("heave: correlation {heave_corr:.5}, amplitude ratio {heave_ratio:.5}");
    eprintln!("pitch: correlation {pitch_corr:.5}, amplitude ratio {pitch_ratio:.5}");
    assert!(heave_corr > 0.99 && (heave_ratio - 1.0).abs() < 0.05, "{heave_corr} {heave_ratio}");
    assert!(pitch_corr > 0.99 && (pitch_ratio - 1.0).abs() < 0.05, "{pitch_corr} {pitch_ratio}");
    // The swell pushes only upwards (heights only): the boat does not travel. Its centre of
    // mass moves sideways only through the drag on the corners' swing about it as the boat
    // pitches (they sit 3 cm above it), a millimetre at most: bound 5 mm.
    let drift = boat.centre_of_mass().x - com_start;
    eprintln!("centre of mass drift after 40 s of swell: {drift:e} m");
    assert!(drift.abs() < 5e-3, "{drift}");
}

/// From rest on still water, full throttle drives the boat along its own forward axis (here
/// turned 40° from world x) and lifts the bow; full astern dips it. The pitch is compared with
/// the same boat idling (the engine's weight trims it by the stern). The thrust's moment about
/// the centre of mass, T·(engine depth + CoM height) ≈ 4000 N × 0.57 m, over the pitch
/// stiffness ρ g Σ A_c x² = 1.36 MN m/rad predicts 1.7 mrad statically (2.3 mrad measured
/// half a second in, with the pitch's own overshoot); bound 0.2 mrad, the sign being the point.
#[test]
fn engine_pushes_forward_and_lifts_the_bow() {
    let params = BoatParams::default();
    let yaw = 40f64.to_radians();
    let keel = DVec3::new(0.0, -params.still_water_draft_m(), 0.0);
    let start = Boat::new(params, &BoatPose::from_angles(keel, yaw, 0.0, 0.0), 0.0).unwrap();
    let settled = settle(start, 600);
    let forward = settled.pose().forward;
    let idle_pitch = settle(settled.clone(), 60).pose().pitch_rad();

    let run = |throttle: f64, steer_rad: f64, frames: usize| {
        let mut b = settled.clone();
        b.controls = BoatControls { throttle, steer_rad };
        let poses = b.simulate(frames, FRAME_S, |_| flat);
        (b, poses)
    };
    let (ahead, poses) = run(1.0, 0.0, 600);
    let moved = ahead.pose().position - settled.pose().position;
    eprintln!(
        "10 s ahead: moved {moved:?} (forward {forward:?}), speed {:.3} m/s",
        ahead.velocities()[0].length()
    );
    assert!(moved.dot(forward) > 10.0, "{moved:?}");
    // Sideways: nothing pushes the symmetric hull off its course but the single diagonal of
    // the constraints, which makes the position projection's second-order path a little
    // lopsided; measured 1e-5 of the distance, bound 1e-4.
    let heading = DVec3::new(forward.x, 0.0, forward.z).normalize();
    let sideways = moved - heading * moved.dot(heading);
    eprintln!("sideways {:e} of the distance", sideways.length() / moved.length());
    assert!(sideways.length() < 1e-4 * moved.length(), "{sideways:?}");
    let lift = poses[30].pitch_rad() - idle_pitch;
    eprintln!("pitch 0.5 s into full ahead: {lift:e} rad above idle");
    assert!(lift > 2e-4, "{lift}");

    let (_, astern) = run(-1.0, 0.0, 60);
    let dip = astern[30].pitch_rad() - idle_pitch;
    eprintln!("pitch 0.5 s into full astern: {dip:e} rad");
    assert!(dip < -2e-4, "{dip}");

    // The helm: positive steering turns the bow to port (yaw up), negative to starboard.
    // Two seconds, so that the turn stays well short of the ±π wrap of the heading.
    let turned = |steer: f64| run(1.0, steer, 120).0.pose().yaw_rad() - yaw;
    let (port, starboard) = (turned(0.3), turned(-0.3));
    eprintln!("yaw after 2 s: steer +0.3 → {port:.4} rad, steer −0.3 → {starboard:.4} rad");
    assert!(port > 0.05 && starboard < -0.05, "{port} {starboard}");
}

/// Hostile inputs leave the state finite: steps that are zero, negative, non-finite or huge;
/// heights that are NaN, infinite, enormous or enormously wavy; a boat started a kilometre
/// down; a helm of NaN and infinity.
#[test]
fn hostile_inputs_stay_finite() {
    let params = BoatParams::default();
    let start = boat_at(params, DVec3::new(0.0, -0.2, 0.0));

    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut b = start.clone();
        assert_eq!(b.step(&flat, dt), 0.0, "dt {dt}");
        assert_eq!(b, start, "dt {dt} changed the boat");
    }

    let mut huge = start.clone();
    let simulated = huge.step(&flat, 1e9);
    eprintln!("a 1e9 s step simulated {simulated} s");
    assert!(simulated > 0.0 && simulated < 1e9 && simulated.is_finite(), "{simulated}");
    assert_eq!(huge.time_s(), 1e9);
    huge.step(&flat, f64::MAX);
    assert_eq!(huge.time_s(), f64::MAX, "the clock saturates instead of overflowing");
    assert_finite(&huge);
    assert_finite(&huge);
    // A step that fits the sub-step budget is simulated in full.
    let mut fits = start.clone();
    assert!((fits.step(&flat, simulated / 2.0) - simulated / 2.0).abs() < 1e-9 * simulated);
    assert_eq!(simulated, MAX_SUBSTEPS as f64 * params.max_substep_s());

    // No water anywhere: free fall, ½ g t² after 1 s.
    let mut falling = start.clone();
    falling.simulate(60, FRAME_S, |_| |_: f64, _: f64| f64::NAN);
    let drop = start.pose().position.y - falling.pose().position.y;
    assert_finite(&falling);
    assert!((drop - 0.5 * GRAVITY).abs() < 0.1, "fell {drop} m in 1 s");

    type Sea<'a> = &'a dyn Fn(f64, f64) -> f64;
    let seas: [(&str, Sea); 5] = [
        ("+inf", &|_, _| f64::INFINITY),
        ("-inf", &|_, _| f64::NEG_INFINITY),
        ("1e300", &|_, _| 1e300),
        ("-1e300", &|_, _| -1e300),
        ("wavy 1e6", &|x, z| 1e6 * (0.01 * x + 0.02 * z).sin()),
    ];
    for (name, sea) in seas {
        let mut b = start.clone();
        b.controls = BoatControls { throttle: f64::NAN, steer_rad: f64::INFINITY };
        for _ in 0..600 {
            b.step(sea, FRAME_S);
        }
        assert_finite(&b);
        // Rigid as in calm water (constraints_hold_in_waves): 1e-12 of the lengths.
        let worst =
            b.constraint_lengths().iter().map(|(r, l)| (l - r).abs() / r).fold(0.0, f64::max);
        assert!(worst < 1e-12, "{name}: constraint error {worst}");
    }

    // A kilometre under water: the capped buoyancy lifts it at a bounded rate,
    // a ≤ ρ g A_c H/m_c − g per corner, so after 1 s it is rising slower than that.
    let mut deep = boat_at(params, DVec3::new(0.0, -1000.0, 0.0));
    deep.simulate(60, FRAME_S, |_| flat);
    assert_finite(&deep);
    let a_max = params.water_density_kg_m3 * GRAVITY * params.length_m * params.beam_m / 4.0
        * params.hull_depth_m
        / ((params.mass_kg - params.engine_mass_kg) / 4.0)
        - GRAVITY;
    let rise = deep.velocities()[0].y;
    eprintln!("a kilometre down, after 1 s: rising at {rise:.3} m/s (bound {a_max:.3})");
    assert!(rise > 0.0 && rise <= a_max, "{rise}");

    // Parameters are checked.
    for bad in [
        BoatParams { length_m: f64::NAN, ..params },
        BoatParams { mass_kg: 0.0, ..params },
        BoatParams { engine_mass_kg: params.mass_kg, ..params },
        BoatParams { engine_depth_m: 0.0, ..params },
        BoatParams { drag_per_s: -1.0, ..params },
        BoatParams { max_steer_rad: 2.0, ..params },
    ] {
        assert!(Boat::new(bad, &start.pose(), 0.0).is_err(), "{bad:?}");
    }
    let nan_pose = BoatPose::from_angles(DVec3::new(f64::NAN, 0.0, 0.0), 0.0, 0.0, 0.0);
    assert!(Boat::new(params, &nan_pose, 0.0).is_err());
    assert!(Boat::new(params, &start.pose(), f64::INFINITY).is_err());
}

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../reference/scenes").join(name);
    Scene::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The real height query of a Gerstner scene (Welch's calm day) and of an FFT scene (`calm`),
/// 100 frames each with the engine at half throttle: the state stays finite and the keel rides
/// at its draft below the water the hull stands in — the mean height under the four corners,
/// which is what the buoyancy balances (the height under the centre alone swings ±0.35 m on
/// the calm day's 12 m waves, which a 6 m hull averages out). Both: off by less than half the
/// draft (it floats at its waterline, neither sunk nor lifted out). The calm day's
/// hull-averaged sea moves 0.19 m with periods near 2.8 s against the boat's 0.89 s heave
/// (r ≈ 0.3, ζ ≈ 0.27): a quasi-static follower, off by ~(r² + 2ζr) ≈ 25 % of that motion in
/// amplitude and phase; bound: error below half the motion's range, correlation above 0.9.
/// (`calm`'s few centimetres of short, fast ripples are near the heave resonance; a boat does
/// not follow those, and the test does not ask it to.)
#[test]
fn floats_on_the_scene_height_query() {
    for (name, frames) in [("welch_calm_day.toml", 100), ("calm.toml", 100)] {
        let scene = scene(name);
        let plan = FramePlan::new(&scene, OutputKind::Ldr);
        let params = BoatParams::default();
        let t0 = scene.ocean.time_s;
        let under_hull = |boat: &Boat, water: &dyn WaterHeight| {
            boat.points()[..4].iter().map(|p| water.water_height(p.x, p.z)).sum::<f64>() / 4.0
        };
        let placed = BoatPose::from_angles(DVec3::ZERO, 0.5, 0.0, 0.0);
        let probe = Boat::new(params, &placed, t0).unwrap();
        let start_water = under_hull(&probe, &surface_query(&scene, &plan, t0).unwrap());
        let keel = DVec3::new(0.0, start_water - params.still_water_draft_m(), 0.0);
        let mut boat = Boat::new(params, &BoatPose::from_angles(keel, 0.5, 0.0, 0.0), t0).unwrap();
        boat.controls.throttle = 0.5;
        let (mut water_line, mut keel_line) = (vec![], vec![]);
        for _ in 0..frames {
            boat.try_simulate(1, FRAME_S, |t| surface_query(&scene, &plan, t)).unwrap();
            assert_finite(&boat);
            let water = surface_query(&scene, &plan, boat.time_s()).unwrap();
            water_line.push(under_hull(&boat, &water));
            keel_line.push(boat.pose().position.y + params.still_water_draft_m());
        }
        let worst =
            water_line.iter().zip(&keel_line).map(|(w, k)| (w - k).abs()).fold(0.0, f64::max);
        let range = water_line.iter().copied().fold(f64::MIN, f64::max)
            - water_line.iter().copied().fold(f64::MAX, f64::min);
        let (corr, _) = correlation_and_ratio(&water_line, &keel_line);
        eprintln!(
            "{name}: worst |keel + draft − η under the hull| = {worst:.4} m over {frames} frames, \
             the hull's water moved {range:.4} m, correlation {corr:.4}"
        );
        assert!(worst < 0.5 * params.still_water_draft_m(), "{name}: {worst}");
        if name.starts_with("welch") {
            assert!(worst < 0.5 * range, "{name}: {worst} vs range {range}");
            assert!(corr > 0.9, "{name}: {corr}");
        }
        assert!(boat.pose().position.length() > 0.5, "{name}: the engine did not move the boat");
    }
}

/// `BoatParams::launch` (a scene's boats): the default hull gives the default launch, and a
/// hull ten times larger is the same boat in its own time — the same draft share, damping per
/// ω and engine proportions, ω smaller by √10 (Froude scaling) — so it settles alike.
#[test]
fn a_launch_is_the_default_boat_made_to_its_hull() {
    let d = BoatParams::default();
    let same = BoatParams::launch(d.length_m, d.hull_depth_m, d.beam_m, None);
    // 1e-12: the loading 3000/(ρ·15) multiplied back by ρ·15.
    for (a, b) in [
        (same.mass_kg, d.mass_kg),
        (same.engine_mass_kg, d.engine_mass_kg),
        (same.engine_depth_m, d.engine_depth_m),
        (same.heave_damping_per_s, d.heave_damping_per_s),
        (same.drag_per_s, d.drag_per_s),
        (same.max_thrust_n, d.max_thrust_n),
    ] {
        assert!((a / b - 1.0).abs() < 1e-12, "{a} against {b}");
    }
    let big = BoatParams::launch(60.0, 10.0, 25.0, None);
    big.validate().expect("a valid boat");
    let ratio = |p: &BoatParams| {
        [
            p.still_water_draft_m() / p.hull_depth_m,
            p.heave_damping_per_s / p.buoyancy_omega(),
            p.drag_per_s / p.buoyancy_omega(),
            p.engine_mass_kg / p.mass_kg,
            p.engine_depth_m / p.hull_depth_m,
        ]
    };
    for (a, b) in ratio(&big).iter().zip(ratio(&d)) {
        assert!((a / b - 1.0).abs() < 1e-12, "{a} against {b}");
    }
    let froude = d.buoyancy_omega() / big.buoyancy_omega();
    assert!((froude - 10f64.sqrt()).abs() < 1e-12, "{froude}");
    // A given mass is kept, and one above ρ L B H does not float.
    assert_eq!(BoatParams::launch(6.0, 1.0, 2.5, Some(4000.0)).mass_kg, 4000.0);
    assert!(!BoatParams::launch(6.0, 1.0, 2.5, Some(16_000.0)).floats());
}
