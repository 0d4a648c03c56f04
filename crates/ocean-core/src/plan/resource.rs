//! The resources of a frame: every texture a pass writes or reads, with the format and size
//! the plan gives it. Both back ends allocate exactly these (a test holds each back end's
//! allocations against this table), so neither chooses a size of its own.

use serde::Serialize;

use super::Pass;

/// Side of the sun's shadow map, texels.
pub const SHADOW_MAP_SIZE: u32 = 1024;

/// A texture of the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ResourceId {
    /// (disp_x, height, disp_z, jacobian) of the displacement map.
    Displacement,
    /// (slope_x, slope_z, 0, 0) of the displacement map.
    DisplacementSlopes,
    /// (slope_x, slope_z, height, jacobian) of the bump map.
    Bump,
    /// Fresnel texture for η (surface seen from above).
    FresnelAbove,
    /// Fresnel texture for 1/η (seen from below).
    FresnelBelow,
    /// Depth of the objects from the sun, in red.
    ShadowMap,
    /// Mirrored objects above the water, alpha = coverage.
    ReflectionMap,
    /// Fogged objects under the water, alpha = coverage.
    RefractionMap,
    /// The linear HDR frame.
    Hdr,
    /// The 8-bit sRGB picture.
    Ldr,
    /// The displacement map's slopes with their second moments, a mip chain (stage
    /// `wave_mips`).
    DisplacementSlopeMips,
    /// The bump map's, likewise.
    BumpMips,
    /// The filtered Fresnel table F̄(r, σ) of far field `variance` (ocean-core's
    /// `far_field::FresnelFilterTable`, computed on the CPU, the same texels on both back ends).
    FresnelFilter,
    /// Post `bloom`: the bright pass and its downsamples, a mip chain at half the frame's size.
    BloomDown,
    /// Post `bloom`: the levels summed back up, a mip chain like [`Self::BloomDown`]; level 0
    /// is what the tonemap adds.
    BloomUp,
    /// Foam `accumulated`'s field (foam in x; stage `foam`): on the displacement map's grid
    /// under waves `fft`, on a lattice around the camera under `gerstner` (`crate::foam`).
    FoamField,
    /// The environment the water reflects and the `sky` pass draws: the sky technique's
    /// uniform block, prepared with the frame's inputs (a `preetham` sky is a fit of the
    /// Perez coefficients, computed on the CPU for both back ends).
    Environment,
}

impl ResourceId {
    /// The float maps both back ends keep and the cross-check compares, in the order the
    /// frame makes them.
    pub const MAPS: [ResourceId; 15] = [
        ResourceId::Displacement,
        ResourceId::DisplacementSlopes,
        ResourceId::Bump,
        ResourceId::DisplacementSlopeMips,
        ResourceId::BumpMips,
        ResourceId::FresnelFilter,
        ResourceId::FoamField,
        ResourceId::FresnelAbove,
        ResourceId::FresnelBelow,
        ResourceId::ShadowMap,
        ResourceId::ReflectionMap,
        ResourceId::RefractionMap,
        ResourceId::Hdr,
        ResourceId::BloomDown,
        ResourceId::BloomUp,
    ];

    /// The slope maps and the mip chains pass `wave_mips` makes of them (source, chain): the
    /// water pass binds the chain where the pass ran, else the map as one level.
    pub const SLOPE_CHAINS: [(ResourceId, ResourceId); 2] = [
        (ResourceId::DisplacementSlopes, ResourceId::DisplacementSlopeMips),
        (ResourceId::Bump, ResourceId::BumpMips),
    ];

    /// Every resource.
    pub const ALL: [ResourceId; 17] = [
        ResourceId::Displacement,
        ResourceId::DisplacementSlopes,
        ResourceId::Bump,
        ResourceId::DisplacementSlopeMips,
        ResourceId::BumpMips,
        ResourceId::FresnelFilter,
        ResourceId::FoamField,
        ResourceId::FresnelAbove,
        ResourceId::FresnelBelow,
        ResourceId::ShadowMap,
        ResourceId::ReflectionMap,
        ResourceId::RefractionMap,
        ResourceId::Hdr,
        ResourceId::BloomDown,
        ResourceId::BloomUp,
        ResourceId::Ldr,
        ResourceId::Environment,
    ];

    /// Its name (`displacement`, …, `ldr`): ocean-cpu's `FrameBuffers` field, the GPU's label
    /// and the cross-check's file names.
    pub fn name(self) -> &'static str {
        match self {
            ResourceId::Displacement => "displacement",
            ResourceId::DisplacementSlopes => "displacement_slopes",
            ResourceId::Bump => "bump",
            ResourceId::DisplacementSlopeMips => "displacement_slope_mips",
            ResourceId::BumpMips => "bump_mips",
            ResourceId::FresnelFilter => "fresnel_filter",
            ResourceId::FresnelAbove => "fresnel_above",
            ResourceId::FresnelBelow => "fresnel_below",
            ResourceId::ShadowMap => "shadow_map",
            ResourceId::ReflectionMap => "reflection_map",
            ResourceId::RefractionMap => "refraction_map",
            ResourceId::Hdr => "hdr",
            ResourceId::BloomDown => "bloom_down",
            ResourceId::BloomUp => "bloom_up",
            ResourceId::FoamField => "foam_field",
            ResourceId::Ldr => "ldr",
            ResourceId::Environment => "environment",
        }
    }

    /// The pass that writes it last (`None`: prepared with the frame's inputs, before any
    /// pass).
    pub fn writer(self) -> Option<Pass> {
        Some(match self {
            ResourceId::Displacement | ResourceId::DisplacementSlopes | ResourceId::Bump => {
                Pass::Waves
            }
            ResourceId::DisplacementSlopeMips
            | ResourceId::BumpMips
            | ResourceId::FresnelFilter => Pass::WaveMips,
            ResourceId::FresnelAbove | ResourceId::FresnelBelow => Pass::FresnelTable,
            ResourceId::ShadowMap => Pass::ShadowMap,
            ResourceId::ReflectionMap => Pass::ReflectionMap,
            ResourceId::RefractionMap => Pass::RefractionMap,
            ResourceId::Hdr => Pass::Water,
            ResourceId::BloomDown | ResourceId::BloomUp => Pass::Bloom,
            ResourceId::FoamField => Pass::Foam,
            ResourceId::Ldr => Pass::Tonemap,
            ResourceId::Environment => return None,
        })
    }
}

/// A texel format (the wgpu name).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Format {
    /// Four f32 channels.
    Rgba32Float,
    /// Four binary16 channels (`crate::frame_format`).
    Rgba16Float,
    /// One f32 channel.
    R32Float,
    /// 8-bit sRGB-encoded RGBA, stored as unorm.
    Rgba8Unorm,
    /// A uniform buffer (its size is [bytes, 1]).
    Uniform,
}

impl Format {
    /// The format a frame colour buffer of `f` has.
    pub fn of_frame(f: crate::frame_format::FrameFormat) -> Self {
        match f {
            crate::frame_format::FrameFormat::Rgba32Float => Format::Rgba32Float,
            crate::frame_format::FrameFormat::Rgba16Float => Format::Rgba16Float,
        }
    }

    /// What a store to a buffer of this format does to a value, as a frame format (f32 for
    /// every format but `rgba16float`: the others hold f32 or are not float buffers).
    pub fn storage(self) -> crate::frame_format::FrameFormat {
        match self {
            Format::Rgba16Float => crate::frame_format::FrameFormat::Rgba16Float,
            _ => crate::frame_format::FrameFormat::Rgba32Float,
        }
    }
}

/// A resource as the plan sizes it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Resource {
    /// Which.
    pub id: ResourceId,
    /// Its texel format.
    pub format: Format,
    /// Width and height, texels (a uniform buffer: bytes and 1).
    pub size: [u32; 2],
    /// Whether a pass writes it this frame; when not, it is a 1×1 zero texture bound in its
    /// place (the shaders multiply what they read from it by the plan's pass flags).
    pub written: bool,
    /// The colour it starts from before its first pass.
    pub clear: [f32; 4],
    /// Its mip levels (1 for a plain texture; the chains of `wave_mips` and `bloom` more).
    pub levels: u32,
}

impl Resource {
    /// The size its read-back has: a mip chain (`displacement_slope_mips`, `bump_mips`,
    /// `bloom_down`, `bloom_up`) comes back as its packed atlas ([`crate::far_field::mip_level_row`]), `size[0]` wide and the
    /// sum of its levels' heights tall; any other resource at its size.
    pub fn readback_size(&self) -> [u32; 2] {
        let [w, h] = self.size;
        if self.levels > 1 {
            [w, crate::far_field::mip_level_row(h, self.levels)]
        } else {
            self.size
        }
    }

    /// Texels (width × height).
    pub fn texels(&self) -> u64 {
        u64::from(self.size[0]) * u64::from(self.size[1])
    }
}
