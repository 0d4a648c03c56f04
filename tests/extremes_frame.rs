//! Extreme views give finite pixels (issue 3): camera at the horizon, straight down, at
//! 10 km, under the water, 10⁶ m from the origin; sun at and below the horizon; no sun.

use ocean_core::scene::{Scene, SceneSource};

fn render(extra: &str) -> (Vec<[f32; 4]>, Vec<u8>) {
    let text = format!("[camera]\nwidth = 96\nheight = 54\n{extra}");
    let mut scene = Scene::builtin();
    let over = Scene::from_toml(&text, SceneSource::Text).expect("valid override");
    scene.camera = over.camera;
    if text.contains("[sun]") {
        scene.sun = over.sun;
    }
    if text.contains("[techniques]") {
        scene.techniques = over.techniques;
        scene.ggx = over.ggx;
        scene.foam = over.foam;
    }
    if text.contains("nosun") {
        scene.sun = None;
    }
    if text.contains("noobjects") {
        scene.objects.clear();
    }
    let r = ocean_cpu::render_scene(&scene, ocean_core::plan::OutputKind::Ldr, &mut |_| {})
        .expect("render");
    (r.buffers.hdr.color, r.ldr.expect("tonemapped"))
}

fn check(name: &str, extra: &str) {
    let (hdr, ldr) = render(extra);
    let bad = hdr.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
    assert_eq!(bad, 0, "{name}: {bad} non-finite HDR pixels");
    assert!(hdr.iter().all(|p| p.iter().all(|&c| c >= 0.0)), "{name}: negative radiance");
    assert_eq!(ldr.len(), 96 * 54 * 4);
}

/// The camera's extreme cases of [`camera_extremes_are_finite`].
const CAMERAS: [(&str, &str); 8] = [
    ("horizon", "position = [0.0, 2.0, 0.0]\nlook_at = [0.0, 2.0, -100.0]\n"),
    ("straight down", "position = [0.0, 30.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\n"),
    ("10 km up", "position = [0.0, 10000.0, 0.0]\nlook_at = [100.0, 0.0, -3000.0]\n"),
    ("under water", "position = [0.0, -4.0, 0.0]\nlook_at = [0.0, 2.0, -30.0]\n"),
    ("under water, down", "position = [0.0, -4.0, 0.0]\nlook_at = [0.0, -10.0, -5.0]\n"),
    (
        "far from the origin",
        "position = [1.0e6, 6.0, -1.0e6]\nlook_at = [1.0e6, 1.0, -1.00006e6]\n",
    ),
    ("looking up", "position = [0.0, 5.0, 0.0]\nlook_at = [0.0, 50.0, -1.0]\n"),
    ("at the surface", "position = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, -10.0]\n"),
];

#[test]
fn camera_extremes_are_finite() {
    for (name, camera) in CAMERAS {
        check(name, camera);
    }
}

/// Seed 002's techniques at the same extremes, and with the sun at the horizon, below it and
/// at the zenith: GGX's 1/(n·l)(n·v) at grazing, the smallest and largest roughness, Schlick's
/// options, the Gerstner waves summed per vertex, and the clipmap under either wave model.
#[test]
fn welch_techniques_at_the_extremes_are_finite() {
    let techniques = [
        "[techniques]\nshading = \"ggx\"\n",
        "[techniques]\nshading = \"ggx\"\n[ggx]\nroughness = 0.01\n",
        "[techniques]\nshading = \"ggx\"\n[ggx]\nroughness = 1.0\nfresnel = \"schlick\"\n\
         geometry = \"schlick_ggx\"\n",
        "[techniques]\nwaves = \"gerstner\"\nfar_field = \"mip\"\nshading = \"ggx\"\n",
        "[techniques]\nwaves = \"gerstner\"\nfar_field = \"mip\"\nsurface = \"clipmap\"\n",
        "[techniques]\nsurface = \"clipmap\"\n",
    ];
    let suns = ["[0.0, 0.0, -1.0]", "[0.0, -0.3, -1.0]", "[0.0, 1.0, 0.0]", "[0.3, 0.05, -1.0]"];
    for t in techniques {
        for (name, camera) in CAMERAS {
            check(&format!("{name} with {t}"), &format!("{camera}{t}"));
        }
        for sun in suns {
            let cam = "position = [0.0, 6.0, 30.0]\nlook_at = [0.0, 1.0, -60.0]\n";
            check(&format!("sun {sun} with {t}"), &format!("{cam}{t}[sun]\ndirection = {sun}\n"));
        }
    }
}

/// The foam techniques at the same extremes and suns, with their keys at the limits: foam
/// everywhere (threshold 10, softness 0.001, growth 1000, decay 0.001 s, full coverage of
/// albedo 1), crests at the smallest scales, and the accumulated field on Gerstner waves'
/// lattice around a camera 10⁶ m out.
#[test]
fn foam_techniques_at_the_extremes_are_finite() {
    let keys = "[foam]\nthreshold = 10.0\nsoftness = 0.001\ngrowth_per_s = 1000.0\n\
                decay_s = 0.001\ncoverage = 1.0\ncolor = [1.0, 1.0, 1.0]\n\
                crest_height_m = 0.001\ncrest_slope = 0.001\nwarmup_steps = 3\n";
    let techniques = [
        "[techniques]\nfoam = \"heuristic\"\n".to_owned(),
        "[techniques]\nfoam = \"jacobian\"\nshading = \"chiu\"\n".to_owned(),
        "[techniques]\nfoam = \"accumulated\"\nshading = \"ggx\"\n".to_owned(),
        format!("[techniques]\nfoam = \"heuristic\"\n{keys}"),
        format!("[techniques]\nfoam = \"accumulated\"\n{keys}"),
        "[techniques]\nwaves = \"gerstner\"\nfar_field = \"mip\"\nfoam = \"accumulated\"\n\
         [foam]\ngrid = 64\ncell_m = 100.0\n"
            .to_owned(),
        format!(
            "[techniques]\nwaves = \"gerstner\"\nfar_field = \"mip\"\nfoam = \"jacobian\"\n{keys}"
        ),
    ];
    let suns = ["[0.0, 0.0, -1.0]", "[0.0, -0.3, -1.0]", "[0.0, 1.0, 0.0]"];
    for t in &techniques {
        for (name, camera) in CAMERAS {
            check(&format!("{name} with {t}"), &format!("{camera}{t}"));
        }
        for sun in suns {
            let cam = "position = [0.0, 6.0, 30.0]\nlook_at = [0.0, 1.0, -60.0]\n";
            check(&format!("sun {sun} with {t}"), &format!("{cam}{t}[sun]\ndirection = {sun}\n"));
        }
    }
}

#[test]
fn sun_extremes_are_finite() {
    let cam = "position = [0.0, 6.0, 30.0]\nlook_at = [0.0, 1.0, -60.0]\n";
    for (name, sun) in [
        ("sun at the horizon", "[sun]\ndirection = [0.0, 0.0, -1.0]\n"),
        ("sun below the horizon", "[sun]\ndirection = [0.0, -0.3, -1.0]\n"),
        ("sun at the zenith", "[sun]\ndirection = [0.0, 1.0, 0.0]\n"),
        ("no sun", "# nosun\n"),
    ] {
        check(name, &format!("{cam}{sun}"));
    }
}

#[test]
fn the_far_camera_sees_the_same_sea_as_the_near_one() {
    // Camera-relative rendering: moving the camera and the scene by a whole number of wave
    // patches (256 m) changes nothing but the objects' absolute coordinates, so with no
    // objects the picture must be the same up to f32 rounding of the positions.
    let near = "# noobjects\nposition = [0.0, 6.0, 30.0]\nlook_at = [0.0, 1.0, -60.0]\n";
    let far = "# noobjects\nposition = [1048576.0, 6.0, 30.0]\nlook_at = [1048576.0, 1.0, -60.0]\n";
    let (a, _) = render(near);
    let (b, _) = render(far);
    let max = a
        .iter()
        .zip(&b)
        .flat_map(|(p, q)| (0..3).map(move |c| (p[c] - q[c]).abs() / p[c].abs().max(1e-3)))
        .fold(0.0f32, f32::max);
    println!("near vs 10⁶ m camera: max relative difference {max:.2e}");
    assert!(max < 1e-3, "camera-relative rendering failed: {max}");
    // Negative control: a shift that is not a whole number of patches shows another sea.
    let other =
        "# noobjects\nposition = [1048500.0, 6.0, 30.0]\nlook_at = [1048500.0, 1.0, -60.0]\n";
    let (c, _) = render(other);
    let differs = a.iter().zip(&c).filter(|(p, q)| p != q).count();
    assert!(differs > a.len() / 4, "{differs} of {} pixels differ", a.len());
}

/// Every sky technique (the enum's list, so a new one is covered when it is declared) at the
/// camera's extremes and with the sun at the horizon, below it and at the zenith: what the
/// water reflects and the sky pass draws stays finite and non-negative.
#[test]
fn every_sky_technique_at_the_extremes_is_finite() {
    use ocean_core::stage::{Sky, StageTechnique};
    let suns = ["[0.0, 0.0, -1.0]", "[0.0, -0.3, -1.0]", "[0.0, 1.0, 0.0]"];
    for sky in Sky::ALL {
        let t = format!("[techniques]\nsky = \"{}\"\n", sky.name());
        for (name, camera) in CAMERAS {
            check(&format!("{name} with {t}"), &format!("{camera}{t}"));
        }
        for sun in suns {
            let cam = "position = [0.0, 6.0, 30.0]\nlook_at = [0.0, 1.0, -60.0]\n";
            check(&format!("sun {sun} with {t}"), &format!("{cam}{t}[sun]\ndirection = {sun}\n"));
        }
    }
}
