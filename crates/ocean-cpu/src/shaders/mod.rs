//! One Rust module per WGSL stage (`shaders/<stage>.wgsl` ↔ `shaders/<stage>.rs`), one per
//! technique of a stage (`shaders/<stage>/<technique>.wgsl` ↔ `<stage>::<technique>`, e.g.
//! [`sky::preetham`]), and one per shared WGSL file (`shaders/shared/<name>.wgsl` ↔
//! [`shared`]`::<name>`).
//!
//! Each mirror keeps the WGSL entry points' names and signatures (`vs_main`, `fs_main`), the
//! same variable names and the same order of operations, in f32, so the two files read side by
//! side. WGSL uniforms become `&` parameters after the shader's own inputs. Vector expressions
//! are written as in the WGSL, with the vector types, operators and built-ins of [`wgsl`]
//! (each operator one plain f32 operation per component, in WGSL's order). No `mul_add` (the
//! WGSL uses no `fma`), no fast-math.

pub mod bloom;
pub mod composite;
pub mod foam;
pub mod fresnel_table;
pub mod objects;
pub mod present;
pub mod shading;
pub mod shadow;
pub mod shared;
pub mod sky;
pub mod spray;
pub mod tonemap;
pub mod water;
pub mod wave_mips;
pub mod waves;
pub mod wgsl;
