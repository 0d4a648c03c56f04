//! Sky technique `preetham_clouds` (seed 001 eq. 4): the cloud layer's opacity against an
//! independent f64 implementation of its definition (`ocean_core::clouds`' module doc), the
//! sky it composes, and the properties a user relies on: coverage sets the share of the sky
//! covered, the clouds stay fixed in the world as the eye moves (also 10⁶ m away) and drift
//! with the wind, and the sun's light is dimmed by the cloud in front of it.

use ocean_core::clouds::{
    CLOUD_PERIOD, cloud_alpha, cloud_mean_opacity, cloud_origin, cloud_threshold,
};
use ocean_core::fuzz::Rng;
use ocean_core::scene::{Clouds, Scene, SceneSource};
use ocean_cpu::shaders::shared::preetham::preetham_radiance;
use ocean_cpu::shaders::sky::preetham_clouds;

/// The hash, as integers (the definition; exact in any precision).
fn hash(i: i64, j: i64, o: u32) -> f64 {
    let p = i64::from(CLOUD_PERIOD);
    let (i, j) = (i.rem_euclid(p) as u32, j.rem_euclid(p) as u32);
    let mut h =
        i.wrapping_mul(0x8da6_b343) ^ j.wrapping_mul(0xd816_3841) ^ o.wrapping_mul(0x9e37_79b9);
    h = (h ^ (h >> 15)).wrapping_mul(0x2c1b_3c6d);
    h = (h ^ (h >> 12)).wrapping_mul(0x297a_2d39);
    h ^= h >> 15;
    f64::from(h >> 8) / 16_777_216.0
}

/// The opacity at lattice point (x, z) in f64: five octaves of smoothstep value noise.
fn alpha64(x: f64, z: f64, threshold: f64) -> f64 {
    let mut sum = 0.0;
    for o in 0..5u32 {
        let f = f64::from(1u32 << o);
        let (x, z) = (x * f, z * f);
        let (i, j) = (x.floor() as i64, z.floor() as i64);
        let s = |t: f64| t * t * (3.0 - 2.0 * t);
        let (ux, uz) = (s(x - x.floor()), s(z - z.floor()));
        let (a, b) = (hash(i, j, o), hash(i + 1, j, o));
        let (c, d) = (hash(i, j + 1, o), hash(i + 1, j + 1, o));
        let (ab, cd) = (a + (b - a) * ux, c + (d - c) * ux);
        sum += 0.5f64.powi(o as i32 + 1) * (ab + (cd - ab) * uz);
    }
    ((sum / (1.0 - 0.5f64.powi(5)) - threshold) * 4.0).clamp(0.0, 1.0)
}

#[test]
fn opacity_is_its_definition_in_f64() {
    let mut rng = Rng(3);
    let (mut worst, mut n) = (0.0f64, 0);
    for _ in 0..20_000 {
        let origin = [
            (rng.unit() * 256.0) as f32,
            (rng.unit() * 256.0) as f32,
            (0.2 + rng.unit() * 3.0) as f32,
            (rng.unit() * 0.8) as f32,
        ];
        // Above the horizon fade: the opacity there is the layer's own.
        let (y, phi) = (0.1 + 0.9 * rng.unit(), rng.unit() * std::f64::consts::TAU);
        let h = (1.0 - y * y).sqrt();
        let dir = [(h * phi.cos()) as f32, y as f32, (h * phi.sin()) as f32];
        let got = f64::from(cloud_alpha(origin, 0.0, dir));
        let t = f64::from(origin[2]) / f64::from(dir[1]);
        let (x, z) = (
            f64::from(origin[0]) + f64::from(dir[0]) * t,
            f64::from(origin[1]) + f64::from(dir[2]) * t,
        );
        let want = alpha64(x, z, f64::from(origin[3]));
        // f32 rounding of the hit point (~1e-5 cells at 1e3 cells) and of the sum, times the
        // opacity's slope 4 and the noise's largest gradient (~3 per cell over 5 octaves, ×32).
        worst = worst.max((got - want).abs());
        n += usize::from((got - want).abs() > 1e-3);
    }
    println!("cloud opacity, f32 vs f64 definition: worst |Δα| {worst:.2e}, {n} beyond 1e-3");
    assert_eq!(n, 0);
    // Negative control: the same comparison against a threshold 0.01 off misses often.
    let mut rng = Rng(3);
    let mut off = 0;
    for _ in 0..2000 {
        let origin = [(rng.unit() * 256.0) as f32, (rng.unit() * 256.0) as f32, 1.0, 0.4];
        let dir = [0.3f32, 0.8, (1.0f32 - 0.73).sqrt()];
        let got = f64::from(cloud_alpha(origin, 0.0, dir));
        let t = 1.0 / f64::from(dir[1]);
        let (x, z) = (
            f64::from(origin[0]) + f64::from(dir[0]) * t,
            f64::from(origin[1]) + f64::from(dir[2]) * t,
        );
        off += usize::from((got - alpha64(x, z, 0.41)).abs() > 1e-3);
    }
    assert!(off > 200, "{off}");
}

#[test]
fn coverage_sets_the_share_of_the_sky_covered() {
    let mut shares = Vec::new();
    for coverage in [0.0f32, 0.25, 0.5, 0.75, 1.0] {
        let threshold = cloud_threshold(coverage);
        let mean = cloud_mean_opacity(threshold);
        let mut covered = 0;
        let n = 128;
        for j in 0..n {
            for i in 0..n {
                let dir = [
                    ((i as f32 + 0.5) / n as f32 - 0.5) * 2.0,
                    1.0,
                    ((j as f32 + 0.5) / n as f32 - 0.5) * 2.0,
                ];
                let l = (dir[0] * dir[0] + 1.0 + dir[2] * dir[2]).sqrt();
                let dir = dir.map(|c| c / l);
                covered += usize::from(cloud_alpha([17.0, 91.0, 40.0, threshold], mean, dir) > 0.5);
            }
        }
        shares.push((coverage, covered as f64 / (n * n) as f64, mean));
    }
    println!("coverage → share of the sky with α > ½, mean α: {shares:?}");
    // The mean opacity is the coverage (the bisection's target, to its grid); the share
    // covered, measured here on other points of the layer, follows it.
    for &(coverage, share, mean) in &shares {
        assert!((f64::from(mean) - f64::from(coverage)).abs() < 1e-3, "{coverage}: mean {mean}");
        assert!((share - f64::from(coverage)).abs() < 0.12, "{coverage}: share {share}");
    }
    assert!(shares[0].1 == 0.0 && shares[4].1 == 1.0, "0 is clear, 1 overcast");
    assert!(shares.windows(2).all(|w| w[1].1 > w[0].1));
}

#[test]
fn clouds_stay_in_the_world_and_drift_with_the_wind() {
    let clouds = Clouds { coverage: 0.5, ..Clouds::default() };
    // A world point on the layer, seen from two eyes (one 10⁶ m away), and at a later time
    // from where the wind has carried it.
    let alpha_at = |eye: [f64; 3], time: f64, p: [f64; 3]| {
        let d = [p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]];
        let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let dir = d.map(|c| (c / l) as f32);
        cloud_alpha(cloud_origin(&clouds, eye, time), 0.0, dir)
    };
    let mut rng = Rng(5);
    let (mut moved, mut windy, mut n) = (0.0f32, 0.0f32, 0);
    for _ in 0..2000 {
        let base = [rng.unit() * 1e6, 10.0, rng.unit() * 1e6];
        let p = [base[0] + 500.0, clouds.altitude_m, base[2] - 700.0];
        let a = alpha_at(base, 0.0, p);
        let b = alpha_at([base[0] + 300.0, 10.0, base[2] + 200.0], 0.0, p);
        let t = 100.0;
        let drifted = [p[0] + clouds.wind[0] * t, p[1], p[2] + clouds.wind[1] * t];
        let c = alpha_at(base, t, drifted);
        moved = moved.max((a - b).abs());
        windy = windy.max((a - c).abs());
        n += usize::from(a > 0.0 && a < 1.0);
    }
    println!(
        "world-fixed: |Δα| ≤ {moved:.2e} as the eye moves, ≤ {windy:.2e} with the wind ({n} partly covered points)"
    );
    assert!(n > 100);
    assert!(moved < 2e-3 && windy < 2e-3);
    // Negative control: without the drift the clouds of t = 100 s are elsewhere.
    let mut differ = 0;
    for k in 0..200 {
        let p = [k as f64 * 37.0, clouds.altitude_m, -500.0];
        differ += usize::from(
            (alpha_at([0.0, 10.0, 0.0], 0.0, p) - alpha_at([0.0, 10.0, 0.0], 100.0, p)).abs()
                > 0.05,
        );
    }
    assert!(differ > 20, "{differ}");
}

#[test]
fn the_sky_is_eq4_and_the_sun_is_dimmed_behind_a_cloud() {
    let text = "[techniques]\nsky = \"preetham_clouds\"\n[sun]\ndirection = [0.3, 0.5, -1.0]\n\
                intensity = 5.0\n[clouds]\ncoverage = 1.0\n";
    let scene = Scene::from_toml(text, SceneSource::Text).expect("scene");
    let plan = ocean_core::plan::FramePlan::new(&scene, ocean_core::plan::OutputKind::Hdr);
    let state = ocean_core::graph::FrameState::default();
    let inputs = ocean_core::graph::FrameInputs::new(&scene, &plan, &state).expect("inputs");
    let sky = &inputs.environment;
    let mut rng = Rng(9);
    for _ in 0..1000 {
        let (y, phi) = (rng.unit(), rng.unit() * std::f64::consts::TAU);
        let h = (1.0 - y * y).sqrt();
        let dir = [(h * phi.cos()) as f32, y as f32, (h * phi.sin()) as f32];
        let a = preetham_clouds::cloud_alpha(sky, dir.into());
        let got: [f32; 3] = preetham_clouds::sky_radiance(sky, dir.into()).into();
        let clear: [f32; 3] = preetham_radiance(sky, dir.into()).into();
        for c in 0..3 {
            let want = f64::from(clear[c]) * f64::from(1.0 - a)
                + f64::from(sky.cloud_color[c]) * f64::from(a);
            assert!((f64::from(got[c]) - want).abs() <= 1e-6 * want.abs() + 1e-9, "{dir:?}");
        }
    }
    // Overcast: the sun's light on the sea is (1 − α) of the clear scene's, here nearly none.
    let clear_scene =
        Scene { clouds: Clouds { coverage: 0.0, ..Clouds::default() }, ..scene.clone() };
    let clear = ocean_core::graph::FrameInputs::new(&clear_scene, &plan, &state).expect("inputs");
    let (dim, full) = (inputs.uniforms.sun.radiance[0], clear.uniforms.sun.radiance[0]);
    println!("sun behind overcast: {dim} of {full}");
    assert!(dim < 0.05 * full, "{dim} vs {full}");
    // The sky technique `preetham` ignores the layer.
    let preetham = ocean_core::plan::FramePlan::new(
        &Scene { techniques: Default::default(), ..scene.clone() },
        ocean_core::plan::OutputKind::Hdr,
    );
    let plain = ocean_core::graph::FrameInputs::new(&scene, &preetham, &state).expect("inputs");
    let undimmed = plain.uniforms.sun.radiance[0];
    assert!(undimmed >= clear.uniforms.sun.radiance[0] && undimmed > 20.0 * dim, "{undimmed}");
}
