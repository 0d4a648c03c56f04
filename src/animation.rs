//! `ocean render --frames`: which frames a run renders and where each one goes.
//!
//! An animation is frames `A..B` of a scene at `F` frames per second: frame n shows the sea at
//! `t₀ + n/F` (t₀ the scene's `ocean.time_s`) through [`ocean_core::graph::FrameState`], which
//! always starts at frame 0, so frame n is a pure function of (scene, F, n): a range that
//! starts later, a shard or a resumed run replays what earlier frames leave behind (foam
//! `accumulated`'s field, the spray's pool) without drawing them, and gets the same frame bit
//! for bit. `--shard i/n` keeps the frames with (n − A) mod count = i, so any batch system can
//! spread a sequence over machines with nothing to coordinate.

use std::path::{Path, PathBuf};

use anyhow::{bail, ensure};

/// The frames of a run: `start..end`, end excluded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameRange {
    /// The first frame.
    pub start: u64,
    /// One past the last frame.
    pub end: u64,
}

impl FrameRange {
    /// Parses `A..B` (B excluded, as Rust's ranges) or `A..=B` (B included).
    ///
    /// # Errors
    /// Anything else, an empty range, or a last frame past `u64::MAX − 1`.
    pub fn parse(s: &str) -> anyhow::Result<Self> {
        let t = s.trim();
        let (a, b, inclusive) = if let Some((a, b)) = t.split_once("..=") {
            (a, b, true)
        } else if let Some((a, b)) = t.split_once("..") {
            (a, b, false)
        } else {
            bail!("`{s}` is not a frame range: write A..B (B excluded) or A..=B (B included)")
        };
        let number = |x: &str, what: &str| {
            x.trim().parse::<u64>().map_err(|_| {
                anyhow::anyhow!("`{s}`: the {what} frame `{x}` is not a whole number ≥ 0")
            })
        };
        let start = number(a, "first")?;
        let last = number(b, "last")?;
        let end = if inclusive {
            last.checked_add(1).ok_or_else(|| anyhow::anyhow!("`{s}`: the range is too long"))?
        } else {
            last
        };
        ensure!(end > start, "`{s}` holds no frame (the end must be after the start)");
        Ok(Self { start, end })
    }

    /// How many frames it holds.
    pub fn len(&self) -> u64 {
        self.end - self.start
    }

    /// Whether it holds no frame (never, once parsed).
    pub fn is_empty(&self) -> bool {
        self.end <= self.start
    }
}

/// `--shard i/n`: the i-th of n interleaved parts of a range, 0 ≤ i < n.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which part, from 0.
    pub index: u64,
    /// How many parts.
    pub count: u64,
}

impl Default for Shard {
    fn default() -> Self {
        Self { index: 0, count: 1 }
    }
}

impl Shard {
    /// Parses `i/n`.
    ///
    /// # Errors
    /// Anything else, n = 0 or i ≥ n.
    pub fn parse(s: &str) -> anyhow::Result<Self> {
        let Some((i, n)) = s.trim().split_once('/') else {
            bail!("`{s}` is not a shard: write i/n, the i-th of n parts counted from 0 (0/4 … 3/4)")
        };
        let (Ok(index), Ok(count)) = (i.trim().parse::<u64>(), n.trim().parse::<u64>()) else {
            bail!("`{s}` is not a shard: i and n must be whole numbers (i/n, 0 ≤ i < n)")
        };
        ensure!(count > 0, "`{s}`: a sequence cannot be split into 0 parts");
        ensure!(
            index < count,
            "`{s}`: shards are counted from 0, so i must be below n (0/{count} … {}/{count})",
            count - 1
        );
        Ok(Self { index, count })
    }

    /// Whether frame `n` of `range` is this shard's.
    pub fn owns(&self, range: &FrameRange, n: u64) -> bool {
        n >= range.start && n < range.end && (n - range.start) % self.count == self.index
    }

    /// This shard's frames of `range`, in order.
    pub fn frames(self, range: FrameRange) -> impl Iterator<Item = u64> {
        (range.start..range.end).filter(move |n| self.owns(&range, *n))
    }
}

/// An output path with one frame-number placeholder: `{}` (the number as is) or `{:0W}` /
/// `{:W}` (padded with zeros or spaces to W digits), as Rust's `format!` writes them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FramePattern {
    before: String,
    after: String,
    width: usize,
    zeros: bool,
}

impl FramePattern {
    /// Parses a pattern such as `out/frame_{:05}.png`.
    ///
    /// # Errors
    /// No placeholder, more than one, or one this does not know.
    pub fn parse(pattern: &Path) -> anyhow::Result<Self> {
        let s = pattern.to_string_lossy();
        let Some(open) = s.find('{') else {
            bail!(
                "output `{s}` has no frame number: with --frames write a pattern such as \
                 'out/frame_{{:05}}.png' (the frame number padded to 5 digits)"
            )
        };
        let Some(close) = s[open..].find('}').map(|c| open + c) else {
            bail!("output `{s}`: the `{{` of its frame number is not closed")
        };
        let (before, spec, after) = (&s[..open], &s[open + 1..close], &s[close + 1..]);
        ensure!(
            !after.contains('{') && !after.contains('}'),
            "output `{s}` has more than one placeholder; it takes one, the frame number"
        );
        let (width, zeros) = match spec {
            "" => (0, false),
            _ => {
                let Some(w) = spec.strip_prefix(':') else {
                    bail!("output `{s}`: write the frame number as {{}} or {{:05}}, not {{{spec}}}")
                };
                let zeros = w.starts_with('0') && w.len() > 1;
                let digits = if zeros { &w[1..] } else { w };
                let Ok(width) = digits.parse::<usize>() else {
                    bail!("output `{s}`: write the frame number as {{}} or {{:05}}, not {{{spec}}}")
                };
                ensure!(width <= 20, "output `{s}`: a frame number has at most 20 digits");
                (width, zeros)
            }
        };
        Ok(Self { before: before.to_owned(), after: after.to_owned(), width, zeros })
    }

    /// The path of frame `n`.
    pub fn path(&self, n: u64) -> PathBuf {
        let number = match (self.width, self.zeros) {
            (0, _) => n.to_string(),
            (w, true) => format!("{n:0w$}"),
            (w, false) => format!("{n:w$}"),
        };
        PathBuf::from(format!("{}{number}{}", self.before, self.after))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_parse_both_ways_and_refuse_empty_ones() {
        assert_eq!(FrameRange::parse("0..10").unwrap(), FrameRange { start: 0, end: 10 });
        assert_eq!(FrameRange::parse(" 5..=9 ").unwrap(), FrameRange { start: 5, end: 10 });
        assert_eq!(FrameRange::parse("7..=7").unwrap().len(), 1);
        for bad in ["10..10", "9..3", "a..3", "3", "-1..4", "0..=18446744073709551615", "1...4"] {
            assert!(FrameRange::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn shards_partition_a_range() {
        let range = FrameRange::parse("3..=17").unwrap();
        let mut all: Vec<u64> =
            (0..4).flat_map(|i| Shard { index: i, count: 4 }.frames(range)).collect();
        all.sort_unstable();
        assert_eq!(all, (3..18).collect::<Vec<_>>());
        assert_eq!(Shard::parse("1/4").unwrap().frames(range).collect::<Vec<_>>(), [4, 8, 12, 16]);
        assert_eq!(Shard::default().frames(range).count(), 15);
        for bad in ["4/4", "1/0", "1", "a/2", "-1/2", "1/2/3"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn patterns_number_the_frames() {
        let p = FramePattern::parse(Path::new("out/frame_{:05}.png")).unwrap();
        assert_eq!(p.path(42), PathBuf::from("out/frame_00042.png"));
        assert_eq!(p.path(1234567), PathBuf::from("out/frame_1234567.png"));
        let p = FramePattern::parse(Path::new("f{}.exr")).unwrap();
        assert_eq!(p.path(7), PathBuf::from("f7.exr"));
        let p = FramePattern::parse(Path::new("f{:3}.exr")).unwrap();
        assert_eq!(p.path(7), PathBuf::from("f  7.exr"));
        for bad in ["out.png", "f{:x}.png", "f{}{}.png", "f{.png", "f{0}.png", "f{:05d}.png"] {
            assert!(FramePattern::parse(Path::new(bad)).is_err(), "{bad}");
        }
    }
}
