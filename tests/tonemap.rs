//! The `tonemap` stage: the CPU mirror (f32) against the closed forms in f64 written here
//! independently (Narkowicz's ACES fit, the IEC 61966-2-1 sRGB OETF, 8-bit rounding with ties
//! to even),
//! its invariants (0 → 0, monotonic, NaN/inf handling) and the full-frame driver against one
//! compute invocation per pixel. Each comparator has a negative control.

use ocean_core::tonemap::TonemapUniforms;
use ocean_cpu::shaders::tonemap::{
    HdrFrame, aces_narkowicz, cs_main, quantize_unorm8, srgb_oetf, store_unorm8, tonemap_to_rgba8,
};

/// Narkowicz (2016): x(ax + b) / (x(cx + d) + e), a = 2.51, b = 0.03, c = 2.43, d = 0.59,
/// e = 0.14; typed from the post, in f64.
fn aces_f64(x: f64) -> f64 {
    let (a, b, c, d, e) = (2.51, 0.03, 2.43, 0.59, 0.14);
    (x * (a * x + b)) / (x * (c * x + d) + e)
}

/// IEC 61966-2-1: V = 12.92 L for L ≤ 0.0031308, else 1.055 L^(1/2.4) − 0.055.
fn srgb_f64(l: f64) -> f64 {
    if l <= 0.0031308 { 12.92 * l } else { 1.055 * l.powf(1.0 / 2.4) - 0.055 }
}

/// The whole pixel pipeline in f64: exposure, clamp at 0, operator, clamp to 1, OETF, 8 bits
/// rounding to nearest, ties to even.
fn pipeline_f64(hdr: f64, exposure: f64) -> u8 {
    let x = (hdr * exposure).max(0.0);
    let v = srgb_f64(aces_f64(x).min(1.0));
    (v * 255.0).round_ties_even() as u8
}

/// One pixel through the CPU fragment shader: the byte of channel 0 (all channels equal).
fn shade(hdr: f32, exposure: f32) -> u8 {
    let texels = [[hdr, hdr, hdr, 1.0]];
    let frame = HdrFrame { width: 1, height: 1, texels: &texels };
    let u = TonemapUniforms { exposure, ..TonemapUniforms::DEFAULT };
    let rgba = cs_main([0, 0], &u, &frame);
    assert_eq!(rgba[0], rgba[1]);
    assert_eq!(rgba[3], 1.0);
    store_unorm8(rgba[0])
}

/// Inputs from 0 to 100 on a log scale plus the special ones.
fn sweep() -> Vec<f32> {
    let mut v: Vec<f32> = (0..=4000).map(|i| 10f32.powf(-6.0 + 8.0 * i as f32 / 4000.0)).collect();
    v.extend([0.0, 1.0, 7.24, 0.0031308]);
    v
}

#[test]
fn operator_matches_its_closed_form() {
    let mut worst = 0.0f64;
    for x in sweep() {
        let got = f64::from(aces_narkowicz([x; 3].into()).x);
        worst = worst.max((got - aces_f64(f64::from(x))).abs());
    }
    println!("ACES fit, f32 vs f64: max abs error {worst:.2e}");
    // Output ≤ 1.033: a few f32 ULP (1.2e-7 each near 1).
    assert!(worst < 5e-7, "{worst}");
    // Negative control: Reinhard's x / (1 + x) is not this operator.
    let reinhard = |x: f64| x / (1.0 + x);
    assert!((reinhard(1.0) - f64::from(aces_narkowicz([1.0; 3].into()).x)).abs() > 0.1);
    // Documented values: f(0) = 0, f(1) ≈ 0.80 ("1 maps to ~0.8"), f reaches 1 at ≈ 7.24.
    assert_eq!(aces_narkowicz([0.0; 3].into()), [0.0; 3].into());
    assert!((aces_f64(1.0) - 0.8038).abs() < 1e-4);
    let one = (0.56 + (0.56f64 * 0.56 + 4.0 * 0.08 * 0.14).sqrt()) / 0.16;
    assert!((aces_f64(one) - 1.0).abs() < 1e-12 && (one - 7.24).abs() < 0.01);
}

#[test]
fn operator_is_monotonic() {
    // f64: strictly increasing on [0, 10⁴] (the derivative's numerator 0.3797x² + 0.7028x +
    // 0.0042 > 0 for x ≥ 0).
    let f: Vec<f64> = (0..=100_000).map(|i| aces_f64(i as f64 * 0.1)).collect();
    assert!(f.windows(2).all(|w| w[1] > w[0]));
    // The stage's observable output, the byte, never decreases as the input grows.
    let bytes: Vec<u8> = (0..=200_000).map(|i| shade(i as f32 * 5e-5, 1.0)).collect();
    assert!(bytes.windows(2).all(|w| w[1] >= w[0]));
    assert_eq!((bytes[0], bytes[200_000]), (0, 255));
}

#[test]
fn srgb_oetf_matches_iec_61966_2_1() {
    let below = 0.0031308f32;
    let above = f32::from_bits(below.to_bits() + 1);
    for l in [0.0, 1e-6, 0.001, below, above, 0.01, 0.18, 0.5, 0.9, 1.0] {
        let got = f64::from(srgb_oetf([l; 3].into()).x);
        let want = srgb_f64(f64::from(l));
        assert!((got - want).abs() < 3e-7, "L = {l}: {got} vs {want}");
    }
    // The two pieces meet at the breakpoint (to 1e-7: the standard's rounded constants).
    let l = 0.0031308f64;
    assert!((12.92 * l - (1.055 * l.powf(1.0 / 2.4) - 0.055)).abs() < 1e-7);
    // The linear piece is used at the breakpoint, the power piece just above.
    assert_eq!(srgb_oetf([below; 3].into()).x, 12.92 * below);
    assert_ne!(srgb_oetf([above; 3].into()).x, 12.92 * above);
    // Negative control: a pure 2.2 gamma differs visibly in the shadows.
    assert!((0.01f64.powf(1.0 / 2.2) - srgb_f64(0.01)).abs() > 0.01);
}

#[test]
fn quantisation_rounds_to_nearest_ties_to_even() {
    // Values v whose v · 255 is exactly k + ½ in f32 go to the even one of k, k + 1; the f32
    // just below and just above go to k and k + 1.
    let mut midpoints = 0;
    for k in 0..255u32 {
        let target = k as f32 + 0.5;
        let guess = target / 255.0;
        let Some(v) =
            [guess, f32::from_bits(guess.to_bits() - 1), f32::from_bits(guess.to_bits() + 1)]
                .into_iter()
                .find(|v| v * 255.0 == target)
        else {
            continue;
        };
        midpoints += 1;
        let even = if k % 2 == 0 { k } else { k + 1 };
        let byte = |v: f32| store_unorm8(quantize_unorm8([v; 3].into()).x);
        assert_eq!(byte(v), even as u8, "k = {k}");
        assert_eq!(quantize_unorm8([v; 3].into()).x, even as f32 / 255.0);
        let mut below = f32::from_bits(v.to_bits() - 1);
        while below * 255.0 >= target {
            below = f32::from_bits(below.to_bits() - 1);
        }
        let mut above = f32::from_bits(v.to_bits() + 1);
        while above * 255.0 <= target {
            above = f32::from_bits(above.to_bits() + 1);
        }
        assert_eq!((byte(below), byte(above)), (k as u8, (k + 1) as u8), "k = {k}");
        // Negative control: rounding halves up differs at every even k.
        if k % 2 == 0 {
            assert_ne!((v * 255.0 + 0.5).floor() as u32, even, "k = {k}");
        }
    }
    assert!(midpoints > 100, "only {midpoints} exact midpoints found");
    // Every output is a multiple of 1/255 that the Rgba8Unorm store maps back exactly.
    for k in 0..=255u8 {
        let q = quantize_unorm8([f32::from(k) / 255.0; 3].into()).x;
        assert_eq!(store_unorm8(q), k);
        assert!(((q * 255.0) - f32::from(k)).abs() < 2e-5);
    }
}

#[test]
fn nan_and_infinities_have_documented_outputs() {
    assert_eq!(shade(f32::NAN, 1.0), 0, "NaN → 0");
    assert_eq!(shade(f32::INFINITY, 1.0), 255, "+inf → white");
    assert_eq!(shade(f32::NEG_INFINITY, 1.0), 0, "−inf → 0");
    assert_eq!(shade(-5.0, 1.0), 0, "negative → 0");
    assert_eq!(shade(f32::MAX, 1.0), 255);
    assert_eq!(shade(f32::MAX, 1e30), 255, "overflow of hdr × exposure → white");
    assert_eq!(shade(1e-30, 1.0), 0);
    // Mixed channels stay independent.
    let texels = [[f32::NAN, 0.18, f32::INFINITY, f32::NAN]];
    let frame = HdrFrame { width: 1, height: 1, texels: &texels };
    let px = cs_main([0, 0], &TonemapUniforms::DEFAULT, &frame);
    assert_eq!(px.map(store_unorm8), [0, pipeline_f64(0.18, 1.0), 255, 255]);
}

#[test]
fn pipeline_matches_the_f64_closed_forms() {
    // The f32 stage and the f64 pipeline agree on the byte except where the f64 value lies
    // within f32 round-off of a rounding boundary: then by one step.
    let mut differ = 0;
    let inputs = sweep();
    for &exposure in &[0.25f32, 1.0, 3.0] {
        for &x in &inputs {
            let (got, want) = (shade(x, exposure), pipeline_f64(f64::from(x), f64::from(exposure)));
            assert!(got.abs_diff(want) <= 1, "x = {x}, exposure = {exposure}: {got} vs {want}");
            if got != want {
                differ += 1;
            }
        }
    }
    let total = 3 * inputs.len();
    println!("tonemap bytes, f32 vs f64: {differ} of {total} differ by 1");
    assert!(differ * 1000 <= total, "{differ} of {total} bytes differ");
    // Negative control: exposure ignored would change most mid-tones.
    let ignored =
        inputs.iter().filter(|&&x| shade(x, 3.0) != pipeline_f64(f64::from(x), 1.0)).count();
    assert!(ignored > inputs.len() / 4);
}

#[test]
fn frame_driver_equals_one_invocation_per_pixel() {
    // tonemap_to_rgba8 calls cs_main once per pixel, as the dispatch does: the same bytes, in
    // RGBA order, row 0 first.
    let (w, h) = (37u32, 23u32);
    let hdr: Vec<[f32; 4]> = (0..w * h)
        .map(|i| {
            let t = i as f32 / (w * h) as f32;
            [t * 8.0, (1.0 - t) * 0.5, if i % 97 == 0 { f32::NAN } else { t * t }, 1.0]
        })
        .collect();
    let u = TonemapUniforms::new(1.3).unwrap();
    let bytes = tonemap_to_rgba8(&hdr, w, h, &u);
    assert_eq!(bytes.len(), (w * h * 4) as usize);

    let frame = HdrFrame { width: w, height: h, texels: &hdr };
    let raster: Vec<u8> = (0..h)
        .flat_map(|y| (0..w).map(move |x| [x, y]))
        .flat_map(|id| cs_main(id, &u, &frame).map(store_unorm8))
        .collect();
    assert_eq!(bytes, raster);
    assert!(bytes.chunks(4).all(|p| p[3] == 255));
    // Negative control: a transposed read (x and y swapped) gives other bytes.
    let mut swapped = bytes.clone();
    swapped.swap(4, 4 * w as usize);
    assert_ne!(swapped, raster);
}

#[test]
fn exposure_is_validated() {
    assert!(TonemapUniforms::new(1.0).is_ok());
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e300, 1e-300] {
        assert!(TonemapUniforms::new(bad).is_err(), "{bad}");
    }
    assert_eq!(TonemapUniforms::DEFAULT.exposure, 1.0);
}
