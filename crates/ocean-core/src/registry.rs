//! The stage registry: every stage of the frame, its WGSL file, entry points, bindings, the
//! uniform and storage structs it shares with Rust, its CPU mirror and its GPU module, listed
//! once. The shader assembler ([`crate::shader_source`]), the GPU pipelines (entry-point
//! names), the naga layout checks and the registry's completeness test (`tests/wgsl.rs`) are
//! derived from these tables, not written again.
//!
//! A technique of a stage with several is one file at every layer
//! (`shaders/<stage>/<technique>.wgsl`, `ocean-cpu/src/shaders/<stage>/<technique>.rs`), listed
//! in [`TECHNIQUE_FILES`] with the functions of the stage's interface it implements; a stage
//! file imports the chosen one with `// #import technique/<stage>`.

use std::mem::{offset_of, size_of};
use std::path::Path;

use crate::atmosphere::SkyLut;
use crate::bloom::BloomUniforms;
use crate::camera_uniforms::CameraUniforms;
use crate::composite::CompositeUniforms;
use crate::detail::DetailBlock;
use crate::foam::{FoamBlock, FoamStepUniforms};
use crate::frame::{
    AmbientBlock, ChiuShadingBlock, FarFieldBlock, FrameUniforms, FresnelTableUniforms,
    GgxShadingBlock, HuShadingBlock, MultiScaleBlock, PassFlags, ProjectedGridBlock, SunBlock,
    TerrainBlock, ViewBlock, WaterBlock, WaveMipsUniforms, WaveTilingBlock,
};
use crate::geometry::ClipmapBlock;
use crate::plan::Stage as TechniqueStage;
use crate::sky::SkyUniforms;
use crate::spray::{Emitter, Particle, SprayUniforms};
use crate::tonemap::TonemapUniforms;
use crate::waves::coastal::{CoastalBlock, CoastalShadingBlock};
use crate::waves::gerstner::GerstnerBlock;
use crate::waves::uniforms::{FftPassUniforms, WaveModeData, WavesUniforms};

/// A Rust type with a WGSL twin: its name in WGSL (`vec4<f32>`, a struct's name).
pub trait WgslType {
    /// The WGSL type.
    const WGSL: &'static str;
}

macro_rules! wgsl_types {
    ($($t:ty => $w:literal),* $(,)?) => { $(impl WgslType for $t { const WGSL: &'static str = $w; })* };
}

wgsl_types!(
    f32 => "f32", u32 => "u32", [f32; 2] => "vec2<f32>", [f32; 3] => "vec3<f32>",
    [f32; 4] => "vec4<f32>", [u32; 2] => "vec2<u32>", [i32; 2] => "vec2<i32>", [u32; 4] => "vec4<u32>",
    [[f32; 4]; 4] => "mat4x4<f32>",
    [[f32; 4]; 128] => "array<vec4<f32>, 128>",
    [[f32; 4]; 24] => "array<vec4<f32>, 24>",
    [[f32; 4]; 32] => "array<vec4<f32>, 32>",
    [[i32; 4]; 24] => "array<vec4<i32>, 24>",
    [[f32; 4]; 2048] => "array<vec4<f32>, 2048>",
);

/// One member of a shared struct, as Rust lays it out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Member {
    /// The field's name (the WGSL member's).
    pub name: &'static str,
    /// Byte offset.
    pub offset: usize,
    /// The WGSL type its Rust type stands for.
    pub wgsl_type: &'static str,
}

/// A struct shared by Rust and WGSL.
#[derive(Clone, Copy, Debug)]
pub struct Block {
    /// Its name, the same in both.
    pub name: &'static str,
    /// Rust's size in bytes (WGSL's span must equal it).
    pub size: usize,
    /// The members in declaration order.
    pub members: fn() -> Vec<Member>,
}

/// The WGSL type of a field, from the field's Rust type.
fn wgsl_of<S, T: WgslType>(_: fn(&S) -> &T) -> &'static str {
    T::WGSL
}

macro_rules! block {
    ($t:ident as $name:literal { $($f:ident),* $(,)? }) => { block!(@make $t, $name, $($f),*) };
    ($t:ident { $($f:ident),* $(,)? }) => { block!(@make $t, stringify!($t), $($f),*) };
    (@make $t:ident, $name:expr, $($f:ident),*) => {
        Block {
            name: $name,
            size: size_of::<$t>(),
            members: || vec![$(Member {
                name: stringify!($f),
                offset: offset_of!($t, $f),
                wgsl_type: wgsl_of(|s: &$t| &s.$f),
            }),*],
        }
    };
}

macro_rules! nested {
    ($($t:ident),* $(,)?) => { $(impl WgslType for $t { const WGSL: &'static str = stringify!($t); })* };
}

nested!(
    ViewBlock,
    SunBlock,
    WaveTilingBlock,
    WaterBlock,
    HuShadingBlock,
    PassFlags,
    AmbientBlock,
    FarFieldBlock,
    ProjectedGridBlock,
    ChiuShadingBlock,
    TerrainBlock,
    MultiScaleBlock,
    GerstnerBlock,
    GgxShadingBlock,
    ClipmapBlock,
    DetailBlock,
    FoamBlock,
    CoastalBlock,
    CoastalShadingBlock
);

/// The kind of an entry point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EntryKind {
    /// `@vertex`.
    Vertex,
    /// `@fragment`.
    Fragment,
    /// `@compute`.
    Compute,
}

/// A `@group(g) @binding(b) var name` of a stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Binding {
    /// Bind group.
    pub group: u32,
    /// Binding within the group.
    pub binding: u32,
    /// The variable's name.
    pub name: &'static str,
}

const fn b(group: u32, binding: u32, name: &'static str) -> Binding {
    Binding { group, binding, name }
}

/// One stage: a WGSL file with entry points, and its twins.
#[derive(Clone, Copy, Debug)]
pub struct StageEntry {
    /// The stage's name (`water`): its pipeline label is `ocean.<name>`.
    pub name: &'static str,
    /// Its file below `shaders/`.
    pub file: &'static str,
    /// The file's text, embedded.
    pub source: &'static str,
    /// Its entry points.
    pub entry_points: &'static [(&'static str, EntryKind)],
    /// Its resource bindings.
    pub bindings: &'static [Binding],
    /// The structs it shares with Rust.
    pub blocks: &'static [Block],
    /// Its CPU mirror below the repository root.
    pub cpu_mirror: &'static str,
    /// Its GPU module below the repository root.
    pub gpu_module: &'static str,
}

impl StageEntry {
    /// The entry point `name` if the stage declares it (GPU pipelines take their names from
    /// here).
    pub fn entry(&self, name: &str) -> Option<&'static str> {
        self.entry_points.iter().find(|(e, _)| *e == name).map(|(e, _)| *e)
    }
}

/// A shared WGSL file (`shaders/shared/*.wgsl`) and its CPU mirror.
#[derive(Clone, Copy, Debug)]
pub struct SharedFile {
    /// Its path below `shaders/`.
    pub file: &'static str,
    /// Its text.
    pub source: &'static str,
    /// The structs it declares that Rust shares.
    pub blocks: &'static [Block],
    /// Its CPU mirror below the repository root.
    pub cpu_mirror: &'static str,
}

/// A technique's file: the functions of its stage's interface.
#[derive(Clone, Copy, Debug)]
pub struct TechniqueFile {
    /// The technique.
    pub technique: &'static crate::stage::TechniqueInfo,
    /// Its path below `shaders/`.
    pub file: &'static str,
    /// Its text.
    pub source: &'static str,
    /// The interface: what every technique of the stage defines, so that the stages that
    /// import `technique/<stage>` work with any of them.
    pub interface: &'static [&'static str],
    /// The structs it declares that Rust shares.
    pub blocks: &'static [Block],
    /// Its CPU mirror below the repository root.
    pub cpu_mirror: &'static str,
}

use EntryKind::{Compute, Fragment, Vertex};

const VS_FS: &[(&str, EntryKind)] = &[("vs_main", Vertex), ("fs_main", Fragment)];

/// Every stage with WGSL, in the order of docs/design.md's stage table, then `present` (the
/// real-time viewer's copy of the output into its window) and `composite` (the output into an
/// embedding program's targets, `ocean_gpu::embed`); neither is a pass of the frame plan.
pub const STAGES: &[StageEntry] = &[
    StageEntry {
        name: "waves",
        file: "waves.wgsl",
        source: include_str!("../../../shaders/waves.wgsl"),
        entry_points: &[
            ("spectrum", Compute),
            ("fft_rows", Compute),
            ("fft_columns", Compute),
            ("spectrum_rows_shared", Compute),
            ("columns_pack_shared", Compute),
            ("pack", Compute),
        ],
        bindings: &[
            b(0, 0, "params"),
            b(0, 1, "modes"),
            b(0, 2, "twiddles"),
            b(1, 0, "fft_pass"),
            b(1, 1, "src"),
            b(1, 2, "dst"),
            b(2, 0, "displacement"),
            b(2, 1, "displacement_slopes"),
            b(2, 2, "bump"),
        ],
        blocks: &[
            block!(WavesUniforms {
                size,
                log2_size,
                time_ticks,
                time_remainder,
                lambda,
                pad0,
                pad1
            }),
            block!(FftPassUniforms { stage, pad0, pad1, pad2 }),
        ],
        cpu_mirror: "crates/ocean-cpu/src/shaders/waves.rs",
        gpu_module: "crates/ocean-gpu/src/waves.rs",
    },
    StageEntry {
        name: "foam",
        file: "foam.wgsl",
        source: include_str!("../../../shaders/foam.wgsl"),
        entry_points: &[("accumulate", Compute)],
        bindings: &[
            b(0, 0, "params"),
            b(0, 1, "frame"),
            b(0, 2, "displacement"),
            b(0, 3, "src"),
            b(0, 4, "dst"),
        ],
        blocks: &[block!(FoamStepUniforms {
            size,
            analytic,
            start,
            start_prev,
            shift,
            start_rel,
            cell_m,
            decay,
            growth,
            threshold,
            inv_softness,
            pad0
        })],
        cpu_mirror: "crates/ocean-cpu/src/shaders/foam.rs",
        gpu_module: "crates/ocean-gpu/src/foam.rs",
    },
    StageEntry {
        name: "fresnel_table",
        file: "fresnel_table.wgsl",
        source: include_str!("../../../shaders/fresnel_table.wgsl"),
        entry_points: &[("main", Compute)],
        bindings: &[b(0, 0, "params"), b(0, 1, "table")],
        blocks: &[block!(FresnelTableUniforms {
            eta,
            size,
            mapping,
            step,
            step2,
            pad0,
            pad1,
            pad2
        })],
        cpu_mirror: "crates/ocean-cpu/src/shaders/fresnel_table.rs",
        gpu_module: "crates/ocean-gpu/src/fresnel_table.rs",
    },
    StageEntry {
        name: "wave_mips",
        file: "wave_mips.wgsl",
        source: include_str!("../../../shaders/wave_mips.wgsl"),
        entry_points: &[("moments", Compute), ("downsample", Compute)],
        bindings: &[b(0, 0, "params"), b(0, 1, "src"), b(0, 2, "dst")],
        blocks: &[block!(WaveMipsUniforms { width, height, src_width, src_height })],
        cpu_mirror: "crates/ocean-cpu/src/shaders/wave_mips.rs",
        gpu_module: "crates/ocean-gpu/src/wave_mips.rs",
    },
    StageEntry {
        name: "sky",
        file: "sky.wgsl",
        source: include_str!("../../../shaders/sky.wgsl"),
        entry_points: &[("cs_main", Compute)],
        bindings: &[b(0, 0, "camera"), b(0, 1, "hdr_frame"), b(1, 0, "sky"), b(1, 1, "sky_lut")],
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/sky.rs",
        gpu_module: "crates/ocean-gpu/src/sky.rs",
    },
    StageEntry {
        name: "objects",
        file: "objects.wgsl",
        source: include_str!("../../../shaders/objects.wgsl"),
        entry_points: &[
            ("vs_main", Vertex),
            ("fs_main", Fragment),
            ("vs_reflect", Vertex),
            ("fs_reflect", Fragment),
            ("vs_refract", Vertex),
            ("fs_refract", Fragment),
            // The compute path: the raster passes write the visibility buffer, compute passes
            // shade it.
            ("fs_visibility_main", Fragment),
            ("fs_visibility_reflect", Fragment),
            ("fs_visibility_refract", Fragment),
            ("cs_shade_main", Compute),
            ("cs_shade_reflect", Compute),
            ("cs_shade_refract", Compute),
        ],
        bindings: &[
            b(0, 0, "frame"),
            b(0, 1, "displacement"),
            b(0, 2, "wrap_linear"),
            b(0, 3, "shadow_map"),
            b(0, 4, "floor_map"),
            b(0, 5, "clamp_linear"),
            b(1, 0, "vis_a"),
            b(1, 1, "vis_b"),
            b(1, 2, "vis_c"),
            b(1, 3, "target_frame"),
        ],
        // ObjectVertex is a vertex-buffer layout (tightly packed), not a WGSL memory layout:
        // ocean-gpu's OBJECT_VERTEX_LAYOUT describes it.
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/objects.rs",
        gpu_module: "crates/ocean-gpu/src/objects.rs",
    },
    StageEntry {
        name: "shadow",
        file: "shadow.wgsl",
        source: include_str!("../../../shaders/shadow.wgsl"),
        entry_points: VS_FS,
        bindings: &[b(0, 0, "frame")],
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shadow.rs",
        gpu_module: "crates/ocean-gpu/src/shadow.rs",
    },
    StageEntry {
        name: "water",
        file: "water.wgsl",
        source: include_str!("../../../shaders/water.wgsl"),
        entry_points: &[
            ("vs_main", Vertex),
            ("fs_main", Fragment),
            // Surface `projected_grid`: the grid from the vertex index.
            ("vs_projected_grid", Vertex),
            // Surface `clipmap`: the levels from the vertex index.
            ("vs_clipmap", Vertex),
            // The compute path: the raster pass writes the visibility buffer, a compute pass
            // shades it.
            ("fs_visibility", Fragment),
            ("cs_shade", Compute),
        ],
        bindings: &[
            b(0, 0, "frame"),
            b(0, 1, "displacement"),
            b(0, 2, "displacement_slopes"),
            b(0, 3, "bump"),
            b(0, 4, "fresnel_above"),
            b(0, 5, "fresnel_below"),
            b(0, 6, "reflection_map"),
            b(0, 7, "refraction_map"),
            b(0, 8, "shadow_map"),
            b(0, 9, "wrap_linear"),
            b(0, 10, "clamp_linear"),
            b(0, 11, "fresnel_filter"),
            b(0, 12, "floor_map"),
            b(0, 13, "foam_field"),
            b(1, 0, "sky"),
            b(1, 1, "sky_lut"),
            b(2, 0, "vis_rel_weight"),
            b(2, 1, "vis_uvs"),
            b(2, 2, "vis_pos_cover"),
            b(2, 3, "hdr_frame"),
        ],
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/water.rs",
        gpu_module: "crates/ocean-gpu/src/water.rs",
    },
    StageEntry {
        name: "spray",
        file: "spray.wgsl",
        source: include_str!("../../../shaders/spray.wgsl"),
        entry_points: &[("step", Compute), ("vs_main", Vertex), ("fs_main", Fragment)],
        bindings: &[
            b(0, 0, "params"),
            b(0, 1, "particles"),
            b(0, 2, "emitters"),
            b(0, 3, "displacement"),
            b(0, 4, "wrap_linear"),
            b(0, 5, "frame"),
            b(0, 6, "sprites"),
            b(0, 7, "draw"),
        ],
        blocks: &[
            block!(SprayUniforms {
                step,
                count,
                emitters,
                seed,
                dt,
                gravity,
                speed,
                lifetime,
                emit_chance,
                inv_patch,
                half_texel,
                waves,
                origin_rel,
                sprite,
                color,
                right,
                up
            }),
            block!(Particle { pos, vel }),
            block!(Emitter { pos, dir }),
        ],
        cpu_mirror: "crates/ocean-cpu/src/shaders/spray.rs",
        gpu_module: "crates/ocean-gpu/src/spray.rs",
    },
    StageEntry {
        name: "bloom",
        file: "bloom.wgsl",
        source: include_str!("../../../shaders/bloom.wgsl"),
        entry_points: &[("bright_down", Compute), ("downsample", Compute), ("upsample", Compute)],
        bindings: &[b(0, 0, "params"), b(0, 1, "src"), b(0, 2, "dst"), b(0, 3, "detail")],
        blocks: &[block!(BloomUniforms {
            width,
            height,
            src_width,
            src_height,
            exposure,
            threshold,
            store_max,
            pad1
        })],
        cpu_mirror: "crates/ocean-cpu/src/shaders/bloom.rs",
        gpu_module: "crates/ocean-gpu/src/bloom.rs",
    },
    StageEntry {
        name: "tonemap",
        file: "tonemap.wgsl",
        source: include_str!("../../../shaders/tonemap.wgsl"),
        entry_points: &[("cs_main", Compute)],
        bindings: &[b(0, 0, "tonemap"), b(0, 1, "hdr_frame"), b(0, 2, "bloom"), b(0, 3, "ldr")],
        blocks: &[block!(TonemapUniforms {
            exposure,
            curve,
            vignette,
            inv_corner2,
            center,
            bloom_scale,
            pad1
        })],
        cpu_mirror: "crates/ocean-cpu/src/shaders/tonemap.rs",
        gpu_module: "crates/ocean-gpu/src/tonemap.rs",
    },
    StageEntry {
        name: "present",
        file: "present.wgsl",
        source: include_str!("../../../shaders/present.wgsl"),
        entry_points: VS_FS,
        bindings: &[b(0, 0, "frame_output")],
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/present.rs",
        gpu_module: "crates/ocean-gpu/src/present.rs",
    },
    StageEntry {
        name: "composite",
        file: "composite.wgsl",
        source: include_str!("../../../shaders/composite.wgsl"),
        entry_points: VS_FS,
        bindings: &[b(0, 0, "composite"), b(0, 1, "frame_output"), b(0, 2, "frame_depth")],
        blocks: &[block!(CompositeUniforms { depth, params })],
        cpu_mirror: "crates/ocean-cpu/src/shaders/composite.rs",
        gpu_module: "crates/ocean-gpu/src/composite.rs",
    },
];

/// Every shared WGSL file.
pub const SHARED: &[SharedFile] = &[
    SharedFile {
        file: "shared/camera.wgsl",
        source: include_str!("../../../shaders/shared/camera.wgsl"),
        blocks: &[block!(CameraUniforms { view_proj, inv_view_proj, eye, viewport })],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/camera.rs",
    },
    SharedFile {
        file: "shared/frame.wgsl",
        source: include_str!("../../../shaders/shared/frame.wgsl"),
        blocks: &[
            block!(ViewBlock {
                view_proj,
                viewport_size,
                inv_viewport_size,
                eye_height,
                pad0,
                pad1,
                pad2
            }),
            block!(SunBlock { shadow_view_proj, direction, lit, radiance, pad }),
            block!(WaveTilingBlock {
                displacement_origin,
                bump_origin,
                mesh_offset,
                pad0,
                pad1,
                inv_displacement_size,
                inv_bump_size,
                displacement_half_texel,
                bump_half_texel,
            }),
            block!(WaterBlock { color, extinction_per_m, eta, inv_eta, volume_model, kd_per_m }),
            block!(HuShadingBlock {
                phong_exponent,
                reflection_distortion,
                refraction_distortion,
                fresnel_scale
            }),
            block!(PassFlags { waves, reflection_map, refraction_map, shadow_map }),
            block!(AmbientBlock { sky, pad }),
            block!(FarFieldBlock {
                mode,
                lod_bias,
                pixel_angle,
                inv_sigma_max,
                lod_offset_d,
                lod_offset_b,
                filter_r_scale,
                filter_r_offset,
                filter_t_scale,
                filter_t_offset,
                max_aniso_log2,
                sun_centre,
                sun_above,
                sun_below,
                sun_tangential,
                sun_rim,
                mesh_leg_scale,
                mesh_leg_min,
                pad0,
                pad1
            }),
            block!(ProjectedGridBlock { corners, cols, rows, shore, cell_angle }),
            block!(ChiuShadingBlock { zeta_m, shininess_per_m, clip_waves, pad1 }),
            block!(TerrainBlock { floor, relief, sun_under, top }),
            block!(MultiScaleBlock {
                inv_size,
                weight,
                origin_x,
                origin_z,
                lod_offset,
                count,
                pad0,
                pad1,
                pad2
            }),
            block!(GerstnerBlock { count, pad0, pad1, pad2, waves }),
            block!(CoastalBlock { center, shape, time, waves, damping, swash, table }),
            block!(CoastalShadingBlock {
                dull_color,
                dull_factor,
                shininess,
                distortion,
                schlick,
                f0
            }),
            block!(GgxShadingBlock { alpha, schlick_fresnel, schlick_geometry, f0 }),
            block!(ClipmapBlock {
                levels,
                cells,
                cell_m,
                morph_start,
                inv_band,
                fade_end,
                fade_inv_span,
                pad0,
                level,
                eye
            }),
            block!(DetailBlock { count, pad0, pad1, pad2, waves }),
            block!(FoamBlock {
                mode,
                intensity,
                threshold,
                inv_softness,
                color,
                inv_crest_height,
                noise_origin,
                inv_noise_cell,
                inv_crest_slope,
                field_origin,
                inv_field_size,
                field_half_texel,
                window_outer,
                inv_window_band,
                seed,
                inv_noise_cell_along,
                wind,
                pad0,
                pad1
            }),
            block!(FrameUniforms {
                view,
                sun,
                tiling,
                water,
                hu,
                passes,
                ambient,
                far,
                grid,
                chiu,
                terrain,
                scales,
                gerstner,
                ggx,
                clip,
                detail,
                foam,
                coastal,
                coastal_shading
            }),
        ],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/frame.rs",
    },
    SharedFile {
        file: "shared/sky_lut.wgsl",
        source: include_str!("../../../shaders/shared/sky_lut.wgsl"),
        blocks: &[block!(SkyLut { texels })],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/sky_lut.rs",
    },
    SharedFile {
        file: "shared/preetham.wgsl",
        source: include_str!("../../../shaders/shared/preetham.wgsl"),
        blocks: &[block!(SkyUniforms {
            perez_a,
            perez_b,
            perez_c,
            perez_d,
            perez_e,
            zenith,
            perez_zenith,
            sun_direction,
            sun_radiance,
            sky_scale,
            cos_theta_min,
            sun_sin_inner,
            sun_sin_outer,
            cloud_origin,
            cloud_color,
        })],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/preetham.rs",
    },
    SharedFile {
        file: "shared/fresnel.wgsl",
        source: include_str!("../../../shaders/shared/fresnel.wgsl"),
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/fresnel.rs",
    },
    SharedFile {
        file: "shared/optics.wgsl",
        source: include_str!("../../../shaders/shared/optics.wgsl"),
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/optics.rs",
    },
    SharedFile {
        file: "shared/trig.wgsl",
        source: include_str!("../../../shaders/shared/trig.wgsl"),
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/trig.rs",
    },
    SharedFile {
        file: "shared/gerstner.wgsl",
        source: include_str!("../../../shaders/shared/gerstner.wgsl"),
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/gerstner.rs",
    },
    SharedFile {
        file: "shared/coastal.wgsl",
        source: include_str!("../../../shaders/shared/coastal.wgsl"),
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/coastal.rs",
    },
    SharedFile {
        file: "shared/detail.wgsl",
        source: include_str!("../../../shaders/shared/detail.wgsl"),
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/detail.rs",
    },
    SharedFile {
        file: "shared/foam.wgsl",
        source: include_str!("../../../shaders/shared/foam.wgsl"),
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/foam.rs",
    },
    SharedFile {
        file: "shared/shadow.wgsl",
        source: include_str!("../../../shaders/shared/shadow.wgsl"),
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/shadow.rs",
    },
    SharedFile {
        file: "shared/floor.wgsl",
        source: include_str!("../../../shaders/shared/floor.wgsl"),
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/floor.rs",
    },
    SharedFile {
        file: "shared/fullscreen.wgsl",
        source: include_str!("../../../shaders/shared/fullscreen.wgsl"),
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shared/fullscreen.rs",
    },
];

/// The sky technique's interface: what `sky.wgsl` and the water's shading call.
const SKY_INTERFACE: &[&str] = &["sky_radiance", "sun_disc"];

/// The shading technique's interface: what `water.wgsl` calls.
const SHADING_INTERFACE: &[&str] = &["shade_above"];

/// The foam technique's interface: what `water.wgsl` calls.
const FOAM_INTERFACE: &[&str] = &["foam_coverage"];

/// Every technique file.
pub const TECHNIQUE_FILES: &[TechniqueFile] = &[
    TechniqueFile {
        technique: crate::stage::Sky::Preetham.row(),
        file: "sky/preetham.wgsl",
        source: include_str!("../../../shaders/sky/preetham.wgsl"),
        interface: SKY_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/sky/preetham.rs",
    },
    TechniqueFile {
        technique: crate::stage::Sky::PreethamClouds.row(),
        file: "sky/preetham_clouds.wgsl",
        source: include_str!("../../../shaders/sky/preetham_clouds.wgsl"),
        interface: SKY_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/sky/preetham_clouds.rs",
    },
    TechniqueFile {
        technique: crate::stage::Sky::Atmosphere.row(),
        file: "sky/atmosphere.wgsl",
        source: include_str!("../../../shaders/sky/atmosphere.wgsl"),
        interface: SKY_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/sky/atmosphere.rs",
    },
    TechniqueFile {
        technique: crate::stage::Sky::Overcast.row(),
        file: "sky/overcast.wgsl",
        source: include_str!("../../../shaders/sky/overcast.wgsl"),
        interface: SKY_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/sky/overcast.rs",
    },
    TechniqueFile {
        technique: crate::stage::Shading::Hu.row(),
        file: "shading/hu.wgsl",
        source: include_str!("../../../shaders/shading/hu.wgsl"),
        interface: SHADING_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shading/hu.rs",
    },
    TechniqueFile {
        technique: crate::stage::Shading::Chiu.row(),
        file: "shading/chiu.wgsl",
        source: include_str!("../../../shaders/shading/chiu.wgsl"),
        interface: SHADING_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shading/chiu.rs",
    },
    TechniqueFile {
        technique: crate::stage::Shading::Ggx.row(),
        file: "shading/ggx.wgsl",
        source: include_str!("../../../shaders/shading/ggx.wgsl"),
        interface: SHADING_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shading/ggx.rs",
    },
    TechniqueFile {
        technique: crate::stage::Shading::Coastal.row(),
        file: "shading/coastal.wgsl",
        source: include_str!("../../../shaders/shading/coastal.wgsl"),
        interface: SHADING_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/shading/coastal.rs",
    },
    TechniqueFile {
        technique: crate::stage::Foam::None.row(),
        file: "foam/none.wgsl",
        source: include_str!("../../../shaders/foam/none.wgsl"),
        interface: FOAM_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/foam/none.rs",
    },
    TechniqueFile {
        technique: crate::stage::Foam::Heuristic.row(),
        file: "foam/heuristic.wgsl",
        source: include_str!("../../../shaders/foam/heuristic.wgsl"),
        interface: FOAM_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/foam/heuristic.rs",
    },
    TechniqueFile {
        technique: crate::stage::Foam::Jacobian.row(),
        file: "foam/jacobian.wgsl",
        source: include_str!("../../../shaders/foam/jacobian.wgsl"),
        interface: FOAM_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/foam/jacobian.rs",
    },
    TechniqueFile {
        technique: crate::stage::Foam::Accumulated.row(),
        file: "foam/accumulated.wgsl",
        source: include_str!("../../../shaders/foam/accumulated.wgsl"),
        interface: FOAM_INTERFACE,
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/foam/accumulated.rs",
    },
];

/// The storage table's element of stage `waves` (its size is the array stride).
pub const WAVE_MODE: Block =
    block!(WaveModeData as "WaveMode" { h0, k, phase_rate, inv_k, frequency });

/// The stage called `name`.
pub fn stage(name: &str) -> Option<&'static StageEntry> {
    STAGES.iter().find(|s| s.name == name)
}

/// The file of technique `technique` of `stage`, when it has one.
pub fn technique_file(technique: &crate::stage::TechniqueInfo) -> Option<&'static TechniqueFile> {
    TECHNIQUE_FILES.iter().find(|t| t.technique == technique)
}

/// What the repository at `root` lacks for the given tables: each stage's WGSL, CPU mirror
/// and GPU module, each shared or technique file and its mirror, and each available
/// technique with WGSL-backed stages (sky) that has no file. One line per missing piece,
/// naming it; empty when nothing is missing.
pub fn missing_pieces(
    root: &Path,
    stages: &[StageEntry],
    shared: &[SharedFile],
    techniques: &[TechniqueFile],
) -> Vec<String> {
    let mut out = Vec::new();
    let mut need = |what: String, path: &str| {
        if !root.join(path).is_file() {
            out.push(format!("{what}: {path} is missing"));
        }
    };
    for s in stages {
        need(format!("stage `{}`: its WGSL", s.name), &format!("shaders/{}", s.file));
        need(format!("stage `{}`: its CPU mirror", s.name), s.cpu_mirror);
        need(format!("stage `{}`: its GPU module", s.name), s.gpu_module);
    }
    for f in shared {
        need(format!("shared file `{}`", f.file), &format!("shaders/{}", f.file));
        need(format!("shared file `{}`: its CPU mirror", f.file), f.cpu_mirror);
    }
    for t in techniques {
        let name = format!("technique {}/{}", t.technique.stage, t.technique.name);
        need(format!("{name}: its WGSL"), &format!("shaders/{}", t.file));
        need(format!("{name}: its CPU mirror"), t.cpu_mirror);
    }
    // A stage whose technique is composed into WGSL needs a file for every technique.
    for stage in [TechniqueStage::Sky, TechniqueStage::Shading, TechniqueStage::Foam] {
        for t in stage.techniques() {
            if !techniques.iter().any(|f| f.technique == t) {
                out.push(format!(
                    "technique {stage}/{}: in the table but not in the registry's technique files",
                    t.name
                ));
            }
        }
    }
    out
}
