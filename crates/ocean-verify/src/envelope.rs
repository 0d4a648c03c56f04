//! The verdict by the envelope (docs/tolerances.md): a texel outside the interval any
//! conformant GPU may produce fails; the figures say how wide the envelope was.
//!
//! Each judged pass is held to its envelope given its inputs as the GPU read them; the
//! resources of passes without an envelope yet are reported as not judged (`ocean::verdict`).

use ocean_core::plan::ResourceId;
use ocean_cpu::envelope::{ByteRange, Iv};
use serde_json::{Value, json};

/// How `ocean compare` holds a GPU's resources.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tolerance {
    /// docs/design.md's float and picture rows (lavapipe's figures): for a software adapter.
    Exact,
    /// The envelope of any conformant implementation: for a hardware or unknown adapter.
    Envelope,
}

impl Tolerance {
    /// The default for an adapter: exact on a software one (lavapipe), the envelope on
    /// hardware and when it is unknown.
    pub fn for_software(software: Option<bool>) -> Tolerance {
        if software == Some(true) { Tolerance::Exact } else { Tolerance::Envelope }
    }

    /// Its name on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Tolerance::Exact => "exact",
            Tolerance::Envelope => "envelope",
        }
    }
}

/// The texel furthest outside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorstByte {
    /// Pixel column and row.
    pub pixel: (u32, u32),
    /// 0 R, 1 G, 2 B.
    pub channel: usize,
    /// The byte the GPU stored.
    pub got: u8,
    /// The bytes allowed.
    pub allowed: ByteRange,
    /// What the exact frame (lavapipe's arithmetic) stores there.
    pub exact: u8,
}

/// An 8-bit picture against its envelope.
#[derive(Clone, Debug, PartialEq)]
pub struct PictureVerdict {
    /// The resource (`ldr`).
    pub name: String,
    /// Bytes judged (R, G, B of every pixel).
    pub bytes: usize,
    /// Bytes outside their range.
    pub outside: usize,
    /// The envelope's width in codes (hi − lo) at the median and the 99th percentile.
    pub codes_p50: u8,
    /// See `codes_p50`.
    pub codes_p99: u8,
    /// The value before the store: the envelope's relative half-width, median and 99th
    /// percentile.
    pub rel_half_width_p50: f64,
    /// See `rel_half_width_p50`.
    pub rel_half_width_p99: f64,
    /// The byte furthest outside, if any.
    pub worst: Option<WorstByte>,
}

/// Judges the RGBA8 picture `rgba` (`width` wide) by `envelope` (one entry per pixel: R, G, B's
/// value before the store and its bytes); `exact` is the exact frame's picture, for the report.
///
/// # Panics
/// If the picture and the envelope differ in pixel count.
pub fn judge_picture(
    name: &str,
    envelope: &[[(Iv, ByteRange); 3]],
    rgba: &[u8],
    exact: &[u8],
    width: u32,
) -> PictureVerdict {
    assert_eq!(rgba.len(), envelope.len() * 4, "picture and envelope sizes differ");
    assert_eq!(exact.len(), rgba.len(), "exact picture size differs");
    let mut outside = 0;
    let mut worst: Option<(u8, WorstByte)> = None;
    let mut codes = Vec::with_capacity(envelope.len() * 3);
    let mut rel = Vec::with_capacity(envelope.len() * 3);
    for (i, px) in envelope.iter().enumerate() {
        // The shader writes alpha 1: every conformant store holds 255.
        if rgba[4 * i + 3] != 255 {
            outside += 1;
        }
        for (c, (value, bytes)) in px.iter().enumerate() {
            let got = rgba[4 * i + c];
            codes.push(bytes.hi - bytes.lo);
            rel.extend(value.rel_half_width());
            let d = bytes.distance(got);
            if d > 0 {
                outside += 1;
                if worst.is_none_or(|(w, _)| d > w) {
                    let w = width.max(1) as usize;
                    let at = WorstByte {
                        pixel: ((i % w) as u32, (i / w) as u32),
                        channel: c,
                        got,
                        allowed: *bytes,
                        exact: exact[4 * i + c],
                    };
                    worst = Some((d, at));
                }
            }
        }
    }
    codes.sort_unstable();
    rel.sort_by(f64::total_cmp);
    PictureVerdict {
        name: name.to_owned(),
        bytes: codes.len(),
        outside,
        codes_p50: quantile(&codes, 0.5).unwrap_or(0),
        codes_p99: quantile(&codes, 0.99).unwrap_or(0),
        rel_half_width_p50: quantile(&rel, 0.5).unwrap_or(0.0),
        rel_half_width_p99: quantile(&rel, 0.99).unwrap_or(0.0),
        worst: worst.map(|(_, w)| w),
    }
}

fn quantile<T: Copy>(sorted: &[T], q: f64) -> Option<T> {
    (!sorted.is_empty()).then(|| sorted[((sorted.len() - 1) as f64 * q).round() as usize])
}

impl PictureVerdict {
    /// No byte outside (alpha included: 255), and something judged.
    pub fn passed(&self) -> bool {
        self.outside == 0 && self.bytes > 0
    }

    /// One line for the terminal.
    pub fn line(&self) -> String {
        let head = format!(
            "{:<20} {} of {} bytes outside the envelope (width p50 {} / p99 {} codes; before the store rel ±{:.1e} / ±{:.1e})",
            self.name,
            self.outside,
            self.bytes,
            self.codes_p50,
            self.codes_p99,
            self.rel_half_width_p50,
            self.rel_half_width_p99
        );
        match self.worst {
            Some(w) => format!(
                "{head}; worst at ({}, {}) {}: {} not in {}..={} (exact {}) FAIL",
                w.pixel.0,
                w.pixel.1,
                ["R", "G", "B"][w.channel],
                w.got,
                w.allowed.lo,
                w.allowed.hi,
                w.exact
            ),
            None => format!("{head} ok"),
        }
    }

    /// The JSON summary's entry.
    pub fn to_json(&self) -> Value {
        json!({
            "name": self.name,
            "tolerance": "envelope",
            "passed": self.passed(),
            "bytes": self.bytes,
            "outside": self.outside,
            "ambiguous_share": 0.0,
            "codes_p50": self.codes_p50,
            "codes_p99": self.codes_p99,
            "rel_half_width_p50": self.rel_half_width_p50,
            "rel_half_width_p99": self.rel_half_width_p99,
            "worst": self.worst.map(|w| json!({
                "pixel": [w.pixel.0, w.pixel.1],
                "channel": w.channel,
                "got": w.got,
                "lo": w.allowed.lo,
                "hi": w.allowed.hi,
                "exact": w.exact,
            })),
        })
    }
}

/// The float texel furthest outside its interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorstTexel {
    /// Column and row (in a chain, of its atlas).
    pub texel: (u32, u32),
    /// 0 R, 1 G, 2 B, 3 A.
    pub channel: usize,
    /// The GPU's value.
    pub got: f32,
    /// The interval.
    pub allowed: Iv,
}

/// A float resource against its envelope.
#[derive(Clone, Debug, PartialEq)]
pub struct FloatVerdict {
    /// The resource.
    pub name: String,
    /// Values judged (R, G, B of every texel with an envelope).
    pub values: usize,
    /// Values outside.
    pub outside: usize,
    /// The envelope's relative half-width, median and 99th percentile.
    pub rel_half_width_p50: f64,
    /// See `rel_half_width_p50`.
    pub rel_half_width_p99: f64,
    /// The value furthest outside (relative to the interval's magnitude), if any.
    pub worst: Option<WorstTexel>,
}

/// Judges a GPU's float resource `gpu` (`width` wide) by `envelope` (per texel, its first `N`
/// channels; `None` where nothing is judged, e.g. a chain's padding).
///
/// # Panics
/// If the two differ in texel count.
pub fn judge_floats<const N: usize>(
    name: &str,
    envelope: &[Option<[Iv; N]>],
    gpu: &[[f32; 4]],
    width: u32,
) -> FloatVerdict {
    assert_eq!(envelope.len(), gpu.len(), "{name}: envelope and resource sizes differ");
    let (mut values, mut outside) = (0, 0);
    let mut worst: Option<(f64, WorstTexel)> = None;
    let mut rel = Vec::new();
    for (i, (e, g)) in envelope.iter().zip(gpu).enumerate() {
        let Some(e) = e else { continue };
        for c in 0..N {
            values += 1;
            rel.extend(e[c].rel_half_width());
            if e[c].contains(g[c]) {
                continue;
            }
            outside += 1;
            let v = f64::from(g[c]);
            let d = if v.is_nan() { f64::INFINITY } else { (e[c].lo - v).max(v - e[c].hi) };
            let d = d / e[c].magnitude().max(f64::MIN_POSITIVE);
            if worst.is_none_or(|(w, _)| d > w) {
                let w = width.max(1) as usize;
                let at = WorstTexel {
                    texel: ((i % w) as u32, (i / w) as u32),
                    channel: c,
                    got: g[c],
                    allowed: e[c],
                };
                worst = Some((d, at));
            }
        }
    }
    rel.sort_by(f64::total_cmp);
    FloatVerdict {
        name: name.to_owned(),
        values,
        outside,
        rel_half_width_p50: quantile(&rel, 0.5).unwrap_or(0.0),
        rel_half_width_p99: quantile(&rel, 0.99).unwrap_or(0.0),
        worst: worst.map(|(_, w)| w),
    }
}

impl FloatVerdict {
    /// No value outside (and something judged).
    pub fn passed(&self) -> bool {
        self.outside == 0 && self.values > 0
    }

    /// One line for the terminal.
    pub fn line(&self) -> String {
        let head = format!(
            "{:<20} {} of {} values outside the envelope (rel half-width p50 {:.1e} / p99 {:.1e})",
            self.name, self.outside, self.values, self.rel_half_width_p50, self.rel_half_width_p99
        );
        match self.worst {
            Some(w) => format!(
                "{head}; worst at ({}, {}) {}: {:e} not in [{:e}, {:e}] FAIL",
                w.texel.0,
                w.texel.1,
                ["R", "G", "B", "A"][w.channel],
                w.got,
                w.allowed.lo,
                w.allowed.hi
            ),
            None if self.values == 0 => format!("{head}: nothing judged FAIL"),
            None => format!("{head} ok"),
        }
    }

    /// The JSON summary's entry.
    pub fn to_json(&self) -> Value {
        json!({
            "name": self.name,
            "tolerance": "envelope",
            "passed": self.passed(),
            "values": self.values,
            "outside": self.outside,
            "ambiguous_share": 0.0,
            "rel_half_width_p50": self.rel_half_width_p50,
            "rel_half_width_p99": self.rel_half_width_p99,
            "worst": self.worst.map(|w| json!({
                "texel": [w.texel.0, w.texel.1],
                "channel": w.channel,
                "got": w.got,
                "lo": w.allowed.lo,
                "hi": w.allowed.hi,
            })),
        })
    }
}

/// A resource the envelope does not judge yet, with why, for the report and the JSON.
pub fn not_judged(id: ResourceId) -> (String, Value) {
    let pass = id.writer().map_or("", |p| p.name());
    let why = format!("pass {pass} has no envelope yet");
    let json = json!({"name": id.name(), "tolerance": "envelope", "judged": false, "why": why});
    (why, json)
}

/// The most of a screen resource that may be ambiguous (pixels whose coverage a conformant
/// rasteriser may change within its sub-pixel precision).
pub const MAX_AMBIGUOUS_SHARE: f64 = 0.02;

/// A screen resource judged on a region of its pixels (e.g. the sky's, where no geometry is
/// drawn): the pixels judged, the ambiguous ones beside them, the rest not judged.
#[derive(Clone, Debug, PartialEq)]
pub struct RegionVerdict {
    /// The values judged.
    pub inner: FloatVerdict,
    /// Pixels judged.
    pub judged: usize,
    /// Pixels counted apart as ambiguous.
    pub ambiguous: usize,
    /// All pixels of the resource.
    pub pixels: usize,
}

/// Judges `gpu` (`width` wide) by `envelope` where `region` is `Some(true)`; where it is
/// `Some(false)` (a pixel another conformant rasteriser may cover) the GPU's pixel is judged
/// when it lies inside, and otherwise counted as ambiguous; `None` leaves a pixel out.
///
/// # Panics
/// If the three differ in length.
pub fn judge_region<const N: usize>(
    name: &str,
    envelope: &[[Iv; N]],
    region: &[Option<bool>],
    gpu: &[[f32; 4]],
    width: u32,
) -> RegionVerdict {
    assert_eq!(envelope.len(), region.len(), "{name}: region and envelope sizes differ");
    assert_eq!(envelope.len(), gpu.len(), "{name}: envelope and resource sizes differ");
    let inside = |e: &[Iv; N], g: &[f32; 4]| (0..N).all(|c| e[c].contains(g[c]));
    let decided: Vec<Option<bool>> = region
        .iter()
        .zip(envelope.iter().zip(gpu))
        .map(|(r, (e, g))| match r {
            Some(false) if inside(e, g) => Some(true),
            r => *r,
        })
        .collect();
    let masked: Vec<Option<[Iv; N]>> =
        envelope.iter().zip(&decided).map(|(e, r)| (*r == Some(true)).then_some(*e)).collect();
    RegionVerdict {
        inner: judge_floats(name, &masked, gpu, width),
        judged: decided.iter().filter(|r| **r == Some(true)).count(),
        ambiguous: decided.iter().filter(|r| **r == Some(false)).count(),
        pixels: region.len(),
    }
}

impl RegionVerdict {
    /// The ambiguous pixels' share of the resource.
    pub fn ambiguous_share(&self) -> f64 {
        self.ambiguous as f64 / self.pixels.max(1) as f64
    }

    /// No value outside, something judged, and at most [`MAX_AMBIGUOUS_SHARE`] ambiguous.
    pub fn passed(&self) -> bool {
        self.inner.passed() && self.ambiguous_share() <= MAX_AMBIGUOUS_SHARE
    }

    /// One line for the terminal.
    pub fn line(&self) -> String {
        let share = format!(
            " on {} of {} pixels, {} ambiguous ({:.2} %, at most {} %)",
            self.judged,
            self.pixels,
            self.ambiguous,
            100.0 * self.ambiguous_share(),
            100.0 * MAX_AMBIGUOUS_SHARE
        );
        let mut l = self.inner.line();
        // The inner line ends in ok or FAIL: say where it was judged before that.
        if let Some(at) = l.find(" values outside the envelope") {
            l.insert_str(at + " values outside the envelope".len(), &share);
        }
        if self.inner.passed() && !self.passed() {
            l.push_str(" — too many ambiguous pixels FAIL");
        }
        l
    }

    /// The JSON summary's entry.
    pub fn to_json(&self) -> Value {
        let mut j = self.inner.to_json();
        j["passed"] = self.passed().into();
        j["pixels_judged"] = self.judged.into();
        j["pixels_ambiguous"] = self.ambiguous.into();
        j["ambiguous_share"] = self.ambiguous_share().into();
        j
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(lo: f64, hi: f64) -> Iv {
        Iv::new(lo, hi)
    }

    /// Values inside their intervals pass; one just past its interval fails and is the worst;
    /// a NaN fails; an envelope with nothing judged fails (nothing was checked).
    #[test]
    fn floats_inside_pass_and_one_outside_fails() {
        let env: Vec<Option<[Iv; 2]>> = (0..6)
            .map(|i| (i != 4).then(|| [iv(0.0, 1.0), iv(f64::from(i), f64::from(i) + 0.5)]))
            .collect();
        let mut gpu: Vec<[f32; 4]> = (0..6).map(|i| [0.5, i as f32 + 0.25, 9.0, 9.0]).collect();
        gpu[4] = [7.0; 4]; // not judged: anything
        let v = judge_floats("f", &env, &gpu, 3);
        assert!(v.passed() && v.values == 10, "{}", v.line());
        gpu[5][1] = 5.5f32.next_up();
        let v = judge_floats("f", &env, &gpu, 3);
        assert!(!v.passed() && v.outside == 1, "{}", v.line());
        let w = v.worst.unwrap();
        assert_eq!((w.texel, w.channel), ((2, 1), 1));
        gpu[5][1] = 5.25;
        gpu[0][0] = f32::NAN;
        assert!(!judge_floats("f", &env, &gpu, 3).passed());
        let none: Vec<Option<[Iv; 2]>> = vec![None; 6];
        assert!(!judge_floats("f", &none, &gpu, 3).passed());
    }

    /// A region: pixels outside it are not judged, ambiguous pixels inside their envelope count
    /// as judged, ambiguous ones outside it count against the 2 % share.
    #[test]
    fn a_region_judges_its_pixels_and_counts_the_ambiguous() {
        let n = 100;
        let env = vec![[iv(0.0, 1.0)]; n];
        let mut gpu = vec![[0.5f32, 0.0, 0.0, 0.0]; n];
        let mut region = vec![Some(true); n];
        region[0] = None;
        gpu[0][0] = 5.0; // outside, but not in the region
        assert!(judge_region("r", &env, &region, &gpu, 10).passed());
        gpu[1][0] = 1.5;
        assert!(!judge_region("r", &env, &region, &gpu, 10).passed());
        gpu[1][0] = 0.5;
        region[2] = Some(false);
        region[3] = Some(false);
        gpu[2][0] = 2.0;
        let v = judge_region("r", &env, &region, &gpu, 10);
        assert!(v.passed() && v.ambiguous == 1, "{}", v.line());
        for r in region.iter_mut().skip(10).take(3) {
            *r = Some(false);
        }
        for g in gpu.iter_mut().skip(10).take(3) {
            g[0] = 2.0;
        }
        let v = judge_region("r", &env, &region, &gpu, 10);
        assert!(!v.passed() && v.inner.passed() && v.ambiguous == 4, "{}", v.line());
    }

    /// A picture's bytes inside their ranges pass; a byte one code out fails, as does an alpha
    /// other than 255.
    #[test]
    fn picture_bytes_inside_pass_and_one_code_out_fails() {
        let range = ByteRange { lo: 10, hi: 12 };
        let env = vec![[(iv(0.04, 0.05), range); 3]; 4];
        let mut rgba = [11u8, 10, 12, 255].repeat(4);
        let exact = rgba.clone();
        assert!(judge_picture("ldr", &env, &rgba, &exact, 2).passed());
        rgba[6] = 13;
        let v = judge_picture("ldr", &env, &rgba, &exact, 2);
        assert!(!v.passed() && v.outside == 1);
        assert_eq!(v.worst.map(|w| (w.pixel, w.channel, w.got)), Some(((1, 0), 2, 13)));
        rgba[6] = 12;
        rgba[15] = 254;
        assert!(!judge_picture("ldr", &env, &rgba, &exact, 2).passed());
    }
}
