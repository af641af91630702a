# brdfcl.plot and `python -m brdfcl plot`: every kind writes a PNG of figsize x dpi pixels that is
# not blank, through the function and through the shell; the arrays returned (and drawn) equal
# brdfcl.evaluate / albedo / lut / render called directly; bad CLI input exits 2, one line, no file.
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import brdfcl
from conftest import MATERIALS, ROOT

pytest.importorskip("matplotlib")
import matplotlib.image  # noqa: E402
from matplotlib.image import AxesImage  # noqa: E402

from brdfcl import plot  # noqa: E402

SIZE = dict(figsize=(4, 3), dpi=50)  # 200 x 150 pixels
RES = {"lobe": 61, "halfdiff": 24, "albedo": 8, "compare": 24}
COAT = 1  # MATERIALS[1]: clearcoat over a red dielectric


def u32(a):
    return np.ascontiguousarray(a, dtype=np.float32).view(np.uint32)


def check_png(path, width=200, height=150):
    """The PNG has the expected size and is a drawing, not a blank canvas with a title: a good
    part of its pixels are neither white nor black text, in many colours."""
    img = matplotlib.image.imread(str(path))
    assert img.shape[:2] == (height, width), f"{path}: {img.shape}"
    rgb = img[..., :3].reshape(-1, 3)
    assert rgb.std() > 0.05
    coloured = np.ptp(rgb, axis=1) > 0.1  # chroma: not white, grey or black
    assert coloured.mean() > 0.01, f"{path}: only {coloured.mean():.3f} of the pixels are coloured"
    assert len(np.unique((rgb * 255).astype(np.uint8), axis=0)) > 50


def run_cli(*args, cwd=ROOT):
    return subprocess.run([sys.executable, "-m", "brdfcl", "plot", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd)


@pytest.fixture(scope="module")
def materials_file(tmp_path_factory):
    p = tmp_path_factory.mktemp("m") / "m.json"
    p.write_text(json.dumps({"materials": MATERIALS}))
    return p


def test_import_brdfcl_leaves_matplotlib_alone():
    code = "import sys, brdfcl; assert 'matplotlib' not in sys.modules; brdfcl.plot.lobe; print('ok')"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr


def test_lobe(tmp_path):
    p = plot.lobe(MATERIALS, COAT, view_angles=(20, 60), resolution=RES["lobe"], radius="log", **SIZE)
    p.save(tmp_path / "lobe.png")
    check_png(tmp_path / "lobe.png")
    fig, a = p  # unpacks
    assert a["L"].shape == (2, 61, 3) and a["theta_l_deg"][0] == -90 and a["theta_l_deg"][-1] == 90
    total = 0
    for lobe in brdfcl.LOBES:
        f = brdfcl.evaluate(MATERIALS[COAT], a["L"].reshape(-1, 3), a["V"].reshape(-1, 3), lobe=lobe)
        assert np.array_equal(u32(f), u32(a[f"f_{lobe}"].reshape(-1, 3))), lobe
        if lobe != "all":
            total = total + a[f"r_{lobe}"]
    # The stacked lobes add up to the total, and the total is drawn: the black line of each axes.
    assert np.allclose(total, a["r_all"], rtol=1e-4, atol=1e-7)
    cos_l = np.cos(np.radians(a["theta_l_deg"]))
    y = a["f_all"].astype(np.float64) @ [0.2126, 0.7152, 0.0722]
    assert np.allclose(a["r_all"], y * np.clip(cos_l, 0, None))
    for k, ax in enumerate(fig.axes):  # log radius: log10(r / (1e-4 peak)), floored at 0
        line = [ln for ln in ax.get_lines() if ln.get_label() == "total"][0]
        lo = a["r_all"][k].max() * 1e-4
        assert np.allclose(line.get_ydata(), np.log10(np.maximum(a["r_all"][k], lo) / lo))
    linear = plot.lobe(MATERIALS, 0, view_angles=(30,), resolution=RES["lobe"], **SIZE)
    line = [ln for ln in linear.figure.axes[0].get_lines() if ln.get_label() == "total"][0]
    assert np.array_equal(line.get_ydata(), linear.arrays["r_all"][0])
    # V lies at +θ_V: the specular peak of the coat is at the mirror direction, -θ_V.
    peak = a["theta_l_deg"][np.argmax(a["r_specular"][1] + a["r_clearcoat"][1])]
    assert abs(peak + 60) <= 3


def test_halfdiff(tmp_path):
    fig, a = plot.halfdiff(MATERIALS, COAT, resolution=RES["halfdiff"], **SIZE)
    fig.savefig(tmp_path / "hd.png")
    check_png(tmp_path / "hd.png")
    f = brdfcl.evaluate(MATERIALS[COAT], a["L"].reshape(-1, 3), a["V"].reshape(-1, 3))
    assert np.array_equal(u32(f), u32(a["f"].reshape(-1, 3)))
    # Rusinkiewicz: H = normalize(L + V) = (sin θ_h, 0, cos θ_h) and the angle from H to L is θ_d.
    L, V = a["L"].astype(np.float64), a["V"].astype(np.float64)
    H = (L + V) / np.linalg.norm(L + V, axis=-1, keepdims=True)
    th, td = np.meshgrid(np.radians(a["theta_h_deg"]), np.radians(a["theta_d_deg"]))
    assert np.allclose(H, np.stack([np.sin(th), 0 * th, np.cos(th)], axis=-1), atol=1e-6)
    assert np.allclose(np.arccos(np.clip((H * L).sum(-1), -1, 1)), td, atol=1e-3)
    image = [c for c in fig.axes[0].get_children() if isinstance(c, AxesImage)][0]
    assert np.array_equal(np.ma.getdata(image.get_array()), a["value"])
    # Only the cells where f is 0 are masked (grey): the coat is positive everywhere on the slice.
    assert np.array_equal(np.ma.getmaskarray(image.get_array()), ~(a["value"] > 0)) and np.all(a["value"] > 0)
    assert image.norm.__class__.__name__ == "LogNorm" and fig.axes[0].get_xlabel() == "θ_h (degrees)"


def test_albedo(tmp_path):
    fig, a = plot.albedo(MATERIALS, 0, resolution=RES["albedo"], **SIZE)
    fig.savefig(tmp_path / "al.png")
    check_png(tmp_path / "al.png")
    direct = brdfcl.albedo(MATERIALS[0], a["cos_theta_v"])
    for lobe in brdfcl.LOBES:
        assert np.array_equal(u32(direct[lobe]), u32(a[f"albedo_{lobe}"])), lobe
    assert np.allclose(a["cos_theta_v"], np.cos(np.radians(a["theta_v_deg"])))
    total = [ln for ln in fig.axes[0].get_lines() if ln.get_label() == "total (all)"][0]
    assert np.array_equal(total.get_ydata(), a["value_all"])
    # The total stays see-through over a lobe equal to it (a metal's specular): dashed, on top,
    # and every lobe carries markers.
    lines = {ln.get_label(): ln for ln in fig.axes[0].get_lines()}
    assert total.get_linestyle() != "-" and total.get_marker() in ("None", "", None)
    for lobe in brdfcl.LOBES[1:]:
        assert lines[lobe].get_marker() not in ("None", "", None), lobe
        assert lines[lobe].get_zorder() < total.get_zorder(), lobe
        assert lines[lobe].get_linewidth() > total.get_linewidth(), lobe


def test_sheen_e(tmp_path):
    fig, a = plot.sheen_e(size=32, sheen_visibility="ashikhmin", **SIZE)
    fig.savefig(tmp_path / "se.png")
    check_png(tmp_path / "se.png")
    assert np.array_equal(u32(a["E"]), u32(brdfcl.lut("sheen-e", 32, sheen_visibility="ashikhmin")))
    assert a["cos_theta_v"][0] == 1e-4 and a["roughness"][-1] == 1
    image = [c for c in fig.axes[0].get_children() if isinstance(c, AxesImage)][0]
    assert np.array_equal(image.get_array(), a["E"])


def test_compare(tmp_path):
    fig, a = plot.compare(MATERIALS, 0, profile="threejs", against="spec", resolution=RES["compare"], **SIZE)
    fig.savefig(tmp_path / "cmp.png")
    check_png(tmp_path / "cmp.png")
    L, V = a["L"].reshape(-1, 3), a["V"].reshape(-1, 3)
    assert np.array_equal(u32(brdfcl.evaluate(MATERIALS[0], L, V, profile="threejs")), u32(a["f_a"].reshape(-1, 3)))
    assert np.array_equal(u32(brdfcl.evaluate(MATERIALS[0], L, V, profile="spec")), u32(a["f_b"].reshape(-1, 3)))
    y = lambda f: f.astype(np.float64) @ [0.2126, 0.7152, 0.0722]  # noqa: E731
    expected = np.log2(np.maximum(y(a["f_a"]), a["floor"]) / np.maximum(y(a["f_b"]), a["floor"]))
    assert np.allclose(a["log2_ratio"], expected, equal_nan=True)
    assert np.nanmax(np.abs(a["log2_ratio"])) > 0  # the profiles differ for a sheen material
    # A profile against itself: ratio 0 everywhere.
    _, same = plot.compare(MATERIALS, 0, profile="spec", against="spec", resolution=4, **SIZE)
    assert np.array_equal(same["log2_ratio"], np.zeros((4, 4)))


def test_image_equals_cli_png(cli, tmp_path):
    p = plot.image(size=(64, 48), exposure=1.0, **SIZE)
    p.save(tmp_path / "img.png")
    check_png(tmp_path / "img.png")
    rendered = brdfcl.render(size=(64, 48))
    assert np.array_equal(u32(rendered), u32(p.arrays["radiance"]))
    # tone_map is `brdfcl render`'s PNG pipeline, the library's own: the same 8-bit values.
    cli("render", "--size", "64x48", "--exposure", "1", "--out", tmp_path / "cli.png")
    png = matplotlib.image.imread(str(tmp_path / "cli.png"))[..., :3]
    assert np.array_equal(np.round(png * 255), np.round(p.arrays["display"] * 255))
    # An array given is drawn as it is, and the Plot shows inline as a PNG.
    again = plot.image(rendered, exposure=1.0, figsize=(2, 2), dpi=40)
    assert np.array_equal(again.arrays["display"], p.arrays["display"])
    assert again._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"


CLI_CASES = {
    "lobe": ["--material", COAT, "--view-angles", "10,50", "--resolution", 31, "--radius", "log"],
    "halfdiff": ["--material", COAT, "--resolution", 16, "--lobe", "specular"],
    "albedo": ["--resolution", 6],
    "sheen-e": ["--size", 16],
    "compare": ["--profile", "filament", "--resolution", 16],
    "image": ["--size", "40x30", "--exposure", "0.5"],
    "samples": ["--count", 20000, "--bins", "9x18", "--view", "50,20"],
}


@pytest.mark.parametrize("kind", [k for k in plot.KINDS if k != "diff"])  # diff: test_plot_cli_figures.py
def test_cli_writes_each_kind(tmp_path, materials_file, kind):
    out = tmp_path / f"{kind}.png"
    mats = [] if kind in ("sheen-e", "image") else ["--materials", materials_file]
    r = run_cli(kind, *mats, *CLI_CASES[kind], "--figsize", "4x3", "--dpi", 50, "--out", out)
    assert r.returncode == 0, r.stderr
    check_png(out)
    assert [p.name for p in tmp_path.iterdir()] == [out.name]  # no temporary file left
    umask = os.umask(0)
    os.umask(umask)
    assert out.stat().st_mode & 0o777 == 0o666 & ~umask  # as any new file, not mkstemp's 0600


def test_cli_warns_in_one_line(tmp_path):
    typo = tmp_path / "typo.json"
    typo.write_text(json.dumps({"materials": [{"pbrMetallicRoughness": {"roughnesFactor": 0.5}}]}))
    r = run_cli("albedo", "--materials", typo, "--resolution", 3, "--out", tmp_path / "a.png")
    assert r.returncode == 0, r.stderr
    assert len(r.stderr.splitlines()) == 1 and r.stderr.startswith("brdfcl: warning: "), r.stderr
    assert "did you mean roughnessFactor" in r.stderr


def test_cli_svg_and_pdf(tmp_path, materials_file):
    for ext, magic in ((".svg", b"<?xml"), (".pdf", b"%PDF")):
        out = tmp_path / f"a{ext}"
        r = run_cli("albedo", "--materials", materials_file, "--resolution", 4, "--out", out)
        assert r.returncode == 0, r.stderr
        assert out.read_bytes()[:5].startswith(magic)


@pytest.mark.parametrize("args, message", [
    (["contour", "--out", "x.png"], r"argument KIND: invalid choice: 'contour'"),
    (["albedo", "--materials", "{m}", "--out", "x.jpg"], r"--out 'x.jpg' must end in .png, .svg or .pdf"),
    (["albedo", "--materials", "{m}", "--material", "7", "--out", "x.png"], r"material 7 is out of range: "
     r"there are 3 materials; use 0 to 2"),
    (["albedo", "--materials", "{m}", "--bogus", "--out", "x.png"], r"unrecognized arguments: --bogus"),
    (["albedo", "--out", "x.png"], r"the following arguments are required: --materials"),
    (["sheen-e", "--lobe", "all", "--out", "x.png"], r"unrecognized arguments: --lobe all"),
    (["lobe", "--materials", "{m}", "--profile", "unreal", "--out", "x.png"], r"--profile"),
    (["lobe", "--materials", "{m}", "--view-angles", "0,95", "--out", "x.png"], r"view_angles must be"),
    (["albedo", "--materials", "{d}/missing.json", "--out", "x.png"], r"missing.json"),
])
def test_cli_errors(tmp_path, materials_file, args, message):
    args = [a.format(m=materials_file, d=tmp_path) for a in args]
    r = run_cli(*args, cwd=tmp_path)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("brdfcl: error: "), r.stderr
    assert __import__("re").search(message, lines[0]), lines[0]
    assert list(tmp_path.iterdir()) == [], "an output (or temporary) file was left"


def test_bad_arguments_raise_error():
    with pytest.raises(brdfcl.Error, match=r"^material 3 is out of range"):
        plot.albedo(MATERIALS, 3)
    with pytest.raises(brdfcl.Error, match=r"^ax holds one polar plot"):
        import matplotlib.figure

        plot.lobe(MATERIALS, 0, view_angles=(0, 30), ax=matplotlib.figure.Figure().add_subplot(projection="polar"))
    with pytest.raises(brdfcl.Error, match=r"^channel must be one of"):
        plot.halfdiff(MATERIALS, 0, resolution=2, channel="alpha")
    with pytest.raises(brdfcl.Error, match=r"^exposure must be a finite number"):
        plot.tone_map(np.zeros((2, 2, 3)), math.inf)
