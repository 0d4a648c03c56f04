//! The `ocean` binary as the test files run it, one runner for all of them:
//! `RUST_BACKTRACE=0`, so that a refusal shows its message rather than a backtrace.

#![allow(dead_code, reason = "each test binary uses the helpers it needs")]

use std::process::{Command, Output};

/// The `ocean` command, ready for arguments and environment.
pub fn command() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_ocean"));
    c.env("RUST_BACKTRACE", "0");
    c
}

/// `ocean ARGS`, run to the end.
pub fn ocean(args: &[&str]) -> Output {
    command().args(args).output().expect("the ocean binary runs")
}

/// `ocean ARGS` with the variables of `env` set.
pub fn ocean_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = command();
    c.args(args);
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("the ocean binary runs")
}
