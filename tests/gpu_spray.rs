//! Spray technique `particles` (seed 001 §3.4): the particle pool's books balance and every
//! transition follows the model's rules (`ocean_core::spray`); the CPU's pool is the same bits
//! over runs and thread counts; and the GPU's pool, kept on the device across frames, equals
//! the CPU's bit for bit after 100 steps of system `chiu`'s rock scene. The step's envelope
//! holds the oracle's step and random conformant GPUs' on the scenes with a spray, the step
//! `ocean compare` probes on the device, and a GPU dump's step, each with its negative control.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[macro_use]
#[path = "support/gpu_harness.rs"]
mod gpu_harness;

#[path = "support/cli.rs"]
mod cli;
#[path = "support/reference_scenes.rs"]
mod reference_scenes;

use std::path::PathBuf;

use ocean_core::graph::FrameState;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::{Scene, SceneSource};
use ocean_core::spray::{Emitter, Particle, SprayUniforms};
use ocean_cpu::sampler::Texture2D;
use ocean_cpu::shaders::spray;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `reference/scenes/chiu_rock.toml` made small: 64×36, 64² maps, no warm-up (every frame one
/// step, so frame n has run n steps).
fn rock() -> Scene {
    let text = std::fs::read_to_string(root().join("reference/scenes/chiu_rock.toml")).unwrap();
    let mut s = Scene::from_toml(&text, SceneSource::Text).unwrap_or_else(|e| panic!("{e}"));
    (s.camera.width, s.camera.height) = (64, 36);
    (s.ocean.resolution, s.ocean.bump_resolution) = (64, 64);
    s.spray.warmup_steps = 0;
    s.spray.particles = 4096;
    s
}

/// The CPU's pool after `frames` frames of `scene`.
fn cpu_pool(scene: &Scene, frames: u64) -> Vec<Particle> {
    let mut state = FrameState::new(1.0 / 30.0);
    for _ in 0..frames {
        let plan = FramePlan::new(scene, OutputKind::Hdr);
        ocean_cpu::render::render_animation_frame(scene, plan, &mut state, &mut |_| {}).unwrap();
    }
    state.spray.unwrap().particles
}

/// Values of `after` outside the step's envelope `env`, over all slots.
fn outside(env: &[spray::SlotStep<ocean_cpu::envelope::Iv>], after: &[Particle]) -> usize {
    env.iter().zip(after).map(|(e, a)| e.values_outside(a)).sum()
}

fn bits(p: &[Particle]) -> Vec<u32> {
    bytemuck::cast_slice::<Particle, u32>(p).to_vec()
}

fn cpu_pool_is_the_same_over_runs_and_threads() {
    let scene = rock();
    let pool = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| cpu_pool(&scene, 40))
    };
    let (one, two, again) = (pool(1), pool(2), pool(2));
    let active = one.iter().filter(|p| p.pos[3] > 0.0).count();
    println!("40 steps: {active} of {} slots active; 1 and 2 threads, twice", one.len());
    assert!(active > 50, "the rock must throw spray: {active}");
    assert_eq!(bits(&one), bits(&two));
    assert_eq!(bits(&two), bits(&again));
}

fn books_balance_and_every_transition_follows_the_rules() {
    // A sea 1 m above the plane everywhere (a constant displacement map): the emitters below
    // y = 1 are under the water, the others never launch.
    let sea = Texture2D::new(4, 4, vec![[0.0, 1.0, 0.0, 1.0]; 16]);
    let emitters: Vec<Emitter> = (0..40)
        .map(|k| {
            let y = -1.0 + k as f32 * 0.1;
            Emitter { pos: [k as f32, y, 0.0, 0.0], dir: [0.0, 1.0, 0.0, 0.0] }
        })
        .collect();
    let n = 2000u32;
    let mut u = SprayUniforms {
        count: n,
        emitters: emitters.len() as u32,
        seed: 7,
        dt: 1.0 / 30.0,
        gravity: 9.81,
        speed: 4.0,
        lifetime: 1.0,
        emit_chance: 0.1,
        inv_patch: 1.0 / 16.0,
        half_texel: 0.125,
        waves: 1.0,
        ..Default::default()
    };
    let mut pool = vec![Particle::default(); n as usize];
    let (mut launched, mut freed) = (0u64, 0u64);
    for step in 0..300u32 {
        u.step = step;
        let before = pool.clone();
        spray::step(&mut pool, &u, &emitters, &sea);
        for (i, (a, b)) in before.iter().zip(&pool).enumerate() {
            let e = emitters[i % emitters.len()];
            match (a.pos[3] > 0.0, b.pos[3] > 0.0) {
                (false, true) => {
                    launched += 1;
                    assert!(e.pos[1] < 1.0, "slot {i} launched from an emitter above the water");
                    assert_eq!(&b.pos[..3], &e.pos[..3], "launched at its emitter");
                    let speed = (b.vel[0].powi(2) + b.vel[1].powi(2) + b.vel[2].powi(2)).sqrt();
                    // 0.6..1.4 × speed along dir, plus a jitter of at most 0.15·√3·speed.
                    assert!(speed <= 4.0 * (1.4 + 0.15 * 3f32.sqrt()) && b.vel[3] == 0.0);
                }
                (true, false) => {
                    freed += 1;
                    let old = b.vel[3] > u.lifetime;
                    let back_in = b.vel[1] < 0.0 && b.pos[1] < 1.0;
                    assert!(old || back_in, "slot {i} freed in flight: {b:?}");
                }
                (true, true) => {
                    assert!(b.vel[3] <= u.lifetime && (b.pos[1] >= 1.0 || b.vel[1] >= 0.0))
                }
                (false, false) => assert_eq!(a, b, "a free slot stays as it was"),
            }
        }
        let active = pool.iter().filter(|p| p.pos[3] > 0.0).count() as u64;
        assert_eq!(launched - freed, active, "step {step}: the books of the pool");
    }
    let active = pool.iter().filter(|p| p.pos[3] > 0.0).count();
    println!("300 steps: {launched} launched, {freed} freed, {active} active of {n}");
    assert!(launched > 1000 && freed > 1000);
}

/// Every live particle of 400 steps of the rock's spray, over a rough sea, lies inside
/// `spray::sprite_box` (which the envelope verdicts leave out of the frame, `spray::reach`),
/// with its sprite, and so does its centre's pixel; a box for a launch 20 % slower, or one
/// whose floor is 0.3 m higher, misses some (the negative controls: the bound is the flight).
fn every_live_sprite_lies_in_the_sprays_reach_and_a_tighter_bound_misses_some() {
    let mut scene = rock();
    (scene.camera.width, scene.camera.height) = (160, 90);
    let plan = FramePlan::new(&scene, OutputKind::Hdr);
    let camera = ocean_core::camera::Camera::from_scene(&scene.camera).unwrap();
    let frame = ocean_core::graph::FrameInputs::new(&scene, &plan, &FrameState::new(0.0)).unwrap();
    let emitters = plan.spray_emitters.as_slice();
    assert!(!emitters.is_empty(), "the rock has emitters");
    let mut u = ocean_core::spray::SprayFrame::new(&scene, &plan, &camera, 0, 0).draw;
    // A rough sea: heights in [-0.9, 1.1] m, 16² texels, so that particles launch (an emitter
    // under the water) and are freed (back under it) all over the pool.
    let mut r = 12345u32;
    let mut next = || {
        r = r.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (r >> 8) as f32 / 16_777_216.0
    };
    let texels: Vec<[f32; 4]> = (0..256).map(|_| [0.0, next() * 2.0 - 0.9, 0.0, 1.0]).collect();
    let lowest = texels.iter().map(|t| f64::from(t[1])).fold(f64::INFINITY, f64::min);
    let sea = Texture2D::new(16, 16, texels);
    let boxed = |speed: f32, lowest: f64| {
        let mut d = u;
        d.speed = speed;
        spray::sprite_box(emitters, &d, Some(lowest)).unwrap()
    };
    let exact = boxed(u.speed, lowest);
    let slow = boxed(u.speed * 0.8, lowest);
    let mut high = exact;
    high[0][1] += 0.3;
    let (w, h) = (scene.camera.width, scene.camera.height);
    let reach = spray::reach(emitters, &u, Some(lowest), &frame.uniforms, w, h);
    let inside = |b: &[[f64; 3]; 2], p: &Particle| {
        (0..3).all(|c| (b[0][c]..=b[1][c]).contains(&f64::from(p.pos[c])))
    };
    let mut pool = vec![Particle::default(); u.count as usize];
    let (mut live, mut outside_slow, mut outside_high, mut drawn) = (0u64, 0u64, 0u64, 0u64);
    for step in 0..400u32 {
        u.step = step;
        spray::step(&mut pool, &u, emitters, &sea);
        for p in pool.iter().filter(|p| p.pos[3] > 0.0) {
            live += 1;
            assert!(inside(&exact, p), "step {step}: a particle outside the box {exact:?}: {p:?}");
            outside_slow += u64::from(!inside(&slow, p));
            outside_high += u64::from(!inside(&high, p));
            let clip = spray::vs_main(0, std::slice::from_ref(p), &frame.uniforms, &u).clip;
            if clip.w > 0.0 {
                let x = (clip.x / clip.w * 0.5 + 0.5) * w as f32;
                let y = (0.5 - clip.y / clip.w * 0.5) * h as f32;
                if (0.0..w as f32).contains(&x) && (0.0..h as f32).contains(&y) {
                    drawn += 1;
                    let i = y as usize * w as usize + x as usize;
                    assert!(reach[i], "step {step}: a sprite at ({x}, {y}) outside the reach");
                }
            }
        }
    }
    let share = reach.iter().filter(|r| **r).count() as f64 / reach.len() as f64;
    println!(
        "{live} live particle-steps ({drawn} on screen) inside the box; reach {:.0} % of the \
         frame; outside a 20 % slower launch's box {outside_slow}, a floor 0.3 m higher \
         {outside_high}",
        100.0 * share
    );
    assert!(live > 10_000 && drawn > 1_000, "too few particles to tell: {live}, {drawn}");
    assert!(outside_slow > 0 && outside_high > 0, "the bound is not the flight's");
    assert!(share < 1.0, "the reach is the whole frame");
}

/// The spray's step on the scenes that run one (every reference scene with a spray, and
/// system `chiu`'s built-in scene), from the CPU oracle's pool after the scene's first frame
/// (its warm-up and one step) and its displacement map: the oracle's step and 8 random
/// conformant GPUs' lie inside the step's envelope at lavapipe's precision and at Vulkan's
/// minimum; GPUs twice as loose as the rules leave it (the negative control).
fn random_conformant_gpus_stay_inside_the_spray_step_envelope() {
    use ocean_cpu::envelope::{JitterRules, Precision};
    let mut scenes = reference_scenes::reference_scenes();
    let chiu = ocean::scene_arg::SystemArg { system: Some("chiu".into()) };
    scenes.push(("builtin-chiu".into(), ocean::scene_arg::load_scene(None, &chiu).unwrap()));
    let (mut judged, mut slots, mut undecided, mut loose) = (Vec::new(), 0, 0, 0);
    for (name, mut scene) in scenes {
        (scene.camera.width, scene.camera.height) = (64, 36);
        let plan = FramePlan::new(&scene, OutputKind::Hdr);
        if !plan.runs(ocean_core::plan::Pass::Spray) {
            continue;
        }
        let mut state = FrameState::new(1.0 / 30.0);
        let r = ocean_cpu::render::render_animation_frame(
            &scene,
            plan.clone(),
            &mut state,
            &mut |_| {},
        )
        .unwrap();
        let pool = state.spray.as_ref().unwrap();
        let params = ocean::verdict::spray::step_uniforms(&scene, &plan, pool.steps).unwrap();
        // The map the frame's own steps read (a 1×1 zero map without pass `waves`).
        let (w, h, map) = r.buffers.map(ocean_core::plan::ResourceId::Displacement).unwrap();
        let displacement = Texture2D::new(w, h, map.to_vec());
        let (before, emitters) = (&pool.particles, &plan.spray_emitters);
        let mut exact = before.clone();
        spray::step(&mut exact, &params, emitters, &displacement);
        let launched = before.iter().zip(&exact).filter(|(b, a)| b.pos[3] == 0.0 && a.pos[3] > 0.0);
        assert!(launched.count() > 0, "{name}: the step launches nothing");
        for precision in [Precision::LAVAPIPE, Precision::VULKAN_MINIMUM] {
            let env = spray::step_envelope(before, &params, emitters, &displacement, precision);
            let outside = |after: &[Particle]| outside(&env, after);
            assert_eq!(outside(&exact), 0, "{name}: the oracle's step");
            undecided += env.iter().filter(|e| !e.decided).count();
            for seed in 0..8 {
                let rules = JitterRules { seed, scale: 1.0 };
                let gpu =
                    spray::step_jitter(before, &params, emitters, &displacement, precision, rules);
                assert_eq!(outside(&gpu), 0, "{name}, seed {seed}, {precision:?}");
                let rules = JitterRules { seed: 1000 + seed, scale: 2.0 };
                let gpu =
                    spray::step_jitter(before, &params, emitters, &displacement, precision, rules);
                loose += outside(&gpu);
            }
            slots += before.len();
        }
        judged.push(name);
    }
    println!(
        "spray steps of {judged:?} at two precisions: {slots} slots × 8 random conformant GPUs inside ({undecided} undecided); twice the rules: {loose} values outside"
    );
    assert!(!judged.is_empty(), "no scene runs a spray");
    assert!(judged.iter().any(|n| n == "chiu_rock") && judged.len() >= 2, "{judged:?}");
    assert!(loose > 0, "a GPU twice as loose as the rules never left the spray step's envelope");
}

fn gpu_pool_equals_the_cpu_pool_after_100_steps() {
    let scene = rock();
    let cpu = cpu_pool(&scene, 100);
    let earlier = cpu_pool(&scene, 99);
    let gpu = ocean_gpu::Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let mut r = ocean_gpu::Renderer::with_gpu(gpu, ocean_gpu::WaveSynthesis::GpuFft).unwrap();
    let mut state = FrameState::new(1.0 / 30.0);
    for _ in 0..100 {
        let plan = FramePlan::new(&scene, OutputKind::Hdr);
        r.run_frame(&scene, &plan, &mut state, ocean_gpu::Readback::None).unwrap();
    }
    let gpu = r.spray_particles().unwrap().expect("the GPU's pool");
    let active = gpu.iter().filter(|p| p.pos[3] > 0.0).count();
    let differ = bits(&gpu).iter().zip(bits(&cpu)).filter(|(a, b)| **a != *b).count();
    println!(
        "after 100 steps on {}: {active} active; {differ} words differ from the CPU's",
        r.adapter()
    );
    assert!(active > 50);
    assert_eq!(differ, 0, "the GPU's pool must equal the CPU's bit for bit");
    // Negative control: the CPU's pool one step earlier is not the GPU's.
    assert_ne!(bits(&gpu), bits(&earlier));
}

/// The step `ocean compare` probes: one more step of the pool a frame left on the device, run
/// there on buffers of its own from the frame's displacement map, equals the CPU mirror's step
/// bit for bit on lavapipe and lies inside the step's envelope (ocean-cpu
/// `spray::step_envelope`); the frame's pool is untouched, and a step with a 1 % faster launch
/// leaves the envelope (the negative control).
fn the_probed_step_equals_the_cpu_step_and_lies_in_its_envelope() {
    use ocean_core::plan::ResourceId;
    let scene = rock();
    let gpu = ocean_gpu::Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let mut r = ocean_gpu::Renderer::with_gpu(gpu, ocean_gpu::WaveSynthesis::GpuFft).unwrap();
    let mut state = FrameState::new(1.0 / 30.0);
    let mut frame = None;
    for k in 0..40 {
        let plan = FramePlan::new(&scene, OutputKind::Hdr);
        let read = if k == 39 { ocean_gpu::Readback::All } else { ocean_gpu::Readback::None };
        frame = Some(r.run_frame(&scene, &plan, &mut state, read).unwrap());
    }
    let frame = frame.unwrap();
    let map = frame.map(ResourceId::Displacement).expect("the displacement map read back");
    let before = r.spray_particles().unwrap().unwrap();
    let steps = r.spray_steps().unwrap();
    assert_eq!(steps, 40);
    let params = ocean::verdict::spray::step_uniforms(&scene, &frame.plan, steps).unwrap();
    let probe = |u: &SprayUniforms| {
        r.spray_probe(&before, u, (map.width, map.height, &map.texels)).unwrap().unwrap()
    };
    let after = probe(&params);
    let texture = Texture2D::new(map.width, map.height, map.texels.clone());
    let emitters = &frame.plan.spray_emitters;
    let mut cpu = before.clone();
    spray::step(&mut cpu, &params, emitters, &texture);
    let differ = bits(&after).iter().zip(bits(&cpu)).filter(|(a, b)| **a != *b).count();
    assert_eq!(differ, 0, "the device's probed step must equal the CPU's bit for bit");
    assert_eq!(bits(&r.spray_particles().unwrap().unwrap()), bits(&before), "the pool moved");
    let launched = before.iter().zip(&after).filter(|(b, a)| b.pos[3] == 0.0 && a.pos[3] > 0.0);
    let launched = launched.count();
    let precision = ocean_cpu::envelope::Precision::LAVAPIPE;
    let env = spray::step_envelope(&before, &params, emitters, &texture, precision);
    let outside = |p: &[Particle]| outside(&env, p);
    let undecided = env.iter().filter(|e| !e.decided).count();
    let fast = probe(&SprayUniforms { speed: params.speed * 1.01, ..params });
    println!(
        "probed step {steps} on {}: {launched} launched, {undecided} of {} slots undecided; \
         a 1 % faster launch: {} values outside",
        r.adapter(),
        before.len(),
        outside(&fast)
    );
    // 43 launches and 129 values outside here; the floors ask for a few launches' worth.
    assert!(launched > 5, "the probed step launches particles: {launched}");
    assert_eq!(outside(&after), 0, "the device's step lies in its envelope");
    assert!(outside(&fast) > 10, "a 1 % faster launch leaves the envelope");
}

/// `ocean render --backend gpu --dump-passes` keeps the probed step (`spray_step.exr`, named
/// in the manifest), and `ocean compare --against` holds it to its envelope: 0 values outside;
/// one velocity 1 % off in the dump, or the manifest's step one off (its random numbers),
/// fails the verdict on `spray_particles`; without the displacement map it is not judged.
fn a_gpu_dump_holds_the_spray_step_and_compare_against_judges_it() {
    use ocean::output::{Channel, encode_exr};
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().join("rock");
    let scene = root().join("reference/scenes/chiu_rock.toml");
    let (scene, d_s) = (scene.to_string_lossy(), d.to_string_lossy());
    let png = dir.path().join("rock.png");
    let o = cli::ocean(&[
        "render",
        &scene,
        "--backend",
        "gpu",
        "--size",
        "96x54",
        "--dump-passes",
        &d_s,
        "-o",
        &png.to_string_lossy(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("manifest.json")).unwrap()).unwrap();
    let slots = m["spray_step"]["slots"].as_u64().expect("the manifest names the spray step");
    assert_eq!(m["spray_step"]["file"], "spray_step.exr");
    let out = dir.path().join("cmp");
    let against = || {
        let o = cli::ocean(&[
            "compare",
            "--against",
            &d_s,
            "--tolerance",
            "envelope",
            "--out-dir",
            &out.to_string_lossy(),
        ]);
        let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
        let find =
            |what: &str| stdout.lines().find(|l| l.contains(what)).unwrap_or_default().to_owned();
        (o.status.success(), find("spray_particles"), find("[water"))
    };
    let (ok, line, water) = against();
    println!("{slots} slots: {line}");
    assert!(ok && line.contains(" 0 of ") && line.ends_with("ok"), "{line}");
    // The water and the sprites over it, from the dump's own maps and pool (the Fresnel
    // filter, an upload the dump does not hold, the plan's own).
    println!("{water}");
    assert!(
        water.contains(" 0 of ")
            && water.contains("where a sprite may add light")
            && water.contains(") ok ("),
        "{water}"
    );
    // One velocity of the step's output 1 % off.
    let image = exr::prelude::read_all_flat_layers_from_file(d.join("spray_step.exr")).unwrap();
    let layer = &image.layer_data[0];
    let mut columns: Vec<(String, Vec<f32>)> = layer
        .channel_data
        .list
        .iter()
        .map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect()))
        .collect();
    let active = (0..slots as usize)
        .find(|&r| columns.iter().any(|(n, v)| n == "w" && v[4 * r + 2] == 1.0))
        .expect("a live particle after the step");
    for (n, v) in &mut columns {
        if n == "y" {
            v[4 * active + 3] *= 1.01;
        }
    }
    let good = std::fs::read(d.join("spray_step.exr")).unwrap();
    let channels =
        columns.iter().map(|(n, v)| Channel { name: n, data: v.clone() }).collect::<Vec<_>>();
    let bytes = encode_exr(4, slots as usize, channels).unwrap();
    std::fs::write(d.join("spray_step.exr"), bytes).unwrap();
    let (ok, line, _) = against();
    assert!(!ok && line.contains("FAIL") && line.contains(" 1 of "), "{line}");
    // The manifest's step one off: the step's random numbers are another step's.
    std::fs::write(d.join("spray_step.exr"), good).unwrap();
    let mut off = m.clone();
    off["spray_step"]["step"] = (m["spray_step"]["step"].as_u64().unwrap() + 1).into();
    std::fs::write(d.join("manifest.json"), serde_json::to_string_pretty(&off).unwrap()).unwrap();
    let (ok, line, _) = against();
    assert!(!ok && line.contains("FAIL"), "{line}");
    // Without the displacement map the step read, the step is not judged (never passed on a
    // map of zeros, which the GPU did not read).
    let mut without = m.clone();
    without["resources"].as_array_mut().unwrap().retain(|r| r["name"] != "displacement");
    let text = serde_json::to_string_pretty(&without).unwrap();
    std::fs::write(d.join("manifest.json"), text).unwrap();
    let (_, line, _) = against();
    assert!(line.contains("not judged: its input displacement is not in the frame"), "{line}");
}

fn main() -> std::process::ExitCode {
    run_tests!(gpu_harness::GPU_ADAPTER;
        cpu: cpu_pool_is_the_same_over_runs_and_threads, books_balance_and_every_transition_follows_the_rules,
            every_live_sprite_lies_in_the_sprays_reach_and_a_tighter_bound_misses_some,
            random_conformant_gpus_stay_inside_the_spray_step_envelope;
        gpu: gpu_pool_equals_the_cpu_pool_after_100_steps,
            the_probed_step_equals_the_cpu_step_and_lies_in_its_envelope,
            a_gpu_dump_holds_the_spray_step_and_compare_against_judges_it)
}
