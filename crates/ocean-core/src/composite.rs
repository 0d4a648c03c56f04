//! The `composite` stage's uniforms (`shaders/composite.wgsl`): the last pass of a sea drawn
//! inside someone else's wgpu program (`ocean_gpu::embed`). The frame is rendered in this
//! crate's own targets, with its reversed-Z infinite projection ([`crate::camera`]); the
//! composite copies its picture into the caller's colour target and writes, per pixel, the
//! depth the same surface point has under the caller's projection, tested against the
//! caller's depth buffer. The caller's objects and the sea then hide each other correctly,
//! whichever is drawn first.
//!
//! Depth: the frame stores d_o = near / distance (distance along the view axis, m;
//! d_o = 0 where only the sky is). With the caller's projection P (column-major, glam's
//! `m[column][row]`), a point at view-space z = −distance has clip z = P₂₂·z + P₃₂ and clip
//! w = P₂₃·z + P₃₃, and the caller's depth is their ratio, clamped to [0, 1]. Sky pixels get
//! the caller's far depth (1 for a `Less` buffer, 0 for a reversed `Greater` one), so they
//! never hide anything the caller drew.
//!
//! Colour: the frame's 8-bit sRGB picture. A non-sRGB 8-bit target stores it as it is; an
//! sRGB or float target gets its linear values (the sRGB curve inverted), so an sRGB target
//! ends with the same bytes. With `radiance`, the HDR frame (linear, before exposure and
//! tonemapping) is copied instead, for a caller who does its own post-processing.

use glam::DMat4;

use crate::camera::NEAR_PLANE_M;

/// The uniforms of the `composite` stage (`CompositeUniforms` in `shaders/composite.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CompositeUniforms {
    /// The caller's projection's depth terms (P₂₂, P₃₂, P₂₃, P₃₃): clip z = x·z_view + y,
    /// clip w = z·z_view + w.
    pub depth: [f32; 4],
    /// (this crate's near plane in m, the caller's far depth, 1 to invert the sRGB curve
    /// else 0, unused 0).
    pub params: [f32; 4],
}

impl CompositeUniforms {
    /// The uniforms for the caller's `projection`, whose depth buffer is cleared to
    /// `far_depth` (1 with `Less`, 0 with reversed-Z `Greater`), with the sRGB curve inverted
    /// when `linear_target` (an sRGB or float colour target).
    pub fn new(projection: DMat4, far_depth: f32, linear_target: bool) -> Self {
        let p = projection;
        Self {
            depth: [p.z_axis.z, p.w_axis.z, p.z_axis.w, p.w_axis.w].map(|v| v as f32),
            params: [NEAR_PLANE_M as f32, far_depth, if linear_target { 1.0 } else { 0.0 }, 0.0],
        }
    }
}
