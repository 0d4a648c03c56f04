//! What an error looks like (issue 18, item 2): for each knob that changes the picture, a crop
//! of the frame at each setting beside the reference's, and the FLIP error map of the setting
//! against it (NVIDIA's ꟻLIP, its magma colour map: black is no visible difference, yellow the
//! most). The crop is the window where the setting furthest from the reference differs most,
//! so the reader looks where the error is; for the far field, the band at the horizon.
//!
//! The measurements hand their frames to [`Pictures`] as they go; [`Pictures::write`] writes
//! the PNGs into `pictures/` beside the page and returns what the page shows.

use std::cell::RefCell;
use std::path::Path;

use ocean::output::write_atomic;

use super::svg::png_rgb;

/// One setting's frame, 8-bit sRGB.
pub(super) struct Shot {
    /// The setting.
    pub setting: String,
    /// RGB, row-major.
    pub rgb: Vec<u8>,
}

/// A knob's frames, one per setting, all `width` × `height`.
pub(super) struct Set {
    /// The knob.
    pub knob: &'static str,
    /// What the reference is (the caption's words).
    pub reference_is: String,
    /// Frame size.
    pub width: u32,
    /// Frame size.
    pub height: u32,
    /// The settings' frames.
    pub shots: Vec<Shot>,
    /// Which of `shots` is the reference.
    pub reference: usize,
    /// Rows to show (the horizon band) instead of the window of largest error.
    pub rows: Option<(u32, u32)>,
}

/// The frames the measurements collected.
#[derive(Default)]
pub(super) struct Pictures(RefCell<Vec<Set>>);

/// One picture of the page: a crop, and where the setting is not the reference its FLIP map.
pub(super) struct Shown {
    /// The setting.
    pub setting: String,
    /// The crop's file, relative to the page.
    pub crop: String,
    /// The FLIP map's file; `None` for the reference.
    pub flip: Option<String>,
    /// The mean FLIP of the whole frame against the reference.
    pub flip_mean: f64,
    /// Whether this is the reference.
    pub is_reference: bool,
}

/// A knob's pictures on the page.
pub(super) struct Written {
    /// The knob.
    pub knob: &'static str,
    /// What the crop is, in words.
    pub caption: String,
    /// Crop size (px).
    pub size: (u32, u32),
    /// The pictures, in the knob's order.
    pub shown: Vec<Shown>,
}

/// The HDR frame through the tonemap pass's own functions (ocean-cpu's mirror of
/// `tonemap.wgsl`: exposure, the default ACES curve, clamp, sRGB, 8-bit rounding), for showing
/// the far field's and the techniques' HDR frames; without the pass's vignette and bloom, which
/// the frame's own output would add. A non-finite value shows as 0.
pub(super) fn display(hdr: &[[f32; 4]], exposure: f32) -> Vec<u8> {
    use ocean_cpu::shaders::tonemap::{TonemapUniforms, quantize_unorm8, srgb_oetf, tone_curve};
    use ocean_cpu::shaders::wgsl::{Vec3, clamp};
    let curve = TonemapUniforms::DEFAULT;
    hdr.iter()
        .flat_map(|p| {
            let exposed = [p[0], p[1], p[2]]
                .map(|c| if c.is_finite() { (c * exposure).max(0.0) } else { 0.0 });
            let mapped =
                clamp(tone_curve(Vec3::from(exposed), &curve), Vec3::splat(0.0), Vec3::splat(1.0));
            let encoded: [f32; 3] = quantize_unorm8(srgb_oetf(mapped)).into();
            encoded.map(|c| (c * 255.0).round() as u8)
        })
        .collect()
}

/// The FLIP map of `test` against `reference` (full frame, values in [0, 1]).
fn flip_map(reference: &[u8], test: &[u8], w: u32, h: u32) -> nv_flip::FlipImageFloat {
    let a = nv_flip::FlipImageRgb8::with_data(w, h, reference);
    let b = nv_flip::FlipImageRgb8::with_data(w, h, test);
    nv_flip::flip(a, b, nv_flip::DEFAULT_PIXELS_PER_DEGREE)
}

/// The `cw` × `ch` window (top-left corner) of `map` with the largest summed value, searched on
/// a grid of sixteenths of the frame.
fn worst_window(map: &[f32], w: u32, h: u32, cw: u32, ch: u32) -> (u32, u32) {
    let (sx, sy) = ((w / 16).max(1), (h / 16).max(1));
    let mut best = (0.0f64, (0, 0));
    let mut y = 0;
    while y + ch <= h {
        let mut x = 0;
        while x + cw <= w {
            let mut s = 0.0f64;
            for j in y..y + ch {
                let row = (j * w) as usize;
                s += map[row + x as usize..row + (x + cw) as usize]
                    .iter()
                    .map(|v| f64::from(*v))
                    .sum::<f64>();
            }
            if s > best.0 {
                best = (s, (x, y));
            }
            x += sx;
        }
        y += sy;
    }
    best.1
}

/// The `(x, y, cw, ch)` crop of an RGB frame `w` wide.
fn crop(rgb: &[u8], w: u32, (x, y, cw, ch): (u32, u32, u32, u32)) -> Vec<u8> {
    let mut out = Vec::with_capacity((cw * ch * 3) as usize);
    for j in y..y + ch {
        let start = ((j * w + x) * 3) as usize;
        out.extend_from_slice(&rgb[start..start + (cw * 3) as usize]);
    }
    out
}

impl Pictures {
    /// Keeps a knob's frames for the page.
    pub(super) fn add(&self, set: Set) {
        self.0.borrow_mut().push(set);
    }

    /// Writes every knob's crops and FLIP maps into `dir/pictures` and returns what the page
    /// shows.
    pub(super) fn write(&self, dir: &Path) -> anyhow::Result<Vec<Written>> {
        let sub = dir.join("pictures");
        std::fs::create_dir_all(&sub)?;
        let lut = nv_flip::magma_lut();
        let mut out = Vec::new();
        for set in self.0.borrow().iter() {
            let (w, h) = (set.width, set.height);
            let reference = &set.shots[set.reference].rgb;
            let maps: Vec<Option<nv_flip::FlipImageFloat>> = set
                .shots
                .iter()
                .enumerate()
                .map(|(i, s)| (i != set.reference).then(|| flip_map(reference, &s.rgb, w, h)))
                .collect();
            let means: Vec<f64> = maps
                .iter()
                .map(|m| {
                    m.as_ref().map_or(0.0, |m| f64::from(nv_flip::FlipPool::from_image(m).mean()))
                })
                .collect();
            let (window, caption) = match set.rows {
                Some((y0, y1)) => {
                    let y1 = y1.min(h).max(y0 + 1);
                    (
                        (0, y0, w, y1 - y0),
                        format!(
                            "rows {y0}–{y1} of the {w}×{h} frame: the sea within 2° of the horizon and the sky above it; reference: {}",
                            set.reference_is
                        ),
                    )
                }
                None => {
                    let (cw, ch) = ((w / 2).max(1), (h / 2).max(1));
                    let worst = means
                        .iter()
                        .enumerate()
                        .max_by(|a, b| a.1.total_cmp(b.1))
                        .map_or(set.reference, |(i, _)| i);
                    let (x, y) = maps[worst]
                        .as_ref()
                        .map_or((w / 4, h / 4), |m| worst_window(&m.to_vec(), w, h, cw, ch));
                    (
                        (x, y, cw, ch),
                        format!(
                            "the {cw}×{ch} window of the {w}×{h} frame where “{}” differs most; reference: {}",
                            set.shots[worst].setting, set.reference_is
                        ),
                    )
                }
            };
            let mut shown = Vec::new();
            for (i, shot) in set.shots.iter().enumerate() {
                let name = format!("{}_{i}.png", set.knob);
                write_atomic(
                    &sub.join(&name),
                    &png_rgb(&crop(&shot.rgb, w, window), window.2, window.3)?,
                )?;
                let flip = match &maps[i] {
                    Some(m) => {
                        let coloured = m.apply_color_lut(&lut).to_vec();
                        let fname = format!("{}_{i}_flip.png", set.knob);
                        write_atomic(
                            &sub.join(&fname),
                            &png_rgb(&crop(&coloured, w, window), window.2, window.3)?,
                        )?;
                        Some(format!("pictures/{fname}"))
                    }
                    None => None,
                };
                shown.push(Shown {
                    setting: shot.setting.clone(),
                    crop: format!("pictures/{name}"),
                    flip,
                    flip_mean: means[i],
                    is_reference: i == set.reference,
                });
            }
            out.push(Written { knob: set.knob, caption, size: (window.2, window.3), shown });
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_window_is_where_the_map_is_largest() {
        let (w, h) = (64, 32);
        let mut map = vec![0.0f32; (w * h) as usize];
        for j in 20..28 {
            for i in 40..56 {
                map[(j * w + i) as usize] = 1.0;
            }
        }
        let (x, y) = worst_window(&map, w, h, 16, 8);
        assert!((36..=40).contains(&x) && (18..=20).contains(&y), "{x} {y}");
        // Control: an empty map leaves the first window.
        assert_eq!(worst_window(&vec![0.0; (w * h) as usize], w, h, 16, 8), (0, 0));
    }

    #[test]
    fn display_maps_black_to_black_and_bright_to_white() {
        let rgb = display(&[[0.0; 4], [1e6, 1e6, 1e6, 1.0], [f32::NAN, 0.0, 0.0, 1.0]], 1.0);
        assert_eq!(&rgb[0..3], &[0, 0, 0]);
        assert_eq!(&rgb[3..6], &[255, 255, 255]);
        assert_eq!(rgb[6], 0);
    }
}
