//! Sampler tests: against an independent f64 bilinear reference for every address mode and
//! coordinates far outside [0, 1]; nearest at texel boundaries; mirror-repeat against the
//! Vulkan specification's formula. Every comparator has a negative control.

use ocean_cpu::sampler::{
    AddressMode, FilterMode, Sampler, Texture2D, texture_sample, texture_sample_level,
};

const MODES: [AddressMode; 3] =
    [AddressMode::Repeat, AddressMode::ClampToEdge, AddressMode::MirrorRepeat];

/// SplitMix64, so the tests need no dependency.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as i64
    }
}

/// A texture of random texels in [−1, 1].
fn random_texture(rng: &mut Rng, width: u32, height: u32) -> Texture2D {
    let texels = (0..width * height)
        .map(|_| std::array::from_fn(|_| (2.0 * rng.unit() - 1.0) as f32))
        .collect();
    Texture2D::new(width, height, texels)
}

// ---------------------------------------------------------------------------------------------
// The reference, written from the Vulkan specification independently of the implementation:
// wrapping by the periodic pattern rather than by formula, weights as the four products.

fn ref_wrap(mode: AddressMode, i: i64, size: i64) -> i64 {
    match mode {
        AddressMode::Repeat => ((i % size) + size) % size,
        AddressMode::ClampToEdge => i.max(0).min(size - 1),
        // 0 1 … n−1 n−1 … 1 0 | 0 1 …: period 2n, the second half reversed.
        AddressMode::MirrorRepeat => {
            let p = ((i % (2 * size)) + 2 * size) % (2 * size);
            if p < size { p } else { 2 * size - 1 - p }
        }
    }
}

fn ref_texel(tex: &Texture2D, i: i64, j: i64) -> [f64; 4] {
    tex.texels[(j * i64::from(tex.width) + i) as usize].map(f64::from)
}

/// Bilinear filtering in f64 with full-precision weights, from the unnormalised texel-space
/// coordinates (u, v) = (s·W − ½, t·H − ½).
fn ref_bilinear(tex: &Texture2D, modes: [AddressMode; 2], u: f64, v: f64) -> [f64; 4] {
    let (i0, j0) = (u.floor(), v.floor());
    let (a, b) = (u - i0, v - j0);
    let (w, h) = (i64::from(tex.width), i64::from(tex.height));
    let (i0, j0) = (i0 as i64, j0 as i64);
    let i = [ref_wrap(modes[0], i0, w), ref_wrap(modes[0], i0 + 1, w)];
    let j = [ref_wrap(modes[1], j0, h), ref_wrap(modes[1], j0 + 1, h)];
    let terms = [
        ((1.0 - a) * (1.0 - b), ref_texel(tex, i[0], j[0])),
        (a * (1.0 - b), ref_texel(tex, i[1], j[0])),
        ((1.0 - a) * b, ref_texel(tex, i[0], j[1])),
        (a * b, ref_texel(tex, i[1], j[1])),
    ];
    std::array::from_fn(|c| terms.iter().map(|(wt, t)| wt * t[c]).sum())
}

/// The comparator: largest per-channel |sampled − reference|.
fn max_abs_diff(a: [f32; 4], b: [f64; 4]) -> f64 {
    (0..4).map(|c| (f64::from(a[c]) - b[c]).abs()).fold(0.0, f64::max)
}

/// Bound for texels in [−1, 1] when the texel-space coordinate is exact in f32: the weights are
/// then exact, and the three lerps `a + w·(b − a)` round at most 3 times each on values ≤ 2,
/// ≲ 10 ulp of 1 in all; 16 ulp (9.5e-7) leaves margin.
const LINEAR_BOUND: f64 = 16.0 / (1u64 << 24) as f64;

#[test]
fn linear_matches_the_f64_reference_far_outside_the_unit_square() {
    let mut rng = Rng(11);
    let mut worst = 0.0f64;
    let mut worst_shifted = 0.0f64;
    for (w, h) in [(8, 8), (5, 3), (7, 4), (1, 1), (2, 9), (16, 1)] {
        let tex = random_texture(&mut rng, w, h);
        for mu in MODES {
            for mv in MODES {
                let sampler =
                    Sampler { address_mode_u: mu, address_mode_v: mv, filter: FilterMode::Linear };
                for _ in 0..2000 {
                    // s, t on a 1/4096 grid in [−100, 100]: s·W − ½ is exact in f32 (< 2^24
                    // units of 2^−12), so the reference sees the same texel-space coordinate.
                    let s = rng.int(-409_600, 409_600) as f64 / 4096.0;
                    let t = rng.int(-409_600, 409_600) as f64 / 4096.0;
                    let got = texture_sample(&tex, &sampler, [s as f32, t as f32]);
                    let (u, v) = (s * f64::from(w) - 0.5, t * f64::from(h) - 0.5);
                    worst = worst.max(max_abs_diff(got, ref_bilinear(&tex, [mu, mv], u, v)));
                    // Negative control: a reference that forgets the half-texel shift.
                    let shifted = ref_bilinear(&tex, [mu, mv], u + 0.5, v + 0.5);
                    worst_shifted = worst_shifted.max(max_abs_diff(got, shifted));
                }
            }
        }
    }
    println!("linear: worst |error| = {worst:.3e} (bound {LINEAR_BOUND:.3e})");
    assert!(worst <= LINEAR_BOUND, "{worst}");
    assert!(worst_shifted > 100.0 * LINEAR_BOUND, "{worst_shifted}");
}

#[test]
fn linear_with_arbitrary_f32_coordinates() {
    // Arbitrary f32 coordinates up to ±1e4 (|u| up to 1e5): the texel-space coordinate is
    // formed in f32 (as the GPU forms it), so the reference starts from the same f32 u, v;
    // the comparison is then exact-weight against f32 lerps, as above.
    let mut rng = Rng(12);
    let tex = random_texture(&mut rng, 13, 6);
    let mut worst = 0.0f64;
    for mu in MODES {
        for mv in MODES {
            let sampler =
                Sampler { address_mode_u: mu, address_mode_v: mv, filter: FilterMode::Linear };
            for k in 0..3000 {
                let scale = [1.0, 10.0, 1e4][k % 3];
                let s = ((2.0 * rng.unit() - 1.0) * scale) as f32;
                let t = ((2.0 * rng.unit() - 1.0) * scale) as f32;
                let got = texture_sample(&tex, &sampler, [s, t]);
                let u = f64::from(s * 13.0 - 0.5);
                let v = f64::from(t * 6.0 - 0.5);
                let expected = ref_bilinear(&tex, [mu, mv], u, v);
                // u − floor(u) is exact in f32 for |u| ≥ 1 but may round for |u| < 1 (by
                // ≤ 2^−25), which moves the result by ≤ 2^−25 · |t1 − t0| ≤ 2^−24.
                worst = worst.max(max_abs_diff(got, expected));
            }
        }
    }
    println!("linear, f32 coordinates: worst |error| = {worst:.3e}");
    assert!(worst <= LINEAR_BOUND + 1.0 / (1u64 << 24) as f64, "{worst}");
}

#[test]
fn linear_at_texel_centres_returns_the_texel_exactly() {
    let mut rng = Rng(13);
    let tex = random_texture(&mut rng, 8, 4);
    for mode in MODES {
        let sampler =
            Sampler { address_mode_u: mode, address_mode_v: mode, filter: FilterMode::Linear };
        for j in 0..4 {
            for i in 0..8 {
                let st = [(i as f32 + 0.5) / 8.0, (j as f32 + 0.5) / 4.0];
                assert_eq!(texture_sample(&tex, &sampler, st), tex.texel(i, j));
                assert_eq!(texture_sample_level(&tex, &sampler, st, 0.0), tex.texel(i, j));
            }
        }
    }
}

#[test]
fn nearest_at_texel_boundaries() {
    // Texel i holds the value i, so a sample tells which texel it read. W = 8 and s = i/8
    // exactly: s·W = i is exact, the boundary belongs to texel i, the float just below it to
    // texel i − 1.
    let tex = Texture2D::new(8, 1, (0..8).map(|i| [i as f32, 0.0, 0.0, 1.0]).collect());
    for mode in MODES {
        let sampler = Sampler {
            address_mode_u: mode,
            address_mode_v: AddressMode::ClampToEdge,
            filter: FilterMode::Nearest,
        };
        let read = |s: f32| texture_sample(&tex, &sampler, [s, 0.5])[0] as i64;
        for i in -40i64..40 {
            let s = i as f32 / 8.0;
            let below = f32::from_bits(if s > 0.0 {
                s.to_bits() - 1
            } else if s == 0.0 {
                (-f32::from_bits(1)).to_bits()
            } else {
                s.to_bits() + 1
            });
            assert!(below < s);
            assert_eq!(read(s), ref_wrap(mode, i, 8), "{mode:?} s = {s}");
            assert_eq!(read(below), ref_wrap(mode, i - 1, 8), "{mode:?} below {s}");
        }
        // Negative control for the comparison: texel i and texel i − 1 differ somewhere.
        assert!((-40..40).any(|i| ref_wrap(mode, i, 8) != ref_wrap(mode, i - 1, 8)));
    }
}

#[test]
fn nearest_matches_the_reference_on_a_grid() {
    let mut rng = Rng(14);
    let tex = random_texture(&mut rng, 5, 7);
    for mu in MODES {
        for mv in MODES {
            let sampler =
                Sampler { address_mode_u: mu, address_mode_v: mv, filter: FilterMode::Nearest };
            for _ in 0..3000 {
                let s = rng.int(-409_600, 409_600) as f64 / 4096.0;
                let t = rng.int(-409_600, 409_600) as f64 / 4096.0;
                let i = ref_wrap(mu, (s * 5.0).floor() as i64, 5);
                let j = ref_wrap(mv, (t * 7.0).floor() as i64, 7);
                let got = texture_sample(&tex, &sampler, [s as f32, t as f32]);
                assert_eq!(got.map(f64::from), ref_texel(&tex, i, j), "{mu:?} {mv:?} {s} {t}");
            }
        }
    }
}

/// `VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT`, transcribed from the Vulkan specification
/// ("Wrapping Operation"): `(size − 1) − mirror((i mod (2 × size)) − size)` with
/// `mirror(a) = a if a ≥ 0, −(1 + a) otherwise` and `mod` the floored remainder.
fn vulkan_spec_mirrored_repeat(i: i64, size: i64) -> i64 {
    let modulo = |a: i64, b: i64| a - b * (a as f64 / b as f64).floor() as i64;
    let mirror = |a: i64| if a >= 0 { a } else { -(1 + a) };
    (size - 1) - mirror(modulo(i, 2 * size) - size)
}

#[test]
fn mirror_repeat_follows_the_vulkan_formula() {
    for size in 1..=7u32 {
        let n = i64::from(size);
        for i in -50..50 {
            let spec = vulkan_spec_mirrored_repeat(i, n);
            assert_eq!(ref_wrap(AddressMode::MirrorRepeat, i, n), spec, "pattern, {i} {size}");
            assert_eq!(i64::from(AddressMode::MirrorRepeat.apply(i, size)), spec);
        }
        // Negative control: mirror repeat is not repeat (for size > 1).
        if size > 1 {
            assert!((-50..50).any(|i| vulkan_spec_mirrored_repeat(i, n)
                != i64::from(AddressMode::Repeat.apply(i, size))));
        }
    }
    // Through the sampler, on texel centres: −1.5 texels reads texel 1 mirrored to 1, …
    let tex = Texture2D::new(4, 1, (0..4).map(|i| [i as f32, 0.0, 0.0, 1.0]).collect());
    let sampler = Sampler {
        address_mode_u: AddressMode::MirrorRepeat,
        address_mode_v: AddressMode::Repeat,
        filter: FilterMode::Nearest,
    };
    let read: Vec<i64> = (-8..12)
        .map(|i| texture_sample(&tex, &sampler, [(i as f32 + 0.5) / 4.0, 0.5])[0] as i64)
        .collect();
    let expected: Vec<i64> = (-8..12).map(|i| vulkan_spec_mirrored_repeat(i, 4)).collect();
    assert_eq!(read, expected);
    assert_eq!(expected, [0, 1, 2, 3, 3, 2, 1, 0, 0, 1, 2, 3, 3, 2, 1, 0, 0, 1, 2, 3]);
}

#[test]
fn repeat_and_clamp_follow_the_vulkan_formula() {
    for size in 1..=7u32 {
        let n = i64::from(size);
        for i in -50..50 {
            assert_eq!(i64::from(AddressMode::Repeat.apply(i, size)), i.rem_euclid(n));
            assert_eq!(i64::from(AddressMode::ClampToEdge.apply(i, size)), i.clamp(0, n - 1));
        }
    }
}

#[test]
fn non_finite_and_huge_coordinates_do_not_panic() {
    let mut rng = Rng(15);
    let tex = random_texture(&mut rng, 3, 5);
    for filter in [FilterMode::Nearest, FilterMode::Linear] {
        for mode in MODES {
            let sampler = Sampler { address_mode_u: mode, address_mode_v: mode, filter };
            for s in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 1e30, -1e30, f32::MAX, 3e9] {
                let c = texture_sample(&tex, &sampler, [s, 0.3]);
                // Finite whenever s·W is (f32::MAX · 3 overflows to infinity, and ∞ − ∞ in
                // the weights is NaN, as on a GPU).
                if (s * 3.0).is_finite() {
                    assert!(c.iter().all(|v| v.is_finite()), "{s}: {c:?}");
                }
            }
        }
    }
}
