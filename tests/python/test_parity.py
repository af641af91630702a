# Python results equal the CLI's bit for bit on the same float32 NPY input: evaluate (every
# profile), evaluate_grid, lut (every kind) and render (the spheres and a glTF asset).
import json

import numpy as np
import pytest

import brdfcl
from conftest import MATERIALS, ROOT


def random_samples(n, seed=1, materials=len(MATERIALS)):
    rng = np.random.default_rng(seed)
    L = rng.normal(size=(n, 3)).astype(np.float32)
    V = rng.normal(size=(n, 3)).astype(np.float32)
    L[:, 2] = np.abs(L[:, 2]) * 3  # mostly above the horizon, a few not
    V[:, 2] = np.abs(V[:, 2]) * 3 - 0.1
    idx = rng.integers(0, materials, size=n)
    return idx, L, V


@pytest.fixture(scope="module")
def materials_file(tmp_path_factory):
    p = tmp_path_factory.mktemp("m") / "m.json"
    p.write_text(json.dumps({"materials": MATERIALS}))
    return p


@pytest.mark.parametrize("profile", brdfcl.PROFILES)
def test_evaluate_equals_cli(cli, tmp_path, materials_file, profile):
    idx, L, V = random_samples(5000)
    np.save(tmp_path / "s.npy", np.column_stack([idx, L, V]).astype(np.float32))
    cli("eval", "--materials", materials_file, "--samples", tmp_path / "s.npy", "--out", tmp_path / "o.npy",
        "--profile", profile)
    expected = np.load(tmp_path / "o.npy")
    got = brdfcl.evaluate(MATERIALS, L, V, idx, profile=profile)
    assert got.dtype == np.float32 and got.shape == (5000, 3)
    assert np.array_equal(got.view(np.uint32), expected.view(np.uint32))
    # The file path reads the very same materials.
    assert np.array_equal(brdfcl.evaluate(materials_file, L, V, idx, profile=profile).view(np.uint32),
                          expected.view(np.uint32))


@pytest.mark.parametrize("lobe", brdfcl.LOBES)
def test_evaluate_lobes_float64_equal_cli(cli, tmp_path, materials_file, lobe):
    idx, L, V = random_samples(2000, seed=2)
    L64, V64 = L.astype(np.float64) * 1e-3, V.astype(np.float64) * 7.5
    np.save(tmp_path / "s.npy", np.column_stack([idx, L64, V64]))
    cli("eval", "--materials", materials_file, "--samples", tmp_path / "s.npy", "--out", tmp_path / "o.npy",
        "--lobe", lobe, "--sheen-visibility", "ashikhmin")
    got = brdfcl.evaluate(MATERIALS, L64, V64, idx, lobe=lobe, sheen_visibility="ashikhmin")
    assert np.array_equal(got.view(np.uint32), np.load(tmp_path / "o.npy").view(np.uint32))


def test_evaluate_grid_equals_cli(cli, tmp_path, materials_file):
    _, L, V = random_samples(3000, seed=3)
    np.save(tmp_path / "d.npy", np.column_stack([L, V]).astype(np.float32))
    cli("eval", "--grid", "--materials", materials_file, "--samples", tmp_path / "d.npy", "--out", tmp_path / "o.npy")
    expected = np.load(tmp_path / "o.npy").reshape(len(MATERIALS), 3000, 3)
    got = brdfcl.evaluate_grid(MATERIALS, L, V)
    assert got.shape == (len(MATERIALS), 3000, 3)
    assert np.array_equal(got.view(np.uint32), expected.view(np.uint32))


@pytest.mark.parametrize("kind", brdfcl.LUT_KINDS)
def test_lut_equals_cli(cli, tmp_path, kind):
    cli("lut", "--kind", kind, "--size", 32, "--out", tmp_path / "l.npy")
    expected = np.load(tmp_path / "l.npy")
    got = brdfcl.lut(kind, 32)
    assert got.shape == expected.shape and got.dtype == np.float32
    assert np.array_equal(got.view(np.uint32), expected.view(np.uint32))


def test_render_spheres_equals_cli(cli, tmp_path):
    cli("render", "--size", "96x64", "--out", tmp_path / "r.exr")
    expected = brdfcl.read_exr(tmp_path / "r.exr")
    got = brdfcl.render(size=(96, 64))
    assert got.shape == (64, 96, 3) and got.dtype == np.float32
    assert np.array_equal(got.view(np.uint32), expected.view(np.uint32))


def test_render_gltf_equals_cli(cli, tmp_path):
    asset = ROOT / "tests" / "fuzz" / "corpus" / "gltf" / "textured.glb"
    cli("render", "--gltf", asset, "--size", "64x48", "--spp", 2, "--environment", "studio", "--profile", "filament",
        "--out", tmp_path / "r.exr")
    expected = brdfcl.read_exr(tmp_path / "r.exr")
    got = brdfcl.render(gltf=asset, size=(64, 48), spp=2, environment="studio", profile="filament")
    assert np.array_equal(got.view(np.uint32), expected.view(np.uint32))


def test_shade_gbuffer_roundtrip(cli, tmp_path):
    cli("gbuffer", "--size", "48x32", "--out", tmp_path / "g.exr")
    g = brdfcl.read_gbuffer(tmp_path / "g.exr")
    assert g["N"].shape == (32, 48, 3) and g["mask"].shape == (32, 48)
    scene = {"lights": [{"type": "directional", "direction": [0, -1, -1], "intensity": 2}]}
    (tmp_path / "scene.json").write_text(json.dumps(scene))
    cli("shade", "--gbuffer", tmp_path / "g.exr", "--scene", tmp_path / "scene.json", "--out", tmp_path / "s.exr")
    expected = brdfcl.read_exr(tmp_path / "s.exr")
    from_path = brdfcl.shade(tmp_path / "g.exr", tmp_path / "scene.json")
    from_dict = brdfcl.shade(g, scene)
    assert np.array_equal(from_path.view(np.uint32), expected.view(np.uint32))
    assert np.array_equal(from_dict.view(np.uint32), expected.view(np.uint32))
    brdfcl.write_gbuffer(tmp_path / "g2.exr", g)
    g2 = brdfcl.read_gbuffer(tmp_path / "g2.exr")
    assert set(g2) == set(g) and all(np.array_equal(g[k], g2[k]) for k in g if k != "camera")


def test_albedo_matches_cli_table(cli):
    a = brdfcl.albedo(MATERIALS[0], [1.0, 0.5])
    assert set(a) == {"diffuse", "specular", "sheen", "clearcoat", "all"}
    assert a["all"].shape == (2, 3) and np.all(a["all"] > 0) and np.all(a["all"] <= 1.0001)
    many = brdfcl.albedo(MATERIALS, 1.0)
    assert many["sheen"].shape == (len(MATERIALS), 3)
