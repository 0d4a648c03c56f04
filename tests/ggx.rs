//! The GGX BRDF of shading technique `ggx` (`ocean_core::ggx`): D is a distribution of normals,
//! Smith's G1 satisfies the visible-normal identity (Heitz 2014, eq. 18) that Schlick's fit only
//! approximates, the white furnace (F = 1) never returns more than comes in and agrees between
//! two parametrisations of the integral, and the BRDF is reciprocal.

use std::f64::consts::{FRAC_PI_2, PI};

use ocean_core::ggx::{
    FresnelTerm, GeometryTerm, cook_torrance, ggx_d, schlick_ggx_g1, smith_g1, smith_g2,
    smith_lambda,
};
use ocean_core::rng::SplitMix64;

const N: [f64; 3] = [0.0, 1.0, 0.0];

/// A unit vector at polar angle θ from +y and azimuth φ.
fn dir(theta: f64, phi: f64) -> [f64; 3] {
    [theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// ∫ over the hemisphere of g(ω) dω by the midpoint rule in (s, φ) with cos θ = 1 − s²
/// (points gathered towards the pole, where a narrow lobe lives).
fn hemisphere(ns: usize, nphi: usize, g: impl Fn([f64; 3]) -> f64) -> f64 {
    let mut sum = 0.0;
    for i in 0..ns {
        let s = (i as f64 + 0.5) / ns as f64;
        let mu = 1.0 - s * s;
        // dω = dμ dφ, dμ = 2 s ds.
        let w = 2.0 * s / ns as f64 * (2.0 * PI / nphi as f64);
        let sin = (1.0 - mu * mu).max(0.0).sqrt();
        for j in 0..nphi {
            let phi = (j as f64 + 0.5) / nphi as f64 * 2.0 * PI;
            sum += w * g([sin * phi.cos(), mu, sin * phi.sin()]);
        }
    }
    sum
}

#[test]
fn d_integrates_to_one_over_the_projected_hemisphere() {
    for alpha in [0.01, 0.05, 0.2, 0.5, 1.0] {
        // Isotropic: 2π ∫ D(μ) μ dμ, μ = 1 − s², 10⁶ midpoints.
        let n = 1_000_000;
        let integral: f64 = (0..n)
            .map(|i| {
                let s = (i as f64 + 0.5) / n as f64;
                let mu = 1.0 - s * s;
                2.0 * PI * ggx_d(mu, alpha) * mu * 2.0 * s / n as f64
            })
            .sum();
        println!("α = {alpha}: ∫ D cos θ dω = {integral:.8}");
        assert!((integral - 1.0).abs() < 1e-6, "α {alpha}: {integral}");
        // Negative control: the denominator not squared (a common slip) is not normalised.
        if alpha < 1.0 {
            let slip = unsquared(alpha);
            assert!((slip - 1.0).abs() > 1e-2, "α {alpha}: {slip}");
        }
    }
}

/// ∫ D' cos with D' = α²/(π(μ²(α² − 1) + 1)), the denominator left unsquared.
fn unsquared(alpha: f64) -> f64 {
    let n = 1_000_000;
    let a2 = alpha * alpha;
    (0..n)
        .map(|i| {
            let s = (i as f64 + 0.5) / n as f64;
            let mu = 1.0 - s * s;
            let t = mu * mu * (a2 - 1.0) + 1.0;
            2.0 * PI * a2 / (PI * t) * mu * 2.0 * s / n as f64
        })
        .sum()
}

#[test]
fn smiths_g1_projects_the_visible_normals_onto_the_macrosurface() {
    // Heitz 2014, eq. 18: ∫ G1(o, m) ⟨o·m⟩ D(m) dm = cos θ_o, with Smith's G1 = 1/(1 + Λ(o)).
    let mut worst_exact: f64 = 0.0;
    let mut worst_schlick: f64 = 0.0;
    for alpha in [0.1, 0.3, 0.6, 1.0] {
        for theta_deg in [0.0, 30.0, 60.0, 75.0, 85.0f64] {
            let o = dir(theta_deg.to_radians(), 0.3);
            let visible = hemisphere(3000, 1024, |m| dot(o, m).max(0.0) * ggx_d(m[1], alpha));
            let cos_o = o[1];
            let exact = smith_g1(cos_o, alpha) * visible;
            let schlick = schlick_ggx_g1(cos_o, alpha) * visible;
            worst_exact = worst_exact.max((exact - cos_o).abs() / cos_o);
            worst_schlick = worst_schlick.max((schlick - cos_o).abs() / cos_o);
        }
    }
    println!(
        "visible-normal identity: Smith's G1 within {worst_exact:.1e}, Schlick-GGX's {worst_schlick:.3}"
    );
    assert!(worst_exact < 2e-4, "{worst_exact}");
    // The seed's Schlick-GGX is a fit: measurably off (the negative control of the identity).
    assert!(worst_schlick > 1e-2, "{worst_schlick}");
}

/// E(v) = ∫ f(l, v) cos θ_l dl with F = 1, integrated over l.
fn albedo_over_l(v: [f64; 3], alpha: f64, g: GeometryTerm) -> f64 {
    hemisphere(2000, 1024, |l| cook_torrance(N, v, l, alpha, 1.333, FresnelTerm::One, g) * l[1])
}

/// The same integral over microfacet normals m: dl = 4 (v·m) dm, l the mirror of v in m, so
/// E = ∫ G(l, v) D(m) (v·m) / (n·v) dm over the m with v·m > 0 and l above the surface.
fn albedo_over_m(v: [f64; 3], alpha: f64) -> f64 {
    hemisphere(2000, 1024, |m| {
        let vm = dot(v, m);
        if vm <= 0.0 {
            return 0.0;
        }
        let l = [2.0 * vm * m[0] - v[0], 2.0 * vm * m[1] - v[1], 2.0 * vm * m[2] - v[2]];
        if l[1] <= 0.0 {
            return 0.0;
        }
        smith_g2(l[1], v[1], alpha) * ggx_d(m[1], alpha) * vm / v[1]
    })
}

#[test]
fn the_white_furnace_returns_at_most_what_comes_in() {
    println!("white furnace E(v), F = 1, Smith height-correlated (θ_v: 0°, 45°, 75°):");
    for alpha in [0.05, 0.2, 0.5, 1.0] {
        let mut row = Vec::new();
        for theta_deg in [0.0, 45.0, 75.0f64] {
            let v = dir(theta_deg.to_radians(), 1.1);
            let e_l = albedo_over_l(v, alpha, GeometryTerm::SmithCorrelated);
            let e_m = albedo_over_m(v, alpha);
            assert!(e_l <= 1.0 + 1e-3 && e_l > 0.0, "α {alpha} θ {theta_deg}: {e_l}");
            assert!((e_l - e_m).abs() < 2e-3, "α {alpha} θ {theta_deg}: {e_l} vs {e_m}");
            row.push(e_l);
        }
        println!("  α = {alpha}: {row:.4?}");
        if alpha <= 0.05 {
            // A near mirror loses almost nothing to the single-scattering model.
            assert!(row[0] > 0.99 && row[1] > 0.99, "{row:?}");
        }
    }
    // α = 1 at normal incidence in closed form: D = 1/π, Λ(l) = (1 − μ)/(2μ), so
    // E = ½ ∫₀¹ 2μ/(1 + μ) dμ·2 = 1 − ln 2.
    let e1 = albedo_over_l(dir(0.0, 0.0), 1.0, GeometryTerm::SmithCorrelated);
    println!("  α = 1, θ_v = 0: E = {e1:.6}, closed form 1 − ln 2 = {:.6}", 1.0 - 2f64.ln());
    assert!((e1 - (1.0 - 2f64.ln())).abs() < 5e-4, "{e1}");
    // Rougher loses more (the energy multiple scattering would return).
    let e = |a: f64| albedo_over_l(dir(0.0, 0.0), a, GeometryTerm::SmithCorrelated);
    assert!(e(0.2) > e(0.5) && e(0.5) > e(1.0), "{} {} {}", e(0.2), e(0.5), e(1.0));
    // Negative control: without masking and shadowing the furnace creates energy at grazing.
    let v = dir(80f64.to_radians(), 0.0);
    let unmasked = hemisphere(2000, 1024, |l| {
        let f = cook_torrance(N, v, l, 0.5, 1.333, FresnelTerm::One, GeometryTerm::SmithCorrelated);
        let g = smith_g2(l[1], v[1], 0.5);
        if g > 0.0 { f / g * l[1] } else { 0.0 }
    });
    println!("  without G at θ_v = 80°, α = 0.5: E = {unmasked:.3}");
    assert!(unmasked > 1.05, "{unmasked}");
}

#[test]
fn the_brdf_is_reciprocal() {
    let mut rng = SplitMix64::new(5);
    let mut worst: f64 = 0.0;
    for _ in 0..10_000 {
        let mut r = || rng.next_open_closed();
        let (v, l) = (dir(FRAC_PI_2 * r(), 2.0 * PI * r()), dir(FRAC_PI_2 * r(), 2.0 * PI * r()));
        let alpha = 0.02 + r();
        for fresnel in [FresnelTerm::Exact, FresnelTerm::Schlick] {
            for g in [GeometryTerm::SmithCorrelated, GeometryTerm::SchlickGgx] {
                let a = cook_torrance(N, v, l, alpha, 1.333, fresnel, g);
                let b = cook_torrance(N, l, v, alpha, 1.333, fresnel, g);
                assert!(a.is_finite() && a >= 0.0);
                worst = worst.max((a - b).abs() / a.max(1e-300));
            }
        }
    }
    println!("reciprocity: worst relative |f(l, v) − f(v, l)| {worst:.1e}");
    assert!(worst < 1e-12, "{worst}");
    // Λ at grazing and below: G goes to 0, never NaN.
    assert_eq!(smith_g1(0.0, 0.5), 0.0);
    assert_eq!(smith_lambda(-0.2, 0.5), f64::INFINITY);
    assert_eq!(
        cook_torrance(
            N,
            [1.0, 0.0, 0.0],
            N,
            0.5,
            1.333,
            FresnelTerm::Exact,
            GeometryTerm::SmithCorrelated
        ),
        0.0
    );
}

/// The shader's sun term (the CPU mirror of `shaders/shading/ggx.wgsl`, f32, D through
/// |n × h|² + (n·h)²α²) against the f64 model at random tilted normals, eyes and suns, α from
/// 0.0025 to 1, for each Fresnel and geometry term; Schlick's Fresnel in the shader against the
/// exact one in the model is the negative control.
#[test]
fn the_shader_brdf_agrees_with_the_f64_model() {
    use ocean_cpu::shaders::shading::ggx::ggx_brdf;
    use ocean_cpu::shaders::wgsl::vec3;
    let mut frame: ocean_core::frame::FrameUniforms = bytemuck::Zeroable::zeroed();
    frame.water.eta = 1.333;
    frame.ggx.f0 = ((0.333f64 / 2.333).powi(2)) as f32;
    let mut rng = SplitMix64::new(11);
    let mut worst: f64 = 0.0;
    let mut control: f64 = 0.0;
    let mut tried = 0;
    while tried < 20_000 {
        let mut r = || rng.next_open_closed();
        let n = dir(1.0 * r(), 2.0 * PI * r());
        let v = dir(FRAC_PI_2 * r(), 2.0 * PI * r());
        let l = dir(FRAC_PI_2 * r(), 2.0 * PI * r());
        let roughness = 0.05 + 0.95 * r();
        let (nl, nv) = (dot(n, l), dot(n, v));
        if nl < 0.02 || nv < 0.02 {
            continue;
        }
        tried += 1;
        let alpha = roughness * roughness;
        let f32v = |a: [f64; 3]| vec3(a[0] as f32, a[1] as f32, a[2] as f32);
        let (nf, vf, lf) = (f32v(n), f32v(v), f32v(l));
        let shader = |frame: &ocean_core::frame::FrameUniforms| {
            let nl = ocean_cpu::shaders::shared::frame::dot3(nf, lf);
            let nv = ocean_cpu::shaders::shared::frame::dot3(nf, vf);
            f64::from(ggx_brdf(nf, vf, lf, nl, nv, (alpha * alpha) as f32, frame))
        };
        for (schlick_f, fresnel) in [(0.0, FresnelTerm::Exact), (1.0, FresnelTerm::Schlick)] {
            for (schlick_g, g) in
                [(0.0, GeometryTerm::SmithCorrelated), (1.0, GeometryTerm::SchlickGgx)]
            {
                frame.ggx.schlick_fresnel = schlick_f;
                frame.ggx.schlick_geometry = schlick_g;
                let want = cook_torrance(n, v, l, alpha, 1.333, fresnel, g);
                let got = shader(&frame);
                worst = worst.max((got - want).abs() / want.max(1e-3));
                if schlick_f == 1.0 && schlick_g == 0.0 {
                    let exact = cook_torrance(n, v, l, alpha, 1.333, FresnelTerm::Exact, g);
                    control = control.max((got - exact).abs() / exact.max(1e-3));
                }
            }
        }
    }
    println!(
        "shader BRDF vs f64 model: worst relative {worst:.1e}; Schlick vs exact {control:.1e}"
    );
    assert!(worst < 1e-4, "{worst}");
    assert!(control > 1e-2, "the comparator must see Schlick's error: {control}");
}
