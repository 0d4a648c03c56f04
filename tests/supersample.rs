//! `ocean render --spp N` (issue 12, item 1): the supersampled ground truth. N = 1 is the
//! plain frame; more samples converge on the 64-sample frame; bad counts are refused.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[path = "support/cli.rs"]
mod ocean_cli;

use ocean_core::plan::OutputKind;
use ocean_core::scene::Scene;
use ocean_core::supersample::{box_filter, grid_side};

use ocean_cli::ocean;

#[test]
fn one_sample_per_pixel_is_the_plain_frame() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.png"), dir.path().join("b.png"));
    let o = ocean(&["render", "--size", "64x36", "-o", a.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = ocean(&["render", "--size", "64x36", "--spp", "1", "-o", b.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap());
}

#[test]
fn sample_counts_that_are_not_squares_or_too_many_are_refused() {
    for n in ["0", "3", "300", "-4", "many"] {
        let o = ocean(&["render", "--size", "16x9", "--spp", n, "-o", "/tmp/never.png"]);
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && e.contains("--spp"), "--spp {n}: {e}");
    }
    // k × the size must fit the largest image.
    let o = ocean(&["render", "--size", "4096x16", "--spp", "25", "-o", "/tmp/never.png"]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("--spp 25 (a 20480×80 frame)") && e.contains("camera.width"), "{e}");
}

/// log(1 + luminance) of each pixel (Rec. 709 weights).
fn log_luminance(hdr: &[[f32; 4]]) -> Vec<f64> {
    hdr.iter()
        .map(|p| {
            (1.0 + 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]))
                .ln()
        })
        .collect()
}

fn mean_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum::<f64>() / a.len() as f64
}

/// The default scene's HDR frame at `w × h`, `spp` samples per pixel.
fn frame(w: u32, h: u32, spp: u32) -> Vec<[f32; 4]> {
    let k = grid_side(spp).unwrap();
    let mut s = Scene::builtin();
    (s.camera.width, s.camera.height) = (w * k, h * k);
    let r = ocean_cpu::render_scene(&s, OutputKind::Hdr, &mut |_| {}).unwrap();
    box_filter(&r.buffers.hdr.color, w, h, k)
}

#[test]
fn more_samples_converge_on_the_64_sample_frame() {
    let (w, h) = (80, 45);
    let reference = log_luminance(&frame(w, h, 64));
    let errors: Vec<(u32, f64)> = [1, 4, 16]
        .into_iter()
        .map(|spp| (spp, mean_abs_diff(&log_luminance(&frame(w, h, spp)), &reference)))
        .collect();
    eprintln!("mean |Δ log(1+L)| against 64 spp at {w}×{h}: {errors:?}");
    // The 1-sample frame is far from the reference (the sparkle the far-field techniques are
    // to remove); stratified sampling of an edge-dominated picture converges as ~1/k, so each
    // doubling of k must take at least a quarter off the error.
    assert!(errors[0].1 > 0.01, "{errors:?}");
    assert!(errors[1].1 < 0.75 * errors[0].1 && errors[2].1 < 0.75 * errors[1].1, "{errors:?}");
}
