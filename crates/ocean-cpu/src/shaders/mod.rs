//! CPU mirrors of the WGSL stages in `shaders/`, one module per stage, same entry points,
//! names and order of operations (DESIGN.md, "One name per stage").

pub mod common;
pub mod fresnel_table;
pub mod objects;
pub mod shadow;
pub mod water;
