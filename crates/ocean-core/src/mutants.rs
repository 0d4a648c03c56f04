//! Planted bugs: a bank of one-line changes to the WGSL, each applied when the shaders are
//! assembled ([`crate::shader_source`]), so that the oracle's power to tell a broken GPU from a
//! correct one is measured, not assumed (`ocean compare --mutant NAME`, `--mutants` lists them).
//!
//! A mutant is a small, plausible bug — a constant off by 0.5–3 %, a flipped sign, swapped
//! channels, a texel offset, a wrong mip level, a missing normalisation, a flipped comparison,
//! a wrong branch — in one file of `shaders/`. The CPU mirrors are never mutated: the oracle
//! renders the correct frame, the GPU the mutated one, and the comparison must fail. Every
//! mutant names a reference scene in which its line runs: of those, the one where the envelope
//! judges the line most sharply (analytic waves rather than wave maps, where it can), since a
//! GPU with the bug fails `ocean selftest` wherever any clean scene leaves its envelope.
//!
//! The active mutant is per thread: the command line activates one on its main thread, where
//! the GPU renderer assembles its shaders; each test thread activates its own.

use std::borrow::Cow;
use std::cell::Cell;

/// One planted bug.
#[derive(Debug)]
pub struct Mutant {
    /// Its name, for `--mutant` (kebab-case).
    pub name: &'static str,
    /// The file it changes, below `shaders/` (`water.wgsl`, `shared/fresnel.wgsl`).
    pub file: &'static str,
    /// The text it replaces: occurs exactly once in the file (`tests/mutants.rs` checks).
    pub find: &'static str,
    /// What it puts there.
    pub replace: &'static str,
    /// What the change does, in a sentence.
    pub changes: &'static str,
    /// The reference scene (`reference/scenes/NAME.toml`) whose frame runs the line.
    pub scene: &'static str,
}

/// The bank.
pub const MUTANTS: &[Mutant] = &[
    Mutant {
        name: "hu-refract-water-color-bgr",
        file: "shading/hu.wgsl",
        find: "frame.water.color * (1.0 - a_refr)",
        replace: "frame.water.color.zyx * (1.0 - a_refr)",
        changes: "Swaps the red and blue channels of the deep-water colour in hu's refraction term (0.004, 0.016, 0.028) -> (0.028, 0.016, 0.004), on every water pixel.",
        scene: "calm",
    },
    Mutant {
        name: "chiu-reflect-dir-plus-2pct",
        file: "shading/chiu.wgsl",
        find: "let r = n * (2.0 * vn) - view;",
        replace: "let r = n * (2.04 * vn) - view;",
        changes: "Scales the normal term of chiu's reflection vector by 2 % (2.0 -> 2.04), tilting the sky lookup and the eq. 5 sun lobe on every water pixel.",
        scene: "coastal_waves",
    },
    Mutant {
        name: "ggx-half-vector-unnormalized",
        file: "shading/ggx.wgsl",
        find: "let h = unit(l + view);",
        replace: "let h = l + view;",
        changes: "Drops the normalisation of GGX's half vector (|l + v| up to 2), so D, the Fresnel at v.h and the whole sun term change wherever n.l > 0.",
        scene: "ggx_sun",
    },
    Mutant {
        name: "ggx-fresnel-branch-flipped",
        file: "shading/ggx.wgsl",
        find: "if (frame.ggx.schlick_fresnel == SWITCH_ON) {",
        replace: "if (frame.ggx.schlick_fresnel != SWITCH_ON) {",
        changes: "Inverts the Fresnel branch: with the default `exact` Fresnel GGX now uses Schlick's approximation for the environment and sun terms on every water pixel.",
        scene: "atmosphere_sunset",
    },
    Mutant {
        name: "coastal-inv-pi-plus-1pct",
        file: "shading/coastal.wgsl",
        find: "const COASTAL_INV_PI: f32 = 0.31830987;",
        replace: "const COASTAL_INV_PI: f32 = 0.32149297;",
        changes: "Raises 1/pi of the dull colour's Lambertian sun term by 1 %, on every water pixel (the dull share d is at least dull_factor 0.2).",
        scene: "coastal_island",
    },
    Mutant {
        name: "preetham-srgb-green-plus-1pct",
        file: "shared/preetham.wgsl",
        find: "1.8758 * xyz.y",
        replace: "1.8946 * xyz.y",
        changes: "Raises the Y coefficient of the XYZ -> linear sRGB green row by 1 % (1.8758 -> 1.8946), tinting the whole Preetham sky and its reflection.",
        scene: "calm",
    },
    Mutant {
        name: "clouds-noise-corner-offset",
        file: "sky/preetham_clouds.wgsl",
        find: "cloud_hash(i + 1, j, octave)",
        replace: "cloud_hash(i + 2, j, octave)",
        changes: "Reads the value noise's (i+1, j) lattice corner one cell too far (i + 2), changing the cloud opacity pattern in every octave.",
        scene: "chiu_rock",
    },
    Mutant {
        name: "sky-lut-row-offset",
        file: "shared/sky_lut.wgsl",
        find: "let j1 = min(j0 + 1.0, SKY_LUT_HEIGHT - 1.0);",
        replace: "let j1 = min(j0 + 2.0, SKY_LUT_HEIGHT - 1.0);",
        changes: "Blends the sky-view table's row j0 with row j0 + 2 instead of j0 + 1 (a one-texel offset in elevation), changing the atmosphere's radiance in almost every direction.",
        scene: "welch_calm_day",
    },
    Mutant {
        name: "tonemap-hdr-bgr",
        file: "tonemap.wgsl",
        find: "textureLoad(hdr_frame, texel, 0).rgb",
        replace: "textureLoad(hdr_frame, texel, 0).bgr",
        changes: "Swaps the red and blue channels of the HDR frame as the tonemap reads it, so the whole 8-bit picture is colour-swapped.",
        scene: "calm",
    },
    Mutant {
        name: "tonemap-curve-branch-flipped",
        file: "tonemap.wgsl",
        find: "if (tonemap.curve == 1u) {",
        replace: "if (tonemap.curve != 1u) {",
        changes: "Inverts the curve selection: a `hable` scene is tone mapped with ACES (e.g. 0.5 maps to 0.62 instead of 0.17), every pixel.",
        scene: "welch_calm_day",
    },
    Mutant {
        name: "bloom-down-texel-offset",
        file: "bloom.wgsl",
        find: "let x = 2 * i - 1;",
        replace: "let x = 2 * i;",
        changes: "Shifts the downsample's (1, 3, 3, 1)/8 tent one source texel to the right in every level of the down chain (bright pass included).",
        scene: "bloom_glitter",
    },
    Mutant {
        name: "shadow-depth-plus-1pct",
        file: "shadow.wgsl",
        find: "return vec4<f32>(frag.z, 0.0, 0.0, 0.0);",
        replace: "return vec4<f32>(frag.z * 1.01, 0.0, 0.0, 0.0);",
        changes: "Writes the shadow map's depth 1 % too far from the sun.",
        scene: "default",
    },
    Mutant {
        name: "fft-twiddle-conjugated",
        file: "waves.wgsl",
        find: "return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);",
        replace: "return vec2<f32>(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y);",
        changes: "complex_mul multiplies the butterfly difference by the conjugate twiddle (twiddle sign flipped) in both FFT kernels, so every wave map is wrong.",
        scene: "calm",
    },
    Mutant {
        name: "fft-butterfly-index-minus-1",
        file: "waves.wgsl",
        find: "let b = src[base + (j + half) * stride];",
        replace: "let b = src[base + (j + half - 1u) * stride];",
        changes: "The one-stage FFT's butterfly reads its second input one element early \
                  (j + half − 1), corrupting every stage of every line (the kernel of software \
                  adapters; the shared-memory kernel that hardware runs has its twin line).",
        scene: "default",
    },
    Mutant {
        name: "wave-mips-downsample-texel-offset",
        file: "wave_mips.wgsl",
        find: "let x1 = min(2u * id.x + 1u, params.src_width - 1u);",
        replace: "let x1 = min(2u * id.x + 2u, params.src_width - 1u);",
        changes: "The 2x2 box of the slope chains' downsample takes its right column one texel too far (2i + 2), in every level above 0.",
        scene: "phillips",
    },
    Mutant {
        name: "fresnel-table-cos-minus-1pct",
        file: "fresnel_table.wgsl",
        find: "fresnel_exact(v.z, params.eta)",
        replace: "fresnel_exact(v.z * 0.99, params.eta)",
        changes: "The Fresnel texture's F is evaluated at 0.99 cos(theta), raising F in every texel off the rim (F0 is kept only at the rim).",
        scene: "gerstner_swell",
    },
    Mutant {
        name: "fresnel-exact-half-plus-1pct",
        file: "shared/fresnel.wgsl",
        find: "return min(0.5 * r_s * r_s",
        replace: "return min(0.505 * r_s * r_s",
        changes: "Raises eq. 2's 1/2 factor by 1 %, so every exact Fresnel value (chiu's per-pixel F, the Fresnel tables) is 1 % too large.",
        scene: "chiu_shallow",
    },
    Mutant {
        name: "objects-main-color-bgr",
        file: "objects.wgsl",
        find: "return vec4<f32>(shade(in.normal, in.color, sun_reaches(in.rel, in.world_y)), 1.0);",
        replace: "return vec4<f32>(shade(in.normal, in.color.bgr, sun_reaches(in.rel, in.world_y)), 1.0);",
        changes: "Swaps the red and blue channels of the objects' and the floor's albedo in the main view (the island's dry sand (0.561, 0.449, 0.326) -> (0.326, 0.449, 0.561)); their reflection and refraction are unchanged.",
        scene: "coastal_island",
    },
    Mutant {
        name: "objects-reflect-clip-flipped",
        file: "objects.wgsl",
        find: "return in.world_y < clip_height(in.rel);",
        replace: "return in.world_y > clip_height(in.rel);",
        changes: "Flips the reflection map's clip: the parts of the objects under the water are mirrored and the parts above it discarded.",
        scene: "default",
    },
    Mutant {
        name: "shadow-compare-flipped",
        file: "shared/shadow.wgsl",
        find: "occluder < s.z - SHADOW_BIAS",
        replace: "occluder > s.z - SHADOW_BIAS",
        changes: "Flips the shadow-map depth test: points behind a caster (the rock's shadow on the water and the floor) are lit, points in front of one are shadowed.",
        scene: "chiu_rock",
    },
    Mutant {
        name: "foam-heuristic-eye-height-plus-1pct",
        file: "foam/heuristic.wgsl",
        find: "let h = in.rel.y + frame.view.eye_height;",
        replace: "let h = in.rel.y + frame.view.eye_height * 1.01;",
        changes: "The heuristic's crest height uses a 1 % too large eye height (3 m -> 3.03 m, +0.03 m against a 0.8 m crest height), so the foam on the crests grows.",
        scene: "welch_calm_day",
    },
    Mutant {
        name: "foam-jacobian-j-minus-1pct",
        file: "foam/jacobian.wgsl",
        find: "jacobian_turbulence(surface_jacobian(in))",
        replace: "jacobian_turbulence(surface_jacobian(in) * 0.99)",
        changes: "The Jacobian fed to the foam is 1 % low (about 0.01 against a 0.12 softness), so the white water on the steep crests widens.",
        scene: "foam_gerstner",
    },
    Mutant {
        name: "foam-step-jacobian-texel-offset",
        file: "foam.wgsl",
        find: "vec2<i32>(min(id.xy, last))",
        replace: "vec2<i32>(min(id.xy + vec2<u32>(1u, 0u), last))",
        changes: "The accumulation step takes J from the displacement map's texel (i + 1, j) instead of (i, j), shifting the foam source one texel in x in every step.",
        scene: "foam_storm",
    },
    Mutant {
        name: "spray-launch-speed-plus-1pct",
        file: "spray.wgsl",
        find: "0.6 + 0.8 * spray_random",
        replace: "0.6 + 0.808 * spray_random",
        changes: "The random part of the spray's launch speed is 1 % larger (0.8 -> 0.808), so every launched particle flies a little faster and farther.",
        scene: "chiu_rock",
    },
    Mutant {
        name: "spray-sprite-color-bgr",
        file: "spray.wgsl",
        find: "return vec4<f32>(draw.color.xyz * a, 0.0);",
        replace: "return vec4<f32>(draw.color.zyx * a, 0.0);",
        changes: "The sprites' colour has its red and blue swapped ((0.9, 0.95, 1.0) becomes (1.0, 0.95, 0.9)): the spray adds 11 % more red and 10 % less blue wherever it covers.",
        scene: "chiu_rock",
    },
    Mutant {
        name: "gerstner-phase-z-sign",
        file: "shared/gerstner.wgsl",
        find: "let p = (a.x * pos.x + a.z) + a.y * pos.y;",
        replace: "let p = (a.x * pos.x + a.z) - a.y * pos.y;",
        changes: "Flips the sign of the z term of every Gerstner wave's phase (waves mirrored in z), changing displacement, slopes and Jacobian everywhere.",
        scene: "welch_calm_day",
    },
    Mutant {
        name: "coastal-phase-sign",
        file: "shared/coastal.wgsl",
        find: "let t = -(phi + frame.coastal.time.x);",
        replace: "let t = phi + frame.coastal.time.x;",
        changes: "Flips the sign of the radial wave's phase, so its crests, front shape and slopes are wrong on every water pixel and vertex.",
        scene: "coastal_sunset",
    },
    Mutant {
        name: "floor-relief-plus-1pct",
        file: "shared/floor.wgsl",
        find: "let relief = textureSampleLevel(floor_map, clamp_linear, uv, 0.0).x;",
        replace: "let relief = textureSampleLevel(floor_map, clamp_linear, uv, 0.0).x * 1.01;",
        changes: "The relief map's height is 1 % too large (up to ~0.2 m on the island's shore), shifting the depth that caps, damps and fades the coastal waves near the shore.",
        scene: "coastal_waves",
    },
    Mutant {
        name: "far-variance-half-plus-1pct",
        file: "water.wgsl",
        find: "variance = 0.5 * (vd",
        replace: "variance = 0.505 * (vd",
        changes: "Far field `variance`: the maps' unresolved slope variance per axis is 1 % too large, changing the filtered Fresnel, sky and sun lobe on every water pixel.",
        scene: "calm",
    },
    Mutant {
        name: "far-lod-displacement-plus-1",
        file: "water.wgsl",
        find: "fp.lods = vec2<f32>(l + frame.far.lod_offset_d,",
        replace: "fp.lods = vec2<f32>(l + 1.0 + frame.far.lod_offset_d,",
        changes: "The displacement slope chain is sampled one mip level too coarse (LOD + 1), blurring the waves' slopes and their variance beyond the near field.",
        scene: "looking_down",
    },
];

thread_local! {
    static ACTIVE: Cell<Option<&'static Mutant>> = const { Cell::new(None) };
}

/// The mutant called `name`.
///
/// # Errors
/// An unknown name, with the known ones.
pub fn find(name: &str) -> Result<&'static Mutant, String> {
    MUTANTS.iter().find(|m| m.name == name).ok_or_else(|| {
        format!(
            "no planted bug `{name}` (`ocean compare --mutants` lists the {}: {})",
            MUTANTS.len(),
            MUTANTS.iter().map(|m| m.name).collect::<Vec<_>>().join(", ")
        )
    })
}

/// Makes `mutant` (or none) the one this thread's shader assembly applies.
pub fn activate(mutant: Option<&'static Mutant>) {
    ACTIVE.with(|a| a.set(mutant));
}

/// The mutant this thread's shader assembly applies, if any.
pub fn active() -> Option<&'static Mutant> {
    ACTIVE.with(Cell::get)
}

/// `text`, the file `file` below `shaders/`, with this thread's active mutant applied when it
/// targets that file.
pub fn apply<'a>(file: &str, text: &'a str) -> Cow<'a, str> {
    match active() {
        Some(m) if m.file == file => Cow::Owned(text.replacen(m.find, m.replace, 1)),
        _ => Cow::Borrowed(text),
    }
}
