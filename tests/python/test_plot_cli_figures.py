# The labelled figures of what the CLI writes without text: `brdfcl diff`'s picture and `brdfcl
# compare`'s heat maps. The CLI's PNGs are the field alone at its own size; brdfcl.plot.diff and
# compare(plane=...) draw the same numbers with titles, axes and colour bars.
import json
import subprocess
import sys

import numpy as np
import pytest

import brdfcl
from conftest import MATERIALS, ROOT

pytest.importorskip("matplotlib")
import matplotlib.image  # noqa: E402

from brdfcl import plot  # noqa: E402
from test_plot import check_png  # noqa: E402


@pytest.fixture(scope="module")
def renders(cli, tmp_path_factory):
    """Two renders of the spheres under the studio, B turned a little (docs/cli.md's example)."""
    d = tmp_path_factory.mktemp("diff")
    cli("render", "--size", "48x32", "--environment", "studio", "--out", d / "a.exr")
    cli("render", "--size", "48x32", "--environment", "studio", "--env-rotation", "0.3", "--out", d / "b.exr")
    return d


def test_cli_diff_picture_is_the_field_without_text(cli, renders):
    out = cli("diff", renders / "a.exr", renders / "b.exr", "--out", renders / "d.png", "--json")
    report = json.loads(out)
    png = matplotlib.image.imread(str(renders / "d.png"))
    assert png.shape[:2] == (32, 48)  # the image's size: no title, axes or colour bar round it
    # The figure draws the CLI's numbers: the same statistics, d from the same reader.
    fig, a = plot.diff(renders / "a.exr", renders / "b.exr", figsize=(4, 3), dpi=50)
    for key in ("pixels", "compared", "floor", "above_threshold", "relative", "absolute", "range"):
        assert a["stats"][key] == report[key], key
    assert a["relative"].shape == (32, 48)
    fig.savefig(renders / "fig.png")
    check_png(renders / "fig.png")
    # Arrays give the same numbers as the files they were read from.
    _, b = plot.diff(brdfcl.read_exr(renders / "a.exr"), brdfcl.read_exr(renders / "b.exr"), figsize=(4, 3), dpi=50)
    assert np.array_equal(b["relative"], a["relative"], equal_nan=True)
    assert b["stats"]["relative"] == a["stats"]["relative"]


def test_python_m_brdfcl_plot_diff(renders):
    out = renders / "cli-fig.png"
    r = subprocess.run([sys.executable, "-m", "brdfcl", "plot", "diff", renders / "a.exr", renders / "b.exr",
                        "--range", "0.5", "--figsize", "4x3", "--dpi", "50", "--out", out], capture_output=True,
                       text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    check_png(out)


def test_diff_errors(renders):
    with pytest.raises(brdfcl.InputError, match=r"^the images differ in shape"):
        plot.diff(np.zeros((4, 4, 3)), np.zeros((4, 5, 3)))
    with pytest.raises(brdfcl.InputError, match=r"^floor must be a finite number > 0"):
        plot.diff(renders / "a.exr", renders / "b.exr", floor=0.0)
    with pytest.raises(brdfcl.InputError, match=r"^a and b must both be"):
        plot.diff(renders / "a.exr", np.zeros((32, 48, 3)))
    with pytest.raises(brdfcl.InputError, match=r"missing.exr"):
        plot.diff(renders / "a.exr", renders / "missing.exr")


def test_cli_compare_maps_are_the_field_and_python_draws_both(cli, tmp_path):
    m = tmp_path / "m.json"
    m.write_text(json.dumps({"materials": MATERIALS[:1]}))
    cli("compare", "--materials", m, "--profile", "threejs", "--pairs", 1000, "--out", tmp_path / "maps")
    for plane in ("inplane", "halfdiff"):
        png = matplotlib.image.imread(str(tmp_path / "maps" / f"0_velvet_threejs_vs_spec_{plane}.png"))
        assert png.shape[:2] == (360, 360)  # 90 cells of 4 pixels, nothing else
        fig, a = plot.compare(MATERIALS, 0, profile="threejs", against="spec", plane=plane, resolution=90,
                              figsize=(4, 3), dpi=50)
        fig.savefig(tmp_path / f"{plane}.png")
        check_png(tmp_path / f"{plane}.png")
        L, V = a["L"].reshape(-1, 3), a["V"].reshape(-1, 3)
        assert np.array_equal(brdfcl.evaluate(MATERIALS[0], L, V, profile="threejs"), a["f_a"].reshape(-1, 3))
        # The CLI's map, rows from the top, is the Python field with theta_V (theta_d) rising upwards:
        # the same cells are blue, white and red.
        cells = png[2::4, 2::4, :3][::-1]
        redness = cells[..., 0] - cells[..., 2]
        assert np.corrcoef(redness.ravel(), a["log2_ratio"].ravel())[0, 1] > 0.9, plane
    assert set(a) >= {"theta_h_deg", "theta_d_deg"}
    with pytest.raises(brdfcl.InputError, match=r"^plane must be inplane or halfdiff"):
        plot.compare(MATERIALS, 0, plane="polar")
