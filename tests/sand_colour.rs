//! The coastal island's sand, measured in the rendered picture: its dry-sand pixels must show
//! the published colour (`ocean_core::sand`, from Maritorena, Morel & Gentili 1994's measured
//! spectrum) under the scene's own light.
//!
//! The light at each pixel is found by rendering the frame again with a white island
//! (`[terrain] color = [1, 1, 1]`): the island is Lambertian, so its radiance is the albedo
//! times that. The dry-sand pixels (the island seen directly, above the wet band's top by a
//! margin) are found independently of the renderer, by marching each pixel's camera ray
//! against the island's f64 height. Two checks, each with a negative control:
//! - in the linear HDR frame, the ratio of the sand's radiance to the white island's is the
//!   published albedo, per channel;
//! - in the 8-bit picture, the dry sand's mean colour lies within [`MAX_DELTA_E`] (CIE76) of
//!   the published albedo under the same light, tonemapped as the frame is; and it reads as
//!   sand: yellow (CIELAB hue angle 60°–100°), not grey (chroma ≥ [`MIN_CHROMA`]). The albedo
//!   this replaced, (0.76, 0.70, 0.50), fails both picture checks.
//!
//! What each part can catch: the HDR ratio and the ΔE check hold the renderer to carrying the
//! default albedo through its light and tonemap (a change of the default, of the terrain's
//! shading or of the tonemap fails them), but they take the published albedo from
//! `ocean_core::sand`: whether *that* is the measured spectrum's colour is `sand.rs`'s own
//! tests (the spectrum recomputed, a flat spectrum grey, a falling one blue, the CIE fit at
//! the table's peaks). The hue and chroma limits are a reading of the picture, and the chroma
//! limit is a regression guard set between the two measured values, not a physical bound.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

use ocean_core::camera::{Camera, pixel_centre_ndc};
use ocean_core::plan::{OutputKind, System};
use ocean_core::sand::DRY_SAND_ALBEDO;
use ocean_core::scene::Scene;
use ocean_core::tonemap::TonemapUniforms;

/// Frame size.
const SIZE: (u32, u32) = (480, 270);
/// How far above the wet band's top a pixel's surface point must be to count as dry sand, m.
const DRY_MARGIN_M: f64 = 0.3;
/// Largest CIE76 distance between the dry sand's mean colour in the picture and the published
/// albedo's under the same light (2.3 is a just-noticeable difference).
const MAX_DELTA_E: f64 = 2.3;
/// Least CIELAB chroma of the dry sand in the picture: sand is coloured, not grey. The
/// scene's light on the island is bluish (the sky's ambient: (1.46, 1.56, 1.82) on a white
/// island, measured), which mutes any albedo: the measured sand shows chroma 7.7 there (its
/// albedo alone, 13), the grey it replaced 6.0.
const MIN_CHROMA: f64 = 7.0;

fn render(scene: &Scene) -> (Vec<[f32; 4]>, Vec<u8>) {
    let r = ocean_cpu::render_scene(scene, OutputKind::Ldr, &mut |_| {}).unwrap();
    (r.buffers.hdr.color.clone(), r.ldr.unwrap())
}

/// The pixels (indices) whose ray meets the island first on dry sand.
fn dry_sand_pixels(scene: &Scene) -> Vec<usize> {
    let terrain = scene.terrain.clone().unwrap();
    let mut terrain = terrain;
    terrain.prepare();
    let dry = ocean_core::frame::wet_top_m(scene) + DRY_MARGIN_M;
    let camera = Camera::from_scene(&scene.camera).unwrap();
    let top = terrain.y_range().1;
    let mut out = Vec::new();
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            let (nx, ny) = pixel_centre_ndc(x, y, SIZE.0, SIZE.1);
            let d = camera.ray_direction(nx, ny);
            let mut t = 0.0;
            while t < 1000.0 {
                let p = camera.eye + d * t;
                if p.y < dry.min(top) || (p.y > top && d.y >= 0.0) {
                    break; // below the dry sand (the sea or the wet band hides it), or past it
                }
                let ground = terrain.height(p.x, p.z);
                if p.y <= ground {
                    if ground > dry {
                        out.push((y * SIZE.0 + x) as usize);
                    }
                    break;
                }
                t += 0.05 + 0.002 * t;
            }
        }
    }
    out
}

/// sRGB 8-bit → CIELAB (D65).
fn lab(rgb: [f64; 3]) -> [f64; 3] {
    let lin = rgb.map(|c| {
        let c = c / 255.0;
        if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
    });
    let x = 0.4124 * lin[0] + 0.3576 * lin[1] + 0.1805 * lin[2];
    let y = 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2];
    let z = 0.0193 * lin[0] + 0.1192 * lin[1] + 0.9505 * lin[2];
    let f = |t: f64| if t > 0.008_856 { t.cbrt() } else { 7.787 * t + 16.0 / 116.0 };
    let (fx, fy, fz) = (f(x / 0.950_47), f(y), f(z / 1.088_83));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// The mean 8-bit colour of `pixels` in an RGBA picture.
fn mean_rgb(ldr: &[u8], pixels: &[usize]) -> [f64; 3] {
    let mut m = [0.0; 3];
    for &i in pixels {
        for (c, v) in m.iter_mut().enumerate() {
            *v += f64::from(ldr[4 * i + c]);
        }
    }
    m.map(|v| v / pixels.len() as f64)
}

/// The figures of one island colour: (median HDR ratio per channel, ΔE to the published
/// albedo's picture, the picture's CIELAB (L, a, b), chroma, hue angle).
struct Measured {
    ratio: [f64; 3],
    delta_e: f64,
    lab: [f64; 3],
    chroma: f64,
    hue_deg: f64,
}

fn measure(base: &Scene, albedo: [f64; 3], pixels: &[usize]) -> Measured {
    let mut white = base.clone();
    white.terrain.as_mut().unwrap().color = [1.0, 1.0, 1.0];
    let mut sand = base.clone();
    sand.terrain.as_mut().unwrap().color = albedo;
    let (light, _) = render(&white);
    let (hdr, ldr) = render(&sand);
    let ratio = std::array::from_fn(|c| {
        let mut r: Vec<f64> =
            pixels.iter().map(|&i| f64::from(hdr[i][c]) / f64::from(light[i][c])).collect();
        r.sort_by(f64::total_cmp);
        r[r.len() / 2]
    });
    // The published albedo under the same light, tonemapped as the frame is.
    let published: Vec<[f32; 4]> = light
        .iter()
        .map(|l| {
            let a = DRY_SAND_ALBEDO;
            [
                (f64::from(l[0]) * a[0]) as f32,
                (f64::from(l[1]) * a[1]) as f32,
                (f64::from(l[2]) * a[2]) as f32,
                l[3],
            ]
        })
        .collect();
    let c = &base.camera;
    let t = TonemapUniforms::for_image(c.exposure, &base.post, SIZE.0, SIZE.1).unwrap();
    let expected = ocean_cpu::shaders::tonemap::tonemap_to_rgba8(&published, SIZE.0, SIZE.1, &t);
    let (got, want) = (lab(mean_rgb(&ldr, pixels)), lab(mean_rgb(&expected, pixels)));
    let delta_e =
        ((got[0] - want[0]).powi(2) + (got[1] - want[1]).powi(2) + (got[2] - want[2]).powi(2))
            .sqrt();
    Measured {
        ratio,
        delta_e,
        lab: got,
        chroma: got[1].hypot(got[2]),
        hue_deg: got[2].atan2(got[1]).to_degrees(),
    }
}

fn picture_reads_as_published_sand(m: &Measured) -> bool {
    m.delta_e <= MAX_DELTA_E && m.chroma >= MIN_CHROMA && (60.0..=100.0).contains(&m.hue_deg)
}

#[test]
fn the_islands_dry_sand_shows_the_published_colour() {
    let mut scene = Scene::builtin_for(System::Coastal);
    (scene.camera.width, scene.camera.height) = SIZE;
    assert_eq!(scene.terrain.as_ref().unwrap().color, DRY_SAND_ALBEDO, "the default sand");
    let pixels = dry_sand_pixels(&scene);
    assert!(pixels.len() > 2000, "too few dry-sand pixels to measure: {}", pixels.len());
    let m = measure(&scene, DRY_SAND_ALBEDO, &pixels);
    println!(
        "{} dry-sand pixels: HDR ratio to the white island {:.4?} (published {DRY_SAND_ALBEDO:?}); \
         picture L*a*b* {:.1?}, chroma {:.1}, hue {:.0}°, ΔE to the published sand {:.2}",
        pixels.len(),
        m.ratio,
        m.lab,
        m.chroma,
        m.hue_deg,
        m.delta_e
    );
    for (r, a) in m.ratio.iter().zip(DRY_SAND_ALBEDO) {
        assert!(
            (r - a).abs() <= 0.01 * a,
            "HDR ratio {:?} vs the published {DRY_SAND_ALBEDO:?}",
            m.ratio
        );
    }
    assert!(picture_reads_as_published_sand(&m), "the picture's sand is off");
    // Negative control: the grey albedo this replaced.
    let old = measure(&scene, [0.76, 0.70, 0.50], &pixels);
    println!(
        "control, albedo (0.76, 0.70, 0.50): L*a*b* {:.1?}, chroma {:.1}, hue {:.0}°, ΔE {:.2}",
        old.lab, old.chroma, old.hue_deg, old.delta_e
    );
    assert!(!picture_reads_as_published_sand(&old), "the old grey sand passed");
    assert!(old.ratio.iter().zip(DRY_SAND_ALBEDO).any(|(r, a)| (r - a).abs() > 0.01 * a));
}
