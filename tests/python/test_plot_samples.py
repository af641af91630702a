# brdfcl.plot.samples and `python -m brdfcl plot samples`: the sampler's histogram on the
# hemisphere agrees with the pdf integrated over each bin (Pearson's chi-square), for the mixture
# and single lobes, the figure is written, and bad options are one-line errors.
import math

import numpy as np
import pytest

import brdfcl
from conftest import MATERIALS

pytest.importorskip("matplotlib")
import matplotlib  # noqa: E402

matplotlib.use("Agg")
from brdfcl import plot  # noqa: E402
from test_plot import check_png, materials_file, run_cli  # noqa: E402,F401

# A coat the bins' quadrature resolves: at clearcoat roughness 0.1 (MATERIALS[1], alpha 0.01) the
# peak is narrower than a quadrature node's spacing and the expected counts of its bins are off.
ROUGH_COAT = {"name": "rough coat", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.1, 1],
                                                              "metallicFactor": 0, "roughnessFactor": 0.5},
              "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 0.4}}}
CASES = MATERIALS[:1] + [ROUGH_COAT] + MATERIALS[2:]


def chi2_bound(dof):
    # Pearson's statistic has mean dof and variance 2 dof: 5 standard deviations above the mean,
    # so that the test fails by chance far less than once in a million runs.
    return dof + 5 * math.sqrt(2 * dof)


@pytest.mark.parametrize("material, lobe, view", [
    (0, "all", (40.0, 30.0)),       # velvet: sheen over a rough dielectric, the mixture
    (0, "sheen", (70.0, 0.0)),      # the Charlie sampler alone, towards grazing
    (1, "all", (20.0, 100.0)),      # clearcoat (roughness 0.4) over a dielectric
    (2, "specular", (50.0, -60.0)), # anisotropic GGX, rotated
])
def test_histogram_agrees_with_the_integrated_pdf(material, lobe, view):
    fig, a = plot.samples(CASES, material, view=view, lobe=lobe, count=200000, seed=7, bins=(12, 24),
                          quadrature=8, figsize=(9, 3.5), dpi=50)
    counts, expected = a["counts"], a["expected"]
    assert counts.shape == expected.shape == (12, 24)
    assert counts.sum() == np.count_nonzero(a["pdf"] > 0)
    # The pdf integrates to the mass the sampler keeps (1 but for the sheen's and GGX's losses).
    assert abs(a["kept"] - a["pdf_mass"]) < 0.005, (a["kept"], a["pdf_mass"])
    assert a["pdf_mass"] <= 1.0 + 1e-3
    assert a["dof"] > 20
    assert a["chi2"] < chi2_bound(a["dof"]), (a["chi2"], a["dof"])
    # The figure's arrays are brdfcl.sample's own rows for that seed.
    tv, pv = (math.radians(x) for x in view)
    V = np.array([[math.sin(tv) * math.cos(pv), math.sin(tv) * math.sin(pv), math.cos(tv)]])
    L, pdf, w = brdfcl.sample(CASES[material], V, count=200000, seed=7, lobe=lobe)
    assert np.array_equal(L, a["L"]) and np.array_equal(pdf, a["pdf"]) and np.array_equal(w, a["weight"])


def test_a_wrong_pdf_fails_the_same_check():
    # The check has teeth: the same histogram against a pdf scaled by 1.05 is far outside the bound.
    _, a = plot.samples(MATERIALS, 0, view=(40.0, 30.0), count=200000, seed=7, bins=(12, 24), quadrature=8,
                        figsize=(9, 3.5), dpi=50)
    big = a["expected"] >= 5
    o, e = a["counts"][big], 1.05 * a["expected"][big]
    assert ((o - e) ** 2 / e).sum() > chi2_bound(int(big.sum()))


def test_figure_is_drawn(tmp_path):
    p = plot.samples(MATERIALS, 2, view=(30.0, 0.0), count=20000, bins=(9, 18), figsize=(4, 3), dpi=50)
    p.save(tmp_path / "s.png")
    check_png(tmp_path / "s.png")


def test_cli_writes_the_figure(tmp_path, materials_file):  # noqa: F811
    out = tmp_path / "s.png"
    r = run_cli("samples", "--materials", materials_file, "--material", 2, "--lobe", "specular", "--view", "60,45",
                "--count", 30000, "--seed", 3, "--bins", "10x20", "--figsize", "8x3", "--dpi", 50, "--out", out)
    assert r.returncode == 0, r.stderr
    check_png(out, 400, 150)
    assert [q.name for q in tmp_path.iterdir()] == [out.name]


@pytest.mark.parametrize("args, message", [
    (["--view", "95,0"], r"view must be \(theta, phi\) in degrees with theta in \[0, 90\)"),
    (["--view", "45"], r"--view '45' must be THETA,PHI in degrees, e.g. 45,0"),
    (["--view", "a,b"], r"--view 'a,b' must be degrees separated by commas"),
    (["--bins", "10"], r"--bins '10' must be THETAxPHI bin counts, e.g. 18x36"),
    (["--bins", "1x20"], r"bins must be 2 to 360 theta bins and 4 to 720 phi bins"),
    (["--count", "5"], r"count must be an integer from 100 to 100000000, got 5"),
    (["--lobe", "velvet"], r"lobe must be one of all, diffuse, specular, sheen, clearcoat, got 'velvet'"),
])
def test_cli_errors_are_one_line(tmp_path, materials_file, args, message):  # noqa: F811
    import re
    out = tmp_path / "s.png"
    r = run_cli("samples", "--materials", materials_file, *args, "--out", out)
    assert r.returncode == 2
    assert len(r.stderr.splitlines()) == 1 and r.stderr.startswith("brdfcl: error: "), r.stderr
    assert re.search(message, r.stderr), r.stderr
    assert not out.exists()
