//! Waves technique `gerstner` (seed 002; `ocean_core::waves::gerstner`): one explicit wave
//! against its closed form and against finite differences, the speed the scene's dispersion
//! gives, the drawn waves' statistics (χ²), the fade's bound between consecutive frames, and
//! the height query's inversion of the horizontal displacement.

use std::f64::consts::{PI, TAU};

use ocean_core::dispersion::Dispersion;
use ocean_core::rng::SplitMix64;
use ocean_core::scene::{Scene, SceneError, SceneSource};
use ocean_core::waves::gerstner::{ActiveWave, Gerstner, GerstnerSea, GerstnerWave};

const G: f64 = 9.81;

fn scene(text: &str) -> Scene {
    Scene::from_toml(text, SceneSource::Text).expect("valid scene")
}

/// The sea of a scene at time t, as the renderer will build it.
fn sea_of(s: &Scene, t: f64) -> GerstnerSea {
    s.gerstner.at(t, &s.ocean.dispersion().expect("dispersion"), s.ocean.wind_direction_deg)
}

#[test]
fn one_wave_is_its_closed_form_at_random_points_and_times() {
    let mut rng = SplitMix64::new(42);
    let mut u = || rng.next_open_closed();
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let (a, lambda) = (0.05 + 2.0 * u(), 2.0 + 150.0 * u());
        let (dir_deg, s, phi) = (360.0 * u() - 180.0, u(), TAU * u());
        let text = format!(
            "[[gerstner.waves]]\namplitude_m = {a}\nwavelength_m = {lambda}\n\
             direction_deg = {dir_deg}\nsteepness = {s}\nphase = {phi}\n"
        );
        let sc = scene(&text);
        let (x, z, t) = (2000.0 * u() - 1000.0, 2000.0 * u() - 1000.0, 500.0 * u());
        let f = sea_of(&sc, t).sample(x, z);
        // The closed form, written out here: deep water ω = √(g k).
        let k = TAU / lambda;
        let (dx, dz) = (dir_deg.to_radians().cos(), dir_deg.to_radians().sin());
        let theta = k * (dx * x + dz * z) - (G * k).sqrt() * t + phi;
        let (sin, cos) = theta.sin_cos();
        let q = s / k;
        let want = [
            (f.height, a * sin),
            (f.disp_x, q * dx * cos),
            (f.disp_z, q * dz * cos),
            (f.slope_x, a * k * dx * cos),
            (f.slope_z, a * k * dz * cos),
            (
                f.jacobian,
                (1.0 - s * dx * dx * sin) * (1.0 - s * dz * dz * sin) - (s * dx * dz * sin).powi(2),
            ),
        ];
        for (got, w) in want {
            worst = worst.max((got - w).abs());
        }
    }
    println!("one wave vs its closed form: worst |Δ| {worst:.1e}");
    // θ of 1e3 rad in f64: a few 1e-13 of phase.
    assert!(worst < 1e-9, "{worst}");
}

#[test]
fn slopes_and_jacobian_are_the_derivatives_of_the_surface() {
    let sc = scene(
        "[ocean]\nwind_direction_deg = 30.0\n[gerstner]\ncount = 24\nchoppiness = 0.8\n\
         median_wavelength_m = 20.0\nmedian_amplitude_m = 0.4\n",
    );
    let sea = sea_of(&sc, 37.0);
    let mut rng = SplitMix64::new(3);
    let (mut worst_slope, mut worst_j) = (0.0f64, 0.0f64);
    let e = 1e-5;
    for _ in 0..500 {
        let (x, z) =
            (400.0 * rng.next_open_closed() - 200.0, 400.0 * rng.next_open_closed() - 200.0);
        let f = sea.sample(x, z);
        let (fx, bx) = (sea.sample(x + e, z), sea.sample(x - e, z));
        let (fz, bz) = (sea.sample(x, z + e), sea.sample(x, z - e));
        let hx = (fx.height - bx.height) / (2.0 * e);
        let hz = (fz.height - bz.height) / (2.0 * e);
        worst_slope = worst_slope.max((hx - f.slope_x).abs()).max((hz - f.slope_z).abs());
        // J of the map (x, z) ↦ (x + Dx, z + Dz) by central differences.
        let a = 1.0 + (fx.disp_x - bx.disp_x) / (2.0 * e);
        let b = (fz.disp_x - bz.disp_x) / (2.0 * e);
        let c = (fx.disp_z - bx.disp_z) / (2.0 * e);
        let d = 1.0 + (fz.disp_z - bz.disp_z) / (2.0 * e);
        worst_j = worst_j.max((a * d - b * c - f.jacobian).abs());
    }
    println!("analytic vs central differences: slopes {worst_slope:.1e}, Jacobian {worst_j:.1e}");
    assert!(worst_slope < 1e-6 && worst_j < 1e-6, "{worst_slope} {worst_j}");
}

#[test]
fn a_wave_travels_at_the_phase_speed_of_the_scenes_dispersion() {
    // Finite depth 5 m: c = √(g tanh(k d)/k), slower than deep water's √(g/k).
    for (depth, lambda) in [("inf", 30.0), ("5.0", 30.0), ("2.0", 60.0)] {
        let sc = scene(&format!(
            "[ocean]\ndepth_m = {depth}\n[[gerstner.waves]]\namplitude_m = 0.5\n\
             wavelength_m = {lambda}\ndirection_deg = 40.0\nsteepness = 0.5\n"
        ));
        let k = TAU / lambda;
        let d: f64 = depth.parse().unwrap_or(f64::INFINITY);
        let c = if d.is_finite() { (G * (k * d).tanh() / k).sqrt() } else { (G / k).sqrt() };
        let dir = 40f64.to_radians();
        let t = 7.3;
        let (s0, s1) = (sea_of(&sc, 0.0), sea_of(&sc, t));
        let mut worst: f64 = 0.0;
        for i in 0..50 {
            let (x, z) = (i as f64 * 1.7, i as f64 * -0.9);
            let now = s1.sample(x, z).height;
            let then = s0.sample(x - c * t * dir.cos(), z - c * t * dir.sin()).height;
            worst = worst.max((now - then).abs());
        }
        println!("depth {depth}: c = {c:.4} m/s, worst |h(x, t) − h(x − c t D, 0)| {worst:.1e}");
        assert!(worst < 1e-9, "depth {depth}: {worst}");
        // Negative control: deep water's speed is wrong at finite depth.
        if d.is_finite() {
            let c_deep = (G / k).sqrt();
            let off = (0..50)
                .map(|i| {
                    let (x, z) = (i as f64 * 1.7, i as f64 * -0.9);
                    let then = s0.sample(x - c_deep * t * dir.cos(), z - c_deep * t * dir.sin());
                    (s1.sample(x, z).height - then.height).abs()
                })
                .fold(0.0, f64::max);
            assert!(off > 0.01, "depth {depth}: {off}");
        }
    }
}

/// χ² of `values` in [lo, hi) against the uniform distribution over `bins` bins.
fn chi2_uniform(values: &[f64], lo: f64, hi: f64, bins: usize) -> f64 {
    let mut count = vec![0usize; bins];
    for v in values {
        assert!((lo..hi).contains(v), "{v} outside [{lo}, {hi})");
        count[(((v - lo) / (hi - lo)) * bins as f64) as usize] += 1;
    }
    let expected = values.len() as f64 / bins as f64;
    count.iter().map(|&c| (c as f64 - expected).powi(2) / expected).sum()
}

#[test]
fn drawn_waves_follow_the_seeds_distributions() {
    let g = Gerstner {
        count: 64,
        median_wavelength_m: 20.0,
        median_amplitude_m: 0.5,
        spread_deg: 135.0,
        choppiness: 0.6,
        min_lifetime_s: 10.0,
        max_lifetime_s: 40.0,
        seed: 9,
        ..Gerstner::default()
    };
    let wind = 25.0;
    let (mut ratio, mut dir, mut steep, mut life, mut phase) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    // 64 slots × 400 instants 37 s apart: each instant meets new generations.
    for step in 0..400 {
        let t = -5000.0 + 37.0 * step as f64;
        for slot in 0..g.count {
            let w = g.drawn(slot, t, wind);
            ratio.push(w.wavelength_m / g.median_wavelength_m);
            assert!((w.amplitude_m / g.median_amplitude_m - ratio.last().unwrap()).abs() < 1e-12);
            dir.push(w.direction.to_degrees() - wind);
            steep.push(w.steepness);
            phase.push(w.phase);
            if step == 0 {
                life.push(w.lifetime_s);
            }
            assert!((0.0..=1.0).contains(&w.weight));
        }
    }
    // 9 degrees of freedom: χ² > 27.9 has probability 0.001.
    let chi = [
        ("ratio", chi2_uniform(&ratio, 0.5, 2.0, 10)),
        ("direction", chi2_uniform(&dir, -135.0, 135.0, 10)),
        ("steepness", chi2_uniform(&steep, 0.95 * 0.6 - 0.05, 0.95 * 0.6 + 0.05, 10)),
        ("phase", chi2_uniform(&phase, 0.0, TAU, 10)),
    ];
    println!("χ² (9 dof) of 25600 draws: {chi:?}");
    for (name, c) in chi {
        assert!(c < 27.9, "{name}: χ² = {c}");
    }
    assert!(life.iter().all(|l| (10.0..40.0).contains(l)));
    // Negative control: the seed's comment (amplitude 0.5–1.5 × median) is not what it draws.
    assert!(
        chi2_uniform(&ratio.iter().map(|r| r.min(1.4999)).collect::<Vec<_>>(), 0.5, 1.5, 10)
            > 100.0
    );
}

/// |d/dt| of slot `i`'s height and horizontal displacement at most: A(π/L + ω) and
/// (s/(k n))(π/L + ω), n the slots (the steepness each wave gets).
fn slot_bound(g: &Gerstner, i: u32, t: f64, wind: f64) -> (f64, f64) {
    let w = g.drawn(i, t, wind);
    let k = TAU / w.wavelength_m;
    let rate = PI / w.lifetime_s + (G * k).sqrt();
    (w.amplitude_m * rate, w.steepness / (k * f64::from(g.count)) * rate)
}

/// The bound summed over the slots.
fn fade_bound(g: &Gerstner, t: f64, wind: f64) -> (f64, f64) {
    (0..g.count).fold((0.0, 0.0), |(v, h), i| {
        let (a, b) = slot_bound(g, i, t, wind);
        (v + a, h + b)
    })
}

#[test]
fn fading_never_moves_the_surface_more_than_its_bound_between_frames() {
    let sc = scene(
        "[gerstner]\ncount = 12\nmin_lifetime_s = 2.0\nmax_lifetime_s = 5.0\nchoppiness = 0.9\n\
         median_amplitude_m = 0.6\n",
    );
    let g = &sc.gerstner;
    let dt = 1.0 / 30.0;
    let wind = sc.ocean.wind_direction_deg;
    let mut worst_ratio: f64 = 0.0;
    let mut handovers = 0;
    for frame in 0..600 {
        let t = frame as f64 * dt;
        let (a, b) = (sea_of(&sc, t), sea_of(&sc, t + dt));
        // Bounds at both ends (a generation may hand over inside the frame).
        let (v0, h0) = fade_bound(g, t, wind);
        let (v1, h1) = fade_bound(g, t + dt, wind);
        let (bv, bh) = (v0.max(v1) * dt, h0.max(h1) * dt);
        handovers += (0..g.count)
            .filter(|&i| g.drawn(i, t, wind).phase != g.drawn(i, t + dt, wind).phase)
            .count();
        for p in 0..40 {
            let (x, z) = (p as f64 * 3.1 - 60.0, p as f64 * -2.3 + 20.0);
            let (fa, fb) = (a.sample(x, z), b.sample(x, z));
            let dv = (fb.height - fa.height).abs();
            let dh = (fb.disp_x - fa.disp_x).hypot(fb.disp_z - fa.disp_z);
            // Second-order slack: the rates change within a frame.
            worst_ratio = worst_ratio.max(dv / (bv * 1.05)).max(dh / (bh * 1.05));
        }
    }
    println!(
        "fade: {handovers} generations handed over in 20 s, worst change / bound {worst_ratio:.3}"
    );
    assert!(handovers > 30, "{handovers}");
    assert!(worst_ratio <= 1.0, "{worst_ratio}");
    // Negative control: without the fade, a handover jumps the surface far past the bound.
    let slot = 0;
    let mut t = 0.0;
    while g.drawn(slot, t, wind).phase == g.drawn(slot, t + dt, wind).phase {
        t += dt;
    }
    let unfaded = |t: f64| {
        let w = g.drawn(slot, t, wind);
        let k = TAU / w.wavelength_m;
        let d = w.direction;
        GerstnerSea {
            waves: vec![ActiveWave {
                kx: k * d.cos(),
                kz: k * d.sin(),
                k,
                amplitude_m: w.amplitude_m,
                steepness: w.steepness,
                theta0: (w.phase - (G * k).sqrt() * t).rem_euclid(TAU),
            }],
        }
    };
    let jump = (0..40)
        .map(|p| {
            let x = p as f64 * 3.1;
            (unfaded(t + dt).sample(x, 0.0).height - unfaded(t).sample(x, 0.0).height).abs()
        })
        .fold(0.0, f64::max);
    let (v, _) = slot_bound(g, slot, t, wind);
    println!(
        "  negative control: an unfaded handover moves the surface {jump:.3} m (bound {:.4} m)",
        v * dt
    );
    assert!(jump > 3.0 * v * dt, "{jump}");
}

#[test]
fn the_height_query_finds_the_displaced_point() {
    let sc = scene(
        "[gerstner]\ncount = 20\nchoppiness = 0.7\nmedian_amplitude_m = 0.5\n\
         median_wavelength_m = 18.0\n",
    );
    let sea = sea_of(&sc, 12.5);
    let mut rng = SplitMix64::new(77);
    let (mut worst, mut naive): (f64, f64) = (0.0, 0.0);
    for _ in 0..2000 {
        let (x, z) = (1e4 * rng.next_open_closed(), -1e4 * rng.next_open_closed());
        let inv = sea.invert(x, z);
        let s = sea.sample(inv.x0, inv.z0);
        let miss = (inv.x0 + s.disp_x - x).hypot(inv.z0 + s.disp_z - z);
        worst = worst.max(miss);
        assert!(inv.converged, "({x}, {z}): residual {}", inv.residual_m);
        assert_eq!(sea.height_at(x, z), inv.sample.height);
        naive = naive.max((sea.sample(x, z).height - inv.sample.height).abs());
    }
    println!(
        "height query: worst |x0 + D(x0) − x| {worst:.1e} m; h(x) itself off by up to {naive:.3} m"
    );
    assert!(worst < 1e-5, "{worst}");
    assert!(naive > 0.05, "the horizontal displacement must matter here: {naive}");
}

#[test]
fn explicit_waves_parse_and_bad_ones_name_their_key() {
    let s = scene(
        "[[gerstner.waves]]\namplitude_m = 1.0\nwavelength_m = 40.0\n\
         [[gerstner.waves]]\namplitude_m = 0.2\nwavelength_m = 9.0\ndirection_deg = 90.0\nsteepness = 0.3\n",
    );
    assert_eq!(s.gerstner.waves.len(), 2);
    assert_eq!(
        s.gerstner.waves[1],
        GerstnerWave {
            amplitude_m: 0.2,
            wavelength_m: 9.0,
            direction_deg: 90.0,
            steepness: 0.3,
            phase: 0.0
        }
    );
    assert_eq!(s.gerstner.wave_count(), 2);
    let bad = |text: &str, key: &str, line: usize| match Scene::from_toml(text, SceneSource::Text) {
        Err(SceneError::Invalid { key: Some(k), line: l, .. }) => {
            assert_eq!((k.as_str(), l), (key, line), "{text}");
        }
        other => panic!("{text}: expected an error at {key}, got {other:?}"),
    };
    bad(
        "[[gerstner.waves]]\namplitude_m = 1.0\nwavelength_m = 40.0\n\
         [[gerstner.waves]]\namplitude_m = 0.2\nwavelength_m = 9.0\nsteepness = 1.5\n",
        "gerstner.waves.1.steepness",
        7,
    );
    bad("[gerstner]\nmin_lifetime_s = 50.0\nmax_lifetime_s = 10.0\n", "gerstner.max_lifetime_s", 3);
    bad("[gerstner]\ncount = 65\n", "gerstner.count", 2);
    bad("[[gerstner.waves]]\namplitude_m = 1.0\n", "gerstner.waves.0", 1);
}

#[test]
fn extreme_seas_stay_finite_and_the_drawn_sea_never_loops() {
    let d = Dispersion::deep(G);
    let mut worst_j = f64::MAX;
    for (choppiness, count) in [(1.0, 1u32), (1.0, 64), (0.0, 64), (0.5, 0)] {
        let g = Gerstner {
            count,
            choppiness,
            min_lifetime_s: 0.01,
            max_lifetime_s: 1e6,
            ..Gerstner::default()
        };
        for t in [0.0, -1e15, 1e15, 3.7e9, f64::MIN_POSITIVE] {
            let sea = g.at(t, &d, 400.0);
            for p in 0..200 {
                let (x, z) = (p as f64 * 1.37e3 - 1e5, p as f64 * -7.1 + 1e7);
                let f = sea.sample(x, z);
                let all = [f.height, f.disp_x, f.disp_z, f.slope_x, f.slope_z, f.jacobian];
                assert!(all.iter().all(|v| v.is_finite()), "t {t} ({x}, {z}): {f:?}");
                worst_j = worst_j.min(f.jacobian);
                assert!(sea.height_at(x, z).is_finite());
            }
        }
    }
    println!("drawn seas at choppiness up to 1: least J {worst_j:.4}");
    assert!(worst_j >= -1e-12, "{worst_j}");
    // The largest explicit waves the limits allow.
    let w = GerstnerWave {
        amplitude_m: 1e3,
        wavelength_m: 0.01,
        direction_deg: -360.0,
        steepness: 1.0,
        phase: -1e3,
    };
    let g = Gerstner { waves: vec![w; 64], ..Gerstner::default() };
    let sea = g.at(1e12, &Dispersion::new(G, 0.01, 0.0).expect("shallow"), 0.0);
    let f = sea.sample(1e7, -1e7);
    assert!([f.height, f.disp_x, f.jacobian].iter().all(|v| v.is_finite()), "{f:?}");
    assert!(sea.height_at(3.0, 4.0).is_finite());
}
