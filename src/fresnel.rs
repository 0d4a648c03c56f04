//! `ocean fresnel`: the exact Fresnel term of eq. 2 (seed 000) as CSV, or the 2D Fresnel
//! texture of §5.1 as EXR (docs/design.md's contracts).

use std::path::PathBuf;

use anyhow::{Context, bail};
use ocean_core::fresnel::{fresnel_exact, fresnel_schlick};
use ocean_core::tables::{FresnelTexture, TextureMapping};

use ocean::output::{Channel, encode_exr, require_extension};

/// Arguments of `ocean fresnel`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Relative index of refraction η = η_t/η_i (water from air: 1.333; from below: 0.75).
    #[arg(long, allow_negative_numbers = true)]
    eta: f64,
    /// Step of the incidence angle in degrees for the CSV (0 to 90 inclusive), at least
    /// 90 / 1,000,000 (a million rows).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    step_deg: f64,
    /// Write the N×N 2D Fresnel texture instead of the CSV (needs -o FILE.exr).
    #[arg(long, value_name = "N")]
    table: Option<usize>,
    /// Which view vectors the texels stand for: `hemisphere` (docs/design.md's contract: x = 2s−1,
    /// y = 2t−1), `half-range` (the paper's V = (s−0.5, t−0.5, …), about ±30° only) or
    /// `grazing` (the renderer's: the rim on the edge texels' centres, radius ∝ sqrt(1 − cos θ);
    /// see docs/commands.md).
    #[arg(long, requires = "table", default_value = "hemisphere", value_parser = parse_mapping)]
    mapping: TextureMapping,
    /// Same as `--mapping half-range` (kept for scripts that used it).
    #[arg(long, requires = "table", conflicts_with = "mapping")]
    paper_half_range: bool,
    /// Output file for --table.
    #[arg(short, long, requires = "table")]
    output: Option<PathBuf>,
}

fn parse_mapping(name: &str) -> Result<TextureMapping, String> {
    TextureMapping::from_name(name).ok_or_else(|| {
        let known: Vec<&str> = TextureMapping::ALL.iter().map(|m| m.name()).collect();
        format!("unknown mapping `{name}`; known: {}", known.join(", "))
    })
}

/// The largest texture side accepted: 8192² RGBA f32 is 1 GiB.
const MAX_TABLE: usize = 8192;

/// Runs `ocean fresnel`.
pub fn run(args: Args) -> anyhow::Result<()> {
    if !(args.eta > 0.0 && args.eta.is_finite()) {
        bail!("--eta must be finite and > 0, got {}", args.eta);
    }
    match args.table {
        Some(n) => write_table(&args, n),
        None => {
            let stdout = std::io::stdout().lock();
            let mut out = std::io::BufWriter::new(stdout);
            write_csv(&mut out, args.eta, args.step_deg)?;
            std::io::Write::flush(&mut out).context("writing the CSV")?;
            Ok(())
        }
    }
}

/// The most CSV rows `--step-deg` may ask for: 90 / step + 1 ≤ a million (about 50 MB), so a
/// tiny step is refused at once instead of running for ever.
pub const MAX_CSV_ROWS: f64 = 1e6;

/// Writes the CSV `theta_deg,cos_theta,exact,schlick`, θ = 0, step, 2·step, … up to 90
/// degrees, row by row as it is computed. Values use Rust's shortest round-trip formatting.
fn write_csv(out: &mut impl std::io::Write, eta: f64, step_deg: f64) -> anyhow::Result<()> {
    let min_step = 90.0 / (MAX_CSV_ROWS - 1.0);
    if !(step_deg >= min_step && step_deg <= 90.0) {
        bail!(
            "--step-deg must be in [{min_step:e}, 90] (at most {MAX_CSV_ROWS:e} rows), got {step_deg:?}"
        );
    }
    let write = |out: &mut dyn std::io::Write, line: std::fmt::Arguments<'_>| {
        out.write_fmt(line).context("writing the CSV")
    };
    write(out, format_args!("theta_deg,cos_theta,exact,schlick\n"))?;
    // θ from an integer count, not by accumulation, so the last row is exactly 90 when the
    // step divides 90; the tolerance absorbs the rounding of 90/step.
    let steps = (90.0 / step_deg * (1.0 + 1e-12)).floor() as usize;
    for i in 0..=steps {
        let theta_deg = (i as f64 * step_deg).min(90.0);
        // cos(π/2) rounds to 6.1e-17, not 0; grazing incidence is printed as exactly 0 so
        // that the last row is the limit F = 1 that eq. 2 gives there.
        let cos_theta = if theta_deg == 90.0 { 0.0 } else { theta_deg.to_radians().cos() };
        let exact = fresnel_exact(cos_theta, eta);
        let schlick = fresnel_schlick(cos_theta, eta);
        write(out, format_args!("{theta_deg},{cos_theta},{exact},{schlick}\n"))?;
    }
    Ok(())
}

fn write_table(args: &Args, n: usize) -> anyhow::Result<()> {
    if !(1..=MAX_TABLE).contains(&n) {
        bail!("--table must be between 1 and {MAX_TABLE}, got {n}");
    }
    let path = args.output.as_ref().context("--table N needs -o FILE.exr")?;
    require_extension(path, "exr")?;
    let out = ocean::output::OutputFile::reserve(path)?;
    let mapping = if args.paper_half_range { TextureMapping::PaperHalfRange } else { args.mapping };
    let tex = FresnelTexture::new(n, args.eta, mapping)?;
    let channel = |c: usize| tex.texels().iter().map(|t| t[c]).collect::<Vec<f32>>();
    let channels = ["R", "G", "B", "A"]
        .iter()
        .enumerate()
        .map(|(c, name)| Channel { name, data: channel(c) })
        .collect();
    out.commit(&encode_exr(n, n, channels)?)?;
    eprintln!("wrote {} ({n}×{n}, η = {}, {} mapping)", path.display(), args.eta, mapping.name());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn csv(eta: f64, step_deg: f64) -> anyhow::Result<String> {
        let mut out = Vec::new();
        write_csv(&mut out, eta, step_deg)?;
        Ok(String::from_utf8(out)?)
    }

    #[test]
    fn csv_rows_cover_0_to_90() {
        let text = csv(1.333, 1.0).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "theta_deg,cos_theta,exact,schlick");
        assert_eq!(lines.len(), 92);
        assert!(lines[1].starts_with("0,1,"));
        assert!(lines[91].starts_with("90,"));
        let text = csv(1.333, 7.0).unwrap();
        assert!(text.lines().last().unwrap().starts_with("84,"));
        assert!(csv(1.333, 0.0).is_err());
        assert!(csv(1.333, f64::NAN).is_err());
    }
}
