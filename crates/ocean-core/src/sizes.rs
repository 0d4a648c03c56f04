//! Memory sizes: the machine's, the default limit of a render, and sizes as a person reads and
//! writes them. A leaf: the input readers and the planner's memory estimate both use it.

/// The default memory limit: three quarters of the machine's physical memory (what is left
/// serves the system and, for `ocean compare`, the other back end's driver), or 8 GiB where
/// the physical memory cannot be read.
pub fn default_limit() -> u64 {
    physical_memory().map_or(8 << 30, |m| m / 4 * 3)
}

/// Total physical memory, bytes (Linux `/proc/meminfo`).
pub fn physical_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Bytes as a person reads them: `512 B`, `3.2 MiB`, `14.5 GiB`.
pub fn bytes(b: u64) -> String {
    const UNITS: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut v = b as f64;
    let mut unit = 0;
    while v >= 1024.0 && unit + 1 < UNITS.len() {
        v /= 1024.0;
        unit += 1;
    }
    if unit == 0 { format!("{b} B") } else { format!("{v:.1} {}", UNITS[unit]) }
}

/// Parses a memory size: a number of bytes, or a number with `K`, `M`, `G`, `T` (powers of
/// 1024; `KiB`/`KB`/`k` and so on are read the same).
///
/// # Errors
/// A message naming what was given and what is accepted.
pub fn parse_bytes(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let split = t.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let scale: u64 = match unit.trim().to_ascii_lowercase().trim_end_matches('b') {
        "" => 1,
        "k" | "ki" => 1 << 10,
        "m" | "mi" => 1 << 20,
        "g" | "gi" => 1 << 30,
        "t" | "ti" => 1 << 40,
        _ => return Err(format!("`{s}` is not a size (use e.g. 512M, 16G or a number of bytes)")),
    };
    let v: f64 = number
        .parse()
        .map_err(|_| format!("`{s}` is not a size (use e.g. 512M, 16G or a number of bytes)"))?;
    let b = v * scale as f64;
    if !(1.0..1.8e19).contains(&b) {
        return Err(format!("`{s}` must be from 1 byte to 16 EiB"));
    }
    Ok(b as u64)
}
