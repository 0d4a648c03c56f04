//! The hardware envelope (ocean-cpu `envelope`, docs/tolerances.md): its operations hold
//! every result a conformant GPU may compute, drawn at random ([`Jitter`]) — and a GPU twice
//! as loose leaves them; the `tonemap` pass's envelope holds the random conformant GPUs on the
//! NVIDIA H200's own HDR frames (`reference/hardware/h200`) and the H200's own 8-bit pictures,
//! and a 3 % exposure error leaves it.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use std::path::{Path, PathBuf};

use ocean_core::plan::{FramePlan, OutputKind, ResourceId};
use ocean_core::rng::SplitMix64;
use ocean_core::tonemap::TonemapUniforms;
use ocean_cpu::envelope::{Iv, Jitter, JitterRules, Precision, Real};
use ocean_cpu::shaders::tonemap;

#[path = "support/reference_scenes.rs"]
mod reference_scenes;
use reference_scenes::reference_scenes;

/// Operands over many binades, both signs, and the edges (0, subnormals).
fn operands(n: usize, seed: u64) -> Vec<f32> {
    let mut g = SplitMix64::new(seed);
    let mut v = vec![0.0, -0.0, 1.0, f32::MIN_POSITIVE, 1e-40, 0.0031308, 65504.0];
    while v.len() < n {
        let m = g.next_open_closed() as f32 + 0.5;
        let e = (g.next_u64() % 40) as i32 - 20;
        let s = if g.next_u64() & 1 == 0 { 1.0 } else { -1.0 };
        v.push(s * m * 2f32.powi(e));
    }
    v
}

type Op<R> = fn(R, R) -> R;

/// The binary operations the mirrors use, each in its Iv and its Jitter form.
fn ops() -> Vec<(&'static str, Op<Iv>, Op<Jitter>, bool)> {
    vec![
        ("+", |a, b| a + b, |a, b| a + b, true),
        ("-", |a, b| a - b, |a, b| a - b, true),
        ("*", |a, b| a * b, |a, b| a * b, true),
        ("/", |a, b| a / b, |a, b| a / b, true),
        // pow takes |a| (the mirrors raise values ≥ 0) and the sRGB exponent or |b|.
        ("pow", |a, b| pow_iv(a, b), |a, b| pow_j(a, b), true),
        ("sqrt", |a, _| abs_iv(a).sqrt(), |a, _| Jitter(a.0.abs()).sqrt(), true),
        ("max", |a, b| a.max(b), |a, b| a.max(b), false),
        ("round", |a, _| a.round(), |a, _| a.round(), false),
    ]
}

fn abs_iv(a: Iv) -> Iv {
    Iv::new(a.lo.abs().min(a.hi.abs()), a.magnitude())
}

fn pow_iv(a: Iv, b: Iv) -> Iv {
    let a = Iv::new(a.lo.abs().min(a.hi.abs()), a.magnitude());
    let e = Iv::new(b.lo.abs().min(b.hi.abs()).min(4.0), b.magnitude().min(4.0));
    a.pow(e)
}

fn pow_j(a: Jitter, b: Jitter) -> Jitter {
    Jitter(a.0.abs()).pow(Jitter(b.0.abs().min(4.0)))
}

/// For each op, over pairs of operands and draws: how many results fall outside the op's
/// envelope at `scale`.
fn escapes(scale: f64) -> Vec<(&'static str, usize, usize)> {
    let xs = operands(200, 1);
    let ys = operands(60, 2);
    let mut out = Vec::new();
    for (name, iv, jit, _) in ops() {
        let (mut tried, mut outside) = (0, 0);
        for (i, &a) in xs.iter().enumerate() {
            for (j, &b) in ys.iter().enumerate() {
                let env = iv(Iv::point(a), Iv::point(b));
                for k in 0..4u64 {
                    Jitter::reseed(JitterRules { seed: k, scale }, (i * 1000 + j) as u64);
                    let v = jit(Jitter(a), Jitter(b)).0;
                    tried += 1;
                    if !env.contains(v) {
                        outside += 1;
                    }
                }
            }
        }
        out.push((name, tried, outside));
    }
    out
}

#[test]
fn every_conformant_result_is_inside_and_twice_the_rules_leaves() {
    for (name, tried, outside) in escapes(1.0) {
        println!("{name:>5}: {outside} of {tried} conformant results outside");
        assert_eq!(outside, 0, "{name}: a result within the rules left the envelope");
    }
    // Negative control: an implementation twice as loose leaves the envelope of every
    // rounding operation (exact ones — max, round — have nothing to loosen).
    let loose = escapes(2.0);
    for ((name, tried, outside), (_, _, _, rounds)) in loose.into_iter().zip(ops()) {
        println!("{name:>5}: {outside} of {tried} results of a GPU twice as loose outside");
        if rounds {
            assert!(outside > 0, "{name}: twice the rules never left the envelope");
        }
    }
}

/// Four-term sums, some cancelling, in any order (`Jitter::sum` reassociates at random):
/// how many of `draws` results leave the `Iv` sum's envelope at `scale`.
fn sum_escapes(scale: f64, draws: u64) -> usize {
    let xs = operands(400, 3);
    let mut outside = 0;
    for (i, w) in xs.windows(4).enumerate() {
        // Every other window cancels: its last term is minus the sum of the others, rounded.
        let mut t = [w[0], w[1], w[2], w[3]];
        if i % 2 == 1 {
            t[3] = -(t[0] + t[1] + t[2]);
        }
        let env = Iv::sum(&t.map(Iv::point));
        for k in 0..draws {
            Jitter::reseed(JitterRules { seed: k, scale }, i as u64);
            if !env.contains(Jitter::sum(&t.map(Jitter)).0) {
                outside += 1;
            }
        }
    }
    outside
}

#[test]
fn reassociated_sums_stay_inside_and_twice_the_rules_leaves() {
    assert_eq!(sum_escapes(1.0, 16), 0, "a reassociated sum within the rules left the envelope");
    let loose = sum_escapes(2.0, 16);
    println!("4-term sums, twice the rules: {loose} of {} outside", 397 * 16);
    assert!(loose > 0, "a sum twice as loose as the rules never left the envelope");
}

#[test]
fn undefined_operations_give_a_full_interval() {
    let x = Iv::point(1.0);
    assert!((x / Iv::point(0.0)).full, "÷ 0");
    assert!((x / Iv::point(1e-40)).full, "÷ a subnormal");
    assert!(Iv::point(-1.0).pow(Iv::point(0.5)).full, "pow of a negative");
    assert!(Iv::point(f32::NAN).full, "a NaN");
    assert!((Iv::point(f32::INFINITY) * Iv::point(0.0)).full, "∞ · 0");
    // Overflow may round to ∞; a subnormal result may flush to 0.
    let big = Iv::point(f32::MAX) + Iv::point(f32::MAX);
    assert!(big.full);
    let tiny = Iv::point(1e-20) * Iv::point(1e-20);
    assert!(tiny.contains(0.0));
    // Finite-math assumption: an infinity read, or a result that may overflow, is anything.
    assert!(Iv::point(f32::INFINITY).full && (Iv::point(1e38) * Iv::point(10.0)).full);
    // Subnormal inputs may be flushed; 1e-40 · 1e30 may be 0.
    assert!((Iv::point(1e-40) * Iv::point(1e30)).contains(0.0));
    // atan2 outside the rule's domain (y = 0; x within 2⁻¹²⁶ of 0) is undefined.
    assert!(Iv::point(0.0).atan2(Iv::point(-1.0)).full);
    assert!(Iv::point(1.0).atan2(Iv::new(-1e-39, 1e-39)).full);
    assert!(!Iv::point(1.0).atan2(Iv::point(1.0)).full);
    // A sum whose partials round up across a power of two: 0.5 + (0.5 − 2⁻²⁵) → 1, then
    // 1 + 2⁻²⁶ → 1 + 2⁻²³ (each rounding up), far from the exact 1 − 2⁻²⁶.
    let t = [0.5f32, 0.5 - 2f32.powi(-25), 2f32.powi(-26)];
    assert!(Iv::sum(&t.map(Iv::point)).contains(1.0 + 2f32.powi(-23)));
    // A subnormal partial sum flushed: 2e-38 − 1.5e-38 → 0, then + 1.5e-38.
    assert!(Iv::sum(&[2e-38f32, -1.5e-38, 1.5e-38].map(Iv::point)).contains(1.5e-38));
    // A point clamped to 1 stores 255 exactly.
    assert_eq!(Iv::point(1.5).store_unorm8(), ocean_cpu::envelope::ByteRange { lo: 255, hi: 255 });
    // And a plain value is not full, nor wide.
    let one = Iv::point(1.0) + Iv::point(2.0);
    assert!(!one.full && one.contains(3.0) && !one.contains(3.001));
}

fn snapshot() -> Vec<PathBuf> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reference/hardware/h200");
    let mut v: Vec<PathBuf> = std::fs::read_dir(root)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.join("manifest.json").is_file())
        .collect();
    v.sort();
    assert_eq!(v.len(), 19, "the snapshot holds 19 scenes");
    v
}

/// A dump's HDR frame, its 8-bit picture and the tonemap's uniforms (`None` where its scene
/// runs post `bloom`, whose output the dump does not hold).
struct Dumped {
    name: String,
    w: u32,
    h: u32,
    hdr: Vec<[f32; 4]>,
    ldr: Vec<u8>,
    tonemap: Option<TonemapUniforms>,
}

fn dumped(dir: &Path) -> Dumped {
    let manifest = ocean::dump::read_manifest(dir).unwrap().unwrap();
    let none = ocean::scene_arg::SystemArg { system: None };
    let scene = manifest.scene("manifest.json", None, &none).unwrap();
    let plan = FramePlan::new(&scene, OutputKind::Ldr);
    let t = ocean_core::graph::tonemap_uniforms(&scene, &plan).unwrap().unwrap();
    let ((w, h), hdr) = ocean::dump::read(dir, ResourceId::Hdr).unwrap();
    let ldr = image::open(dir.join("ldr.png")).unwrap().to_rgba8().into_raw();
    Dumped {
        name: dir.file_name().unwrap().to_string_lossy().into_owned(),
        w,
        h,
        hdr,
        ldr,
        tonemap: (t.bloom_scale == 0.0).then_some(t),
    }
}

/// Texels (pixel, channel) of `bytes` (RGBA) outside the envelope's bytes.
fn bytes_outside(env: &[[(Iv, ocean_cpu::envelope::ByteRange); 3]], bytes: &[u8]) -> usize {
    env.iter()
        .enumerate()
        .map(|(i, px)| (0..3).filter(|&c| !px[c].1.contains(bytes[4 * i + c])).count())
        .sum()
}

#[test]
fn random_conformant_gpus_stay_inside_the_tonemap_envelope() {
    let (mut texels, mut frames) = (0usize, 0usize);
    let mut loose_outside = 0usize;
    for dir in snapshot() {
        let d = dumped(&dir);
        let Some(t) = d.tonemap else { continue };
        let env = tonemap::envelope_of(&d.hdr, None, d.w, d.h, &t);
        for seed in 0..8 {
            let rules = JitterRules { seed, scale: 1.0 };
            let got = tonemap::jitter(&d.hdr, None, d.w, d.h, &t, rules);
            for (e, g) in env.iter().zip(&got) {
                for c in 0..3 {
                    assert!(
                        e[c].0.contains(g[c].0) && e[c].1.contains(g[c].1),
                        "{} seed {seed}: {:?} / {} outside {:?}",
                        d.name,
                        g[c],
                        g[c].1,
                        e[c]
                    );
                }
            }
            texels += 3 * got.len();
            frames += 1;
        }
        // Negative control: twice the rules leaves the float envelope somewhere.
        let got = tonemap::jitter(&d.hdr, None, d.w, d.h, &t, JitterRules { seed: 99, scale: 2.0 });
        loose_outside += env
            .iter()
            .zip(&got)
            .map(|(e, g)| (0..3).filter(|&c| !e[c].0.contains(g[c].0)).count())
            .sum::<usize>();
    }
    println!("{frames} frames, {texels} texels of random conformant GPUs: 0 outside");
    println!("twice the rules: {loose_outside} texels outside");
    assert!(frames >= 8 * 17, "{frames} frames");
    assert!(loose_outside > 0, "a GPU twice as loose as the rules never left the envelope");
}

#[test]
fn the_h200_pictures_are_inside_the_tonemap_envelope_and_an_exposure_error_is_not() {
    let mut judged = 0;
    for dir in snapshot() {
        let d = dumped(&dir);
        let Some(t) = d.tonemap else {
            println!("{}: not judged (post bloom: its output is not in the dump)", d.name);
            continue;
        };
        let env = tonemap::envelope_of(&d.hdr, None, d.w, d.h, &t);
        let outside = bytes_outside(&env, &d.ldr);
        // The oracle's own tonemap of the same frame is one conformant GPU.
        let ours = tonemap::tonemap_to_rgba8(&d.hdr, d.w, d.h, &t);
        let ours_outside = bytes_outside(&env, &ours);
        // Power: the same frame with a 3 % exposure error.
        let off = TonemapUniforms { exposure: t.exposure * 1.03, ..t };
        let wrong = tonemap::tonemap_to_rgba8(&d.hdr, d.w, d.h, &off);
        let wrong_outside = bytes_outside(&env, &wrong);
        let width: Vec<u8> =
            env.iter().flat_map(|px| px.iter().map(|(_, b)| b.hi - b.lo)).collect();
        let wide = width.iter().filter(|&&w| w > 2).count();
        println!(
            "{}: H200 {outside}, oracle {ours_outside}, exposure +3 % {wrong_outside} of {} bytes outside; envelope wider than 3 codes at {wide}",
            d.name,
            3 * env.len()
        );
        assert_eq!(outside, 0, "{}: the H200's picture left the envelope", d.name);
        assert_eq!(ours_outside, 0, "{}: the oracle's picture left the envelope", d.name);
        assert!(wrong_outside > 0, "{}: a 3 % exposure error stayed inside", d.name);
        judged += 1;
    }
    assert_eq!(judged, 17, "17 of the 19 scenes run no bloom");
}

/// A bloom scene's frame: the H200's HDR frame and the scene's bloom inputs.
fn bloom_frames() -> Vec<(String, ocean_cpu::sampler::Texture2D, ocean_core::graph::BloomInputs)> {
    snapshot()
        .into_iter()
        .filter_map(|dir| {
            let manifest = ocean::dump::read_manifest(&dir).unwrap().unwrap();
            let none = ocean::scene_arg::SystemArg { system: None };
            let scene = manifest.scene("manifest.json", None, &none).unwrap();
            let plan = FramePlan::new(&scene, OutputKind::Ldr);
            plan.runs(ocean_core::plan::Pass::Bloom).then(|| {
                let ((w, h), hdr) = ocean::dump::read(&dir, ResourceId::Hdr).unwrap();
                let name = dir.file_name().unwrap().to_string_lossy().into_owned();
                let inputs = ocean_core::graph::BloomInputs::new(&scene);
                (name, ocean_cpu::sampler::Texture2D::new(w, h, hdr), inputs)
            })
        })
        .collect()
}

/// Values of `chain` outside `env` (atlas layout).
fn chain_outside(env: &[Option<[Iv; 3]>], chain: &ocean_cpu::mip::MipChain) -> usize {
    let v = ocean_verify::envelope::judge_floats("chain", env, &chain.atlas.texels, chain.width);
    assert!(v.values > 0, "nothing judged");
    v.outside
}

#[test]
fn random_conformant_gpus_stay_inside_the_bloom_envelope() {
    use ocean_cpu::shaders::bloom;
    let frames = bloom_frames();
    assert_eq!(frames.len(), 2, "the snapshot's two bloom scenes");
    let (mut runs, mut loose) = (0, 0);
    for (name, hdr, inputs) in &frames {
        // The oracle's own chains are one conformant GPU's.
        let (down, up) = bloom::dispatch(hdr, inputs);
        let (de, ue) = bloom::envelope(hdr, &down, &up, inputs);
        assert_eq!(chain_outside(&de, &down) + chain_outside(&ue, &up), 0, "{name}: the oracle");
        // Negative control of the comparator: one value of the up chain 0.1 % off.
        let mut bad = up.clone();
        let k = bad.atlas.texels.len() / 3;
        bad.atlas.texels[k][1] = bad.atlas.texels[k][1] * 1.001 + 1e-3;
        assert_eq!(chain_outside(&ue, &bad), 1, "{name}: a value 0.1 % off");
        for seed in 0..8 {
            let (down, up) = bloom::jitter(hdr, inputs, JitterRules { seed, scale: 1.0 });
            let (de, ue) = bloom::envelope(hdr, &down, &up, inputs);
            let out = chain_outside(&de, &down) + chain_outside(&ue, &up);
            assert_eq!(out, 0, "{name} seed {seed}: a conformant GPU left the bloom envelope");
            runs += 1;
        }
        let (down, up) = bloom::jitter(hdr, inputs, JitterRules { seed: 99, scale: 2.0 });
        let (de, ue) = bloom::envelope(hdr, &down, &up, inputs);
        loose += chain_outside(&de, &down) + chain_outside(&ue, &up);
    }
    println!(
        "{runs} bloom pyramids of random conformant GPUs: 0 outside; twice the rules: {loose} outside"
    );
    assert!(loose > 0, "a GPU twice as loose as the rules never left the bloom envelope");
}

#[test]
fn random_conformant_gpus_stay_inside_the_wave_mips_envelope() {
    use ocean_cpu::sampler::Texture2D;
    use ocean_cpu::shaders::wave_mips;
    // The oracle's slope maps of a reference scene, and a non-square random map.
    let mut scene = ocean_core::scene::Scene::load(
        &PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reference/scenes/calm.toml"),
    )
    .unwrap();
    (scene.camera.width, scene.camera.height) = (64, 36);
    let r = ocean_cpu::render_scene(&scene, OutputKind::Ldr, &mut |_| {}).unwrap();
    let mut maps = Vec::new();
    for id in [ResourceId::DisplacementSlopes, ResourceId::Bump] {
        let (w, h, t) = r.buffers.map(id).unwrap();
        maps.push((id.name().to_owned(), Texture2D::new(w, h, t.to_vec())));
    }
    let mut g = SplitMix64::new(7);
    let random: Vec<[f32; 4]> = (0..64 * 16)
        .map(|_| std::array::from_fn(|_| (g.next_open_closed() as f32 - 0.5) * 3.0))
        .collect();
    maps.push(("random 64x16".to_owned(), Texture2D::new(64, 16, random)));
    let (mut runs, mut loose) = (0, 0);
    for (name, slopes) in &maps {
        let exact = wave_mips::dispatch(slopes);
        let judge = |env: &[Option<[Iv; 4]>], c: &ocean_cpu::mip::MipChain| {
            let v = ocean_verify::envelope::judge_floats("mips", env, &c.atlas.texels, c.width);
            assert!(v.values > 0);
            v.outside
        };
        assert_eq!(judge(&wave_mips::envelope(slopes, &exact), &exact), 0, "{name}: the oracle");
        let mut bad = exact.clone();
        let k = bad.width as usize * bad.height as usize + 3;
        bad.atlas.texels[k][2] = bad.atlas.texels[k][2] * 1.0001 + 1e-6;
        assert_eq!(judge(&wave_mips::envelope(slopes, &exact), &bad), 1, "{name}: one value off");
        for seed in 0..8 {
            let c = wave_mips::jitter(slopes, JitterRules { seed, scale: 1.0 });
            assert_eq!(judge(&wave_mips::envelope(slopes, &c), &c), 0, "{name} seed {seed}");
            runs += 1;
        }
        let c = wave_mips::jitter(slopes, JitterRules { seed: 99, scale: 2.0 });
        loose += judge(&wave_mips::envelope(slopes, &c), &c);
    }
    println!(
        "{runs} wave_mips chains of random conformant GPUs: 0 outside; twice the rules: {loose} outside"
    );
    assert!(loose > 0, "a GPU twice as loose as the rules never left the wave_mips envelope");
}

#[test]
fn random_conformant_gpus_stay_inside_the_fresnel_table_envelope() {
    use ocean_core::frame::FresnelTableUniforms;
    use ocean_core::tables::TextureMapping;
    use ocean_cpu::shaders::fresnel_table;
    let (mut runs, mut loose) = (0, 0);
    // Water from above and below, η → 1 (the cancelling branch), η > 2 (the direct branch),
    // η = 1 exactly (no interface); every mapping.
    for eta in [1.333f32, 1.0 / 1.333, 1.0001, 2.5, 1.0] {
        for mapping in
            [TextureMapping::Hemisphere, TextureMapping::PaperHalfRange, TextureMapping::Grazing]
        {
            let params = FresnelTableUniforms::new(eta, 48, mapping);
            let env = fresnel_table::envelope(&params);
            let judge = |t: &ocean_cpu::sampler::Texture2D| {
                ocean_verify::envelope::judge_floats("table", &env, &t.texels, t.width).outside
            };
            assert_eq!(
                judge(&fresnel_table::dispatch(&params)),
                0,
                "η {eta} {mapping:?}: the oracle"
            );
            for seed in 0..8 {
                let t = fresnel_table::jitter(&params, JitterRules { seed, scale: 1.0 });
                assert_eq!(judge(&t), 0, "η {eta} {mapping:?} seed {seed}");
                runs += 1;
            }
            loose += judge(&fresnel_table::jitter(&params, JitterRules { seed: 99, scale: 2.0 }));
        }
    }
    println!(
        "{runs} Fresnel tables of random conformant GPUs: 0 outside; twice the rules: {loose} outside"
    );
    assert!(loose > 0, "a GPU twice as loose as the rules never left the Fresnel table's envelope");
}

#[test]
fn random_conformant_gpus_stay_inside_the_sky_envelope() {
    use ocean_cpu::shaders::sky;
    let (mut runs, mut loose, mut scenes) = (0, 0, 0);
    for (path, mut scene) in reference_scenes() {
        (scene.camera.width, scene.camera.height) = (96, 54);
        let plan = FramePlan::new(&scene, OutputKind::Ldr);
        let technique = plan.techniques.sky();
        let frame = ocean_core::graph::FrameInputs::new(
            &scene,
            &plan,
            &ocean_core::graph::FrameState::new(0.0),
        )
        .unwrap();
        let inputs = sky::SkyInputs {
            camera: &frame.camera_uniforms,
            sky: &frame.environment,
            lut: &frame.sky_lut,
        };
        let size = (96, 54);
        let env = sky::envelope(technique, inputs, size, plan.frame_format);
        scenes += 1;
        let outside = |v: &[[f32; 3]]| {
            env.iter()
                .zip(v)
                .map(|(e, g)| (0..3).filter(|&c| !e[c].contains(g[c])).count())
                .sum::<usize>()
        };
        let exact = sky::exact(technique, inputs, size, plan.frame_format);
        assert_eq!(outside(&exact), 0, "{}: the oracle", path);
        for seed in 0..8 {
            let rules = JitterRules { seed, scale: 1.0 };
            let j = sky::jitter(technique, inputs, size, plan.frame_format, rules);
            assert_eq!(outside(&j), 0, "{} seed {seed}", path);
            runs += 1;
        }
        let rules = JitterRules { seed: 99, scale: 2.0 };
        loose += outside(&sky::jitter(technique, inputs, size, plan.frame_format, rules));
    }
    println!(
        "{runs} skies ({scenes} scenes, every sky technique) of random conformant GPUs: 0 outside; twice the rules: {loose} outside"
    );
    assert!(scenes >= 14, "{scenes} scenes with a sky that has an envelope");
    assert!(loose > 0, "a GPU twice as loose as the rules never left the sky's envelope");
}

/// Every reference scene's distinct ocean, both mode sets: the oracle's wave maps and 8
/// random conformant GPUs' inside the `waves` pass's envelope (spectrum, 2·log2 N Stockham
/// stages, pack). The negative control is per dispatch: the frame's envelope composes each
/// stage's, and random roundings average out over an FFT's many terms where the envelope must
/// hold their worst case, so a twice-as-loose GPU is caught where one dispatch is judged from
/// the buffer it read (as the other passes' chains are).
#[test]
fn random_conformant_gpus_stay_inside_the_waves_envelope() {
    use ocean_cpu::shaders::waves::{WaveTextures, WavesMirror};
    use rayon::prelude::*;
    let mut oceans: Vec<(String, ocean_core::scene::Ocean)> = Vec::new();
    for (path, scene) in reference_scenes() {
        let ocean = scene.ocean;
        if !oceans.iter().any(|(_, o)| *o == ocean) {
            oceans.push((path, ocean));
        }
    }
    let modes_checked_by_dispatch = |p: &str| oceans.iter().take(4).any(|(q, _)| q == p);
    let rel_of = |env: &[Vec<[Iv; 4]>; 3]| -> Vec<f64> {
        env.iter().flatten().flat_map(|t| t.iter().filter_map(|c| c.rel_half_width())).collect()
    };
    let maps = |w: &WaveTextures| {
        [&w.displacement, &w.displacement_slopes, &w.bump].map(|t| t.texels.clone())
    };
    let results: Vec<(usize, usize, usize, Vec<f64>)> = oceans
        .par_iter()
        .flat_map(|(path, ocean)| {
            let surface = ocean.surface().unwrap();
            [surface.displacement, surface.bump].into_par_iter().map(move |modes| {
                let m = WavesMirror::new(&modes).unwrap();
                let params = m.uniforms(ocean.time_s, ocean.choppiness).unwrap();
                let env = m.envelope(&params);
                let outside = |g: [Vec<[f32; 4]>; 3]| -> usize {
                    env.iter()
                        .zip(&g)
                        .flat_map(|(e, g)| e.iter().zip(g))
                        .map(|(e, g)| (0..4).filter(|&c| !e[c].contains(g[c])).count())
                        .sum()
                };
                let exact = m.run(ocean.time_s, ocean.choppiness).unwrap();
                assert_eq!(outside(maps(&exact)), 0, "{}: the oracle", path);
                for seed in 0..8 {
                    let j = m.jitter(&params, JitterRules { seed, scale: 1.0 });
                    assert_eq!(outside(maps(&j)), 0, "{} seed {seed}", path);
                }
                // One dispatch at a time, each from the buffer the random GPU itself wrote (on a
                // few oceans: the rules are the same everywhere).
                if !modes_checked_by_dispatch(path) {
                    return (8, 0, 0, rel_of(&env));
                }
                let mut buffer = Vec::new();
                m.run_traced(&params, &mut |d, b| {
                    if d == ocean_cpu::shaders::waves::Dispatch::Spectrum {
                        buffer = b.to_vec();
                    }
                });
                let (mut stage_in, mut stage_loose) = (0, 0);
                let (mut conformant, mut loose) = (buffer.clone(), buffer);
                for p in 0..m.fft_dispatches() {
                    let outside = |env: &[[Iv; 2]], g: &[[f32; 2]]| -> usize {
                        env.iter()
                            .zip(g)
                            .map(|(e, g)| (0..2).filter(|&c| !e[c].contains(g[c])).count())
                            .sum()
                    };
                    let next = m.fft_dispatch_jitter(
                        &params,
                        p,
                        &conformant,
                        JitterRules { seed: p as u64, scale: 1.0 },
                    );
                    stage_in += outside(&m.fft_dispatch_envelope(&params, p, &conformant), &next);
                    conformant = next;
                    let next = m.fft_dispatch_jitter(
                        &params,
                        p,
                        &loose,
                        JitterRules { seed: 99, scale: 2.0 },
                    );
                    stage_loose += outside(&m.fft_dispatch_envelope(&params, p, &loose), &next);
                    loose = next;
                }
                (8, stage_in, stage_loose, rel_of(&env))
            })
        })
        .collect();
    let runs: usize = results.iter().map(|r| r.0).sum();
    let stage_in: usize = results.iter().map(|r| r.1).sum();
    let stage_loose: usize = results.iter().map(|r| r.2).sum();
    let mut rel: Vec<f64> = results.into_iter().flat_map(|r| r.3).collect();
    rel.sort_by(f64::total_cmp);
    let q = |p: f64| rel[((rel.len() - 1) as f64 * p) as usize];
    println!(
        "{runs} wave-map frames ({} oceans × 2 mode sets × 8 seeds) of random conformant GPUs: 0 outside; \
         dispatch by dispatch: conformant {stage_in} outside, twice the rules {stage_loose} outside; \
         relative half-width p50 {:.1e}, p99 {:.1e}",
        oceans.len(),
        q(0.5),
        q(0.99)
    );
    assert!(oceans.len() >= 15, "{} distinct oceans", oceans.len());
    assert_eq!(stage_in, 0, "a conformant dispatch left its envelope");
    assert!(stage_loose > 0, "a GPU twice as loose as the rules never left a dispatch's envelope");
}

/// Pass `foam`'s field after a state's first frame (the warm-up and one step) for `fft` waves
/// (`foam_storm`, J from the oracle's displacement map) and `gerstner` waves (`foam_gerstner`
/// with foam `accumulated`, J analytic): the oracle's field and 8 random conformant GPUs'
/// inside its envelope. The negative control is per step, each from the field the random GPU
/// itself held (the field decays, so ninety steps' roundings average out where the envelope
/// keeps their worst case).
#[test]
fn random_conformant_gpus_stay_inside_the_foam_envelope() {
    use ocean_cpu::sampler::Texture2D;
    use ocean_cpu::shaders::foam;
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reference/scenes");
    let storm = ocean_core::scene::Scene::load(&root.join("foam_storm.toml")).unwrap();
    let mut gerstner = ocean_core::scene::Scene::load(&root.join("foam_gerstner.toml")).unwrap();
    gerstner.techniques.foam = Some(ocean_core::plan::Foam::Accumulated);
    let (mut runs, mut texels, mut loose) = (0, 0, 0);
    for (name, scene) in [("foam_storm", storm), ("foam_gerstner (accumulated)", gerstner)] {
        let plan = FramePlan::new(&scene, OutputKind::Ldr);
        assert!(plan.runs(ocean_core::plan::Pass::Foam), "{name}: no foam pass");
        let state = ocean_core::graph::FrameState::new(0.0);
        let frame = ocean_core::graph::FrameInputs::new(&scene, &plan, &state).unwrap();
        let eye = [frame.camera.eye.x, frame.camera.eye.z];
        let work = ocean_core::graph::FoamWork::new(&scene, &plan, &state, eye, frame.mesh.origin);
        let displacement = if work.steps[0].analytic == 0 {
            let surface = scene.ocean.surface().unwrap();
            ocean_cpu::shaders::waves::WavesMirror::new(&surface.displacement)
                .unwrap()
                .run(scene.ocean.time_s, scene.ocean.choppiness)
                .unwrap()
                .displacement
        } else {
            Texture2D::new(1, 1, vec![[0.0; 4]])
        };
        let u = &frame.uniforms;
        let env = foam::envelope(&work.steps, u, &displacement);
        let outside = |g: &[f32]| env.iter().zip(g).filter(|(e, g)| !e.contains(**g)).count();
        let exact: Vec<f32> = foam::run_steps(&work.steps, u, &displacement);
        assert_eq!(outside(&exact), 0, "{name}: the oracle");
        assert!(exact.iter().filter(|&&f| f > 0.0).count() > exact.len() / 100, "{name}: no foam");
        for seed in 0..8 {
            let j = foam::jitter(&work.steps, u, &displacement, JitterRules { seed, scale: 1.0 });
            assert_eq!(outside(&j), 0, "{name} seed {seed}");
            runs += 1;
        }
        texels += exact.len();
        // Step by step from the GPU's own field: a conformant step stays inside, a twice as
        // loose one leaves.
        let j_iv: Vec<Iv> = foam::jacobian_field(&work.steps[0], u, &displacement);
        let j_exact: Vec<f32> = foam::jacobian_field(&work.steps[0], u, &displacement);
        let mut field = vec![0.0f32; exact.len()];
        for (k, step) in work.steps.iter().enumerate().take(12) {
            let env: Vec<Iv> = foam::step_field(
                step,
                &j_iv,
                &field.iter().map(|&v| Iv::point(v)).collect::<Vec<_>>(),
            );
            for (scale, seed) in [(1.0, k as u64), (2.0, 1000 + k as u64)] {
                Jitter::reseed(JitterRules { seed, scale }, 0);
                let src: Vec<Jitter> = field.iter().map(|&v| Jitter(v)).collect();
                let jj: Vec<Jitter> = j_exact.iter().map(|&v| Jitter(v)).collect();
                let next: Vec<f32> =
                    foam::step_field(step, &jj, &src).into_iter().map(|v| v.0).collect();
                let out = env.iter().zip(&next).filter(|(e, g)| !e.contains(**g)).count();
                if scale == 1.0 {
                    assert_eq!(out, 0, "{name} step {k}: a conformant step left its envelope");
                    field = next;
                } else {
                    loose += out;
                }
            }
        }
    }
    println!(
        "{runs} foam fields ({texels} texels × 8 seeds) of random conformant GPUs: 0 outside; one step at a time, twice the rules: {loose} outside"
    );
    assert!(loose > 0, "a GPU twice as loose as the rules never left a foam step's envelope");
}

/// Pass `shadow_map` of every reference scene that draws one: the oracle's map (lavapipe's
/// rasteriser, 8 sub-pixel bits) and 8 random conformant rasterisers' (any rounding, any
/// tie-break, the depth plane through the snapped or unsnapped vertices) inside the
/// rasteriser's envelope, at Vulkan's minimum of 4 sub-pixel bits and at lavapipe's 8, each
/// GPU against the envelope of its device; one twice as loose (snaps twice as far, twice the
/// depth error) at 4 bits leaves it; at 8 bits twice stays inside these maps (reported) and
/// three times leaves (the 8-bit device's negative control: 6 texels over the 6 scenes when
/// measured, and at four times some in every scene).
#[test]
fn random_conformant_rasterisers_stay_inside_the_shadow_map_envelope() {
    use ocean_core::plan::Pass;
    use ocean_cpu::shaders::shadow;
    let (mut scenes, mut runs, mut loose, mut texels, mut ambiguous) =
        (0, 0, [0; 2], [0; 2], [0; 2]);
    let mut looser = [0; 2];
    for (path, mut scene) in reference_scenes() {
        (scene.camera.width, scene.camera.height) = (64, 36);
        let plan = FramePlan::new(&scene, OutputKind::Ldr);
        let Some(pass) = plan.pass(Pass::ShadowMap).filter(|_| plan.runs(Pass::ShadowMap)) else {
            continue;
        };
        let mut state = ocean_core::graph::FrameState::new(0.0);
        let frame = ocean_core::graph::FrameInputs::new(&scene, &plan, &state).unwrap();
        let tris: Vec<[[f32; 3]; 3]> =
            ocean_core::frame::pass_triangles(&scene, &frame.poses, pass, frame.camera.eye)
                .iter()
                .map(|t| t.map(|v| v.position))
                .collect();
        let oracle = ocean_cpu::frame::render_frame(
            &frame,
            ocean_cpu::frame::Environment::Planned,
            &mut state,
            &mut |_| {},
        )
        .unwrap();
        let (w, h, map) = oracle.map(ResourceId::ShadowMap).unwrap();
        let exact: Vec<f32> = map.iter().map(|t| t[0]).collect();
        assert!(exact.iter().any(|&z| z < 1.0), "{}: nothing in the shadow map", path);
        for (k, precision) in
            [Precision::VULKAN_MINIMUM, Precision::LAVAPIPE].into_iter().enumerate()
        {
            let (env, amb) = shadow::envelope(&tris, &frame.uniforms, [w, h], precision);
            let outside = |g: &[f32]| env.iter().zip(g).filter(|(e, g)| !e.contains(**g)).count();
            assert_eq!(outside(&exact), 0, "{}: the oracle at {precision:?}", path);
            for seed in 0..8 {
                let rules = JitterRules { seed, scale: 1.0 };
                let j = shadow::jitter(&tris, &frame.uniforms, [w, h], rules, precision);
                assert_eq!(outside(&j), 0, "{} seed {seed} at {precision:?}", path);
                runs += 1;
            }
            for (scale, count) in [(2.0, &mut loose[k]), (3.0, &mut looser[k])] {
                let rules = JitterRules { seed: 99, scale };
                *count +=
                    outside(&shadow::jitter(&tris, &frame.uniforms, [w, h], rules, precision));
            }
            texels[k] += env.len();
            ambiguous[k] += amb.iter().filter(|&&a| a).count();
        }
        scenes += 1;
    }
    let share = |k: usize| 100.0 * ambiguous[k] as f64 / texels[k].max(1) as f64;
    println!(
        "{runs} shadow maps ({scenes} scenes × 8 seeds × 2 precisions) of random conformant \
         rasterisers: 0 outside; twice the rules: {loose:?} outside (4, 8 sub-pixel bits), \
         three times: {looser:?}; coverage ambiguous at {:.2} % and {:.2} % of texels",
        share(0),
        share(1)
    );
    assert!(scenes >= 3, "{scenes} scenes draw a shadow map");
    // At 8 bits, twice the rules (2/256 px, twice the depth allowance) stays inside on these
    // maps: the control is the 4-bit device's, as before the envelope took the device's snap.
    assert!(loose[0] > 0, "a rasteriser twice as loose never left: {loose:?}");
    assert!(looser[1] > 0, "at 8 bits a rasteriser three times as loose never left: {looser:?}");
}

/// Pass `objects`' reflection and refraction maps of every reference scene that draws one
/// the envelope carries (not the refraction map over a floor with relief shadows; shading
/// `chiu`'s clip height through the filter's envelope), at 320×180: the oracle's map (at
/// both precisions' envelopes) and 8 random conformant GPUs' (4 at lavapipe's 8 sub-pixel
/// bits, 4 at Vulkan's minimum of 4, each against its device's envelope; the
/// rasteriser's freedoms, the clipper's, perspective-correct interpolation from either vertex
/// set, random roundings in the fragment shader) inside the envelope; one twice as loose
/// leaves it. Both read the oracle's shadow map.
#[test]
fn random_conformant_gpus_stay_inside_the_object_maps_envelope() {
    use ocean_core::plan::Pass;
    use ocean_cpu::shaders::objects::{self, ObjectMap};
    let (mut runs, mut loose, mut texels, mut ambiguous, mut covered) = (0, [0; 2], 0, 0, 0);
    let mut rel = Vec::new();
    let mut kinds = [0; 2];
    for (path, mut scene) in reference_scenes() {
        (scene.camera.width, scene.camera.height) = (320, 180);
        let plan = FramePlan::new(&scene, OutputKind::Ldr);
        let mut state = ocean_core::graph::FrameState::new(0.0);
        let frame = ocean_core::graph::FrameInputs::new(&scene, &plan, &state).unwrap();
        let u = frame.uniforms;
        let mut oracle = None;
        for (kind, map, pass, id) in [
            (0, ObjectMap::Reflection, Pass::ReflectionMap, ResourceId::ReflectionMap),
            (1, ObjectMap::Refraction, Pass::RefractionMap, ResourceId::RefractionMap),
        ] {
            let Some(planned) = plan.pass(pass).filter(|_| plan.runs(pass)) else { continue };
            let r = plan.resource(id).unwrap().clone();
            let o = oracle.get_or_insert_with(|| {
                ocean_cpu::frame::render_frame(
                    &frame,
                    ocean_cpu::frame::Environment::Planned,
                    &mut state,
                    &mut |_| {},
                )
                .unwrap()
            });
            let (sw, sh, shadow) = o.map(ResourceId::ShadowMap).unwrap_or((1, 1, &[[1.0; 4]]));
            let dims = [sw, sh];
            let occ = |x: u32, y: u32| shadow[y as usize * sw as usize + x as usize][0];
            let occ_iv = |x: u32, y: u32| Iv::point(occ(x, y));
            let tris =
                ocean_core::frame::pass_triangles(&scene, &frame.poses, planned, frame.camera.eye);
            let (dw, dh, disp) = o.map(ResourceId::Displacement).unwrap_or((1, 1, &[[0.0; 4]]));
            let displacement = ocean_cpu::sampler::Texture2D::new(dw, dh, disp.to_vec());
            // The relief's march: carried step by step for the envelope, each random GPU's
            // own roundings and filter for the GPUs.
            let (fw, fh, floor) = ocean_core::terrain::relief_texels(scene.terrain.as_ref());
            let floor_map = ocean_cpu::sampler::Texture2D::new(fw, fh, floor);
            // Each random GPU against the envelope of its device: even seeds at lavapipe's 8
            // sub-pixel bits, odd ones at Vulkan's minimum of 4.
            let precisions = [Precision::LAVAPIPE, Precision::VULKAN_MINIMUM];
            let envelope_inputs = |precision| objects::MapInputs {
                frame: &u,
                size: r.size,
                format: r.format.storage(),
                clear: r.clear,
                shadow_dims: dims,
                occluder: &occ_iv,
                displacement: &displacement,
                floor_map: &floor_map,
                precision,
            };
            let gpu_inputs = |precision| objects::MapInputs {
                frame: &u,
                size: r.size,
                format: r.format.storage(),
                clear: r.clear,
                shadow_dims: dims,
                occluder: &occ,
                displacement: &displacement,
                floor_map: &floor_map,
                precision,
            };
            let envs = precisions.map(|p| objects::map_envelope(map, &tris, &envelope_inputs(p)));
            let (_, _, exact) = o.map(id).unwrap();
            let outside = |k: usize, g: &[[f32; 4]]| -> usize {
                envs[k]
                    .0
                    .iter()
                    .zip(g)
                    .map(|(e, g)| (0..4).filter(|&c| !e[c].contains(g[c])).count())
                    .sum()
            };
            for k in 0..2 {
                assert_eq!(outside(k, exact), 0, "{} {map:?}: the oracle at {k}", path);
            }
            let drawn = exact.iter().filter(|t| t[3] > 0.0).count();
            if drawn == 0 {
                // Nothing of this map in view (chiu_shallow's rock under the waves): the
                // envelope said so (the oracle is inside), nothing more to learn from it.
                continue;
            }
            for seed in 0..8 {
                let rules = JitterRules { seed, scale: 1.0 };
                let k = seed as usize % 2;
                let j = objects::map_jitter(map, &tris, &gpu_inputs(precisions[k]), rules);
                assert_eq!(outside(k, &j), 0, "{} {map:?} seed {seed}", path);
                runs += 1;
            }
            for (k, p) in precisions.into_iter().enumerate() {
                let rules = JitterRules { seed: 99, scale: 2.0 };
                loose[k] += outside(k, &objects::map_jitter(map, &tris, &gpu_inputs(p), rules));
            }
            let (env, amb) = &envs[0];
            kinds[kind] += 1;
            texels += env.len();
            covered += drawn;
            ambiguous += amb.iter().filter(|&&a| a).count();
            rel.extend(
                env.iter()
                    .zip(exact)
                    .filter(|(_, m)| m[3] > 0.0)
                    .flat_map(|(e, _)| e[..3].iter().filter_map(|c| c.rel_half_width())),
            );
        }
    }
    rel.sort_by(f64::total_cmp);
    let q =
        |p: f64| rel.get(((rel.len().max(1) - 1) as f64 * p) as usize).copied().unwrap_or(f64::NAN);
    println!(
        "{runs} object maps ({} reflection, {} refraction × 8 seeds) of random conformant GPUs: 0 outside; \
         twice the rules: {loose:?} outside (8, 4 sub-pixel bits); {covered} texels drawn of \
         {texels}, {ambiguous} ambiguous at lavapipe's precision; \
         colour rel half-width on drawn texels p50 {:.1e}, p99 {:.1e}",
        kinds[0],
        kinds[1],
        q(0.5),
        q(0.99)
    );
    assert!(kinds[0] >= 3 && kinds[1] >= 3, "{kinds:?} maps the envelope judges");
    assert!(loose.iter().all(|&l| l > 0), "a GPU twice as loose never left: {loose:?}");
}

/// `length` of a vector whose components may be 0 (Preetham's |dir × sun| near the sun): each
/// square is never negative, so the square root is bounded and holds every f32 length in the
/// box. Negative control: the squares taken as products of two independent intervals reach
/// below 0, and the root is anything (what made the reflected sky unbounded around the sun).
#[test]
fn a_length_through_zero_is_bounded_and_holds_every_f32_length() {
    use ocean_cpu::envelope::{Af, Real, dot3, length2, length3};
    let b = [(-1e-3, 2e-3), (-5e-4, 5e-4), (-2e-3, 1e-3)];
    let a = b.map(|(lo, hi)| Iv::new(lo, hi));
    // The most a length may be: the box's farthest corner, plus a few f32 ULP (6e-8 relative
    // each) for the squares, the sum and the root.
    let most = |n: usize| {
        let corner = b[..n].iter().map(|(lo, hi)| f64::max(-lo, *hi).powi(2)).sum::<f64>();
        corner.sqrt() * (1.0 + 1e-5)
    };
    let len = length3(a);
    assert!(!len.full && len.lo >= 0.0 && len.hi <= most(3), "{len:?}");
    let af = length3(a.map(Af::input));
    assert!(af.least() >= 0.0 && af.most() <= most(3), "{af:?}");
    let mut g = ocean_core::rng::SplitMix64::new(3);
    for _ in 0..10_000 {
        let v = b.map(|(lo, hi)| (lo + (hi - lo) * g.next_open_closed()) as f32);
        let exact = length3(v);
        assert!(len.contains(exact) && af.to_iv().contains(exact), "{v:?}: {exact}");
    }
    assert!(dot3(a, a).sqrt().full, "the products' root was bounded: the control tests nothing");
    // The same for two components (the heuristic foam's slope, the sky table's azimuth).
    let len2 = length2([a[0], a[1]]);
    assert!(!len2.full && len2.lo >= 0.0 && len2.hi <= most(2), "{len2:?}");
    for _ in 0..10_000 {
        let v = [b[0], b[1]].map(|(lo, hi)| (lo + (hi - lo) * g.next_open_closed()) as f32);
        let exact = (v[0] * v[0] + v[1] * v[1]).sqrt();
        assert_eq!(length2(v).to_bits(), exact.to_bits(), "{v:?}: the exact frame moved");
        assert!(len2.contains(exact), "{v:?}: {exact}");
    }
    assert!((a[0] * a[0] + a[1] * a[1]).sqrt().full, "the 2-component control tests nothing");
}

/// The Preetham sky 90° from the sun: its angle γ = 2·atan2(|d × s|, 1 + d·s) keeps atan2's
/// second argument near 1 there, inside the domain where WGSL bounds atan2 (|x| ≥ 2⁻¹²⁶), so
/// boxes of directions across that circle have a bounded sky that holds the oracle's and 8
/// random conformant GPUs' values at 200 points each. Negative control: the form it replaced,
/// atan2(|d × s|, d·s), has a second argument that may be 0 in each box, and is anything.
#[test]
fn the_preetham_sky_is_bounded_ninety_degrees_from_the_sun() {
    use ocean_cpu::envelope::{cross3, dot3, length3};
    use ocean_cpu::shaders::shared::preetham::preetham_radiance_r;
    let (_, scene) = reference_scenes()
        .into_iter()
        .find(|(name, _)| name == "underwater_object")
        .expect("the scene");
    let plan = FramePlan::new(&scene, OutputKind::Ldr);
    assert_eq!(plan.techniques.sky(), ocean_core::plan::Sky::Preetham);
    let frame = ocean_core::graph::FrameInputs::new(
        &scene,
        &plan,
        &ocean_core::graph::FrameState::new(0.0),
    )
    .unwrap();
    let sky = &frame.environment;
    let sd = sky.sun_direction;
    let s = glam::DVec3::new(f64::from(sd[0]), f64::from(sd[1]), f64::from(sd[2]));
    let u = s.cross(glam::DVec3::Y).normalize();
    let w = s.cross(u).normalize();
    let (mut boxes, mut values, mut old_full) = (0, 0, 0);
    let mut g = SplitMix64::new(11);
    for k in 0..64u32 {
        let phi = std::f64::consts::TAU * f64::from(k) / 64.0;
        let d = u * phi.cos() + w * phi.sin();
        if d.y < 0.05 {
            continue;
        }
        let half = 2e-3;
        let b = d.to_array().map(|c| Iv::new(c - half, c + half));
        let env = preetham_radiance_r(sky, b);
        assert!(env.iter().all(|c| !c.full), "φ = {phi}: {env:?}");
        let sun = [sd[0], sd[1], sd[2]].map(Iv::point);
        old_full += usize::from(length3(cross3(b, sun)).atan2(dot3(b, sun)).full);
        boxes += 1;
        for i in 0..200 {
            let p = d.to_array().map(|c| (c + half * (2.0 * g.next_open_closed() - 1.0)) as f32);
            let exact = preetham_radiance_r(sky, p);
            assert!((0..3).all(|c| env[c].contains(exact[c])), "{p:?}: {exact:?} {env:?}");
            for seed in 0..8 {
                Jitter::reseed(JitterRules { seed, scale: 1.0 }, u64::from(k * 200 + i));
                let j = preetham_radiance_r(sky, p.map(Jitter));
                assert!((0..3).all(|c| env[c].contains(j[c].0)), "{p:?} seed {seed}: {env:?}");
                values += 1;
            }
        }
    }
    println!("Preetham 90° from the sun: {boxes} boxes bounded, {values} GPU values inside");
    assert!(boxes >= 16, "{boxes} boxes above the horizon");
    assert_eq!(old_full, boxes, "atan2(sin γ, cos γ) was bounded: the control tests nothing");
}
