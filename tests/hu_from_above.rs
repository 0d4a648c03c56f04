//! Hu's surface seen from high up keeps its waves (issue 38 item 3): seed 000's near patch
//! follows the viewer, and the far patch beyond it carries neither displacement nor the
//! displacement map's slopes (only the bump map's), so an eye too high for the near patch to
//! cover its view sees the sea as bump-map speckle without its swell. The projected grid of
//! the same sea, from the same eye, displaces and shades every visible point with the
//! displacement map: it is the reference here.
//!
//! The measure, **large-scale wave contrast**: the frame's log-luminance band-passed — its mean
//! over a 3×3 box (the bump map's pixel-scale speckle averages out) less its mean over a 25×25
//! box (the Fresnel gradient towards the horizon and the glitter path's breadth cancel) —
//! RMS over the pixels whose coarse box lies below the horizon by [`BELOW_HORIZON_RAD`] (judged
//! at the box's top row, in the frame's centre column). From eye heights 10, 100, 300 and
//! 1000 m the `hu` frame's contrast must lie within [`MAX_RATIO`] of the projected grid's, both
//! ways. Negative control: the same measure tells a sea without its swell (the projected grid
//! of a calmer sea) apart.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use ocean_core::camera::{Camera, pixel_centre_ndc};
use ocean_core::plan::OutputKind;
use ocean_core::scene::{Scene, SceneSource};

/// Frame size.
const SIZE: (u32, u32) = (384, 216);
/// The band-pass's fine box: its half side, pixels (the bump map's speckle averages out).
const NARROW: usize = 1;
/// The band-pass's coarse box: its half side, pixels (the Fresnel gradient and the glitter
/// path's breadth stay in it and cancel).
const WIDE: usize = 12;
/// Blocks are measured where every pixel's ray is at least this far below the horizon, rad.
const BELOW_HORIZON_RAD: f64 = 0.03;
/// Largest ratio between the two frames' contrasts, either way.
const MAX_RATIO: f64 = 1.5;

/// The default sea (hu) seen from `height_m` up, looking down 15° towards −z, with surface
/// `surface`.
fn scene(height_m: f64, surface: &str, wind: f64) -> Scene {
    let ahead = height_m / 15f64.to_radians().tan();
    let text = format!(
        "system = \"hu\"\n[techniques]\nsurface = \"{surface}\"\n[ocean]\nwind_speed = {wind}\n\
         [camera]\nposition = [0.0, {height_m}, 0.0]\nlook_at = [0.0, 0.0, {}]\nwidth = {}\n\
         height = {}\n[sun]\ndirection = [0.35, 0.5, -1.0]\nintensity = 5.0\n",
        -ahead, SIZE.0, SIZE.1
    );
    Scene::from_toml(&text, SceneSource::Text).unwrap_or_else(|e| panic!("{e}"))
}

/// The mean of `img` (`w` wide) over the square of side 2r + 1 about (x, y), all inside.
fn box_mean(img: &[f64], w: usize, x: usize, y: usize, r: usize) -> f64 {
    let mut sum = 0.0;
    for yy in y - r..=y + r {
        sum += img[yy * w + x - r..=yy * w + x + r].iter().sum::<f64>();
    }
    sum / ((2 * r + 1) * (2 * r + 1)) as f64
}

/// The wave contrast of a scene's frame (the module doc).
fn contrast(scene: &Scene) -> f64 {
    let r = ocean_cpu::render_scene(scene, OutputKind::Hdr, &mut |_| {}).unwrap();
    let (w, h) = (SIZE.0 as usize, SIZE.1 as usize);
    let log_l: Vec<f64> = r
        .buffers
        .hdr
        .color
        .iter()
        .map(|c| f64::from(0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]).max(1e-6).ln())
        .collect();
    let camera = Camera::from_scene(&scene.camera).unwrap();
    let (mut sum2, mut n) = (0.0, 0usize);
    for y in WIDE..h - WIDE {
        // The window's top row is the nearest to the horizon.
        let (nx, ny) = pixel_centre_ndc(SIZE.0 / 2, (y - WIDE) as u32, SIZE.0, SIZE.1);
        if camera.ray_direction(nx, ny).y > -BELOW_HORIZON_RAD.sin() {
            continue;
        }
        for x in WIDE..w - WIDE {
            let band = box_mean(&log_l, w, x, y, NARROW) - box_mean(&log_l, w, x, y, WIDE);
            sum2 += band * band;
            n += 1;
        }
    }
    assert!(n > 1000, "too few pixels below the horizon: {n}");
    (sum2 / n as f64).sqrt()
}

/// Ok when `a` and `b` lie within [`MAX_RATIO`] of each other.
fn within_ratio(a: f64, b: f64) -> bool {
    a > 0.0 && b > 0.0 && a / b <= MAX_RATIO && b / a <= MAX_RATIO
}

#[test]
fn hus_sea_keeps_its_swell_from_every_height() {
    let mut failures = Vec::new();
    for height in [10.0, 100.0, 300.0, 1000.0] {
        let hu = contrast(&scene(height, "hu_patches", 9.0));
        let grid = contrast(&scene(height, "projected_grid", 9.0));
        let line = format!(
            "eye {height:6} m: contrast hu {hu:.4}, projected grid {grid:.4}, ratio {:.2}",
            hu / grid
        );
        println!("{line}");
        if !within_ratio(hu, grid) {
            failures.push(line);
        }
    }
    // Negative control: the projected grid of a calmer sea, whose swell is a fraction of the
    // height, against the sea's.
    let calm = contrast(&scene(300.0, "projected_grid", 3.0));
    let sea = contrast(&scene(300.0, "projected_grid", 9.0));
    println!("control from 300 m: projected grid at 3 m/s {calm:.4} against 9 m/s {sea:.4}");
    assert!(!within_ratio(calm, sea), "the measure did not tell a calmer sea apart");
    assert!(failures.is_empty(), "hu loses its waves:\n{}", failures.join("\n"));
}
