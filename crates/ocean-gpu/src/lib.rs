//! placeholder
pub mod waves;
