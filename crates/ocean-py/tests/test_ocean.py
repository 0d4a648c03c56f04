"""The Python bindings against independent numpy formulas, published values and the Rust CLI.

Run after building the module (see docs/commands.md, "Python"):
    pytest crates/ocean-py/tests
The CLI is `target/release/ocean` (or $OCEAN_BIN); tests that need it fail when it is missing.
"""

import csv
import io
import math
import os
import pathlib
import subprocess

import numpy as np
import pytest

import ocean

ROOT = pathlib.Path(__file__).resolve().parents[3]
G = 9.81


def cli(*args):
    exe = os.environ.get("OCEAN_BIN", str(ROOT / "target" / "release" / "ocean"))
    assert pathlib.Path(exe).exists(), f"the ocean CLI is not built at {exe} (cargo build --release)"
    return subprocess.run([exe, *args], check=True, capture_output=True, text=True)


def fresnel_sp(eta, c):
    """Unpolarised Fresnel reflectance from the s and p amplitudes (Born & Wolf), written
    independently of eq. 2: 1 under total internal reflection."""
    c = np.asarray(c, dtype=float)
    s2 = 1.0 - c * c
    t2 = 1.0 - s2 / (eta * eta)
    out = np.ones_like(c)
    ok = t2 >= 0
    ct = np.sqrt(np.where(ok, t2, 0.0))
    rs = (c - eta * ct) / (c + eta * ct)
    rp = (eta * c - ct) / (eta * c + ct)
    out[ok] = (0.5 * (rs * rs + rp * rp))[ok]
    return out


def test_fresnel_matches_the_s_p_formula_and_keeps_the_shape():
    c = np.linspace(1e-3, 1.0, 2001)
    for eta in (1.333, 1.5, 1.0 / 1.333, 1.0001):
        f = ocean.fresnel(eta, c)
        assert f.shape == c.shape and f.dtype == np.float64
        np.testing.assert_allclose(f, fresnel_sp(eta, c), rtol=0, atol=1e-12)
    grid = ocean.fresnel(1.333, c.reshape(3, 667))
    assert grid.shape == (3, 667)
    assert float(ocean.fresnel(1.333, 1.0)) == pytest.approx(((1.333 - 1) / (1.333 + 1)) ** 2, abs=1e-15)
    # Negative control: the comparison sees a 1e-9 change.
    assert np.abs(ocean.fresnel(1.333, c) - fresnel_sp(1.333 + 1e-6, c)).max() > 1e-9


def test_fresnel_is_finite_at_the_extremes():
    c = np.array([0.0, 1e-300, 1e-9, 0.5, 1.0])
    for eta in (1.333, 0.75, 1.0 + 1e-12, 1.0 - 1e-12):
        f = ocean.fresnel(eta, c)
        assert np.all(np.isfinite(f)) and np.all((0 <= f) & (f <= 1)), (eta, f)
    # Past the critical angle from below: total internal reflection.
    assert np.all(ocean.fresnel(0.75, np.array([0.1, 0.5])) == 1.0)


def test_schlick_is_its_formula():
    c = np.linspace(0.0, 1.0, 501)
    r0 = ((1.333 - 1) / (1.333 + 1)) ** 2
    np.testing.assert_allclose(ocean.fresnel_schlick(1.333, c), r0 + (1 - r0) * (1 - c) ** 5, atol=1e-14)


def test_fresnel_equals_the_cli_csv():
    out = cli("fresnel", "--eta", "1.333", "--step-deg", "0.5").stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 181
    c = np.array([float(r["cos_theta"]) for r in rows])
    np.testing.assert_array_equal(ocean.fresnel(1.333, c), [float(r["exact"]) for r in rows])
    np.testing.assert_array_equal(ocean.fresnel_schlick(1.333, c), [float(r["schlick"]) for r in rows])


def test_dispersion_is_g_k_tanh_kh():
    k = np.geomspace(1e-4, 10.0, 400)
    np.testing.assert_allclose(ocean.dispersion(k), np.sqrt(G * k), rtol=1e-14)
    for h in (0.5, 5.0, 50.0):
        np.testing.assert_allclose(ocean.dispersion(k, depth=h), np.sqrt(G * k * np.tanh(k * h)), rtol=1e-12)
    np.testing.assert_allclose(ocean.dispersion(k, gravity=3.71), np.sqrt(3.71 * k), rtol=1e-14)
    with pytest.raises(ValueError):
        ocean.dispersion(k, depth=-1.0)


PM = """
[ocean]
spectrum = "pierson-moskowitz"
wind_speed = 10.0
patch_size_m = 2000.0
resolution = 512
choppiness = 0.0
seed = {seed}
"""


def test_a_fully_developed_pm_sea_has_hs_near_0_22_u2_over_g():
    # Pierson & Moskowitz (1964): Hs ≈ 0.22 U10²/g. Eight seeds of a 2 km patch at N = 512;
    # the band the grid leaves out is 1 % of the variance (tests/sea_state.rs): 3 % allowed.
    var = np.mean([np.mean(ocean.heightfield(PM.format(seed=s), 0.0)["height"].astype(np.float64) ** 2)
                   for s in range(1, 9)])
    hs = 4 * math.sqrt(var)
    published = 0.22 * 10.0 ** 2 / G
    assert abs(hs / published - 1) < 0.03, (hs, published)


def test_heightfield_equals_the_cli_exr(tmp_path):
    import OpenEXR

    scene = (ROOT / "reference" / "scenes" / "calm.toml").read_text()
    maps = ocean.heightfield(scene, 7.5)
    assert list(maps) == ["height", "disp_x", "disp_z", "slope_x", "slope_z", "jacobian"]
    out = tmp_path / "h.exr"
    cli("heightfield", str(ROOT / "reference" / "scenes" / "calm.toml"), "--time", "7.5", "-o", str(out))
    with OpenEXR.File(str(out)) as f:
        channels = f.channels()
        for name, a in maps.items():
            assert a.dtype == np.float32 and a.shape[0] == a.shape[1]
            np.testing.assert_array_equal(a, channels[name].pixels, err_msg=name)


SMALL = """
[ocean]
spectrum = "jonswap"
wind_speed = 9.0
fetch_km = 80.0
patch_size_m = 100.0
resolution = 64
choppiness = 0.0
seed = 5
"""


def test_the_height_query_is_the_map_at_its_texels():
    # Without choppiness a texel's sample is its own point: the query (f64, every mode)
    # equals the f32 map there to the f32 FFT's rounding (docs/design.md: FFT vs direct sum,
    # rel 1e-5 in f32, here of the map's range).
    m = ocean.heightfield(SMALL, 3.0)["height"].astype(np.float64)
    i = np.array([0, 5, 17, 40, 63])
    x, z = np.meshgrid(i * 100.0 / 64, i * 100.0 / 64)
    h = ocean.height(SMALL, 3.0, x, z)
    assert h.shape == x.shape
    scale = np.abs(m).max()
    np.testing.assert_allclose(h, m[np.ix_(i, i)], rtol=0, atol=1e-5 * scale)
    # Negative control: half a texel away it is another height.
    assert np.abs(ocean.height(SMALL, 3.0, x + 0.78, z) - h).max() > 1e-3 * scale
    with pytest.raises(ValueError, match="shape"):
        ocean.height(SMALL, 3.0, x, z[:2])


def test_render_equals_the_cli_and_refuses_bad_input(tmp_path):
    import OpenEXR

    path = ROOT / "reference" / "scenes" / "calm.toml"
    scene = path.read_text() + "\n[camera]\nwidth = 64\nheight = 36\n"
    small = tmp_path / "small.toml"
    small.write_text(scene)
    img = ocean.render(scene)
    h, w = img.shape[:2]
    assert img.shape[2] == 4 and img.dtype == np.float32 and np.all(np.isfinite(img))
    out = tmp_path / "f.exr"
    cli("render", str(small), "-o", str(out))
    with OpenEXR.File(str(out)) as f:
        ch = f.channels()
        rgba = np.stack([ch[c].pixels for c in "RGBA"], axis=-1) if "R" in ch else ch["RGBA"].pixels
    assert rgba.shape == (h, w, 4)
    np.testing.assert_array_equal(img, rgba)
    with pytest.raises(ValueError, match="backend"):
        ocean.render(scene, backend="gpu")
    with pytest.raises(ValueError, match="wind_speed"):
        ocean.render("[ocean]\nwind_speed = -3.0\n")


PM_SPEC = '[ocean]\nspectrum = "pierson-moskowitz"\nwind_speed = 10.0\n'


def test_spectrum_integrates_to_the_published_hs_and_spreading_to_one():
    w = np.linspace(1e-3, 30.0, 300001)
    s = ocean.spectrum(PM_SPEC, w)
    assert s.shape == w.shape and np.all(s >= 0) and np.all(np.isfinite(s))
    hs = 4 * math.sqrt(np.trapezoid(s, w))
    assert abs(hs / (0.22 * 100 / G) - 1) < 0.01, hs
    theta = np.linspace(-math.pi, math.pi, 200001)
    for k in (0.02, 0.1, 0.5, 3.0):
        d = ocean.spreading(PM_SPEC, np.full_like(theta, k), theta)
        # 1e-6: the trapezoid rule's error at 2·10⁵ points on the sech² lobe (≪ 1e-6).
        assert abs(np.trapezoid(d, theta) - 1) < 1e-6, (k, np.trapezoid(d, theta))
    # Negative control: twice the wind is another sea.
    s2 = ocean.spectrum(PM_SPEC.replace("10.0", "20.0"), w)
    assert abs(4 * math.sqrt(np.trapezoid(s2, w)) / hs - 4) < 0.05


def test_the_amplitudes_carry_the_maps_variance():
    # Parseval: at t = 0 the height is Σ h̃ e^{ik·x} with h̃(k) = h̃₀(k) + conj(h̃₀(−k)), so the
    # map's mean square is Σ |h̃|² (rel 1e-5: docs/design.md's f32 FFT tolerance).
    h0 = ocean.amplitudes(SMALL)
    n = h0.shape[0]
    assert h0.shape == (n, n) and h0.dtype == np.complex128
    neg = (-np.arange(n)) % n
    ht = h0 + np.conj(h0[np.ix_(neg, neg)])
    m = ocean.heightfield(SMALL, 0.0)["height"].astype(np.float64)
    np.testing.assert_allclose(np.mean(m * m), np.sum(np.abs(ht) ** 2), rtol=1e-5)
    # Another seed draws other amplitudes of the same spectrum.
    other = ocean.amplitudes(SMALL.replace("seed = 5", "seed = 6"))
    assert np.abs(other - h0).max() > 0.1 * np.abs(h0).max()


# Hostile inputs (issue 36, item 9): the module refuses what the command line refuses, with a
# ValueError naming the argument, and reads a heightmap's header before its pixels.


@pytest.mark.parametrize("eta", [float("nan"), 0.0, -1.33, float("inf")])
def test_fresnel_refuses_an_eta_the_cli_refuses(eta):
    for f in (ocean.fresnel, ocean.fresnel_schlick):
        with pytest.raises(ValueError, match="eta"):
            f(eta, [0.5])
    # Control: the same call with a valid eta answers.
    assert np.isfinite(ocean.fresnel(1.33, [0.5])).all()


def test_render_applies_the_memory_estimate():
    scene = "[camera]\nwidth = 64\nheight = 36\n"
    with pytest.raises(ValueError, match="memory_limit"):
        ocean.render(scene, memory_limit=1 << 20)
    with pytest.raises(ValueError, match="memory_limit"):
        ocean.render(scene, memory_limit=0)
    assert ocean.render(scene, memory_limit=8 << 30).shape == (36, 64, 4)


def forged_exr(w, h):
    """An EXR header (one float channel Y, no compression) whose data window claims w x h,
    and no pixels: a few hundred bytes."""
    import struct

    out = bytearray(b"\x76\x2f\x31\x01\x02\x00\x00\x00")

    def attr(name, kind, value):
        out.extend(name.encode() + b"\0" + kind.encode() + b"\0")
        out.extend(struct.pack("<i", len(value)) + value)

    attr("channels", "chlist", b"Y\0" + struct.pack("<i", 2) + b"\0\0\0\0" + struct.pack("<ii", 1, 1) + b"\0")
    attr("compression", "compression", b"\0")
    window = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    attr("dataWindow", "box2i", window)
    attr("displayWindow", "box2i", window)
    attr("lineOrder", "lineOrder", b"\0")
    attr("pixelAspectRatio", "float", struct.pack("<f", 1.0))
    attr("screenWindowCenter", "v2f", b"\0" * 8)
    attr("screenWindowWidth", "float", struct.pack("<f", 1.0))
    out.extend(b"\0" + b"\0" * 64)
    return bytes(out)


def floor_scene(path):
    return (
        f'[terrain]\nkind = "heightmap"\nheightmap = "{path}"\nheight_range_m = [-2.0, 6.0]\n'
        "depth_m = 10.0\ncenter = [0.0, -30.0]\nextent_m = 60.0\n"
    )


def test_heightmaps_are_checked_before_decoding(tmp_path):
    forged = tmp_path / "claims32k.exr"
    forged.write_bytes(forged_exr(32768, 32768))
    for f in (ocean.render, lambda s: ocean.height(s, 0.0, [0.0], [0.0])):
        with pytest.raises(ValueError, match="32768×32768"):
            f(floor_scene(forged))
    fifo = tmp_path / "pipe.png"
    os.mkfifo(fifo)
    with pytest.raises(ValueError, match="named pipe"):
        ocean.render(floor_scene(fifo))
