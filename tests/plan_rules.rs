//! The planner's rules (issue 5): for each rule a scene that triggers it, the plan, and proof
//! that the picture is unchanged — the CPU frame by the pruned plan is bit-identical to the
//! frame by `FramePlan::full` — with the time saved printed (measured, not asserted: these
//! machines are shared). A negative control shows that the comparison fails when a pass that
//! contributes is left out.

use std::path::PathBuf;
use std::time::Instant;

use ocean_core::plan::{FramePlan, OutputKind, Pass};
use ocean_core::scene::{Object, ObjectKind, Scene, Sun};
use ocean_cpu::render_scene_with_plan;

/// Small enough for CI, large enough that every pass shows.
const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;

fn reference(name: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("reference/scenes/{name}"));
    let mut s = Scene::load(&path).expect("reference scene");
    s.camera.width = WIDTH;
    s.camera.height = HEIGHT;
    s
}

fn sphere(center: [f64; 3]) -> Object {
    Object {
        kind: ObjectKind::Sphere,
        center,
        radius: Some(1.0),
        size: None,
        heading_deg: None,
        mass_kg: None,
        color: [0.6, 0.5, 0.4],
    }
}

/// The HDR bits and the 8-bit picture of a frame, and its wall time in ms (the fastest of
/// three runs: the least disturbed by the other work on the machine).
fn render(scene: &Scene, plan: FramePlan) -> (Vec<u32>, Vec<u8>, f64) {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..3 {
        let t0 = Instant::now();
        let r = render_scene_with_plan(scene, plan.clone(), &mut |_| {}).expect("render");
        best = best.min(t0.elapsed().as_secs_f64() * 1e3);
        last = Some(r);
    }
    let r = last.expect("three runs");
    let bits = r.buffers.hdr.color.iter().flat_map(|p| p.map(f32::to_bits)).collect();
    (bits, r.ldr.expect("LDR output"), best)
}

/// Renders `scene` by its pruned and its full plan, checks that the pruned plan leaves out
/// `expect_pruned` (the rule fired) and that both pictures are identical; prints the time
/// saved.
fn check_rule(rule: &str, scene: &Scene, expect_pruned: &[Pass]) {
    let pruned = FramePlan::new(scene, OutputKind::Ldr);
    let full = FramePlan::full(scene, OutputKind::Ldr);
    let left_out = pruned.pruned_from(&full);
    for p in expect_pruned {
        assert!(left_out.contains(p), "{rule}: {p} not pruned\n{pruned}");
    }
    let (a, la, t_pruned) = render(scene, pruned.clone());
    let (b, lb, t_full) = render(scene, full);
    let differing = a.chunks(4).zip(b.chunks(4)).filter(|(x, y)| x != y).count();
    assert_eq!(differing, 0, "{rule}: {differing} HDR pixels differ\n{pruned}");
    assert_eq!(la, lb, "{rule}: 8-bit pictures differ");
    let names: Vec<&str> = left_out.iter().map(|p| p.name()).collect();
    println!(
        "{rule:<40} pruned [{}]: {t_pruned:.0} ms vs full {t_full:.0} ms, saved {:.0} ms",
        names.join(", "),
        t_full - t_pruned
    );
}

#[test]
fn no_wind_no_waves() {
    let mut s = reference("calm.toml");
    s.ocean.wind_speed = 0.0;
    check_rule("wind 0 → no waves", &s, &[Pass::Waves]);
}

#[test]
fn no_sun_or_sun_below_no_shadow_map() {
    let mut s = reference("default.toml");
    s.sun = None;
    check_rule("no sun → no shadow map", &s, &[Pass::ShadowMap]);
    s.sun = Some(Sun { direction: [0.3, -0.2, -1.0], ..Sun::default() });
    check_rule("sun below the horizon → no shadow map", &s, &[Pass::ShadowMap]);
}

#[test]
fn nothing_above_no_reflection_map_nothing_below_no_refraction_map() {
    let s = reference("underwater_object.toml");
    check_rule("nothing above → no reflection/shadow map", &s, &[Pass::ReflectionMap]);
    let mut s = reference("default.toml");
    s.objects = vec![sphere([6.0, 3.0, -22.0])];
    check_rule("nothing below → no refraction map", &s, &[Pass::RefractionMap]);
    let s = reference("calm.toml");
    check_rule("no objects → no object passes", &s, &[Pass::Objects, Pass::ReflectionMap]);
}

#[test]
fn single_frame_no_cyclic_precompute() {
    // A looping sea at t = 0, frame 0 of the cycle: the cycle's picture equals the direct one.
    let mut s = reference("shallow_reef.toml");
    s.ocean.resolution = 64;
    s.ocean.bump_resolution = 64;
    s.ocean.loop_period_s = 8.0;
    s.ocean.time_s = 0.0;
    check_rule("single frame → no cyclic precompute", &s, &[Pass::Cycle]);
    assert!(FramePlan::for_frames(&s, OutputKind::Ldr, 2).runs(Pass::Cycle));
}

#[test]
fn far_patch_outside_the_frustum_not_built() {
    let s = reference("looking_down.toml");
    check_rule("far patch outside the view → not built", &s, &[Pass::FarPatch]);
    let plan = FramePlan::new(&s, OutputKind::Ldr);
    let camera = ocean_core::camera::Camera::from_scene(&s.camera).unwrap();
    let near_only = plan.water_mesh(&s, &camera).unwrap();
    let full = FramePlan::full(&s, OutputKind::Ldr).water_mesh(&s, &camera).unwrap();
    println!(
        "  water mesh: {} triangles instead of {}",
        near_only.indices.len(),
        full.indices.len()
    );
    assert_eq!(near_only.indices[..], full.indices[..near_only.indices.len()]);
    assert!(near_only.indices.len() < full.indices.len());
}

#[test]
fn objects_and_mirror_images_outside_the_frustum_culled_per_pass() {
    // Camera at (0, 6, 30) looking along −z: #2 behind it (culled from every pass), #3 far
    // above the view (culled from the main view; its mirror image is in view), #4 behind and
    // under the water (culled from the refraction map).
    let mut s = reference("default.toml");
    s.objects.push(sphere([0.0, 3.0, 80.0]));
    s.objects.push(sphere([0.0, 208.0, -370.0]));
    s.objects.push(sphere([2.0, -3.0, 90.0]));
    let plan = FramePlan::new(&s, OutputKind::Ldr);
    assert_eq!(plan.objects().objects, [0, 1], "{plan}");
    assert_eq!(plan.objects().reflection_map, [0, 1, 3], "{plan}");
    assert_eq!(plan.objects().refraction_map, [0, 1], "{plan}");
    println!("{plan}");
    check_rule("objects outside the view → culled per pass", &s, &[]);
    // Every object above the water behind the camera: no reflection map, no objects pass.
    let mut s = reference("calm.toml");
    s.objects = vec![sphere([0.0, 3.0, 80.0])];
    check_rule("all mirror images outside → no reflection map", &s, &[Pass::ReflectionMap]);
}

#[test]
fn the_comparison_fails_when_a_contributing_pass_is_left_out() {
    // Negative control: the default scene's reflection map shows the buoy; dropping it by hand
    // changes pixels, and culling an object in view does too.
    let s = reference("default.toml");
    let full = FramePlan::full(&s, OutputKind::Ldr);
    let mut broken = full.clone();
    let i = broken.passes.iter().position(|p| p.name == Pass::ReflectionMap).unwrap();
    broken.skipped.push(broken.passes.remove(i));
    let (a, ..) = render(&s, full.clone());
    let (b, ..) = render(&s, broken);
    assert_ne!(a, b, "dropping the reflection map must change the picture");
    let mut culled = full.clone();
    let objects_pass = culled.passes.iter_mut().find(|p| p.name == Pass::Objects).unwrap();
    objects_pass.objects = vec![1];
    let (c, ..) = render(&s, culled);
    assert_ne!(a, c, "culling the buoy must change the picture");
}
