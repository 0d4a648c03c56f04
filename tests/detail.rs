//! Shading `ggx`'s detail normal map (seed 002 §Normal maps, `ocean_core::detail`): the
//! shader's slopes (the CPU mirror of `shaders/shared/detail.wgsl`, which the cross-check holds
//! the GPU to) against the f64 sum of the block's sinusoids, and the footprint filter moving
//! the slopes into the BRDF's variance without creating or losing slope energy on average.

use bytemuck::Zeroable;
use ocean_core::detail::{DetailBlock, detail_waves};
use ocean_core::frame::FrameUniforms;
use ocean_core::fuzz::Rng;
use ocean_cpu::shaders::shared::detail::detail_slopes;

fn frame(strength: f64) -> FrameUniforms {
    let mut u = FrameUniforms::zeroed();
    u.detail = DetailBlock::new(&detail_waves(0.8, strength), 0.4, 30.0, 12.5, [3.0, -7.0]);
    u.far.mode = 2.0;
    u
}

/// The f64 slopes of the block's sinusoids at `pos` (relative to the reference point).
fn exact(u: &FrameUniforms, pos: [f64; 2]) -> [f64; 2] {
    let mut s = [0.0; 2];
    for w in &u.detail.waves[..u.detail.count as usize] {
        let [fx, fz, p0, a] = w.map(f64::from);
        let c = (std::f64::consts::TAU * (fx * pos[0] + fz * pos[1] + p0)).cos();
        s[0] += a * fx * c;
        s[1] += a * fz * c;
    }
    s
}

#[test]
fn unfiltered_slopes_match_the_f64_sum() {
    let u = frame(0.1);
    assert_eq!(u.detail.count, 32.0);
    let mut rng = Rng(7);
    let mut worst = 0.0f64;
    for _ in 0..5000 {
        let pos = [(80.0 * rng.unit() - 40.0), (80.0 * rng.unit() - 40.0)];
        let p = [pos[0] as f32, pos[1] as f32];
        let s = detail_slopes(p.into(), [1.0, 0.0].into(), 0.0, 0.0, &u);
        let e = exact(&u, p.map(f64::from));
        // f32's own limit: each phase (turns) is formed from |f·pos| + ½ in three roundings of
        // at most ½ ulp, and cis_turns adds a few ulp; the slope moves by a·|f|·2π per turn.
        let bound: f64 = u.detail.waves[..32]
            .iter()
            .map(|w| {
                let [fx, fz, _, a] = w.map(f64::from);
                let turns = (fx * f64::from(p[0])).abs() + (fz * f64::from(p[1])).abs() + 0.5;
                a * fx.hypot(fz) * std::f64::consts::TAU * (3.0 * turns * 2f64.powi(-24) + 4e-7)
            })
            .sum();
        let err = (f64::from(s.x) - e[0]).abs().max((f64::from(s.y) - e[1]).abs());
        worst = worst.max(err / bound);
        assert_eq!(s.z, 0.0, "nothing is filtered with a zero footprint");
    }
    println!("detail slopes against f64: worst error / f32 bound {worst:.3}");
    assert!(worst <= 1.0, "{worst}");
    // Negative control: a quarter turn on one sinusoid is seen.
    let mut v = u;
    v.detail.waves[5][2] += 0.25;
    let p = [1.3f32, 2.1];
    let moved = (0..200)
        .map(|i| {
            let q = [p[0] + 0.07 * i as f32, p[1]];
            let s = detail_slopes(q.into(), [1.0, 0.0].into(), 0.0, 0.0, &v);
            let e = exact(&u, q.map(f64::from));
            (f64::from(s.x) - e[0]).abs().max((f64::from(s.y) - e[1]).abs())
        })
        .fold(0.0, f64::max);
    assert!(moved > 1e-3, "a shifted sinusoid passed: {moved}");
}

#[test]
fn the_filter_moves_slope_energy_into_the_variance() {
    let u = frame(0.1);
    let mut rng = Rng(11);
    // Over many points, E[s_x² + s_z²] + 2·variance (per axis) is the unfiltered E[|s|²] =
    // strength² for any footprint: the average removes from the mean what it adds to the
    // variance.
    for sigma in [0.0f32, 0.05, 0.2, 1.0, 5.0] {
        let (mut energy, n) = (0.0f64, 20000);
        let mut mean_var = 0.0f64;
        for _ in 0..n {
            let p = [(100.0 * rng.unit() - 50.0) as f32, (100.0 * rng.unit() - 50.0) as f32];
            let s = detail_slopes(p.into(), [0.6, 0.8].into(), 2.0 * sigma, sigma, &u);
            energy += f64::from(s.x * s.x + s.y * s.y) + 2.0 * f64::from(s.z);
            mean_var += f64::from(s.z);
        }
        energy /= f64::from(n);
        mean_var /= f64::from(n);
        println!("σ {sigma}: E|s|² + 2 var = {energy:.5}, mean variance {mean_var:.2e}");
        // Sampling noise of the cross terms over 20,000 points: about 1e-4.
        assert!((energy - 0.01).abs() < 3e-4, "σ {sigma}: {energy}");
        if sigma >= 1.0 {
            assert!(mean_var > 0.004, "a wide footprint leaves the slopes to the variance");
        }
    }
    // Negative control: under far field `mip` (no variance term) the wide footprint's slope
    // energy is gone.
    let mut v = u;
    v.far.mode = 1.0;
    let lost: f32 = (0..2000)
        .map(|i| {
            let s = detail_slopes([i as f32 * 0.37, 1.0].into(), [0.6, 0.8].into(), 2.0, 1.0, &v);
            s.x * s.x + s.y * s.y + 2.0 * s.z
        })
        .sum::<f32>()
        / 2000.0;
    assert!(lost < 1e-3, "without the variance the energy stays: {lost}");
}
