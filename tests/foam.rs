//! Stage `foam` (issue 14, item 4): the foam techniques' turbulence rises with the wind and
//! with the choppiness; waves `gerstner`'s analytic Jacobian against its closed form and the
//! closed form against finite differences; foam `accumulated`'s field after n frames equals n
//! fixed steps from an empty start of an independent f64 model on world lattice points (the
//! camera moving, so texels leave and enter the window), on the CPU, and the GPU's field (kept
//! on the device across frames) equals the CPU's. Every comparison has a negative control.
//! Run with `--nocapture` for the figures.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[macro_use]
#[path = "support/gpu_harness.rs"]
mod gpu_harness;

use std::collections::HashMap;
use std::path::PathBuf;

use ocean_core::foam::{FoamBlock, heuristic_turbulence, jacobian_turbulence};
use ocean_core::frame::FrameUniforms;
use ocean_core::graph::FrameState;
use ocean_core::plan::{Foam, FramePlan, OutputKind, ResourceId, Shading, Waves};
use ocean_core::rng::SplitMix64;
use ocean_core::scene::{Scene, SceneSource};
use ocean_core::waves::gerstner::GerstnerBlock;
use ocean_core::waves::{Synthesizer, WaveMaps};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn reference(name: &str) -> Scene {
    let path = root().join(format!("reference/scenes/{name}.toml"));
    let text = std::fs::read_to_string(&path).expect("the reference scene");
    Scene::from_toml(&text, SceneSource::Text).unwrap_or_else(|e| panic!("{e}"))
}

/// The displacement map of `scene`'s sea at its time (ocean-core's synthesis, f32).
fn maps(scene: &Scene) -> WaveMaps<f32> {
    let surface = scene.ocean.surface().expect("a sea");
    let mut synth = Synthesizer::<f32>::new(surface.displacement.resolution()).expect("a size");
    synth
        .synthesize(&surface.displacement, scene.ocean.time_s, scene.ocean.choppiness)
        .expect("the maps")
}

/// Mean turbulence of the map's texels under `jacobian` and `heuristic` (the model functions
/// the shaders write out).
fn mean_turbulence(scene: &Scene) -> (f64, f64) {
    let m = maps(scene);
    let foam = FoamBlock::new(scene, Foam::Jacobian, Waves::Fft, [0.0, 0.0]);
    let n = m.jacobian.len() as f64;
    let (mut j_sum, mut h_sum) = (0.0, 0.0);
    for i in 0..m.jacobian.len() {
        let s = (m.slope_x[i] * m.slope_x[i] + m.slope_z[i] * m.slope_z[i]).sqrt();
        j_sum += f64::from(jacobian_turbulence(m.jacobian[i], &foam));
        h_sum += f64::from(heuristic_turbulence(m.height[i], s, m.jacobian[i], &foam));
    }
    (j_sum / n, h_sum / n)
}

/// A Pierson–Moskowitz sea on a 512 m, 256² patch.
fn sea(wind: f64, chop: f64) -> Scene {
    let mut s = Scene::builtin();
    s.ocean.spectrum = ocean_core::spectrum::SpectrumKind::PiersonMoskowitz;
    s.ocean.wind_speed = wind;
    s.ocean.choppiness = chop;
    s.ocean.patch_size_m = 512.0;
    s.ocean.resolution = 256;
    s
}

/// Ok when every value is above the one before it by more than 1 % of it.
fn strictly_rising(what: &str, values: &[f64]) -> Result<(), String> {
    for w in values.windows(2) {
        if w[1] <= w[0] * 1.01 || w[1] <= 0.0 {
            return Err(format!("{what}: {values:?} does not rise at {} -> {}", w[0], w[1]));
        }
    }
    Ok(())
}

fn turbulence_rises_with_wind_and_with_choppiness() {
    let winds = [6.0, 10.0, 14.0, 18.0, 22.0, 26.0];
    let by_wind: Vec<_> = winds.iter().map(|&w| mean_turbulence(&sea(w, 1.0))).collect();
    let chops = [0.5, 1.0, 1.5, 2.0];
    let by_chop: Vec<_> = chops.iter().map(|&c| mean_turbulence(&sea(16.0, c))).collect();
    for (w, t) in winds.iter().zip(&by_wind) {
        println!("wind {w:4} m/s: mean turbulence jacobian {:.5}, heuristic {:.5}", t.0, t.1);
    }
    for (c, t) in chops.iter().zip(&by_chop) {
        println!("choppiness {c}: mean turbulence jacobian {:.5}, heuristic {:.5}", t.0, t.1);
    }
    let mut errors = Vec::new();
    let col = |v: &[(f64, f64)], k: usize| v.iter().map(|t| [t.0, t.1][k]).collect::<Vec<_>>();
    errors.extend(strictly_rising("jacobian by wind", &col(&by_wind, 0)).err());
    // The heuristic is 0 on the calmest sea (no crest both high and steep): from 10 m/s on.
    errors.extend(strictly_rising("heuristic by wind", &col(&by_wind, 1)[1..]).err());
    errors.extend(strictly_rising("jacobian by choppiness", &col(&by_chop, 0)).err());
    errors.extend(strictly_rising("heuristic by choppiness", &col(&by_chop, 1)).err());
    // Waves `gerstner`: steeper waves fold more (the Jacobian over a grid of one sea).
    let gerstner: Vec<f64> = [0.6, 0.8, 1.0]
        .iter()
        .map(|&c| {
            let mut s = reference("foam_gerstner");
            s.gerstner.choppiness = c;
            let d = s.ocean.dispersion().unwrap();
            let waves = s.gerstner.at(0.0, &d, s.ocean.wind_direction_deg);
            let foam = FoamBlock::new(&s, Foam::Jacobian, Waves::Gerstner, [0.0, 0.0]);
            let mut sum = 0.0;
            for i in 0..100 {
                for j in 0..100 {
                    let p = waves.sample(f64::from(i) * 0.37, f64::from(j) * 0.41);
                    sum += f64::from(jacobian_turbulence(p.jacobian as f32, &foam));
                }
            }
            sum / 1e4
        })
        .collect();
    println!("gerstner choppiness 0.6, 0.8, 1.0: mean turbulence jacobian {gerstner:?}");
    errors.extend(strictly_rising("gerstner jacobian by choppiness", &gerstner).err());
    assert!(errors.is_empty(), "{}", errors.join("\n"));
    // Negative control: the checker rejects a sequence that falls somewhere.
    let mut fallen = col(&by_wind, 0);
    fallen.swap(2, 3);
    assert!(strictly_rising("control", &fallen).is_err());
}

/// Waves `gerstner`'s f64 displacement at a world point (x, z) of a sea.
fn gerstner_disp(sea: &ocean_core::waves::gerstner::GerstnerSea, x: f64, z: f64) -> (f64, f64) {
    let s = sea.sample(x, z);
    (s.disp_x, s.disp_z)
}

fn gerstner_jacobian_matches_its_closed_form() {
    let scene = reference("foam_gerstner");
    let d = scene.ocean.dispersion().unwrap();
    let t = 3.7;
    let sea = scene.gerstner.at(t, &d, scene.ocean.wind_direction_deg);
    let origin = [123.25, -48.5];
    let mut frame: FrameUniforms = bytemuck::Zeroable::zeroed();
    frame.gerstner = GerstnerBlock::new(&sea, origin);
    let mut rng = SplitMix64::new(14);
    let (mut worst_mirror, mut worst_fd, mut worst_control) = (0.0f64, 0.0f64, 0.0f64);
    let later = scene.gerstner.at(t + 0.05, &d, scene.ocean.wind_direction_deg);
    let mut min_j = f64::INFINITY;
    for _ in 0..2000 {
        let pos = [rng.next_open_closed() * 60.0 - 30.0, rng.next_open_closed() * 60.0 - 30.0];
        let (x, z) = (origin[0] + pos[0], origin[1] + pos[1]);
        let exact = sea.sample(x, z).jacobian;
        min_j = min_j.min(exact);
        // The shader's f32 sum at the point relative to the mesh's reference point.
        let p32 = ocean_cpu::shaders::wgsl::vec2(pos[0] as f32, pos[1] as f32);
        let mirror = ocean_cpu::shaders::shared::gerstner::gerstner_jacobian(p32, &frame);
        worst_mirror = worst_mirror.max((f64::from(mirror) - exact).abs());
        // The closed form against central differences of the displacement (h = 1 mm).
        let h = 1e-3;
        let (xp, zp) = (gerstner_disp(&sea, x + h, z), gerstner_disp(&sea, x, z + h));
        let (xm, zm) = (gerstner_disp(&sea, x - h, z), gerstner_disp(&sea, x, z - h));
        let (dxx, dzx) = ((xp.0 - xm.0) / (2.0 * h), (xp.1 - xm.1) / (2.0 * h));
        let (dxz, dzz) = ((zp.0 - zm.0) / (2.0 * h), (zp.1 - zm.1) / (2.0 * h));
        let fd = (1.0 + dxx) * (1.0 + dzz) - dxz * dzx;
        worst_fd = worst_fd.max((fd - exact).abs());
        // Negative control: the sea 50 ms later.
        worst_control = worst_control.max((later.sample(x, z).jacobian - exact).abs());
    }
    println!(
        "gerstner J over 2000 points (min J {min_j:.3}): f32 mirror vs f64 closed form max \
         |Δ| {worst_mirror:.2e}; closed form vs central differences {worst_fd:.2e}; control \
         (50 ms later) {worst_control:.2e}"
    );
    // f32: 32 waves' sums of terms up to ~1 with phases to 2⁻²⁴ turns.
    const MIRROR_LIMIT: f64 = 1e-4;
    // Central differences: O(h²·k³·A) with h = 1 mm.
    const FD_LIMIT: f64 = 1e-6;
    assert!(min_j < 0.9, "the sea should compress somewhere: min J {min_j}");
    assert!(worst_mirror < MIRROR_LIMIT, "mirror {worst_mirror:e}");
    assert!(worst_fd < FD_LIMIT, "finite differences {worst_fd:e}");
    assert!(worst_control > 100.0 * MIRROR_LIMIT, "control {worst_control:e}");
}

/// Foam `accumulated` on waves `gerstner`, small: a 32×18 frame, a 64² lattice of 0.5 m, no
/// warm-up (frame n has run n + 1 steps).
fn gerstner_accumulated() -> Scene {
    let mut s = reference("foam_gerstner");
    s.techniques.foam = Some(Foam::Accumulated);
    (s.camera.width, s.camera.height) = (32, 18);
    s.foam.warmup_steps = 0;
    s.foam.grid = 64;
    s.foam.cell_m = 0.5;
    s
}

/// Frame k's scene: the camera moved by k·0.7 m along x and k·0.3 m along z (the lattice's
/// window follows it, so texels leave and enter).
fn moved(scene: &Scene, k: u64) -> Scene {
    let mut s = scene.clone();
    let d = [0.7 * k as f64, 0.0, -0.3 * k as f64];
    for (a, d) in d.iter().enumerate() {
        s.camera.position[a] += d;
        s.camera.look_at[a] += d;
    }
    s
}

/// The CPU's field after each of `frames` frames.
fn cpu_fields(scene: &Scene, frames: u64) -> Vec<Vec<[f32; 4]>> {
    let mut state = FrameState::new(1.0 / 30.0);
    (0..frames)
        .map(|k| {
            let s = moved(scene, k);
            let plan = FramePlan::new(&s, OutputKind::Hdr);
            ocean_cpu::render::render_animation_frame(&s, plan, &mut state, &mut |_| {}).unwrap();
            state.foam.as_ref().expect("the CPU's field").texels.clone()
        })
        .collect()
}

/// The independent f64 model after `frames` frames (`skip_last`: one step fewer, the negative
/// control): a map from world lattice point to foam, stepped over each frame's window; a point
/// that enters the window starts at 0.
fn model_field(scene: &Scene, frames: u64, skip_last: bool) -> (Vec<f64>, [i64; 2]) {
    let f = &scene.foam;
    let d = scene.ocean.dispersion().unwrap();
    let n = i64::from(f.grid);
    let mut field: HashMap<(i64, i64), f64> = HashMap::new();
    let mut start = [0, 0];
    let steps = if skip_last { frames - 1 } else { frames };
    for k in 0..steps {
        let s = moved(scene, k);
        let t = s.ocean.time_s + k as f64 / 30.0;
        let sea = s.gerstner.at(t, &d, s.ocean.wind_direction_deg);
        let eye = [s.camera.position[0], s.camera.position[2]];
        start = eye.map(|e| (e / f.cell_m).floor() as i64 - n / 2);
        let mut next = HashMap::new();
        for i in start[0]..start[0] + n {
            for j in start[1]..start[1] + n {
                let jac = sea.sample(i as f64 * f.cell_m, j as f64 * f.cell_m).jacobian;
                let source = ((f.threshold - jac) / f.softness).clamp(0.0, 1.0);
                let old = field.get(&(i, j)).copied().unwrap_or(0.0);
                let v = old * (-f.step_s / f.decay_s).exp() + f.growth_per_s * f.step_s * source;
                next.insert((i, j), v.min(1.0));
            }
        }
        field = next;
    }
    // Texel (a, b) holds lattice point start + ((a, b) − start mod n).
    let mut texels = vec![0.0; (n * n) as usize];
    for b in 0..n {
        for a in 0..n {
            let i = start[0] + (a - start[0]).rem_euclid(n);
            let j = start[1] + (b - start[1]).rem_euclid(n);
            texels[(b * n + a) as usize] = field.get(&(i, j)).copied().unwrap_or(0.0);
        }
    }
    (texels, start)
}

fn max_abs(a: &[[f32; 4]], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (f64::from(x[0]) - y).abs()).fold(0.0, f64::max)
}

fn accumulated_field_after_n_frames_is_n_steps_from_empty() {
    let scene = gerstner_accumulated();
    let frames = 12;
    let fields = cpu_fields(&scene, frames);
    let (model, start) = model_field(&scene, frames, false);
    let (control, _) = model_field(&scene, frames, true);
    let last = fields.last().unwrap();
    let err = max_abs(last, &model);
    let err_control = max_abs(last, &control);
    let mean = model.iter().sum::<f64>() / model.len() as f64;
    let foamy = model.iter().filter(|&&v| v > 0.05).count();
    println!(
        "accumulated (gerstner, 64² lattice, camera moving): after {frames} frames the CPU field \
         vs {frames} f64 steps from empty: max |Δ| {err:.2e} (mean foam {mean:.4}, {foamy} \
         texels > 0.05, window at {start:?}); control ({} steps): {err_control:.2e}",
        frames - 1
    );
    // f32 J (1e-4 at most, the Jacobian test) times growth·Δt/softness per step, summed.
    const LIMIT: f64 = 1e-4;
    assert!(foamy > 20, "the test sea should foam: {foamy} texels");
    assert!(err < LIMIT, "{err:e}");
    assert!(err_control > 10.0 * LIMIT, "control {err_control:e}");
}

/// Foam `accumulated` on the storm's FFT sea, small (64² maps, 32×18 frame, no warm-up).
fn fft_accumulated() -> Scene {
    let mut s = reference("foam_storm");
    (s.camera.width, s.camera.height) = (32, 18);
    (s.ocean.resolution, s.ocean.bump_resolution) = (64, 64);
    s.foam.warmup_steps = 0;
    s
}

/// The GPU's field after each of `frames` frames (the camera moving as on the CPU).
fn gpu_fields(scene: &Scene, frames: u64) -> Vec<Vec<[f32; 4]>> {
    let gpu = ocean_gpu::Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let mut r = ocean_gpu::Renderer::with_gpu(gpu, ocean_gpu::WaveSynthesis::GpuFft).unwrap();
    let mut state = FrameState::new(1.0 / 30.0);
    (0..frames)
        .map(|k| {
            let s = moved(scene, k);
            let plan = FramePlan::new(&s, OutputKind::Hdr);
            let f = r.run_frame(&s, &plan, &mut state, ocean_gpu::Readback::All).unwrap();
            f.map(ResourceId::FoamField).expect("the field read back").texels.clone()
        })
        .collect()
}

/// The largest |cpu − gpu| beyond docs/design.md's float tolerance (rel 1e-5, abs 1e-6), and the
/// largest difference.
fn float_compare(cpu: &[[f32; 4]], gpu: &[[f32; 4]]) -> (usize, f64) {
    assert_eq!(cpu.len(), gpu.len());
    let mut beyond = 0;
    let mut worst = 0.0f64;
    for (c, g) in cpu.iter().zip(gpu) {
        let d = f64::from((c[0] - g[0]).abs());
        worst = worst.max(d);
        if d > 1e-6 && d > 1e-5 * f64::from(c[0].abs()) {
            beyond += 1;
        }
    }
    (beyond, worst)
}

fn gpu_accumulated_field_equals_the_cpus_frame_by_frame() {
    let frames = 12;
    for (name, scene) in [("gerstner", gerstner_accumulated()), ("fft", fft_accumulated())] {
        let cpu = cpu_fields(&scene, frames);
        let gpu = gpu_fields(&scene, frames);
        let mut worst = 0.0f64;
        for k in 0..frames as usize {
            let (beyond, w) = float_compare(&cpu[k], &gpu[k]);
            worst = worst.max(w);
            assert_eq!(beyond, 0, "{name} frame {k}: {beyond} texels beyond the tolerance");
        }
        let (control, _) = float_compare(&cpu[frames as usize - 2], &gpu[frames as usize - 1]);
        let mean = cpu.last().unwrap().iter().map(|t| f64::from(t[0])).sum::<f64>()
            / cpu.last().unwrap().len() as f64;
        println!(
            "accumulated ({name}): GPU vs CPU over {frames} frames: max |Δ| {worst:.2e}; mean \
             foam {mean:.4}; control (CPU one frame earlier): {control} texels beyond"
        );
        assert!(mean > 1e-3, "{name}: the test sea should foam");
        assert!(control > 0, "{name}: the control must fail");
    }
}

/// The HDR frame of `scene` on the CPU.
fn hdr(scene: &Scene) -> Vec<[f32; 4]> {
    ocean_cpu::render_scene(scene, OutputKind::Hdr, &mut |_| {}).unwrap().buffers.hdr.color
}

fn foam_is_drawn_over_every_shading_and_zero_coverage_changes_nothing() {
    for shading in [Shading::Hu, Shading::Chiu, Shading::Ggx] {
        let mut base = fft_accumulated();
        (base.camera.width, base.camera.height) = (96, 54);
        base.techniques.shading = Some(shading);
        base.foam.warmup_steps = 60;
        let with = |foam: Foam, coverage: f64| {
            let mut s = base.clone();
            s.techniques.foam = Some(foam);
            s.foam.coverage = coverage;
            hdr(&s)
        };
        let none = with(Foam::None, 0.9);
        for foam in [Foam::Heuristic, Foam::Jacobian, Foam::Accumulated] {
            let zero = with(foam, 0.0);
            let drawn = with(foam, 0.9);
            let same =
                none.iter().zip(&zero).all(|(a, b)| a.map(f32::to_bits) == b.map(f32::to_bits));
            let changed: Vec<(f32, f32)> = none
                .iter()
                .zip(&drawn)
                .filter(|(a, b)| a != b)
                .map(|(a, b)| (a[0] + a[1] + a[2], b[0] + b[1] + b[2]))
                .collect();
            let brighter = changed.iter().filter(|(a, b)| b > a).count();
            println!(
                "{shading} + {foam}: coverage 0 equals none bit for bit: {same}; coverage 0.9 \
                 changes {} of {} pixels, {brighter} of them brighter",
                changed.len(),
                none.len()
            );
            assert!(same, "{shading} + {foam}: zero coverage changed the picture");
            assert!(changed.len() > 20, "{shading} + {foam}: no foam drawn");
            // White foam over dark water; over the sun's glitter it may be the darker.
            assert!(brighter * 3 > changed.len() * 2, "{shading} + {foam}: foam is white");
        }
    }
}

fn main() -> std::process::ExitCode {
    run_tests!(gpu_harness::GPU_ADAPTER;
        cpu: turbulence_rises_with_wind_and_with_choppiness,
            gerstner_jacobian_matches_its_closed_form,
            accumulated_field_after_n_frames_is_n_steps_from_empty,
            foam_is_drawn_over_every_shading_and_zero_coverage_changes_nothing;
        gpu: gpu_accumulated_field_equals_the_cpus_frame_by_frame)
}
