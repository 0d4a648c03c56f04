//! The comparators of docs/design.md's tolerance table, each with a negative control in the tests:
//! - [`compare_float`] for float buffers (wave maps, Fresnel tables, shadow, reflection and
//!   refraction maps, the HDR frame): a value passes when |gpu − cpu| ≤ max([`FLOAT_ABS`],
//!   [`FLOAT_REL`]·|cpu|), computed in f64; reports max abs/rel error and where. A buffer in
//!   `rgba16float` ([`compare_float_in`]) also allows one binary16 step at the CPU's value
//!   (`ocean_core::frame_format`: two f32 values within the tolerance can store a step
//!   apart).
//! - [`compare_image`] for the 8-bit output: the share of pixels whose R, G and B each lie
//!   within 1/255, a per-channel difference histogram, and FLIP mean and P99 (NVIDIA's ꟻLIP,
//!   `nv-flip`, CPU image as the reference, 67 pixels per degree), against [`ImageLimits`].

use ocean_core::frame_format::FrameFormat;
use ocean_gpu::AdapterReport;
use serde_json::{Value, json};

/// Relative limit for CPU vs GPU float buffers (docs/design.md: "lavapipe matches CPU f32 to a
/// few ULP (measured)").
pub const FLOAT_REL: f64 = 1e-5;
/// Absolute limit for CPU vs GPU float buffers (docs/design.md, same row), for values near 0.
pub const FLOAT_ABS: f64 = 1e-6;

/// Limits of the final 8-bit image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageLimits {
    /// Least share of pixels whose channels all lie within 1/255, if the row has one.
    pub min_within_1: Option<f64>,
    /// Largest FLIP mean.
    pub max_flip_mean: f32,
    /// Largest FLIP 99th percentile, if the row has one.
    pub max_flip_p99: Option<f32>,
    /// Where the numbers come from.
    pub origin: &'static str,
}

impl ImageLimits {
    /// docs/design.md, "CPU vs GPU final image (lavapipe)": same raster rules, transcendental ULP
    /// differences.
    pub const SOFTWARE: Self = Self {
        min_within_1: Some(0.995),
        max_flip_mean: 0.005,
        max_flip_p99: None,
        origin: "docs/design.md tolerance table, CPU vs GPU final image (lavapipe)",
    };
    /// docs/design.md, "CPU vs GPU final image (hardware GPU)": real GPUs fuse and approximate
    /// more.
    pub const HARDWARE: Self = Self {
        min_within_1: None,
        max_flip_mean: 0.02,
        max_flip_p99: Some(0.1),
        origin: "docs/design.md tolerance table, CPU vs GPU final image (hardware GPU)",
    };

    /// The row for an adapter: the software row for a CPU rasterizer (lavapipe), else the
    /// hardware row.
    pub fn for_adapter(adapter: &AdapterReport) -> Self {
        if adapter.is_software { Self::SOFTWARE } else { Self::HARDWARE }
    }
}

/// One float value: where it is and both sides.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Texel {
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// Channel 0–3 (RGBA).
    pub channel: usize,
    /// The CPU's value.
    pub cpu: f32,
    /// The GPU's value.
    pub gpu: f32,
}

impl Texel {
    fn to_json(self) -> Value {
        json!({"x": self.x, "y": self.y, "channel": self.channel,
               "cpu": self.cpu, "gpu": self.gpu})
    }
}

/// The comparison of one float buffer.
#[derive(Clone, Debug, PartialEq)]
pub struct FloatStats {
    /// The buffer's name.
    pub name: String,
    /// Whether its pass ran (a skipped pass leaves a 1×1 zero map on both sides).
    pub ran: bool,
    /// CPU size.
    pub cpu_size: (u32, u32),
    /// GPU size.
    pub gpu_size: (u32, u32),
    /// The size the frame plan gives the resource, when the comparison is of a frame: both
    /// back ends must have allocated exactly that.
    pub plan_size: Option<(u32, u32)>,
    /// Largest |gpu − cpu| and where.
    pub max_abs: f64,
    /// Its location.
    pub max_abs_at: Option<Texel>,
    /// Largest |gpu − cpu| / |cpu| over values with cpu ≠ 0, and where.
    pub max_rel: f64,
    /// Its location.
    pub max_rel_at: Option<Texel>,
    /// Values beyond the limit (a NaN on one side only counts).
    pub beyond: usize,
    /// The value furthest beyond, relative to its allowance.
    pub worst: Option<Texel>,
    /// Values compared.
    pub values: usize,
    /// The buffers' format: `rgba16float` allows one binary16 step besides the tolerance.
    pub format: FrameFormat,
}

impl FloatStats {
    /// Whether the buffer is within the limits (and the sizes agree).
    pub fn passed(&self) -> bool {
        self.sizes_agree() && self.beyond == 0
    }

    /// Whether the CPU, the GPU and (when given) the plan agree on the size.
    pub fn sizes_agree(&self) -> bool {
        self.cpu_size == self.gpu_size && self.plan_size.is_none_or(|p| p == self.cpu_size)
    }

    /// A one-line summary.
    pub fn line(&self) -> String {
        let at = |t: &Option<Texel>| {
            t.map_or(String::new(), |t| {
                format!(" at ({}, {}).{} cpu {:e} gpu {:e}", t.x, t.y, t.channel, t.cpu, t.gpu)
            })
        };
        if !self.sizes_agree() {
            return format!(
                "{:<20} FAIL size cpu {:?} gpu {:?} plan {:?}",
                self.name, self.cpu_size, self.gpu_size, self.plan_size
            );
        }
        format!(
            "{:<20} {} {}x{}{}{} max abs {:.3e}{}; max rel {:.3e}{}; beyond limit {} of {}",
            self.name,
            if self.passed() { "ok  " } else { "FAIL" },
            self.cpu_size.0,
            self.cpu_size.1,
            if self.ran { "" } else { " (skipped)" },
            match self.format {
                FrameFormat::Rgba32Float => "",
                FrameFormat::Rgba16Float => " f16 (+1 step)",
            },
            self.max_abs,
            at(&self.max_abs_at),
            self.max_rel,
            at(&self.max_rel_at),
            self.beyond,
            self.values
        )
    }

    /// The comparison as JSON.
    pub fn to_json(&self) -> Value {
        json!({
            "name": self.name, "ran": self.ran, "passed": self.passed(),
            "cpu_size": [self.cpu_size.0, self.cpu_size.1],
            "gpu_size": [self.gpu_size.0, self.gpu_size.1],
            "plan_size": self.plan_size.map(|p| [p.0, p.1]),
            "max_abs": self.max_abs, "max_abs_at": self.max_abs_at.map(Texel::to_json),
            "max_rel": self.max_rel, "max_rel_at": self.max_rel_at.map(Texel::to_json),
            "beyond_limit": self.beyond, "worst": self.worst.map(Texel::to_json),
            "values": self.values,
            "format": self.format.name(),
            "limit": {"rel": FLOAT_REL, "abs": FLOAT_ABS,
                      "half_steps": if self.format == FrameFormat::Rgba16Float { 1 } else { 0 },
                      "origin": "docs/design.md tolerance table, CPU vs GPU float buffers; one \
                                 binary16 step on rgba16float buffers (ocean_core::frame_format)"},
        })
    }
}

/// The allowance of a CPU value: max(abs, rel·|cpu|).
pub fn allowance(cpu: f32) -> f64 {
    FLOAT_ABS.max(FLOAT_REL * f64::from(cpu).abs())
}

/// The allowance of a CPU value stored in `format`: [`allowance`], or one binary16 step at
/// the value where that is more (`rgba16float`).
pub fn allowance_in(cpu: f32, format: FrameFormat) -> f64 {
    allowance(cpu).max(f64::from(format.step(cpu)))
}

/// Compares two RGBA f32 buffers of `size` texels each (row-major).
pub fn compare_float(
    name: &str,
    ran: bool,
    cpu: ((u32, u32), &[[f32; 4]]),
    gpu: ((u32, u32), &[[f32; 4]]),
) -> FloatStats {
    compare_float_in(name, ran, cpu, gpu, FrameFormat::Rgba32Float)
}

/// [`compare_float`] of two buffers of `format` ([`allowance_in`]).
pub fn compare_float_in(
    name: &str,
    ran: bool,
    cpu: ((u32, u32), &[[f32; 4]]),
    gpu: ((u32, u32), &[[f32; 4]]),
    format: FrameFormat,
) -> FloatStats {
    let mut s = FloatStats {
        name: name.to_owned(),
        ran,
        cpu_size: cpu.0,
        gpu_size: gpu.0,
        plan_size: None,
        max_abs: 0.0,
        max_abs_at: None,
        max_rel: 0.0,
        max_rel_at: None,
        beyond: 0,
        worst: None,
        values: 0,
        format,
    };
    if cpu.0 != gpu.0 || cpu.1.len() != gpu.1.len() {
        s.beyond = 1;
        return s;
    }
    let width = cpu.0.0.max(1);
    let mut worst_ratio = 1.0;
    for (i, (c, g)) in cpu.1.iter().zip(gpu.1).enumerate() {
        for ch in 0..4 {
            s.values += 1;
            let (a, b) = (c[ch], g[ch]);
            let texel =
                Texel { x: i as u32 % width, y: i as u32 / width, channel: ch, cpu: a, gpu: b };
            if a.is_nan() || b.is_nan() {
                if a.is_nan() != b.is_nan() {
                    s.beyond += 1;
                    s.worst = Some(texel);
                    worst_ratio = f64::INFINITY;
                }
                continue;
            }
            if a == b {
                continue; // equal values, infinities included
            }
            let err = (f64::from(b) - f64::from(a)).abs();
            if err > s.max_abs {
                s.max_abs = err;
                s.max_abs_at = Some(texel);
            }
            if a != 0.0 {
                let rel = err / f64::from(a).abs();
                if rel > s.max_rel {
                    s.max_rel = rel;
                    s.max_rel_at = Some(texel);
                }
            }
            let ratio = err / allowance_in(a, format);
            if ratio > 1.0 {
                s.beyond += 1;
                if ratio > worst_ratio {
                    worst_ratio = ratio;
                    s.worst = Some(texel);
                }
            }
        }
    }
    s
}

/// Buckets of the per-channel difference histogram: |Δ| = 0, 1, 2, 3–4, 5–8, 9–16, 17–32,
/// 33–64, 65–255 (in 1/255 steps).
pub const HISTOGRAM_BUCKETS: [(u8, u8); 9] =
    [(0, 0), (1, 1), (2, 2), (3, 4), (5, 8), (9, 16), (17, 32), (33, 64), (65, 255)];

/// The comparison of two 8-bit RGBA pictures.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageStats {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Share of pixels whose R, G and B each differ by at most 1/255.
    pub within_1: f64,
    /// Largest per-channel difference, in 1/255.
    pub max_diff: u8,
    /// Counts of per-channel differences in [`HISTOGRAM_BUCKETS`] (R, G and B of every pixel).
    pub histogram: [u64; 9],
    /// FLIP mean.
    pub flip_mean: f32,
    /// FLIP 99th percentile.
    pub flip_p99: f32,
    /// The per-pixel FLIP error, row-major.
    pub flip_map: Vec<f32>,
}

impl ImageStats {
    /// What fails the limits, empty when it passes.
    pub fn failures(&self, limits: &ImageLimits) -> Vec<String> {
        let mut f = Vec::new();
        if let Some(min) = limits.min_within_1
            && self.within_1 < min
        {
            f.push(format!(
                "{:.3} % of pixels within 1/255 < {:.1} %",
                100.0 * self.within_1,
                100.0 * min
            ));
        }
        if self.flip_mean > limits.max_flip_mean {
            f.push(format!("FLIP mean {:.5} > {}", self.flip_mean, limits.max_flip_mean));
        }
        if let Some(max) = limits.max_flip_p99
            && self.flip_p99 > max
        {
            f.push(format!("FLIP P99 {:.5} > {max}", self.flip_p99));
        }
        f
    }

    /// A one-line summary.
    pub fn line(&self, limits: &ImageLimits) -> String {
        let fails = self.failures(limits);
        format!(
            "{:<20} {} {}x{} within 1/255 {:.3} %, max diff {}/255, FLIP mean {:.5} P99 {:.5}; \
             |Δ| histogram {:?}{}",
            "ldr",
            if fails.is_empty() { "ok  " } else { "FAIL" },
            self.width,
            self.height,
            100.0 * self.within_1,
            self.max_diff,
            self.flip_mean,
            self.flip_p99,
            self.histogram,
            if fails.is_empty() { String::new() } else { format!(" ({})", fails.join("; ")) }
        )
    }

    /// The comparison as JSON.
    pub fn to_json(&self, limits: &ImageLimits) -> Value {
        json!({
            "width": self.width, "height": self.height,
            "passed": self.failures(limits).is_empty(),
            "within_1_of_255": self.within_1, "max_diff": self.max_diff,
            "histogram": HISTOGRAM_BUCKETS.iter().zip(self.histogram)
                .map(|((lo, hi), n)| json!({"from": lo, "to": hi, "count": n}))
                .collect::<Vec<_>>(),
            "flip_mean": self.flip_mean, "flip_p99": self.flip_p99,
            "limits": {"min_within_1_of_255": limits.min_within_1,
                       "max_flip_mean": limits.max_flip_mean,
                       "max_flip_p99": limits.max_flip_p99, "origin": limits.origin},
        })
    }
}

fn rgb(rgba: &[u8]) -> Vec<u8> {
    rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect()
}

/// Compares the GPU's 8-bit RGBA picture with the CPU's (the reference).
///
/// # Panics
/// If either buffer does not hold `width · height` RGBA pixels.
pub fn compare_image(cpu: &[u8], gpu: &[u8], width: u32, height: u32) -> ImageStats {
    let n = width as usize * height as usize;
    assert!(cpu.len() == 4 * n && gpu.len() == 4 * n, "pictures must be {width}x{height} RGBA");
    let mut histogram = [0u64; 9];
    let mut within = 0usize;
    let mut max_diff = 0u8;
    for (c, g) in cpu.chunks_exact(4).zip(gpu.chunks_exact(4)) {
        let mut pixel_ok = true;
        for ch in 0..3 {
            let d = c[ch].abs_diff(g[ch]);
            max_diff = max_diff.max(d);
            pixel_ok &= d <= 1;
            if let Some(b) = HISTOGRAM_BUCKETS.iter().position(|(lo, hi)| (*lo..=*hi).contains(&d))
            {
                histogram[b] += 1;
            }
        }
        within += usize::from(pixel_ok);
    }
    let reference = nv_flip::FlipImageRgb8::with_data(width, height, &rgb(cpu));
    let test = nv_flip::FlipImageRgb8::with_data(width, height, &rgb(gpu));
    let error = nv_flip::flip(reference, test, nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let mut pool = nv_flip::FlipPool::from_image(&error);
    ImageStats {
        width,
        height,
        within_1: within as f64 / n.max(1) as f64,
        max_diff,
        histogram,
        flip_mean: pool.mean(),
        flip_p99: pool.get_percentile(0.99, false),
        flip_map: error.to_vec(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn buffer(n: usize, seed: u32) -> Vec<[f32; 4]> {
        (0..n)
            .map(|i| {
                let x = (i as f32 + 1.0) * 0.37 + seed as f32;
                [x.sin(), x.cos() * 1e3, 1e-8 * x, 0.5 + 0.25 * x.sin()]
            })
            .collect()
    }

    /// A buffer against itself and against values moved within the allowance passes; one value
    /// moved just past it fails, and is named as the worst (the negative control).
    #[test]
    fn float_values_within_the_allowance_pass_and_one_past_it_fails() {
        let cpu = buffer(64, 0);
        assert!(compare_float("x", true, ((8, 8), &cpu), ((8, 8), &cpu)).passed());
        let near: Vec<[f32; 4]> =
            cpu.iter().map(|t| t.map(|v| (f64::from(v) + 0.9 * allowance(v)) as f32)).collect();
        let s = compare_float("x", true, ((8, 8), &cpu), ((8, 8), &near));
        assert!(s.passed() && s.max_abs > 0.0, "{}", s.line());
        let mut far = cpu.clone();
        far[19][1] = (f64::from(cpu[19][1]) + 1.5 * allowance(cpu[19][1])) as f32;
        let s = compare_float("x", true, ((8, 8), &cpu), ((8, 8), &far));
        assert!(!s.passed() && s.beyond == 1, "{}", s.line());
        let w = s.worst.unwrap();
        assert_eq!((w.x, w.y, w.channel), (3, 2, 1));
    }

    /// Near 0 the absolute floor holds: 1e-7 apart passes, 1e-5 apart fails.
    #[test]
    fn near_zero_the_absolute_floor_decides() {
        let cpu = vec![[0.0f32; 4]; 4];
        let mut gpu = cpu.clone();
        gpu[2][0] = 1e-7;
        assert!(compare_float("z", true, ((2, 2), &cpu), ((2, 2), &gpu)).passed());
        gpu[2][0] = 1e-5;
        assert!(!compare_float("z", true, ((2, 2), &cpu), ((2, 2), &gpu)).passed());
    }

    /// A NaN on one side only fails; on both sides it is equal; different sizes fail.
    #[test]
    fn a_nan_on_one_side_and_different_sizes_fail() {
        let cpu = buffer(4, 1);
        let mut gpu = cpu.clone();
        gpu[0][3] = f32::NAN;
        assert!(!compare_float("n", true, ((2, 2), &cpu), ((2, 2), &gpu)).passed());
        let both = gpu.clone();
        assert!(compare_float("n", true, ((2, 2), &both), ((2, 2), &gpu)).passed());
        assert!(!compare_float("n", true, ((2, 2), &cpu), ((4, 1), &cpu)).passed());
    }

    /// `rgba16float` allows one binary16 step at the value; two steps fail.
    #[test]
    fn a_half_float_buffer_allows_one_step() {
        let cpu = vec![[1.0f32; 4]; 1];
        let step = FrameFormat::Rgba16Float.step(1.0);
        let one = vec![[1.0 + step, 1.0, 1.0, 1.0]];
        let two = vec![[1.0 + 2.0 * step, 1.0, 1.0, 1.0]];
        let f = FrameFormat::Rgba16Float;
        assert!(compare_float_in("h", true, ((1, 1), &cpu), ((1, 1), &one), f).passed());
        assert!(!compare_float_in("h", true, ((1, 1), &cpu), ((1, 1), &two), f).passed());
        assert!(!compare_float("h", true, ((1, 1), &cpu), ((1, 1), &one)).passed());
    }

    fn picture(w: u32, h: u32) -> Vec<u8> {
        (0..w * h)
            .flat_map(|i| {
                let (x, y) = (i % w, i / w);
                [(x * 7 % 256) as u8, (y * 5 % 256) as u8, ((x + y) * 3 % 256) as u8, 255]
            })
            .collect()
    }

    /// A picture against itself passes both rows; one channel off by 1 everywhere still
    /// passes the software row; a block of wrong colour fails it, and a grey wash fails the
    /// hardware row too (the negative controls).
    #[test]
    fn pictures_pass_within_one_code_and_fail_with_a_visible_error() {
        let (w, h) = (48, 32);
        let cpu = picture(w, h);
        let same = compare_image(&cpu, &cpu, w, h);
        assert!(same.failures(&ImageLimits::SOFTWARE).is_empty());
        assert!(same.failures(&ImageLimits::HARDWARE).is_empty());
        assert_eq!((same.max_diff, same.within_1), (0, 1.0));
        let off: Vec<u8> =
            cpu.iter().enumerate().map(|(i, &b)| if i % 4 == 1 { b ^ 1 } else { b }).collect();
        let s = compare_image(&cpu, &off, w, h);
        assert!(
            s.failures(&ImageLimits::SOFTWARE).is_empty(),
            "{}",
            s.line(&ImageLimits::SOFTWARE)
        );
        assert_eq!((s.max_diff, s.histogram[1]), (1, u64::from(w * h)));
        let mut block = cpu.clone();
        for y in 0..8 {
            for x in 0..8 {
                let i = 4 * (y * w + x) as usize;
                block[i..i + 3].copy_from_slice(&[255, 0, 255]);
            }
        }
        let s = compare_image(&cpu, &block, w, h);
        assert!(!s.failures(&ImageLimits::SOFTWARE).is_empty());
        let grey: Vec<u8> =
            cpu.iter().enumerate().map(|(i, &b)| if i % 4 == 3 { b } else { b / 2 + 64 }).collect();
        let s = compare_image(&cpu, &grey, w, h);
        assert!(
            !s.failures(&ImageLimits::HARDWARE).is_empty(),
            "{}",
            s.line(&ImageLimits::HARDWARE)
        );
    }
}
