//! The viewer's window-free parts (issue 6): the fly camera and the panel's parameter → scene
//! mapping. The window itself is tested in `tests/view_window.rs`.

use glam::DVec3;
use ocean::view::controller::{
    BOOST, CameraController, MAX_PITCH_DEG, MAX_STEP_S, Motion, SCROLL_FACTOR, SPEED_RANGE,
};
use ocean::view::params::{Preset, ViewParams, range, sun_angles, sun_direction};
use ocean::view::{fixed_step_time, swept_wind};
use ocean_core::camera::Camera;
use ocean_core::frame::{FrameUniforms, ObjectPoses};
use ocean_core::plan::{FramePlan, OutputKind, Pass};
use ocean_core::scene::Scene;

fn reference_scenes() -> Vec<(String, Scene)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("reference/scenes");
    let mut out: Vec<(String, Scene)> = std::fs::read_dir(&dir)
        .expect("reference/scenes")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| (p.display().to_string(), Scene::load(&p).expect("reference scene loads")))
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    assert!(out.len() >= 8, "expected the 8 reference scenes, found {}", out.len());
    out
}

fn close(a: DVec3, b: DVec3, tol: f64) -> bool {
    (a - b).length() <= tol
}

fn camera_of(c: &CameraController) -> ocean_core::scene::Camera {
    let mut cam = Scene::builtin().camera;
    c.apply(&mut cam);
    cam
}

// ---- camera controller ----

#[test]
fn untouched_controller_hands_back_the_scene_camera_bit_for_bit() {
    for (name, scene) in reference_scenes() {
        let c = CameraController::new(&scene.camera);
        let mut cam = scene.camera.clone();
        cam.position = [1.0, 2.0, 3.0];
        c.apply(&mut cam);
        assert_eq!(cam, scene.camera, "{name}");
        // Its own view direction is the scene's, too.
        let d = (DVec3::from_array(scene.camera.look_at)
            - DVec3::from_array(scene.camera.position))
        .normalize();
        let pitch = d.y.asin().to_degrees();
        if pitch.abs() < MAX_PITCH_DEG {
            assert!(close(c.forward(), d, 1e-12), "{name}: {:?} vs {d:?}", c.forward());
        }
    }
}

#[test]
fn flight_keys_move_along_the_view_level_and_vertical() {
    let home = Scene::builtin().camera;
    let start = DVec3::from_array(home.position);
    let mut c = CameraController::new(&home);
    c.speed = 10.0;
    let fwd = c.forward();
    let right = c.right();
    assert!(fwd.is_normalized() && right.is_normalized());
    assert!(right.dot(fwd).abs() < 1e-12 && right.y == 0.0, "right is level and ⟂ view");

    c.set_held(Motion::Forward, true);
    c.update(0.1);
    assert!(close(c.position, start + fwd, 1e-12), "W: 1 m along the view, at {:?}", c.position);
    c.set_held(Motion::Forward, false);

    let p = c.position;
    c.set_held(Motion::Right, true);
    c.update(0.1);
    assert!(close(c.position, p + right, 1e-12));
    c.set_held(Motion::Right, false);

    let p = c.position;
    c.set_held(Motion::Up, true);
    c.update(0.1);
    assert!(close(c.position, p + DVec3::Y, 1e-12));
    c.set_held(Motion::Up, false);
    c.set_held(Motion::Down, true);
    c.update(0.2);
    assert!(close(c.position, p - DVec3::Y, 1e-12));
    c.set_held(Motion::Down, false);

    // Opposite keys cancel; released keys stop; a diagonal is no faster than straight.
    let p = c.position;
    c.set_held(Motion::Left, true);
    c.set_held(Motion::Right, true);
    c.update(0.1);
    assert_eq!(c.position, p);
    c.release_all();
    c.update(0.1);
    assert_eq!(c.position, p);
    assert!(!c.is_moving());
    c.set_held(Motion::Forward, true);
    c.set_held(Motion::Right, true);
    c.update(0.1);
    assert!(((c.position - p).length() - 1.0).abs() < 1e-12);
    c.release_all();

    // Boost.
    let p = c.position;
    c.boost = true;
    c.set_held(Motion::Back, true);
    c.update(0.1);
    assert!(close(c.position, p - fwd * BOOST, 1e-9));
}

#[test]
fn a_stalled_frame_or_bad_time_step_does_not_teleport() {
    let mut c = CameraController::new(&Scene::builtin().camera);
    c.speed = 10.0;
    c.set_held(Motion::Forward, true);
    let p = c.position;
    c.update(30.0);
    assert!(((c.position - p).length() - 10.0 * MAX_STEP_S).abs() < 1e-9);
    let p = c.position;
    for dt in [f64::NAN, f64::INFINITY, -1.0, 0.0] {
        c.update(dt);
        assert_eq!(c.position, p, "dt = {dt}");
    }
}

#[test]
fn mouse_look_turns_right_and_up_and_stops_short_of_the_poles() {
    let mut c = CameraController::new(&Scene::builtin().camera);
    c.look_at_horizon();
    let (yaw, f) = (c.yaw, c.forward());
    c.look(100.0, 0.0);
    assert!(c.yaw > yaw);
    // Turning right: the new view has a component along the old right vector.
    let old_right = DVec3::new(yaw.cos(), 0.0, yaw.sin());
    assert!(c.forward().dot(old_right) > 0.0 && c.forward().dot(f) < 1.0);
    c.look(0.0, -100.0);
    assert!(c.pitch > 0.0, "mouse up looks up");
    c.look(0.0, -1e9);
    assert!((c.pitch.to_degrees() - MAX_PITCH_DEG).abs() < 1e-9);
    c.look(0.0, 1e9);
    assert!((c.pitch.to_degrees() + MAX_PITCH_DEG).abs() < 1e-9);
    let before = (c.yaw, c.pitch);
    c.look(f64::NAN, 1.0);
    c.look(1.0, f64::INFINITY);
    assert_eq!((c.yaw, c.pitch), before, "non-finite motion is ignored");
    // Straight down is still a valid camera.
    Camera::from_scene(&camera_of(&c)).expect("valid camera at the pitch limit");
}

#[test]
fn scroll_scales_speed_within_bounds() {
    let mut c = CameraController::new(&Scene::builtin().camera);
    c.speed = 10.0;
    c.scroll(2.0);
    assert!((c.speed - 10.0 * SCROLL_FACTOR * SCROLL_FACTOR).abs() < 1e-12);
    c.scroll(-2.0);
    assert!((c.speed - 10.0).abs() < 1e-12);
    c.scroll(1e6);
    assert_eq!(c.speed, SPEED_RANGE.1);
    c.scroll(-1e6);
    assert_eq!(c.speed, SPEED_RANGE.0);
    c.scroll(f64::NAN);
    assert_eq!(c.speed, SPEED_RANGE.0);
}

#[test]
fn jumps_go_home_and_level_with_the_horizon() {
    let home = Scene::builtin().camera;
    let mut c = CameraController::new(&home);
    c.look(300.0, 200.0);
    c.set_held(Motion::Forward, true);
    c.update(0.2);
    c.release_all();
    assert_ne!(camera_of(&c).position, home.position);

    c.look_at_horizon();
    let cam = camera_of(&c);
    assert_eq!(c.pitch, 0.0);
    assert_eq!(cam.look_at[1], cam.position[1], "a level view");
    let plan = FramePlan::new(&Scene { camera: cam, ..Scene::builtin() }, OutputKind::Ldr);
    assert!(plan.runs(Pass::Sky) && plan.runs(Pass::Water));

    c.jump_home();
    assert_eq!(camera_of(&c), home, "back at the scene camera, bit for bit");
}

#[test]
fn far_away_and_under_water_give_valid_cameras() {
    let mut c = CameraController::new(&Scene::builtin().camera);
    c.position = DVec3::new(1e6, 3.0, -1e6);
    c.look(1.0, 0.0);
    let cam = camera_of(&c);
    assert_ne!(cam.position, cam.look_at, "look-at distinct from the eye a million metres out");
    Camera::from_scene(&cam).expect("valid");
    c.position = DVec3::new(0.0, -5.0, 0.0);
    c.look(0.0, -50.0);
    let scene = Scene { camera: camera_of(&c), ..Scene::builtin() };
    scene.validate().expect("under water is a valid scene");
    let plan = FramePlan::new(&scene, OutputKind::Ldr);
    assert!(!plan.runs(Pass::Sky), "under water: no sky pass");
}

// ---- parameters → scene ----

#[test]
fn untouched_parameters_leave_every_reference_scene_unchanged() {
    for (name, scene) in reference_scenes() {
        let p = ViewParams::from_scene(&scene);
        assert_eq!(p.apply(&scene).expect("applies"), scene, "{name}");
        let builtin = Scene::builtin();
        assert_eq!(ViewParams::from_scene(&builtin).apply(&builtin).expect("applies"), builtin);
    }
}

#[test]
fn each_slider_lands_in_its_scene_key() {
    let base = Scene::builtin();
    let p0 = ViewParams::from_scene(&base);
    let check = |edit: &dyn Fn(&mut ViewParams), test: &dyn Fn(&Scene) -> bool, what: &str| {
        let mut p = p0.clone();
        edit(&mut p);
        let s = p.apply(&base).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert!(test(&s), "{what}");
        assert_ne!(s, base, "{what} changed nothing");
    };
    use ocean_core::spectrum::SpectrumKind;
    check(&|p| p.spectrum = SpectrumKind::Tma, &|s| s.ocean.spectrum == SpectrumKind::Tma, "kind");
    check(&|p| p.wind_speed = 15.5, &|s| s.ocean.wind_speed == 15.5, "wind");
    check(&|p| p.wind_direction_deg = 200.0, &|s| s.ocean.wind_direction_deg == 200.0, "dir");
    check(&|p| p.fetch_km = 7.0, &|s| s.ocean.fetch_km == 7.0, "fetch");
    check(
        &|p| {
            p.deep = false;
            p.depth_m = 6.0;
        },
        &|s| s.ocean.depth_m == 6.0,
        "depth",
    );
    check(&|p| p.choppiness = 0.3, &|s| s.ocean.choppiness == 0.3, "choppiness");
    check(&|p| p.patch_size_m = 100.0, &|s| s.ocean.patch_size_m == 100.0, "patch");
    check(&|p| p.extinction_per_m = 0.5, &|s| s.water.extinction_per_m == 0.5, "extinction");
    check(&|p| p.water_color = [0.1, 0.2, 0.3], &|s| s.water.color[2] == 0.3f32 as f64, "colour");
    check(
        &|p| p.sun_elevation_deg = 45.0,
        &|s| {
            let d = DVec3::from_array(s.sun.as_ref().expect("sun").direction);
            (d.y - 45f64.to_radians().sin()).abs() < 1e-12
        },
        "sun elevation",
    );
    check(&|p| p.sun = false, &|s| s.sun.is_none(), "sun off");

    // Deep again: depth = ∞ whatever the depth slider says.
    let mut p = p0.clone();
    p.deep = true;
    p.depth_m = 3.0;
    assert!(p.apply(&base).expect("applies").ocean.depth_m.is_infinite());
}

#[test]
fn water_colour_and_extinction_reach_the_shaders() {
    let base = Scene::builtin();
    let mut p = ViewParams::from_scene(&base);
    p.water_color = [0.01, 0.05, 0.04];
    p.extinction_per_m = 0.4;
    let s = p.apply(&base).expect("applies");
    let cam = Camera::from_scene(&s.camera).expect("camera");
    let plan = FramePlan::new(&s, OutputKind::Ldr);
    let u = FrameUniforms::new(&s, &cam, &plan, [0.0, 0.0], &ObjectPoses::resting(&s));
    assert_eq!((u.water.color, u.water.extinction_per_m), ([0.01, 0.05, 0.04], 0.4));
    let u0 = FrameUniforms::new(
        &base,
        &cam,
        &FramePlan::new(&base, OutputKind::Ldr),
        [0.0; 2],
        &ObjectPoses::resting(&base),
    );
    assert_eq!(
        (u0.water.color, u0.water.extinction_per_m),
        ([0.004, 0.016, 0.028], 0.12),
        "defaults = the old constants"
    );
}

#[test]
fn sun_angles_and_direction_are_inverse() {
    assert!(close(DVec3::from_array(sun_direction(90.0, 0.0)), DVec3::Y, 1e-15));
    assert!(close(DVec3::from_array(sun_direction(0.0, 0.0)), DVec3::NEG_Z, 1e-15));
    assert!(close(DVec3::from_array(sun_direction(0.0, 90.0)), DVec3::X, 1e-15));
    for d in [[0.35, 0.22, -1.0], [0.2, 0.8, -0.5], [-0.2, 0.35, -1.0], [0.0, -0.1, 1.0]] {
        let (e, a) = sun_angles(d);
        let back = DVec3::from_array(sun_direction(e, a));
        assert!(close(back, DVec3::from_array(d).normalize(), 1e-14), "{d:?}");
    }
}

#[test]
fn sun_below_the_horizon_drops_the_shadow_map_and_a_sunless_scene_gets_one_back() {
    let base = Scene::builtin();
    let mut p = ViewParams::from_scene(&base);
    p.sun_elevation_deg = range::SUN_ELEVATION_DEG.0;
    let s = p.apply(&base).expect("applies");
    assert!(!FramePlan::new(&s, OutputKind::Ldr).runs(Pass::ShadowMap));

    let sunless = Scene { sun: None, ..Scene::builtin() };
    let mut p = ViewParams::from_scene(&sunless);
    assert!(!p.sun);
    assert_eq!(p.apply(&sunless).expect("applies"), sunless);
    p.sun = true;
    p.sun_elevation_deg = 30.0;
    let s = p.apply(&sunless).expect("applies");
    let d = DVec3::from_array(s.sun.expect("a sun").direction);
    assert!((d.y - 0.5).abs() < 1e-12);
}

#[test]
fn wind_from_zero_to_the_top_of_the_slider_is_valid_and_calm_has_no_waves_pass() {
    let base = Scene::builtin();
    let mut p = ViewParams::from_scene(&base);
    for i in 0..=20 {
        p.wind_speed = swept_wind(i, 21);
        let s = p.apply(&base).expect("every wind on the slider applies");
        let plan = FramePlan::new(&s, OutputKind::Ldr);
        assert_eq!(plan.runs(Pass::Waves), i > 0, "wind {}", p.wind_speed);
    }
    assert_eq!(swept_wind(0, 60), 0.0);
    assert_eq!(swept_wind(59, 60), range::WIND_SPEED.1, "the last frame is exactly the top");
    assert_eq!(swept_wind(0, 1), range::WIND_SPEED.1);
}

#[test]
fn every_slider_extreme_applies_together() {
    let base = Scene::builtin();
    for corner in 0..2u32.pow(8) {
        let pick = |bit: u32, (lo, hi): (f64, f64)| if corner >> bit & 1 == 0 { lo } else { hi };
        let mut p = ViewParams::from_scene(&base);
        p.wind_speed = pick(0, range::WIND_SPEED);
        p.fetch_km = pick(1, range::FETCH_KM);
        p.deep = false;
        p.depth_m = pick(2, range::DEPTH_M);
        p.choppiness = pick(3, range::CHOPPINESS);
        p.patch_size_m = pick(4, range::PATCH_SIZE_M);
        p.sun_elevation_deg = pick(5, range::SUN_ELEVATION_DEG);
        p.extinction_per_m = pick(6, range::EXTINCTION_PER_M);
        let c = pick(7, (f64::from(range::WATER_COLOR.0), f64::from(range::WATER_COLOR.1)));
        p.water_color = [c as f32; 3];
        let s = p.apply(&base).unwrap_or_else(|e| panic!("corner {corner:#b}: {e}"));
        // The physics accepts it too: the modes can be drawn.
        s.ocean.wave_spectrum().unwrap_or_else(|e| panic!("corner {corner:#b}: {e}"));
    }
}

#[test]
fn a_refused_value_names_its_key() {
    let base = Scene::builtin();
    let mut p = ViewParams::from_scene(&base);
    p.deep = false;
    p.depth_m = 0.0;
    let e = p.apply(&base).expect_err("depth 0 is refused");
    assert!(e.contains("ocean.depth_m"), "{e}");
    let mut p = ViewParams::from_scene(&base);
    p.water_color = [f32::NAN, 0.0, 0.0];
    assert!(p.apply(&base).expect_err("NaN colour").contains("water.color"));
    let mut p = ViewParams::from_scene(&base);
    p.wind_speed = f64::INFINITY;
    assert!(p.apply(&base).expect_err("infinite wind").contains("ocean.wind_speed"));
}

#[test]
fn presets_order_the_seas_by_wave_height_and_keep_the_camera() {
    let base = Scene::builtin();
    let p0 = ViewParams { time_scale: 3.0, paused: true, ..ViewParams::from_scene(&base) };
    let hs = |preset: Preset| {
        let p = p0.with_preset(preset);
        assert_eq!((p.time_scale, p.paused), (3.0, true), "{preset:?} keeps the clock");
        let s = p.apply(&base).unwrap_or_else(|e| panic!("{preset:?}: {e}"));
        assert_eq!(s.camera, base.camera);
        s.ocean.wave_spectrum().expect("spectrum").significant_wave_height()
    };
    let (lake, ocean, storm, reef) =
        (hs(Preset::CalmLake), hs(Preset::OpenOcean), hs(Preset::Storm), hs(Preset::ShallowReef));
    eprintln!("Hs: lake {lake:.3} m, reef {reef:.3} m, ocean {ocean:.3} m, storm {storm:.3} m");
    assert!(lake < reef && reef < ocean && ocean < storm);
    assert!(lake < 0.2, "a calm lake, Hs {lake} m");
    assert!(storm > 5.0, "a storm, Hs {storm} m");
    // Open ocean is the default scene's sea.
    let s = p0.with_preset(Preset::OpenOcean).apply(&base).expect("applies");
    assert_eq!(s.ocean, base.ocean);
    assert_eq!(s.water, base.water);
    // Welch's presets: the stormy sunset's Gerstner sea is higher and its sun low ahead.
    let calm = p0.with_preset(Preset::WelchCalmDay).apply(&base).expect("applies");
    let stormy = p0.with_preset(Preset::WelchStormySunset).apply(&base).expect("applies");
    assert!(stormy.gerstner.bounds().0 > 3.0 * calm.gerstner.bounds().0);
    let (e, a) = sun_angles(stormy.sun.as_ref().expect("sun").direction);
    assert!((e - 3.0).abs() < 1e-9 && a.abs() < 1e-9, "sun {e}° {a}°");
    // Shallow reef is finite-depth water, and every preset validates on every scene.
    let reef = p0.with_preset(Preset::ShallowReef);
    assert!(!reef.deep && reef.depth_m < 10.0);
    for (name, scene) in reference_scenes() {
        for preset in Preset::ALL {
            ViewParams::from_scene(&scene)
                .with_preset(preset)
                .apply(&scene)
                .unwrap_or_else(|e| panic!("{name} {preset:?}: {e}"));
        }
    }
}

#[test]
fn fixed_step_times_are_what_the_screenshot_test_renders() {
    assert_eq!(fixed_step_time(12.0, 0), 12.0);
    assert_eq!(fixed_step_time(12.0, 59), 12.0 + 59.0 * (1.0 / 60.0));
    // Printing and parsing the time (as `--time` does) gives back the same f64.
    let t = fixed_step_time(12.0, 59);
    assert_eq!(t.to_string().parse::<f64>().expect("parses"), t);
}

#[test]
fn the_coast_sliders_land_in_their_keys_and_the_water_level_lowers_the_floor() {
    let base = Scene::builtin_for(ocean_core::plan::System::Coastal);
    let p0 = ViewParams::from_scene(&base);
    let mut p = p0.clone();
    (p.coastal_amplitude_m, p.coastal_wavelength_m) = (1.7, 44.0);
    let s = p.apply(&base).expect("applies");
    assert_eq!((s.coastal.amplitude_m, s.coastal.wavelength_m), (1.7, 44.0));
    let t0 = base.terrain.as_ref().expect("the coastal scene has an island");
    for level in [-1.5, 0.5, 2.0] {
        let p = ViewParams { water_level_m: level, ..p0.clone() };
        let s = p.apply(&base).expect("every level of the slider applies");
        let t = s.terrain.as_ref().expect("terrain");
        // Every point of the floor (the island's relief too) moves down by the level.
        for (x, z) in [(0.0, 0.0), (61.0, 3.0), (-120.0, 80.0), (150.0, -150.0)] {
            let moved = t0.height(x, z) - t.height(x, z);
            assert!((moved - level).abs() < 1e-9, "level {level}: ({x}, {z}) moved {moved}");
        }
        // And the waves see it: the run-up's beach is where the floor now crosses the sea.
        assert!(ocean_core::frame::wet_top_m(&s) > 0.0);
    }
    // Negative control: level 0 is the scene itself.
    assert_eq!(p0.apply(&base).expect("applies"), base);
    // The two coastal presets give their scenes' waves and keep the camera.
    let noon = p0.with_preset(Preset::CoastalNoon).apply(&base).expect("noon");
    let sunset = p0.with_preset(Preset::CoastalSunset).apply(&base).expect("sunset");
    assert_eq!((noon.coastal.amplitude_m, noon.coastal.wavelength_m), (0.9, 30.0));
    assert_eq!((sunset.coastal.amplitude_m, sunset.coastal.wavelength_m), (1.1, 36.0));
    let (e, _) = sun_angles(sunset.sun.as_ref().expect("sun").direction);
    assert!((e - 5.0).abs() < 1e-9, "{e}");
    assert_eq!(sunset.camera, base.camera);
}
