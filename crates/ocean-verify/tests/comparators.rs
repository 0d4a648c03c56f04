//! The comparators of docs/design.md's tolerance table, each at its limit: one ULP (or one
//! pixel) past it fails, at it passes — the negative controls every comparison in the project
//! leans on, tested here with no GPU and no renderer.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use ocean_verify::compare::{
    FLOAT_ABS, FLOAT_REL, ImageLimits, allowance, compare_float, compare_image,
};

/// The float comparator at its boundary: a value exactly at the allowance passes, one ULP
/// beyond fails, for values where the relative and where the absolute limit governs.
#[test]
fn float_comparator_fails_one_ulp_past_the_limit() {
    for cpu in [1.0f32, -3.75, 0.02, 1e-3, 0.0, 2e-7, 12345.678] {
        let allowed = allowance(cpu);
        assert_eq!(allowed, FLOAT_ABS.max(FLOAT_REL * f64::from(cpu).abs()));
        // The largest f32 above cpu still within the allowance, and the next one.
        let mut at = (f64::from(cpu) + allowed) as f32;
        while f64::from(at) - f64::from(cpu) > allowed {
            at = at.next_down();
        }
        while f64::from(at.next_up()) - f64::from(cpu) <= allowed {
            at = at.next_up();
        }
        let beyond = at.next_up();
        let texels = |v: f32| vec![[0.5, 0.25, 0.0, 1.0], [0.5, v, 0.0, 1.0]];
        let base = texels(cpu);
        let ok = compare_float("control", true, ((2, 1), &base), ((2, 1), &texels(at)));
        assert!(ok.passed(), "cpu {cpu}: {at} is within the allowance {allowed}: {}", ok.line());
        let bad = compare_float("control", true, ((2, 1), &base), ((2, 1), &texels(beyond)));
        assert!(!bad.passed(), "cpu {cpu}: {beyond} is one ULP past the limit: {}", bad.line());
        let w = bad.worst.expect("the worst value is located");
        assert_eq!((w.x, w.y, w.channel), (1, 0, 1));
    }
    // A NaN on one side, and a size mismatch, fail.
    let a = vec![[1.0; 4]];
    assert!(
        !compare_float("nan", true, ((1, 1), &a), ((1, 1), &[[1.0, f32::NAN, 1.0, 1.0]])).passed()
    );
    assert!(!compare_float("size", true, ((1, 1), &a), ((2, 1), &[[1.0; 4]; 2])).passed());
    assert!(compare_float("same", true, ((1, 1), &a), ((1, 1), &a)).passed());
}

/// The allowance of an `rgba16float` buffer: one binary16 step at the CPU's value passes,
/// the next f32 beyond it fails, where the step is more than the f32 tolerance (everywhere
/// but near 0, where the absolute 1e-6 covers the subnormal steps); an f32 buffer does not
/// take the step (negative control).
#[test]
fn half_comparator_allows_one_binary16_step_and_no_more() {
    use ocean_core::frame_format::{FrameFormat, half_step};
    use ocean_verify::compare::compare_float_in;
    let f16 = FrameFormat::Rgba16Float;
    for cpu in [1.0f32, 0.37, 3.25, 1234.5, 0.002, 65504.0 - 32.0] {
        let step = half_step(cpu);
        assert!(f64::from(step) > allowance(cpu), "cpu {cpu}: the step is the larger allowance");
        let at = cpu + step;
        let beyond = at.next_up();
        let one = |v: f32| vec![[cpu, 0.5, 0.25, 1.0], [v, 0.5, 0.25, 1.0]];
        let base = one(cpu);
        let ok = compare_float_in("half", true, ((2, 1), &base), ((2, 1), &one(at)), f16);
        assert!(ok.passed(), "cpu {cpu}: one step {step} passes: {}", ok.line());
        let bad = compare_float_in("half", true, ((2, 1), &base), ((2, 1), &one(beyond)), f16);
        assert!(!bad.passed(), "cpu {cpu}: past one step fails: {}", bad.line());
        let f32_buffer = compare_float("f32", true, ((2, 1), &base), ((2, 1), &one(at)));
        assert!(!f32_buffer.passed(), "cpu {cpu}: an f32 buffer allows no step");
    }
}

/// A smooth test picture (FLIP of a picture with itself is 0).
fn gradient(w: u32, h: u32) -> Vec<u8> {
    (0..w * h)
        .flat_map(|i| {
            let (x, y) = (i % w, i / w);
            [(x * 255 / w) as u8, (y * 255 / h) as u8, 128, 255]
        })
        .collect()
}

/// The image comparator: each limit fails just past it.
#[test]
fn image_comparator_fails_past_each_limit() {
    let (w, h) = (64u32, 64u32);
    let n = (w * h) as usize;
    let cpu = gradient(w, h);
    let limits = ImageLimits::SOFTWARE;
    let same = compare_image(&cpu, &cpu, w, h);
    assert_eq!(same.within_1, 1.0);
    assert_eq!(same.flip_mean, 0.0);
    assert!(same.failures(&limits).is_empty());

    // Within 1/255 everywhere still passes that criterion.
    let off_by_one: Vec<u8> = cpu.iter().map(|&v| v.saturating_add(1)).collect();
    assert_eq!(compare_image(&cpu, &off_by_one, w, h).within_1, 1.0);

    // ≥ 99.5 %: the largest number of pixels allowed 2/255 off, then one more.
    let allowed = n - (0.995 * n as f64).ceil() as usize;
    let mut gpu = cpu.clone();
    for p in 0..allowed {
        gpu[4 * (p * 97 % n)] ^= 2; // spread over the picture, 2/255 off
    }
    let s = compare_image(&cpu, &gpu, w, h);
    assert!(s.failures(&limits).is_empty(), "{}", s.line(&limits));
    let mut extra = allowed;
    while gpu[4 * (extra * 97 % n)] != cpu[4 * (extra * 97 % n)] {
        extra += 1;
    }
    gpu[4 * (extra * 97 % n)] ^= 2;
    let s = compare_image(&cpu, &gpu, w, h);
    assert!(
        s.failures(&limits).iter().any(|f| f.contains("within 1/255")),
        "one pixel past 99.5 %: {}",
        s.line(&limits)
    );

    // FLIP mean: a block of inverted pixels, grown until the mean passes 0.005; the block
    // one pixel smaller passes.
    let mut prev_ok: Option<Vec<u8>> = None;
    for k in 1..n {
        let mut gpu = cpu.clone();
        for p in 0..k {
            for c in 0..3 {
                gpu[4 * p + c] = 255 - gpu[4 * p + c];
            }
        }
        let s = compare_image(&cpu, &gpu, w, h);
        let loose = ImageLimits { min_within_1: None, ..limits };
        if s.flip_mean > limits.max_flip_mean {
            assert!(!s.failures(&loose).is_empty(), "{}", s.line(&loose));
            let ok = prev_ok.expect("a single changed pixel keeps the mean under 0.005");
            assert!(compare_image(&cpu, &ok, w, h).failures(&loose).is_empty());
            break;
        }
        prev_ok = Some(gpu);
    }
    // FLIP P99 (hardware row): the same with the P99 limit.
    let hw = ImageLimits::HARDWARE;
    let mut gpu = cpu.clone();
    for p in 0..n / 50 {
        for c in 0..3 {
            gpu[4 * p + c] = 255 - gpu[4 * p + c];
        }
    }
    let s = compare_image(&cpu, &gpu, w, h);
    assert!(s.flip_p99 > 0.1, "{}", s.line(&hw));
    assert!(s.failures(&hw).iter().any(|f| f.contains("P99")), "{}", s.line(&hw));
}

/// The envelope's comparators at their edges: a value at an interval's end passes and the next
/// f32 past it fails; a byte at its range's end passes and the next fails; a region with more
/// than 2 % ambiguous pixels fails even with nothing outside; nothing judged is no pass.
#[test]
fn envelope_comparators_fail_one_step_past_the_envelope() {
    use ocean_cpu::envelope::{ByteRange, Iv};
    use ocean_verify::envelope::{MAX_AMBIGUOUS_SHARE, judge_floats, judge_picture, judge_region};
    let e = Iv::new(1.0, 1.5);
    let env = vec![Some([e; 3]); 4];
    let inside = vec![[1.0f32, 1.5, 1.25, 0.0]; 4];
    assert!(judge_floats("x", &env, &inside, 2).passed());
    let mut past = inside.clone();
    past[3][1] = 1.5f32.next_up();
    let v = judge_floats("x", &env, &past, 2);
    assert_eq!((v.outside, v.worst.map(|w| (w.texel, w.channel))), (1, Some(((1, 1), 1))));
    assert!(!v.passed());
    past[3][1] = f32::NAN;
    assert!(!judge_floats("x", &env, &past, 2).passed(), "a NaN outside a bounded interval");
    let none: Vec<Option<[Iv; 3]>> = vec![None; 4];
    assert!(!judge_floats("x", &none, &inside, 2).passed(), "nothing judged");

    let bytes = vec![[(Iv::new(0.5, 0.5), ByteRange { lo: 100, hi: 102 }); 3]; 2];
    let exact = vec![101u8; 8];
    let ok = vec![100u8, 102, 101, 255, 101, 101, 101, 255];
    assert!(judge_picture("ldr", &bytes, &ok, &exact, 2).passed());
    let mut off = ok.clone();
    off[5] = 103;
    let p = judge_picture("ldr", &bytes, &off, &exact, 2);
    assert_eq!(
        (p.outside, p.worst.map(|w| (w.pixel, w.channel, w.got))),
        (1, Some(((1, 0), 1, 103)))
    );

    // 100 pixels: a pixel next to geometry that holds the sky's value is judged; one that
    // does not (the GPU covered it) is ambiguous: 2 pass, 3 fail.
    let env = vec![[e; 3]; 100];
    let mut gpu = vec![[1.2f32; 4]; 100];
    for k in [0, 1, 3] {
        gpu[k] = [5.0; 4];
    }
    let mut region = vec![Some(true); 100];
    region[0] = Some(false);
    region[1] = Some(false);
    region[2] = None;
    region[3] = None;
    region[5] = Some(false);
    let r = judge_region("hdr", &env, &region, &gpu, 10);
    assert_eq!((r.judged, r.ambiguous), (96, 2), "{}", r.line());
    let r = judge_region("hdr", &env, &region, &gpu, 10);
    assert!(r.passed() && r.ambiguous_share() <= MAX_AMBIGUOUS_SHARE, "{}", r.line());
    region[3] = Some(false);
    let r = judge_region("hdr", &env, &region, &gpu, 10);
    assert!(!r.passed(), "3 % ambiguous passed: {}", r.line());
    // A picture whose alpha is not 255 fails; an empty one is no pass.
    let mut alpha = ok.clone();
    alpha[3] = 254;
    assert!(!judge_picture("ldr", &bytes, &alpha, &exact, 2).passed());
    assert!(!judge_picture("ldr", &[], &[], &[], 2).passed(), "nothing judged");
}
