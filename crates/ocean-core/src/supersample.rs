//! Supersampled frames (`ocean render --spp N`): the ground truth the far-field techniques
//! are measured against (issue 12).
//!
//! **Pattern.** N = k² samples per pixel on the regular stratified k × k grid: sample (i, j)
//! of pixel (x, y) is at (x + (i + ½)/k, y + (j + ½)/k). It is rendered as the frame at
//! k·width × k·height (the same camera, so the same field of view) on either back end: every
//! pass runs at that size, so what is sampled is the whole frame, waves, maps and all.
//!
//! **Filter.** A box over each pixel's k² samples, of the *linear* HDR radiance (a pixel
//! integrates radiance; the tonemap is applied once, to the mean), summed in f64 in row-major
//! order and rounded once to f32: deterministic, independent of threads.

use crate::{Error, Result};

/// The largest samples per pixel: 16 × 16.
pub const MAX_SPP: u32 = 256;

/// k for N = k² samples per pixel.
///
/// # Errors
/// N not a perfect square from 1 to [`MAX_SPP`].
pub fn grid_side(spp: u32) -> Result<u32> {
    let k = f64::from(spp).sqrt().round() as u32;
    if spp == 0 || spp > MAX_SPP || k * k != spp {
        return Err(Error::InvalidParameter {
            name: "spp",
            value: f64::from(spp),
            reason: format!(
                "samples per pixel must be a perfect square k² (1, 4, 9, …, {MAX_SPP}): the \
                 samples lie on a k × k grid in each pixel"
            ),
        });
    }
    Ok(k)
}

/// The box filter of a `k·width × k·height` RGBA image down to `width × height`: each output
/// texel the mean of its k × k block.
///
/// # Panics
/// If `samples` does not hold `k·width × k·height` texels.
pub fn box_filter(samples: &[[f32; 4]], width: u32, height: u32, k: u32) -> Vec<[f32; 4]> {
    let (w, h, k) = (width as usize, height as usize, k as usize);
    assert_eq!(samples.len(), w * k * h * k, "a {w}×{h} frame at {k}×{k} samples per pixel");
    let row = w * k;
    let inv = 1.0 / (k * k) as f64;
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let mut sum = [0.0f64; 4];
            for j in 0..k {
                let start = (y * k + j) * row + x * k;
                for s in &samples[start..start + k] {
                    for c in 0..4 {
                        sum[c] += f64::from(s[c]);
                    }
                }
            }
            out.push(sum.map(|v| (v * inv) as f32));
        }
    }
    out
}

/// The bands of sea the far-field checks measure separately, by the depression of a pixel
/// row's centre ray below the horizon (docs/design.md, "Filtering and ground truth").
pub const BAND_NAMES: [&str; 3] = ["horizon", "middle", "near"];

/// Upper bounds of the horizon and middle bands' depressions, degrees: horizon below 2°,
/// middle 2°–8°, near beyond.
pub const BAND_EDGES_DEG: [f64; 2] = [2.0, 8.0];

/// The pixel rows of each band of [`BAND_NAMES`] for `camera` at `height` rows (rows whose
/// centre ray does not point below the horizon belong to none). The rows' rays are taken at
/// the image's centre column: a band is a set of whole rows.
pub fn sea_bands(camera: &crate::camera::Camera, height: u32) -> [Vec<u32>; 3] {
    let mut out = [Vec::new(), Vec::new(), Vec::new()];
    for y in 0..height {
        let ndc_y = 1.0 - (f64::from(y) + 0.5) / f64::from(height) * 2.0;
        let d = camera.ray_direction(0.0, ndc_y);
        let depression = (-d.y).asin().to_degrees();
        if depression > 0.0 {
            let band = BAND_EDGES_DEG.iter().filter(|&&e| depression >= e).count();
            out[band].push(y);
        }
    }
    out
}

/// log(1 + luminance) of a linear RGBA pixel (Rec. 709 weights), the metric's scale: close
/// to relative error in bright pixels, to absolute error in dark ones.
pub fn log_luminance(p: &[f32; 4]) -> f64 {
    (1.0 + luminance(p)).ln()
}

/// Rec. 709 luminance of a linear RGBA pixel.
pub fn luminance(p: &[f32; 4]) -> f64 {
    0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2])
}

/// Mean |log(1 + L_a) − log(1 + L_b)| over the rows `rows` of two `width`-wide frames; NaN
/// for no rows.
pub fn band_error(a: &[[f32; 4]], b: &[[f32; 4]], width: u32, rows: &[u32]) -> f64 {
    band_mean(width, rows, |i| (log_luminance(&a[i]) - log_luminance(&b[i])).abs())
}

/// Mean luminance over the rows `rows` of a `width`-wide frame; NaN for no rows.
pub fn band_luminance(a: &[[f32; 4]], width: u32, rows: &[u32]) -> f64 {
    band_mean(width, rows, |i| luminance(&a[i]))
}

fn band_mean(width: u32, rows: &[u32], f: impl Fn(usize) -> f64) -> f64 {
    let w = width as usize;
    let sum: f64 = rows.iter().flat_map(|&y| (0..w).map(move |x| y as usize * w + x)).map(f).sum();
    sum / (rows.len() * w) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_perfect_squares_are_sample_counts() {
        for (n, k) in [(1, 1), (4, 2), (9, 3), (64, 8), (256, 16)] {
            assert_eq!(grid_side(n).ok(), Some(k));
        }
        for n in [0, 2, 3, 8, 63, 257, 1024] {
            assert!(grid_side(n).is_err(), "{n}");
        }
    }

    #[test]
    fn the_box_filter_averages_each_block() {
        // A 2×1 frame at 2×2 samples: left block 0, 1, 2, 3 (mean 1.5), right block all 8.
        let s = |v: f32| [v, 2.0 * v, 0.0, 1.0];
        let samples = [s(0.0), s(1.0), s(8.0), s(8.0), s(2.0), s(3.0), s(8.0), s(8.0)];
        let out = box_filter(&samples, 2, 1, 2);
        assert_eq!(out, vec![[1.5, 3.0, 0.0, 1.0], [8.0, 16.0, 0.0, 1.0]]);
        // k = 1 is the identity.
        assert_eq!(box_filter(&samples, 4, 2, 1), samples.to_vec());
    }

    #[test]
    fn band_metrics_average_their_rows_only() {
        // 2 × 3 frame: row 0 luminance 1, row 1 luminance e − 1 (log 1), row 2 luminance 3.
        let grey = |v: f32| [v, v, v, 1.0];
        let e1 = std::f32::consts::E - 1.0;
        let a = [grey(1.0), grey(1.0), grey(e1), grey(e1), grey(3.0), grey(3.0)];
        let b = [grey(0.0); 6];
        assert!((band_luminance(&a, 2, &[0, 2]) - 2.0).abs() < 1e-6);
        assert!((band_error(&a, &b, 2, &[1]) - 1.0).abs() < 1e-6);
        assert_eq!(band_error(&a, &a, 2, &[0, 1, 2]), 0.0);
        assert!(band_error(&a, &b, 2, &[]).is_nan());
    }

    #[test]
    fn bands_split_the_rows_below_the_horizon_by_depression() {
        let scene = crate::scene::Scene::builtin();
        let mut cam = scene.camera.clone();
        cam.height = 180;
        let camera = crate::camera::Camera::from_scene(&cam).expect("the built-in camera");
        let bands = sea_bands(&camera, 180);
        for (band, rows) in bands.iter().enumerate() {
            for &y in rows {
                let ndc_y = 1.0 - (f64::from(y) + 0.5) / 180.0 * 2.0;
                let dep = (-camera.ray_direction(0.0, ndc_y).y).asin().to_degrees();
                let (lo, hi) = [(0.0, 2.0), (2.0, 8.0), (8.0, 90.0)][band];
                assert!(dep > lo && dep <= hi + 1e-9 && (band == 2 || dep < hi), "{y}: {dep}");
            }
        }
        // Every band of the built-in view holds rows, and rows are in order horizon → near.
        assert!(bands.iter().all(|r| !r.is_empty()));
        assert!(bands[0].last() < bands[1].first() && bands[1].last() < bands[2].first());
    }
}
