//! The step's envelope: the exact step and random conformant GPUs inside it, a looser GPU
//! and a planted launch-speed change outside it.

use super::*;

/// A rough little sea (heights ±0.6 m over a 16 m patch), emitters on a ring at the mean
/// level, and the step's uniforms.
fn setup() -> (Texture2D, Vec<Emitter>, SprayUniforms) {
    let n = 16u32;
    let texels = (0..n * n)
        .map(|i| {
            let (x, z) = ((i % n) as f32, (i / n) as f32);
            [0.0, 0.6 * (0.7 * x).sin() * (0.45 * z + 1.0).cos(), 0.0, 0.0]
        })
        .collect();
    let emitters = (0..24)
        .map(|k| {
            let a = k as f32 * 0.2618;
            let d = [a.cos() * 0.45, 0.89, a.sin() * 0.45];
            Emitter {
                pos: [3.0 * a.cos() + 5.0, -0.05, 3.0 * a.sin() + 5.0, 0.0],
                dir: [d[0], d[1], d[2], 0.0],
            }
        })
        .collect();
    let params = SprayUniforms {
        step: 0,
        count: 2048,
        emitters: 24,
        seed: 0x5eed_0001,
        dt: 1.0 / 30.0,
        gravity: 9.81,
        speed: 4.0,
        lifetime: 1.5,
        emit_chance: 0.05,
        inv_patch: 1.0 / 16.0,
        half_texel: 0.5 / 16.0,
        waves: 1.0,
        ..SprayUniforms::default()
    };
    (Texture2D::new(n, n, texels), emitters, params)
}

/// The pool after `steps` exact steps from free slots, and the uniforms of the next step.
fn warm(steps: u32) -> (Vec<Particle>, Texture2D, Vec<Emitter>, SprayUniforms) {
    let (d, e, mut u) = setup();
    let mut pool = vec![Particle::default(); u.count as usize];
    for s in 0..steps {
        u.step = s;
        step(&mut pool, &u, &e, &d);
    }
    u.step = steps;
    (pool, d, e, u)
}

/// Values of `after` outside `env`, over all slots, and the slots with an undecided branch.
fn outside(env: &[SlotStep<Iv>], after: &[Particle]) -> (usize, usize) {
    let out = env.iter().zip(after).map(|(e, a)| e.values_outside(a)).sum();
    (out, env.iter().filter(|e| !e.decided).count())
}

#[test]
fn the_exact_step_and_conformant_gpus_lie_inside_the_envelope() {
    let (pool, d, e, u) = warm(60);
    let active = pool.iter().filter(|p| p.pos[3] > 0.0).count();
    // The setup's own check, not a tolerance: some of the 2,048 slots live and some are free,
    // so the step both moves and launches.
    assert!(active > 200 && active < 2000, "a warmed pool, some slots live: {active}");
    let env = step_envelope(&pool, &u, &e, &d, Precision::LAVAPIPE);
    let mut exact = pool.clone();
    step(&mut exact, &u, &e, &d);
    let launched = pool.iter().zip(&exact).filter(|(b, a)| b.pos[3] == 0.0 && a.pos[3] > 0.0);
    assert!(launched.count() > 5, "the step launches particles");
    let (out, undecided) = outside(&env, &exact);
    assert_eq!(out, 0, "the exact step");
    // The verdict's own bound on ambiguous entries (MAX_AMBIGUOUS_SHARE, 2 %); 1 slot here.
    assert!(undecided < pool.len() / 50, "few slots undecided: {undecided}");
    for seed in 0..8 {
        let rules = JitterRules { seed, scale: 1.0 };
        let gpu = step_jitter(&pool, &u, &e, &d, Precision::LAVAPIPE, rules);
        assert_eq!(outside(&env, &gpu).0, 0, "seed {seed}");
    }
}

#[test]
fn a_looser_gpu_and_a_faster_launch_leave_the_envelope() {
    let (pool, d, e, u) = warm(60);
    let env = step_envelope(&pool, &u, &e, &d, Precision::LAVAPIPE);
    // A GPU twice as loose as the rules (about 1,800 values outside here).
    let rules = JitterRules { seed: 1, scale: 2.0 };
    let loose = step_jitter(&pool, &u, &e, &d, Precision::LAVAPIPE, rules);
    // About 1,800 here: a floor of 100 leaves room for another seed, not for passing.
    assert!(outside(&env, &loose).0 > 100, "a GPU twice as loose as the rules");
    // Launches 0.8 % faster (the planted bug `spray-launch-speed-plus-1pct` makes the random
    // part of the speed 1 % larger).
    let mut fast = pool.clone();
    step(&mut fast, &SprayUniforms { speed: u.speed * 1.008, ..u }, &e, &d);
    let (out, _) = outside(&env, &fast);
    // Every launch of the step moves its three velocity values; more than 10 is a few launches.
    assert!(out > 10, "launches 0.8 % faster: {out} values outside");
}
