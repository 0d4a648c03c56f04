//! The library half of the `ocean` package: what the command line (`src/main.rs`) and the
//! integration tests share.
//!
//! - [`cross_check`]: the CPU ↔ GPU comparison behind `ocean compare` and
//!   `tests/gpu_cross_check.rs`.

pub mod cross_check;
