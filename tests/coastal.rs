//! Waves technique `coastal` (issue 15, seed 004): the per-vertex waves (the CPU mirror of
//! `shared/coastal.wgsl`, whose arithmetic the GPU's matches: the cross-check scene
//! `reference/scenes/coastal_waves.toml`) against the seed's closed form over a flat floor;
//! crests running to the shore at the phase speed of the depth under them; water over the
//! sand only as the run-out's film, up to Hunt's run-up; a continuous waterline; shore foam
//! where the rules say, growing with steepness; wet sand; the f64 height query agreeing with
//! what the vertices draw.

use std::f64::consts::TAU;

use ocean_core::camera::Camera;
use ocean_core::frame::{FrameUniforms, coastal_sea};
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::{Scene, SceneSource};
use ocean_cpu::sampler::Texture2D;
use ocean_cpu::shaders::shared::coastal::{COASTAL_FILM_M, coastal_shore, coastal_wave};
use ocean_cpu::shaders::shared::floor::floor_height;
use ocean_cpu::shaders::wgsl::vec2;

const G: f64 = 9.81;

/// An island scene (reference/scenes/island.toml's floor) with waves `coastal`, `extra`
/// appended to `[coastal]`.
fn scene(coastal: &str, terrain: bool, time_s: f64) -> Scene {
    let floor = if terrain {
        "[terrain]\nkind = \"island\"\ndepth_m = 10.0\ncenter = [0.0, 0.0]\nextent_m = 420.0\n\
         island_radius_m = 60.0\nisland_height_m = 12.0\nshore_slope = 0.08\n"
    } else {
        ""
    };
    // Times beyond ±2⁵⁵ s need a loop period (for the FFT's tick count; the coastal waves
    // do not loop).
    let looped = if time_s.abs() > 1e15 { "loop_period_s = 1000.0\n" } else { "" };
    let text = format!(
        "system = \"chiu\"\n[techniques]\nwaves = \"coastal\"\nsky = \"preetham\"\n\
         [ocean]\ntime_s = {time_s:?}\n{looped}\
         [camera]\nposition = [20.0, 5.0, 110.0]\nlook_at = [0.0, 2.0, 0.0]\nwidth = 64\nheight = 36\n\
         {floor}[coastal]\n{coastal}\n"
    );
    Scene::from_toml(&text, SceneSource::Text).expect("scene")
}

/// The frame's uniforms for a mesh whose reference point is world `origin`, and its floor map.
fn frame(scene: &Scene, origin: [f64; 2]) -> (FrameUniforms, Texture2D) {
    let plan = FramePlan::new(scene, OutputKind::Hdr);
    let camera = Camera::from_scene(&scene.camera).expect("camera");
    let poses = ocean_core::frame::ObjectPoses::resting(scene);
    let u = FrameUniforms::new(scene, &camera, &plan, origin, &poses);
    let (w, h, texels) = ocean_core::terrain::relief_texels(scene.terrain.as_ref());
    (u, Texture2D::new(w, h, texels))
}

/// The mirror's (height, slope x, slope z, phase) at world (x, z).
fn wave(u: &FrameUniforms, floor: &Texture2D, origin: [f64; 2], x: f64, z: f64) -> [f64; 4] {
    let pos = vec2((x - origin[0]) as f32, (z - origin[1]) as f32);
    let w = coastal_wave(pos, vec2(0.0, 0.0), vec2(0.0, 0.0), vec2(0.0, 0.0), u, floor);
    [w.x, w.y, w.z, w.w].map(f64::from)
}

/// The floor's height under world (x, z) as the shaders see it (floor_height takes
/// camera-relative coordinates).
fn ground(s: &Scene, u: &FrameUniforms, floor: &Texture2D, x: f64, z: f64) -> f64 {
    let eye = s.camera.position;
    f64::from(floor_height((x - eye[0]) as f32, (z - eye[2]) as f32, u, floor))
}

/// k solving ω² = g k tanh(k h), by bisection (independent of ocean-core's Newton).
fn wavenumber(omega: f64, h: f64) -> f64 {
    let (mut lo, mut hi) = (1e-9, 1e3);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if G * mid * (mid * h).tanh() < omega * omega { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

/// A deterministic stream of uniforms in [0, 1).
fn uniforms(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The seed's profile: clamp(s^p·A·m − A(m − 1), 0, A), m = 2 where s·cos φ < 0.
fn seed_height(phase_turns: f64, a: f64) -> f64 {
    let (s, c) = (TAU * phase_turns).sin_cos();
    let m = if s * c < 0.0 { 2.0 } else { 1.0 };
    (s.powi(7) * a * m - a * (m - 1.0)).clamp(0.0, a)
}

/// The largest difference between the mirror's radial wave over the open sea's flat floor
/// (chiu's 20 m) and the seed's closed form with φ = −k r − ω t + `phase_shift` and the
/// amplitude shoaled to 20 m (K_s = 0.9991 for λ₀ = 28 m), at 4000 random points within 600 m
/// of the centre.
fn closed_form_error(phase_shift: f64) -> f64 {
    let (a, lambda, t) = (1.2, 28.0, 7.3);
    let s = scene(
        &format!(
            "center = [37.0, -12.0]\namplitude_m = {a}\nwavelength_m = {lambda}\ncorrections = []"
        ),
        false,
        t,
    );
    let origin = [-150.0, 80.0];
    let (u, floor) = frame(&s, origin);
    let omega = (G * TAU / lambda).sqrt();
    let k = wavenumber(omega, 20.0);
    // Linear theory's shoaling over 20 m: K_s = √(c_g,deep / c_g), c_g = ½ (ω/k)(1 + 2kh/sinh 2kh).
    let cg = 0.5 * omega / k * (1.0 + 2.0 * k * 20.0 / (2.0 * k * 20.0).sinh());
    let a = a * (0.5 * G / omega / cg).sqrt();
    let mut r = uniforms(7);
    let mut worst: f64 = 0.0;
    for _ in 0..4000 {
        let (rad, ang) = (600.0 * r(), TAU * r());
        let (x, z) = (37.0 + rad * ang.cos(), -12.0 + rad * ang.sin());
        let dist = (x - 37.0).hypot(z + 12.0);
        let phase = (-(k * dist) - omega * t) / TAU + phase_shift;
        let expected = seed_height(phase, a);
        worst = worst.max((wave(&u, &floor, origin, x, z)[0] - expected).abs());
    }
    worst
}

#[test]
fn the_radial_wave_is_the_seeds_closed_form_over_a_flat_floor() {
    // The mirror forms the phase in f32 (Φ up to 21 turns at 600 m: ulp 2e-6 turns) and the
    // profile's steepest part changes by 2·7·2π·A ≈ 106 m per turn at A = 1.2 m, so f32
    // round-off alone allows about 2e-4 m; the segments' quadratic is exact for Φ = k r.
    let err = closed_form_error(0.0);
    assert!(err < 1e-3, "mirror vs closed form: {err} m");
    // Negative control: the same waves 1/50 of a period later are told apart.
    let shifted = closed_form_error(0.02);
    assert!(shifted > 0.1, "a 0.02-turn phase error must show: {shifted} m");
}

/// The crest nearest `r0` along +x from the island's centre, at time `t`: the radius of the
/// highest sample within ±λ/2, sampled every 1 mm.
fn crest(u: &FrameUniforms, floor: &Texture2D, r0: f64, half_width: f64) -> f64 {
    let n = (2.0 * half_width / 0.001) as usize;
    (0..=n)
        .map(|i| r0 - half_width + i as f64 * 0.001)
        .map(|r| (r, wave(u, floor, [0.0, 0.0], r, 0.0)[0]))
        .fold((r0, f64::MIN), |best, (r, h)| if h > best.1 { (r, h) } else { best })
        .0
}

#[test]
fn crests_run_to_the_shore_at_the_phase_speed_of_the_depth_under_them() {
    let lambda = 28.0;
    let omega = (G * TAU / lambda).sqrt();
    let dt = 0.1;
    let deep_speed = omega / (TAU / lambda);
    // Crests near the open floor (10 m), about 5 m and about 2 m of water.
    for r0 in [230.0, 125.0, 87.0] {
        let s0 = scene("corrections = []", true, 20.0);
        let (u0, floor) = frame(&s0, [0.0, 0.0]);
        let k = wavenumber(omega, -ground(&s0, &u0, &floor, r0, 0.0));
        // The crest nearest r0 at t, and the same crest dt later (it moved about c·dt in).
        let c0 = crest(&u0, &floor, r0, 0.5 * TAU / k);
        let (u1, _) = frame(&scene("corrections = []", true, 20.0 + dt), [0.0, 0.0]);
        let c1 = crest(&u1, &floor, c0 - omega / k * dt, 1.0);
        // The phase speed ω/k of the depth under the crest, halfway.
        let depth = -ground(&s0, &u0, &floor, 0.5 * (c0 + c1), 0.0);
        let speed = omega / wavenumber(omega, depth);
        let measured = (c0 - c1) / dt;
        assert!(
            (measured / speed - 1.0).abs() < 0.02,
            "crest at {c0:.2} m, depth {depth:.2} m: speed {measured:.3} m/s, phase speed {speed:.3}"
        );
        // Negative control: in shallow water the deep-water speed is told apart.
        if depth < 6.0 {
            assert!(
                (measured / deep_speed - 1.0).abs() > 0.1,
                "depth {depth:.2} m: {measured:.3} m/s is not slower than deep water's {deep_speed:.3}"
            );
        }
    }
}

#[test]
fn water_stands_over_sand_only_as_the_run_outs_film_and_waves_break_by_the_depth() {
    // Steep, high waves with the corrections on, over many times.
    let film = f64::from(COASTAL_FILM_M);
    let (mut checked_dry, mut filmed) = (0, 0);
    let mut highest_ratio: f64 = 0.0;
    let mut highest_film: f64 = 0.0;
    let mut run_up = 0.0;
    for t in [0.0, 1.7, 3.1, 9.9, 41.0, 44.2, 47.0] {
        let s = scene("amplitude_m = 2.5", true, t);
        let (u, floor) = frame(&s, [0.0, 0.0]);
        run_up = coastal_sea(&s, t).expect("sea").run_up_m;
        for i in 0..=240 {
            for j in 0..=8 {
                let r = i as f64 * 0.5 + 20.0;
                let ang = TAU * j as f64 / 9.0 + 0.3;
                let (x, z) = (r * ang.cos(), r * ang.sin());
                let ground = ground(&s, &u, &floor, x, z);
                let h = wave(&u, &floor, [0.0, 0.0], x, z)[0];
                assert!(h.is_finite());
                if ground >= run_up {
                    checked_dry += 1;
                    assert!(h < ground, "water {h} m high over dry sand at ({x}, {z}), {ground} m");
                } else if ground >= 0.0 {
                    // The run-out zone: at most the film over the sand.
                    assert!(h <= ground + film + 1e-5, "{h} m over sand at {ground} m");
                    if h > ground {
                        filmed += 1;
                        highest_film = highest_film.max(ground);
                    }
                } else {
                    // Radial wave ≤ γ h, corrections ≤ their amplitudes (0.13 m together),
                    // or the film.
                    let bound = (0.78 * -ground + 0.13).max(ground + film) + 1e-5;
                    assert!(h <= bound, "{h} m over {} m of water", -ground);
                    // (Deeper than the film can reach.)
                    if -ground > 0.05 && -ground < 2.0 {
                        highest_ratio = highest_ratio.max(h / -ground);
                    }
                }
            }
        }
    }
    assert!(checked_dry > 1000, "the sweep must cross the beach: {checked_dry} dry points");
    // Hunt's run-up for the island's 1:12.5 beach: R = ξ A, ξ = 0.08/√(A/L₀).
    let hunt = 0.08 / (2.5_f64 / 28.0).sqrt() * 2.5;
    // (The relief's 0.41 m bilinear texels, averaged round 64 azimuths, give the foreshore a
    // slope of 0.0803 where the profile's is 0.08: 0.3 %.)
    assert!((run_up - hunt).abs() < 5e-3 * hunt, "run-up {run_up} m, Hunt {hunt} m");
    // Negative controls: the waves do reach the breaker limit in the shallows (a cap that
    // flattened everything would pass the bound above trivially), and the swash does run
    // up the sand, most of the way to R at some time.
    assert!(highest_ratio > 0.6, "highest wave over depth in the shallows: {highest_ratio}");
    assert!(filmed > 20, "the swash must cover some sand: {filmed} points");
    assert!(highest_film > 0.6 * run_up, "the swash reached {highest_film} m of {run_up} m");
}

/// The largest step between neighbouring samples of `h` along a line, m.
fn largest_step(h: &[f64]) -> f64 {
    h.windows(2).map(|w| (w[1] - w[0]).abs()).fold(0.0, f64::max)
}

#[test]
fn the_waterline_is_continuous_and_the_sea_meets_the_sand() {
    let film = f64::from(COASTAL_FILM_M);
    for t in [0.0, 2.3, 5.9, 13.4] {
        let s = scene("", true, t);
        let (u, floor) = frame(&s, [0.0, 0.0]);
        for j in 0..7 {
            let ang = TAU * j as f64 / 7.0 + 0.1;
            // 1 cm steps over 8 m across the waterline (r = 60 m).
            let line: Vec<(f64, f64)> = (0..=800)
                .map(|i| {
                    let r = 56.0 + i as f64 * 0.01;
                    (r * ang.cos(), r * ang.sin())
                })
                .collect();
            let h: Vec<f64> =
                line.iter().map(|&(x, z)| wave(&u, &floor, [0.0; 2], x, z)[0]).collect();
            let g: Vec<f64> = line.iter().map(|&(x, z)| ground(&s, &u, &floor, x, z)).collect();
            // The surface's steepest slope here is the breaking front's, under 1 (45°):
            // no step of a 1 cm sample apart above 1 cm.
            let step = largest_step(&h);
            assert!(step < 0.01, "t {t} angle {ang}: a {step} m step in the surface");
            // Where the sand comes out of the water the sea lies on it, within the film.
            let k = g.windows(2).position(|w| w[0] >= 0.0 && w[1] < 0.0).expect("a waterline");
            assert!(
                h[k] >= g[k] - 1e-6 && h[k] <= g[k] + film + 1e-5,
                "t {t}: the sea at {} m over sand at {} m",
                h[k],
                g[k]
            );
        }
    }
    // Negative control: the step finder sees a 2 cm crack.
    let mut cracked: Vec<f64> = (0..100).map(|i| i as f64 * 1e-3).collect();
    cracked[50] += 0.02;
    assert!(largest_step(&cracked) > 0.01);
}

/// Mean shore foam turbulence (the f64 reference) over the ring 40–170 m from the island's
/// centre, at waves of amplitude `a`, over several times.
fn mean_shore_foam(a: f64) -> f64 {
    let s = scene(&format!("amplitude_m = {a}"), true, 0.0);
    let sea = coastal_sea(&s, 0.0).expect("sea");
    let mut sum = 0.0;
    let mut n = 0;
    for t in [0.0, 1.1, 2.6, 3.3] {
        let sea = sea.at_time(t);
        for i in 0..260 {
            for j in 0..24 {
                let (r, ang) = (40.0 + i as f64 * 0.5, TAU * j as f64 / 24.0);
                sum += sea.shore_foam(r * ang.cos(), r * ang.sin());
                n += 1;
            }
        }
    }
    sum / f64::from(n)
}

#[test]
fn shore_foam_lies_where_the_rules_say_and_grows_with_steepness() {
    let s = scene("amplitude_m = 1.2", true, 6.1);
    let origin = [12.0, -7.0];
    let (u, floor) = frame(&s, origin);
    let sea = coastal_sea(&s, 6.1).expect("sea");
    let level_max = sea.run_up_m;
    let mut r = uniforms(11);
    let (mut offshore, mut surf, mut high, mut diff, mut n) = (0, 0, 0, 0.0, 0);
    for _ in 0..6000 {
        let (rad, ang) = (30.0 + 150.0 * r(), TAU * r());
        let (x, z) = (rad * ang.cos(), rad * ang.sin());
        let pos = vec2((x - origin[0]) as f32, (z - origin[1]) as f32);
        let mirror = f64::from(coastal_shore(pos, vec2(0.0, 0.0), vec2(0.0, 0.0), &u, &floor).y);
        let reference = sea.shore_foam(x, z);
        assert!((0.0..=1.0).contains(&mirror) && (0.0..=1.0).contains(&reference));
        diff += (mirror - reference).abs();
        n += 1;
        let depth = sea.depth(x, z);
        let shoaled = sea.profile(rad)[3] * 1.2;
        if depth > 0.05 && shoaled <= 0.78 * depth {
            // Seaward of the breaking line: no shore foam.
            offshore += 1;
            assert_eq!(mirror, 0.0, "foam {mirror} offshore at ({x}, {z}), {depth} m deep");
            assert_eq!(reference, 0.0);
        } else if depth < -level_max {
            // Above the highest run-up: dry sand, no foam.
            high += 1;
            assert_eq!(mirror, 0.0, "foam {mirror} on dry sand at ({x}, {z})");
        } else if depth > 0.05 {
            surf += 1;
            assert!(reference > 0.0, "no foam in the surf zone at ({x}, {z}), {depth} m");
        }
    }
    assert!(offshore > 1000 && surf > 50 && high > 500, "{offshore} {surf} {high}");
    // The f32 mirror and the f64 reference agree on average (they part only where the
    // phase's segments and nodes differ, in the last centimetres of the shallows).
    let mean = diff / f64::from(n);
    assert!(mean < 0.01, "mirror vs reference: mean |Δ| {mean}");
    // Steeper waves (higher, same wavelength) break further out and harder.
    let coverage: Vec<f64> = [0.3, 0.6, 1.2, 2.4].iter().map(|&a| mean_shore_foam(a)).collect();
    assert!(coverage.windows(2).all(|w| w[1] > 1.2 * w[0]), "coverage by amplitude: {coverage:?}");
    assert!(coverage[0] > 0.0, "even low waves foam at the waterline: {coverage:?}");
}

#[test]
fn sand_below_the_run_up_is_wet() {
    use ocean_core::terrain::wet_sand_color;
    let sand = [0.76, 0.70, 0.50];
    let k = ocean_core::waves::coastal::WET_SAND_DARKENING;
    assert_eq!(wet_sand_color(sand, -3.0, 0.5), sand.map(|c| c * k));
    assert_eq!(wet_sand_color(sand, 0.3, 0.5), sand.map(|c| c * k));
    assert_eq!(wet_sand_color(sand, 0.5, 0.5), sand);
    assert_eq!(wet_sand_color(sand, 2.0, 0.5), sand);
    let mid = wet_sand_color(sand, 0.4375, 0.5);
    assert!((mid[0] - 0.76 * (1.0 + k) / 2.0).abs() < 1e-12, "{mid:?}");
    // No band without a run-up (other waves, or no beach).
    assert_eq!(wet_sand_color(sand, -3.0, 0.0), sand);
    // The drawn island: its vertices below R are darker than those above.
    let s = scene("", true, 0.0);
    let r = ocean_core::frame::wet_top_m(&s);
    assert!(r > 0.1, "run-up {r} m");
    let t = s.terrain.as_ref().expect("terrain");
    let tris = ocean_core::terrain::terrain_triangles(t, glam::DVec3::ZERO, r);
    let red = t.color[0];
    let (mut wet, mut dry) = (0, 0);
    for v in tris.iter().flatten() {
        let y = f64::from(v.position[1]);
        let c = f64::from(v.color[0]);
        if y < 0.7 * r {
            wet += 1;
            assert!((c - red * k).abs() < 1e-6, "{c} at {y} m");
        } else if y > 1.01 * r {
            dry += 1;
            assert!((c - red).abs() < 1e-6, "{c} at {y} m");
        }
    }
    assert!(wet > 100 && dry > 100, "{wet} {dry}");
    // Negative control: another waves technique leaves the sand dry.
    let hu =
        Scene::from_toml("[terrain]\nkind = \"island\"\nextent_m = 420.0\n", SceneSource::Text)
            .expect("scene");
    assert_eq!(ocean_core::frame::wet_top_m(&hu), 0.0);
}

#[test]
fn the_height_query_agrees_with_the_drawn_surface() {
    let s = scene("", true, 12.5);
    let origin = [30.0, -40.0];
    let (u, floor) = frame(&s, origin);
    let sea = coastal_sea(&s, 12.5).expect("sea");
    let mut r = uniforms(3);
    // (worst over water deeper than 1 m, worst in the shallows)
    let mut worst = [0.0_f64; 2];
    for _ in 0..3000 {
        let (x, z) = (400.0 * r() - 200.0, 400.0 * r() - 200.0);
        let drawn = wave(&u, &floor, origin, x, z)[0];
        let e = (sea.height_at(x, z) - drawn).abs();
        let shallow = usize::from(sea.depth(x, z) < 1.0);
        worst[shallow] = worst[shallow].max(e);
    }
    // The query's f64 nodes (every 15 cm) vs the vertices' f32 quadratic segments (4.7 m):
    // within 1 cm of a 0.8 m sea where the water is deeper than 1 m; in the shallows Φ
    // bends as 1/√h towards the waterline, which a segment's quadratic follows to about
    // 0.01 turn, under a wave capped at γ·h < 0.78 m (measured 3.2 cm).
    assert!(worst[0] < 0.01, "height query vs drawn surface, deeper than 1 m: {} m", worst[0]);
    assert!(worst[1] < 0.05, "height query vs drawn surface, shallower: {} m", worst[1]);
    // The surface's slopes are its height's: a central difference of the query, over the
    // flat floor beyond the shore (where K_s and the depth weights are constant: their own
    // gradients are left out of the slopes).
    for (x, z) in [(-150.0, 150.0), (180.0, -120.0), (0.0, 205.0)] {
        let [_, sx, sz] = sea.sample(x, z);
        let e = 1e-4;
        let dx = (sea.height_at(x + e, z) - sea.height_at(x - e, z)) / (2.0 * e);
        let dz = (sea.height_at(x, z + e) - sea.height_at(x, z - e)) / (2.0 * e);
        assert!(
            (sx - dx).abs() < 1e-3 && (sz - dz).abs() < 1e-3,
            "({x}, {z}): {sx} {sz} vs {dx} {dz}"
        );
    }
}

#[test]
fn extreme_times_and_amplitudes_stay_finite() {
    for (t, extra) in [
        (1.0e9, ""),
        (-f64::MAX, ""),
        (f64::MAX, ""),
        (0.0, "amplitude_m = 0.0"),
        (3.0, "amplitude_m = 100.0"),
    ] {
        let s = scene(extra, true, t);
        let (u, floor) = frame(&s, [0.0, 0.0]);
        let sea = coastal_sea(&s, t).expect("sea");
        for (x, z) in [(0.0, 0.0), (61.0, 0.0), (150.0, -3.0), (5000.0, 9000.0)] {
            let w = wave(&u, &floor, [0.0, 0.0], x, z);
            assert!(w.iter().all(|v| v.is_finite()), "t {t} {extra}: {w:?} at ({x}, {z})");
            assert!(sea.sample(x, z).iter().all(|v| v.is_finite()));
        }
    }
}

#[test]
fn a_sea_moved_to_another_time_is_the_sea_made_at_that_time() {
    // What a floating object's settle run uses (the profile built once, the phases moved).
    let s = scene("", true, 3.0);
    let moved = coastal_sea(&s, 3.0).expect("sea").at_time(17.25);
    let made = coastal_sea(&s, 17.25).expect("sea");
    for (x, z) in [(100.0, 20.0), (-70.0, 40.0), (0.0, -150.0)] {
        assert_eq!(moved.sample(x, z), made.sample(x, z), "({x}, {z})");
    }
    // Negative control: the time does move the sea.
    assert_ne!(moved.sample(100.0, 20.0), coastal_sea(&s, 3.0).expect("sea").sample(100.0, 20.0));
}

#[test]
fn the_profile_moments_match_closed_forms_and_an_independent_integral() {
    use ocean_core::waves::coastal::profile_moments;
    // p = 1 without steepening: f = max(sin φ, 0), mean 1/π, var ¼ − 1/π², mean f′² = ¼.
    let (mean, rms) = profile_moments(1, 1.0);
    let pi = std::f64::consts::PI;
    assert!((mean - 1.0 / pi).abs() < 1e-6, "{mean}");
    let expected = (0.25 / (0.25 - 1.0 / (pi * pi))).sqrt();
    assert!((rms - expected).abs() < 1e-3, "{rms} vs {expected}");
    // The seed's profile (p = 7, front ×2), by the midpoint rule on another grid.
    let n = 100_003;
    let f = |x: f64| {
        let (s, c) = x.sin_cos();
        let m = if s * c < 0.0 { 2.0 } else { 1.0 };
        (s.powi(7) * m - (m - 1.0)).clamp(0.0, 1.0)
    };
    let h = TAU / n as f64;
    let xs: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) * h).collect();
    let m1 = xs.iter().map(|&x| f(x)).sum::<f64>() / n as f64;
    let var = xs.iter().map(|&x| (f(x) - m1).powi(2)).sum::<f64>() / n as f64;
    let d2 =
        xs.iter().map(|&x| ((f(x + 1e-6) - f(x - 1e-6)) / 2e-6).powi(2)).sum::<f64>() / n as f64;
    let (mean, rms) = profile_moments(7, 2.0);
    assert!((mean - m1).abs() < 1e-5, "{mean} vs {m1}");
    assert!((rms - (d2 / var).sqrt()).abs() < 1e-2 * rms, "{rms} vs {}", (d2 / var).sqrt());
    // The narrow crest's harmonics: its RMS wavenumber is several times the fundamental's.
    assert!(rms > 2.5, "{rms}");
}

#[test]
fn vertices_too_far_apart_for_a_wave_fade_it_to_its_mean() {
    let s = scene("corrections = []", false, 5.0);
    let origin = [0.0, 0.0];
    let (u, floor) = frame(&s, origin);
    let mean = f64::from(u.coastal.swash[2]);
    let rms = f64::from(u.coastal.swash[3]);
    let amp = f64::from(u.coastal.shape[1]) * 0.9991; // K_s over chiu's 20 m
    let lambda = 28.0 * 0.999; // about λ₀ over 20 m of water
    let at = |x: f64, spacing: f64| {
        let pos = vec2(x as f32, 0.0);
        let w = coastal_wave(
            pos,
            vec2(1.0, 0.0),
            vec2(0.0, 0.0),
            vec2(spacing as f32, 0.0),
            &u,
            &floor,
        );
        f64::from(w.x)
    };
    let (mut spread_near, mut spread_far) = (0.0_f64, 0.0_f64);
    for i in 0..400 {
        let x = 300.0 + i as f64 * 0.07;
        // Unfaded: spacing 0 is bit for bit the unfiltered wave.
        let w0 = coastal_wave(
            vec2(x as f32, 0.0),
            vec2(0.0, 0.0),
            vec2(0.0, 0.0),
            vec2(0.0, 0.0),
            &u,
            &floor,
        );
        assert_eq!(at(x, 0.0), f64::from(w0.x));
        // Held (16 vertices per crest wavelength λ/rms): unchanged.
        assert_eq!(at(x, lambda / rms / 16.0), at(x, 0.0));
        spread_near = spread_near.max((at(x, 0.0) - mean * amp).abs());
        // Four vertices per λ/rms or fewer: the mean, exactly as the formula gives it.
        let far = at(x, lambda / rms / 3.5);
        spread_far = spread_far.max((far - mean * amp).abs());
    }
    assert!(spread_far < 1e-5, "a wave the vertices cannot hold must be flat: {spread_far}");
    // Negative control: the unfaded wave does swing about its mean.
    assert!(spread_near > 0.5 * amp, "{spread_near}");
}
