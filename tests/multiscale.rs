//! Eq. 1 of seed 001 (shading `chiu`): the water's vertices are Σ_i a_i·D(x/s_i) of the
//! displacement map D at the point's object-space position, and the height query of the frame
//! (`frame::surface_query`) is that same surface, so a floating object agrees with the picture.

use glam::DVec3;
use ocean_core::frame::surface_query;
use ocean_core::fuzz::Rng;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::{Scene, SceneSource};
use ocean_cpu::frame::FrameBuffers;
use ocean_cpu::sampler::Texture2D;
use ocean_cpu::shaders::water;

fn scene(scales: &str) -> Scene {
    let text = format!(
        "[techniques]\nshading = \"chiu\"\nsurface = \"projected_grid\"\n\
         [ocean]\nwind_speed = 9.0\npatch_size_m = 64.0\nresolution = 64\nbump_resolution = 64\n\
         choppiness = 1.0\ntime_s = 7.0\n\
         [camera]\nposition = [3.0, 6.0, 5.0]\nlook_at = [0.0, 0.0, -20.0]\nwidth = 64\nheight = 36\n\
         [chiu]\nscales = {scales}\n"
    );
    Scene::from_toml(&text, SceneSource::Text).expect("scene")
}

fn render(scene: &Scene) -> FrameBuffers {
    let plan = FramePlan::new(scene, OutputKind::Hdr);
    ocean_cpu::render::render_scene_with_plan(scene, plan, &mut |_| {}).expect("render").buffers
}

/// The water stage's vertex (CPU mirror) at world (x, z): the displaced point, world.
fn vertex(fb: &FrameBuffers, eye: DVec3, x: f64, z: f64) -> DVec3 {
    let unbound = water::Unbound::default();
    // The vertex stage reads no shading: `vertex_stage`'s `hu` stands for `chiu` here.
    let b = water::Bindings::vertex_stage(&fb.uniforms, &fb.displacement, &unbound);
    let off = fb.uniforms.tiling.mesh_offset;
    // pos is relative to the mesh's reference point c = eye + mesh_offset.
    let pos = [(x - eye.x - f64::from(off[0])) as f32, (z - eye.z - f64::from(off[1])) as f32];
    let o = water::water_vertex(pos.into(), 1.0, &b);
    eye + DVec3::new(f64::from(o.rel.x), f64::from(o.rel.y), f64::from(o.rel.z))
}

/// The map's (disp_x, height, disp_z) at world (x, z), bilinear between its samples at
/// (i, j)·L/N (f64, from its texels).
fn map_at(map: &Texture2D, patch: f64, x: f64, z: f64) -> DVec3 {
    let n = f64::from(map.width);
    let (u, v) = (x / patch * n, z / patch * n);
    let (i, j) = (u.floor(), v.floor());
    let (fu, fv) = (u - i, v - j);
    let at = |di: f64, dj: f64| {
        let w = i64::from(map.width);
        let t = map
            .texel(((i + di) as i64).rem_euclid(w) as u32, ((j + dj) as i64).rem_euclid(w) as u32);
        DVec3::new(f64::from(t[0]), f64::from(t[1]), f64::from(t[2]))
    };
    let top = at(0.0, 0.0) * (1.0 - fu) + at(1.0, 0.0) * fu;
    let bottom = at(0.0, 1.0) * (1.0 - fu) + at(1.0, 1.0) * fu;
    top * (1.0 - fv) + bottom * fv
}

#[test]
fn the_vertices_are_the_direct_sum_of_the_scaled_maps() {
    let scales = [1.0, 2.618034, 0.41];
    let s = scene("[1.0, 2.618034, 0.41]");
    let fb = render(&s);
    let eye = DVec3::from_array(s.camera.position);
    let l = s.ocean.patch_size_m;
    let a = 1.0 / (scales.len() as f64).sqrt();
    let mut rng = Rng(21);
    let (mut worst, mut worst_unit_weights) = (0.0f64, 0.0f64);
    for _ in 0..5000 {
        let (x, z) = (eye.x + (rng.unit() - 0.5) * 400.0, eye.z + (rng.unit() - 0.5) * 400.0);
        let p = vertex(&fb, eye, x, z);
        let got = DVec3::new(p.x - x, p.y, p.z - z);
        let sum = |w: f64| {
            scales
                .iter()
                .fold(DVec3::ZERO, |acc, &sc| acc + map_at(&fb.displacement, l, x / sc, z / sc) * w)
        };
        worst = worst.max((got - sum(a)).abs().max_element());
        worst_unit_weights = worst_unit_weights.max((got - sum(1.0)).abs().max_element());
    }
    println!(
        "eq. 1 at 5000 random points, 3 scales: |vertex − Σ a_i·D(x/s_i)| ≤ {worst:.2e} m \
         (with a_i = 1: {worst_unit_weights:.2e} m)"
    );
    // f32 positions 200 m from the eye (~1e-5 m) through map slopes of order 1, and f32 texel
    // weights: 1e-4 m.
    assert!(worst < 1e-4, "{worst}");
    assert!(worst_unit_weights > 100.0 * 1e-4, "negative control: {worst_unit_weights}");
}

#[test]
fn the_height_query_is_the_rendered_surface() {
    // Scales 1 and 2: at world points on the grid of spacing 2L/N both scales' samples fall
    // on the map's nodes, where the map is the direct sum to the synthesis' f32 round-off.
    let s = scene("[1.0, 2.0]");
    let fb = render(&s);
    let plan = FramePlan::new(&s, OutputKind::Hdr);
    let query = surface_query(&s, &plan, s.ocean.time_s).expect("query");
    let single = ocean_core::waves::SurfaceQuery::new(
        &s.ocean.displacement_modes().expect("modes"),
        s.ocean.time_s,
        s.ocean.choppiness,
    )
    .expect("query");
    let eye = DVec3::from_array(s.camera.position);
    let step = 2.0 * s.ocean.patch_size_m / f64::from(s.ocean.resolution);
    let (mut sample_err, mut height_err, mut single_err, mut n) = (0.0f64, 0.0f64, 0.0f64, 0);
    for i in -20..20 {
        for j in -20..20 {
            let (x, z) = (f64::from(i) * step, f64::from(j) * step);
            let p = vertex(&fb, eye, x, z);
            let q = query.sample(x, z);
            let want = DVec3::new(x + q.disp_x, q.height, z + q.disp_z);
            sample_err = sample_err.max((p - want).abs().max_element());
            // The surface above the rendered point's (x, z): the query's inversion.
            height_err = height_err.max((query.height_at(p.x, p.z) - p.y).abs());
            single_err = single_err.max((single.height_at(p.x, p.z) - p.y).abs());
            n += 1;
        }
    }
    println!(
        "{n} vertices: |vertex − query sample| ≤ {sample_err:.2e} m, |height_at − rendered y| ≤ \
         {height_err:.2e} m (the single field's query: {single_err:.2e} m)"
    );
    // The maps against the f64 direct sum (docs/chiu.md: within 1e-5 of the map's range) and the f32
    // vertex: 2e-5 m on a sea of H_s ≈ 2 m.
    assert!(sample_err < 2e-5 && height_err < 2e-5, "{sample_err} {height_err}");
    assert!(single_err > 1e-2, "negative control: {single_err}");
}

#[test]
fn the_surface_does_not_swim_when_the_camera_moves() {
    // The same sea seen from two eyes 1 km apart: a world point's displaced position is the
    // same (eq. 1 samples at object-space positions; each scale's origin is reduced modulo
    // L·s_i in f64).
    let a = scene("[1.0, 2.618034]");
    let mut b = a.clone();
    b.camera.position = [1003.7, 6.0, -512.3];
    b.camera.look_at = [1000.0, 0.0, -540.0];
    let (fa, fb) = (render(&a), render(&b));
    let (ea, eb) = (DVec3::from_array(a.camera.position), DVec3::from_array(b.camera.position));
    let mut rng = Rng(4);
    let (mut worst, mut shifted) = (0.0f64, 0.0f64);
    for _ in 0..2000 {
        let (x, z) = (500.0 + (rng.unit() - 0.5) * 300.0, -250.0 + (rng.unit() - 0.5) * 300.0);
        let here = vertex(&fa, ea, x, z);
        worst = worst.max((here - vertex(&fb, eb, x, z)).abs().max_element());
        // Negative control: the surface 1.3 m away is another surface.
        shifted = shifted.max((here - vertex(&fb, eb, x + 1.3, z)).abs().max_element() - 1.3);
    }
    println!("a world point seen from two eyes 1 km apart: |Δ| ≤ {worst:.2e} m");
    assert!(shifted > 1e-2, "{shifted}");
    // f32 positions up to ~700 m from either eye: ~1e-4 m of position, times slopes of order 1.
    assert!(worst < 2e-4, "{worst}");
}
