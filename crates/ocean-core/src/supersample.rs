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
}
