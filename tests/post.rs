//! Stage `post` beyond the ACES tonemap (`tests/tonemap.rs`): Hable's filmic curve, the
//! vignette and the `[post]` keys. The closed forms here are typed from the sources in f64,
//! independently of `ocean_core::tonemap`; every comparator has a negative control.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use ocean_core::scene::{Post, Scene, SceneSource};
use ocean_core::tonemap::{Curve, HABLE_WHITE_SCALE, TonemapUniforms};
use ocean_cpu::shaders::tonemap::{
    HdrFrame, aces_narkowicz, cs_main, hable, store_unorm8, tone_curve, tonemap_to_rgba8,
    vignette_factor,
};
use ocean_cpu::shaders::wgsl::Vec3;

/// Hable, "Filmic Tonemapping Operators" (2010): A = 0.15, B = 0.50, C = 0.10, D = 0.20,
/// E = 0.02, F = 0.30, W = 11.2; g(x) = ((x(Ax+CB)+DE)/(x(Ax+B)+DF)) − E/F; typed from the
/// post, in f64.
fn hable_g(x: f64) -> f64 {
    let (a, b, c, d, e, f) = (0.15, 0.50, 0.10, 0.20, 0.02, 0.30);
    ((x * (a * x + c * b) + d * e) / (x * (a * x + b) + d * f)) - e / f
}

/// The normalised curve f(x) = g(x)/g(W), f64.
fn hable_f64(x: f64) -> f64 {
    hable_g(x) / hable_g(11.2)
}

/// Narkowicz's ACES fit in f64 (as tests/tonemap.rs types it).
fn aces_f64(x: f64) -> f64 {
    (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)
}

fn curve_f32(curve: Curve, x: f32) -> f32 {
    let u = TonemapUniforms { curve: curve.index(), ..TonemapUniforms::DEFAULT };
    tone_curve(Vec3::splat(x), &u).x
}

/// Inputs over [0, 10⁴]: 0, then a log sweep from 10⁻⁶ with 400,000 points, then the white
/// points.
fn sweep() -> Vec<f32> {
    let mut v: Vec<f32> = vec![0.0];
    v.extend((0..=400_000).map(|i| 10f32.powf(-6.0 + 10.0 * i as f32 / 400_000.0)));
    v
}

/// The first place a sampled curve (after the stage's clamp to [0, 1]) decreases, if any.
fn first_decrease(f: &dyn Fn(f32) -> f32, xs: &[f32]) -> Option<(f32, f32, f32)> {
    let ys: Vec<f32> = xs.iter().map(|&x| f(x).clamp(0.0, 1.0)).collect();
    (1..xs.len()).find(|&i| ys[i] < ys[i - 1]).map(|i| (xs[i], ys[i - 1], ys[i]))
}

#[test]
fn hable_matches_the_published_closed_form() {
    let mut worst = 0.0f64;
    for x in sweep() {
        let got = f64::from(hable(Vec3::splat(x)).x);
        worst = worst.max((got - hable_f64(f64::from(x))).abs());
    }
    println!("Hable, f32 rearranged vs f64 published: max abs error {worst:.2e}");
    // Outputs ≤ 1.29: a few f32 ULP (1.2e-7 each near 1).
    assert!(worst < 5e-7, "{worst}");
    // The white point maps to 1 and the shader's factor is 1/g(W) of the published form.
    assert_eq!(HABLE_WHITE_SCALE, (1.0 / hable_g(11.2)) as f32);
    let at_w = f64::from(hable(Vec3::splat(11.2)).x);
    println!("Hable f32 at W = 11.2: {at_w} (f64 {})", hable_f64(11.2));
    assert!((at_w - 1.0).abs() < 3e-7, "{at_w}");
    // Negative controls: without the normalisation W maps to g(W) ≈ 0.725; with Hable's
    // constants A and B swapped the curve is another one.
    assert!((hable_g(11.2) - 1.0).abs() > 0.2);
    let swapped = |x: f64| {
        let (a, b, c, d, e, f) = (0.50, 0.15, 0.10, 0.20, 0.02, 0.30);
        ((x * (a * x + c * b) + d * e) / (x * (a * x + b) + d * f)) - e / f
    };
    assert!((swapped(1.0) / swapped(11.2) - f64::from(hable(Vec3::splat(1.0)).x)).abs() > 0.01);
}

#[test]
fn both_curves_are_zero_at_zero_and_monotone_up_to_ten_thousand() {
    let xs = sweep();
    for curve in [Curve::Aces, Curve::Hable] {
        assert_eq!(curve_f32(curve, 0.0), 0.0, "{curve:?} at 0");
        let d = first_decrease(&|x| curve_f32(curve, x), &xs);
        assert_eq!(d, None, "{curve:?} decreases");
        // White at the top of the range.
        assert_eq!(curve_f32(curve, 1.0e4).clamp(0.0, 1.0), 1.0);
    }
    // In f64 too, strictly, on [0, 10⁴] in steps of 0.1.
    let f: Vec<f64> = (0..=100_000).map(|i| hable_f64(f64::from(i) * 0.1)).collect();
    assert!(f.windows(2).all(|w| w[1] > w[0]));
    assert!(hable_f64(0.0).abs() < 1e-17);
    // Negative control: the same check catches a curve that is not monotone (x e^(1 − x),
    // which peaks at 1 at x = 1), and one that steps down by a single ULP at one sample
    // (x = 0.1) below its neighbour's value.
    assert!(first_decrease(&|x| x * (1.0 - x).exp(), &xs).is_some());
    let stepped = |x: f32| {
        if x == xs[200_000] {
            f32::from_bits(curve_f32(Curve::Hable, xs[199_999]).to_bits() - 1)
        } else {
            curve_f32(Curve::Hable, x)
        }
    };
    assert!(first_decrease(&stepped, &xs).is_some());
    // The curves differ (the selector works): at x = 1 ACES gives 0.80, Hable 0.42.
    let (a, h) = (curve_f32(Curve::Aces, 1.0), curve_f32(Curve::Hable, 1.0));
    assert!((f64::from(a) - aces_f64(1.0)).abs() < 1e-6 && (a - h).abs() > 0.3, "{a} {h}");
}

/// The published form evaluated in f32 leaves a residue at 0 (two E/F terms that do not
/// cancel exactly), which is why the shader evaluates the rearranged form.
#[test]
fn the_rearranged_form_is_exact_at_zero() {
    let (d, e, f) = (0.20f32, 0.02f32, 0.30f32);
    let published_at_0 = (d * e) / (d * f) - e / f;
    println!("Hable's published form in f32 at 0: {published_at_0:e}");
    // Negative control: the published form is not 0 at 0 in f32.
    assert_ne!(published_at_0, 0.0);
    assert_eq!(hable(Vec3::splat(0.0)).x, 0.0);
    assert_eq!(aces_narkowicz(Vec3::splat(0.0)).x, 0.0);
}

fn uniforms(curve: Curve, vignette: f64, w: u32, h: u32) -> TonemapUniforms {
    TonemapUniforms::for_image(1.0, &Post { curve, vignette, ..Post::default() }, w, h).unwrap()
}

#[test]
fn vignette_is_one_at_the_centre_and_its_formula_at_the_corners() {
    // Odd sides: the centre pixel's centre is the image's centre.
    let (w, h) = (65u32, 37u32);
    let s = 0.7;
    let u = uniforms(Curve::Aces, s, w, h);
    let at = |x: u32, y: u32| vignette_factor([x as f32 + 0.5, y as f32 + 0.5].into(), &u);
    assert_eq!(at(32, 18), 1.0);
    let (cx, cy) = (f64::from(w) / 2.0, f64::from(h) / 2.0);
    let formula = |x: u32, y: u32| {
        let (dx, dy) = (f64::from(x) + 0.5 - cx, f64::from(y) + 0.5 - cy);
        1.0 - s * (dx * dx + dy * dy) / (cx * cx + cy * cy)
    };
    let mut worst = 0.0f64;
    for (x, y) in [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1), (5, 30), (64, 18), (32, 0)] {
        let err = (f64::from(at(x, y)) - formula(x, y)).abs();
        worst = worst.max(err);
        assert!(err < 1e-6, "({x}, {y}): {} vs {}", at(x, y), formula(x, y));
    }
    println!(
        "vignette 0.7 at the corner pixel: {} (f64 {}), max error {worst:.1e}",
        at(0, 0),
        formula(0, 0)
    );
    // At the corner pixel r² = 0.95 here (its centre is half a pixel inside the corner).
    assert!((formula(0, 0) - (1.0 - s)).abs() < 0.03);
    // Symmetric about the centre: the four corners are equal bits.
    assert!(at(0, 0) == at(w - 1, 0) && at(0, 0) == at(0, h - 1) && at(0, 0) == at(w - 1, h - 1));
    // Negative control: r normalised to the half height instead of the half diagonal is
    // caught at the corner.
    let wrong = 1.0 - s * ((f64::from(w) / 2.0 - 0.5).powi(2) + (cy - 0.5).powi(2)) / (cy * cy);
    assert!((f64::from(at(0, 0)) - wrong).abs() > 1e-6);
    // Strength 1 at the far corner is never negative (the clamp at 0).
    let u1 = uniforms(Curve::Aces, 1.0, 1, 1);
    assert!(vignette_factor([0.0, 0.0].into(), &u1) >= 0.0);
}

#[test]
fn vignette_darkens_the_frame_by_its_factor_and_zero_strength_changes_no_bit() {
    let (w, h) = (41u32, 23u32);
    let hdr: Vec<[f32; 4]> = (0..w * h)
        .map(|i| {
            let t = i as f32 / (w * h) as f32;
            [t * 8.0, 0.3, 1.0 - t, 1.0]
        })
        .collect();
    for curve in [Curve::Aces, Curve::Hable] {
        let plain = TonemapUniforms { curve: curve.index(), ..TonemapUniforms::DEFAULT };
        let base = tonemap_to_rgba8(&hdr, w, h, &plain);
        assert_eq!(base, tonemap_to_rgba8(&hdr, w, h, &uniforms(curve, 0.0, w, h)));
        let dark = tonemap_to_rgba8(&hdr, w, h, &uniforms(curve, 0.5, w, h));
        let centre = 4 * (11 * w + 20) as usize;
        assert_eq!(base[centre..centre + 4], dark[centre..centre + 4], "{curve:?}");
        // Every channel of every pixel: never brighter, and the corner darker.
        assert!(base.iter().zip(&dark).all(|(b, d)| d <= b));
        assert!(dark[4] < base[4] && dark[2] < base[2], "{curve:?}");
        // The corner pixel's byte equals the f64 pipeline at hdr · (1 − s r²) within one step.
        let (cx, cy) = (f64::from(w) / 2.0, f64::from(h) / 2.0);
        let v = 1.0 - 0.5 * ((0.5 - cx).powi(2) + (0.5 - cy).powi(2)) / (cx * cx + cy * cy);
        let f = |x: f64| match curve {
            Curve::Aces => aces_f64(x),
            Curve::Hable => hable_f64(x),
        };
        let srgb =
            |l: f64| if l <= 0.0031308 { 12.92 * l } else { 1.055 * l.powf(1.0 / 2.4) - 0.055 };
        let want = (srgb(f(f64::from(hdr[0][2]) * v).min(1.0)) * 255.0).round_ties_even() as u8;
        assert!(dark[2].abs_diff(want) <= 1, "{curve:?}: {} vs {want}", dark[2]);
        // Negative control: without the vignette the corner byte is another.
        assert!(base[2].abs_diff(want) > 1, "{curve:?}");
    }
}

#[test]
fn extreme_inputs_give_documented_outputs_with_both_curves_and_a_vignette() {
    for curve in [Curve::Aces, Curve::Hable] {
        let u = uniforms(curve, 1.0, 3, 3);
        for (hdr, want) in [
            (f32::NAN, 0u8),
            (f32::NEG_INFINITY, 0),
            (-5.0, 0),
            (0.0, 0),
            (65504.0, 255),
            (f32::INFINITY, 255),
            (f32::MAX, 255),
        ] {
            let texels = [[hdr; 4]; 9];
            let frame = HdrFrame { width: 3, height: 3, texels: &texels };
            // The centre pixel (factor 1) and a corner (factor 1 − 8/9·… > 0).
            for (x, y) in [(1u32, 1u32), (0, 0)] {
                let px = cs_main([x, y], &u, &frame);
                assert!(px.iter().all(|c| c.is_finite()), "{curve:?} {hdr}: {px:?}");
                assert_eq!(store_unorm8(px[0]), want, "{curve:?} {hdr} at ({x}, {y})");
            }
        }
    }
}

#[test]
fn post_keys_are_parsed_validated_and_named_in_errors() {
    let s = Scene::from_toml("[post]\ncurve = \"hable\"\nvignette = 0.25\n", SceneSource::Text)
        .unwrap();
    assert_eq!((s.post.curve, s.post.vignette), (Curve::Hable, 0.25));
    let d = Scene::from_toml("", SceneSource::Text).unwrap();
    assert_eq!((d.post.curve, d.post.vignette), (Curve::Aces, 0.0));
    for (text, key, line) in [
        ("[post]\nvignette = 1.5\n", "post.vignette", 2),
        ("[post]\nvignette = -0.1\n", "post.vignette", 2),
        ("[post]\n\ncurve = \"reinhard\"\n", "post.curve", 3),
        ("[post]\nexposure = 2.0\n", "post.exposure", 2),
    ] {
        let e = Scene::from_toml(text, SceneSource::Text).unwrap_err().to_string();
        assert!(e.contains(&format!(":{line}:")), "{text}: {e}");
        assert!(e.contains(key) || e.contains(key.rsplit('.').next().unwrap()), "{text}: {e}");
        println!("{e}");
    }
    // The uniforms refuse what validation refuses (a vignette beyond 1).
    let bad = Post { vignette: 1.5, ..Post::default() };
    assert!(TonemapUniforms::for_image(1.0, &bad, 4, 4).is_err());
}

// ---------------------------------------------------------------------------------------
// Post technique `bloom` (ocean_core::bloom): the pyramid's energy, its symmetry, what it
// leaves alone, on the CPU mirror (the GPU's chains are held to it by the cross-check).

use ocean_core::graph::BloomInputs;
use ocean_core::plan::{FramePlan, OutputKind, Pass, ResourceId};
use ocean_cpu::sampler::Texture2D;
use ocean_cpu::shaders::bloom;

/// A scene whose frame is `w` × `h` with the given bloom keys (exposure 1).
fn bloom_scene(w: u32, h: u32, threshold: f64, levels: u32) -> Scene {
    let mut s = Scene::default();
    (s.camera.width, s.camera.height, s.camera.exposure) = (w, h, 1.0);
    s.post.bloom_threshold = threshold;
    s.post.bloom_levels = levels;
    s
}

/// The bloom the tonemap adds at every pixel, before × strength: up(u_0) / L (f64 sums of
/// the f32 values).
fn full_bloom(hdr: &Texture2D, inputs: &BloomInputs) -> Vec<[f64; 3]> {
    let (_, up) = bloom::dispatch(hdr, inputs);
    let glow = bloom::level0(&up);
    let l = inputs.levels.len() as f64;
    (0..hdr.height as i32)
        .flat_map(|y| (0..hdr.width as i32).map(move |x| (x, y)))
        .map(|(x, y)| {
            let v = bloom::upsample_at(&glow, [x, y]);
            [f64::from(v.x) / l, f64::from(v.y) / l, f64::from(v.z) / l]
        })
        .collect()
}

fn frame(w: u32, h: u32, lit: &[(u32, u32, [f32; 3])]) -> Texture2D {
    let mut t = vec![[0.0f32; 4]; (w * h) as usize];
    for &(x, y, c) in lit {
        t[(y * w + x) as usize] = [c[0], c[1], c[2], 1.0];
    }
    Texture2D::new(w, h, t)
}

/// Σ of a channel of the bright pass over the frame, f64.
fn bright_sum(hdr: &Texture2D, inputs: &BloomInputs) -> [f64; 3] {
    let mut s = [0.0; 3];
    for t in &hdr.texels {
        let b = bloom::bright([t[0], t[1], t[2]].into(), &inputs.down[0]);
        for (c, v) in s.iter_mut().zip([b.x, b.y, b.z]) {
            *c += f64::from(v);
        }
    }
    s
}

fn relative_energy_error(bloom: &[[f64; 3]], want: [f64; 3]) -> f64 {
    (0..3)
        .map(|c| {
            let got: f64 = bloom.iter().map(|p| p[c]).sum();
            ((got - want[c]) / want[c]).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn the_pyramid_keeps_the_bright_pass_energy() {
    // 128 × 64, five levels (64×32 down to 4×2: every side even), bright texels inside, on
    // the border and in a corner; the threshold 1 cuts a part of each.
    let scene = bloom_scene(128, 64, 1.0, 5);
    let inputs = BloomInputs::new(&scene);
    assert_eq!(inputs.levels, [[64, 32], [32, 16], [16, 8], [8, 4], [4, 2]]);
    let hdr = frame(
        128,
        64,
        &[
            (40, 20, [50.0, 30.0, 10.0]),
            (41, 20, [2.0, 1.5, 0.5]),
            (90, 45, [500.0, 400.0, 300.0]),
            (0, 31, [20.0, 20.0, 20.0]),
            (127, 63, [8.0, 4.0, 2.0]),
        ],
    );
    let want = bright_sum(&hdr, &inputs);
    let b = full_bloom(&hdr, &inputs);
    let err = relative_energy_error(&b, want);
    println!("bloom energy: Σ bright pass {want:?}, relative error of Σ bloom {err:.2e}");
    // f32 sums of up to 5 levels × 16 weighted taps: a few ULP of the texels' values.
    assert!(err < 1e-6, "{err}");
    // Negative controls: without the division by L the light is 5×; a pyramid that keeps
    // 0.1 % too much is caught.
    let unnormalised: Vec<[f64; 3]> = b.iter().map(|p| p.map(|v| v * 5.0)).collect();
    assert!(relative_energy_error(&unnormalised, want) > 3.9);
    let leaky: Vec<[f64; 3]> = b.iter().map(|p| p.map(|v| v * 1.001)).collect();
    assert!(relative_energy_error(&leaky, want) > 9e-4);
    // Below the threshold nothing blooms: the chains are zero.
    let dim = frame(128, 64, &[(40, 20, [0.99, 0.5, 1.0])]);
    assert!(full_bloom(&dim, &inputs).iter().all(|p| *p == [0.0; 3]));
}

#[test]
fn a_centred_block_spreads_symmetrically_and_a_pixel_mirrors() {
    let (w, h) = (64u32, 64u32);
    let scene = bloom_scene(w, h, 0.0, 5);
    let inputs = BloomInputs::new(&scene);
    // A 2×2 block on the frame's centre: the pyramid's grid is symmetric about it.
    let c = [10.0f32, 5.0, 1.0];
    let block = frame(w, h, &[(31, 31, c), (32, 31, c), (31, 32, c), (32, 32, c)]);
    let b = full_bloom(&block, &inputs);
    let at = |x: u32, y: u32| b[(y * w + x) as usize][0];
    let peak = at(32, 32);
    let mut worst = 0.0f64;
    for y in 0..h {
        for x in 0..w {
            for other in [at(w - 1 - x, y), at(x, h - 1 - y), at(y, x)] {
                worst = worst.max((at(x, y) - other).abs() / peak);
            }
        }
    }
    println!("bloom of a centred block: peak {peak:.4}, worst asymmetry {worst:.1e} of it");
    // Mirrored sums add the same terms in the other order: f32 rounding only.
    assert!(worst < 1e-6, "{worst}");
    // It spreads: falling away from the block along a row, and reaching 16 pixels out.
    let row: Vec<f64> = (32..64).map(|x| at(x, 32)).collect();
    assert!(row.windows(2).all(|p| p[1] <= p[0]), "{row:?}");
    assert!(at(48, 32) > 1e-4 * peak);
    // Negative control: the block moved by one pixel is not symmetric about the centre.
    let moved = frame(w, h, &[(32, 31, c), (33, 31, c), (32, 32, c), (33, 32, c)]);
    let m = full_bloom(&moved, &inputs);
    let asym = (0..w)
        .map(|x| (m[(32 * w + x) as usize][0] - m[(32 * w + w - 1 - x) as usize][0]).abs())
        .fold(0.0, f64::max);
    assert!(asym / peak > 1e-3, "{asym}");
    // A single pixel anywhere: its bloom mirrored is the bloom of the mirrored pixel.
    let one = full_bloom(&frame(w, h, &[(20, 9, c)]), &inputs);
    let mirrored = full_bloom(&frame(w, h, &[(w - 1 - 20, 9, c)]), &inputs);
    let p1 = one.iter().map(|p| p[0]).fold(0.0, f64::max);
    let worst = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            (one[(y * w + x) as usize][0] - mirrored[(y * w + w - 1 - x) as usize][0]).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst / p1 < 1e-6, "{worst}");
}

#[test]
fn bloom_off_is_the_tonemap_frame_bit_for_bit() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/reference/scenes/bloom_glitter.toml"
    ))
    .unwrap();
    let mut scene = Scene::from_toml(&text, SceneSource::Text).unwrap();
    (scene.camera.width, scene.camera.height) = (96, 54);
    let render = |s: &Scene, plan: FramePlan| {
        ocean_cpu::render_scene_with_plan(s, plan, &mut |_| {}).unwrap().ldr.unwrap()
    };
    let mut plain = scene.clone();
    plain.techniques.post = Some(ocean_core::plan::Post::Tonemap);
    let reference = render(&plain, FramePlan::new(&plain, OutputKind::Ldr));
    // Strength 0: the plan leaves the pass out, with its reason …
    let mut off = scene.clone();
    off.post.bloom_strength = 0.0;
    let plan = FramePlan::new(&off, OutputKind::Ldr);
    let skipped = plan.skipped.iter().find(|p| p.name == Pass::Bloom).unwrap();
    assert!(skipped.reason.contains("bloom_strength = 0"), "{}", skipped.reason);
    assert_eq!(render(&off, plan), reference);
    // … and the full plan runs it and adds 0 × the pyramid: the same bits.
    let full = FramePlan::full(&off, OutputKind::Ldr);
    assert!(full.runs(Pass::Bloom));
    assert_eq!(render(&off, full), reference);
    // EXR output keeps linear HDR: no bloom pass.
    assert!(!FramePlan::new(&scene, OutputKind::Hdr).runs(Pass::Bloom));
    // Negative control: the scene's own strength changes the picture, only brightening it.
    let bloomed = render(&scene, FramePlan::new(&scene, OutputKind::Ldr));
    let changed = bloomed.iter().zip(&reference).filter(|(a, b)| a != b).count();
    println!("bloom_glitter 96×54: {changed} of {} bytes changed by the bloom", bloomed.len());
    assert!(changed > 100);
    assert!(bloomed.iter().zip(&reference).all(|(a, b)| a >= b));
}

#[test]
fn bloom_of_extreme_frames_stays_finite_and_levels_follow_the_frame() {
    let scene = bloom_scene(33, 17, 0.0, 8);
    let inputs = BloomInputs::new(&scene);
    // 16×8 at level 0: five levels (16, 8, 4, 2, 1 wide), not the eight asked for.
    assert_eq!(inputs.levels.len(), 5);
    assert_eq!(BloomInputs::new(&bloom_scene(1, 1, 1.0, 8)).levels, [[1, 1]]);
    let specials = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, f32::MAX, 65504.0, -1.0, 0.0];
    let texels: Vec<[f32; 4]> = (0..33 * 17)
        .map(|i| {
            let v = specials[i % specials.len()];
            [v, specials[(i + 3) % specials.len()], v, 1.0]
        })
        .collect();
    let hdr = Texture2D::new(33, 17, texels.clone());
    let (down, up) = bloom::dispatch(&hdr, &inputs);
    assert!(
        down.atlas.texels.iter().chain(&up.atlas.texels).all(|t| t.iter().all(|v| v.is_finite()))
    );
    // Through the tonemap at the largest strength: every byte defined.
    let mut u = TonemapUniforms::for_image(1.0, &Post::default(), 33, 17).unwrap();
    u.bloom_scale = (10.0 / inputs.levels.len() as f64) as f32;
    let bytes = ocean_cpu::shaders::tonemap::tonemap_to_rgba8_with_bloom(
        &texels,
        33,
        17,
        &u,
        &bloom::level0(&up),
    );
    // NaN and −∞ texels next to 65504 ones are lit by their neighbours' bloom, never NaN.
    assert!(bytes.chunks(4).all(|p| p[3] == 255));
    assert_eq!(bytes[0], 255, "a 65504 neighbourhood is white");
}

// ---------------------------------------------------------------------------------------
// The `rgba16float` frame buffers (ocean_core::frame_format; system `welch`'s default).

/// Welch's stormy sunset draws its frame with the sky and then the water (no pass reads the
/// frame before the bloom): so the CPU frame in `rgba16float` is exactly the `rgba32float` frame
/// stored through the format, texel by texel, and the bloom chains are the f32 pyramid's
/// arithmetic on it, each texel truncated. The picture moves by at most one 8-bit level.
#[test]
fn the_half_frame_is_the_f32_frame_stored_in_binary16() {
    use ocean_core::frame_format::{FrameFormat, round_to_half};
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/reference/scenes/welch_stormy_sunset.toml"
    ))
    .unwrap();
    let mut scene = Scene::from_toml(&text, SceneSource::Text).unwrap();
    (scene.camera.width, scene.camera.height) = (96, 54);
    assert_eq!(scene.frame_format(), FrameFormat::Rgba16Float, "welch's default");
    let mut wide = scene.clone();
    wide.post.frame_format = Some(FrameFormat::Rgba32Float);
    let render = |s: &Scene| {
        let plan = FramePlan::new(s, OutputKind::Ldr);
        assert_eq!(plan.resource(ResourceId::Hdr).unwrap().format.storage(), s.frame_format());
        ocean_cpu::render_scene_with_plan(s, plan, &mut |_| {}).unwrap()
    };
    let (half, full) = (render(&scene), render(&wide));
    let stored: Vec<[f32; 4]> =
        full.buffers.hdr.color.iter().map(|c| c.map(round_to_half)).collect();
    assert_eq!(half.buffers.hdr.color, stored, "the f16 frame is the f32 frame, truncated");
    // Negative control: rounding to nearest is a different frame (the truncation matters).
    let nearest =
        full.buffers.hdr.color.iter().flatten().zip(half.buffers.hdr.color.iter().flatten());
    let differ = nearest.filter(|(f, h)| half::f16::from_f32(**f).to_f32() != **h).count();
    assert!(differ > 1000, "round-to-nearest differs on {differ} values only");
    // The bloom chains hold binary16 values, and the picture moves by at most one level.
    let chain = |r: &ocean_cpu::Rendered| r.buffers.map(ResourceId::BloomUp).unwrap().2.to_vec();
    assert!(chain(&half).iter().flatten().all(|v| round_to_half(*v) == *v));
    assert!(chain(&full).iter().flatten().any(|v| round_to_half(*v) != *v));
    let (a, b) = (half.ldr.unwrap(), full.ldr.unwrap());
    let max = a.iter().zip(&b).map(|(x, y)| x.abs_diff(*y)).max().unwrap();
    let moved = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    println!(
        "welch_stormy_sunset 96×54: {differ} values round differently to nearest; LDR: {moved} of {} bytes moved, at most {max}",
        a.len()
    );
    assert!(max <= 1, "f16 frame moved a byte by {max}");
}
