# brdfcl.sample and brdfcl.pdf: the CLI's rows for the same seed, the pdf agreeing with the
# sample's, weights averaging to the albedo, out= filled in place, and one-line errors.

import numpy as np
import pytest

import brdfcl
from conftest import MATERIALS


def test_sample_matches_the_cli(cli, tmp_path):
    import json
    (tmp_path / "m.json").write_text(json.dumps({"materials": MATERIALS}))
    (tmp_path / "v.csv").write_text("material,Vx,Vy,Vz\n0,0.3,0.1,0.9\n2,0,0.8,0.2\n")
    cli("sample", "--materials", tmp_path / "m.json", "--views", tmp_path / "v.csv", "--out", tmp_path / "o.npy",
        "--count", "64", "--seed", "5")
    want = np.load(tmp_path / "o.npy")
    V = np.array([[0.3, 0.1, 0.9], [0, 0.8, 0.2]])
    L, pdf, w = brdfcl.sample(MATERIALS, V, material=[0, 2], count=64, seed=5)
    assert L.shape == (128, 3) and pdf.shape == (128,) and w.shape == (128, 3)
    np.testing.assert_array_equal(np.hstack([L, pdf[:, None], w]), want)


def test_pdf_agrees_and_out_is_filled():
    V = np.tile([[0.2, -0.3, 0.8]], (1000, 1))
    out = np.empty((1000, 7), dtype=np.float32)
    L, p, w = brdfcl.sample(MATERIALS[0], V, count=None, u=np.random.default_rng(1).random((1000, 3)), out=out)
    assert np.shares_memory(L, out) and np.shares_memory(w, out)
    kept = p > 0
    assert kept.sum() > 900
    again = brdfcl.pdf(MATERIALS[0], L[kept], V[kept])
    np.testing.assert_allclose(again, p[kept], rtol=1e-5)


def test_mean_weight_is_the_albedo():
    mu = 0.6
    V = np.array([[np.sqrt(1 - mu * mu), 0.0, mu]])
    _, _, w = brdfcl.sample(MATERIALS[1], V, count=200000, seed=3)
    albedo = brdfcl.albedo(MATERIALS[1], mu)["all"]
    np.testing.assert_allclose(w.mean(axis=0), albedo, rtol=0.02)


def test_errors():
    with pytest.raises(brdfcl.InputError, match="give u"):
        brdfcl.sample(MATERIALS[0], [[0, 0, 1]])
    with pytest.raises(brdfcl.InputError, match=r"u row 0 must lie in \[0, 1\)"):
        brdfcl.sample(MATERIALS[0], [[0, 0, 1]], u=[[0.5, 1.0, 0.5]])
    with pytest.raises(brdfcl.InputError, match="out of range"):
        brdfcl.sample(MATERIALS, [[0, 0, 1]], material=[7], count=1)
    with pytest.raises(brdfcl.InputError, match="not a finite non-zero direction"):
        brdfcl.pdf(MATERIALS[0], [[0, 0, 0]], [[0, 0, 1]])
