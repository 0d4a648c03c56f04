//! How `ocean` checks itself, shared by the tests, `ocean compare` and `ocean report`:
//!
//! - [`compare`]: the comparators of docs/design.md's tolerance table (float buffers, 8-bit
//!   pictures with FLIP), each with its limits.
//! - [`cross_check`]: one scene and plan through the CPU oracle and the wgpu path, every map
//!   compared and held to the plan's size; artefacts for a failure.
//! - [`envelope`]: the verdict by the hardware envelope (any conformant GPU).
//! - [`stability`]: the numerical-stability table on stiff and extreme inputs.

pub mod compare;
pub mod cross_check;
pub mod envelope;
pub mod stability;
