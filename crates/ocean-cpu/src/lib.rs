//! The deterministic software renderer of `ocean`: the correctness oracle for the wgpu path.
//!
//! Everything here follows the Vulkan rules as Mesa's lavapipe implements them (see the
//! "Determinism contract" in the project's docs/design.md), and every result is a pure function of
//! its inputs: bit-identical across runs and across any number of rayon threads.
//!
//! - [`raster`]: triangle rasterizer (clipping, 8-bit sub-pixel snapping, top-left fill rule,
//!   perspective-correct varyings, f32 depth test), parallel over disjoint row bands.
//! - [`sampler`]: `textureSample` / `textureSampleLevel` on a 2D f32 texture, level 0.
//! - [`mip`]: mip chains and `textureSampleLevel` between their levels, as lavapipe blends.
//! - [`envelope`]: the scalar types a mirror runs over: exact f32, the hardware envelope,
//!   a random conformant GPU.
//! - [`shaders`]: one module per WGSL stage (and per shared WGSL file), same names, same
//!   order of operations.

pub mod envelope;
pub mod float;
pub mod frame;
pub mod mip;
pub mod raster;
pub mod render;
pub mod sampler;
pub mod shaders;

pub use render::{
    Rendered, render_animation_frame, render_ldr, render_scene, render_scene_with_plan,
};
