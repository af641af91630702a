# brdfcl.shade with a dict G-buffer is checked and warned about as `brdfcl shade` checks and warns
# about a G-buffer file: the same range-check messages (check=True) and the same camera warning.
import json
import subprocess
import warnings

import numpy as np
import pytest

import brdfcl

SCENE = {"lights": [{"type": "directional", "direction": [0, -1, -1], "intensity": 2}]}


def gbuffer(h=4, w=6):
    """A small G-buffer without a camera and without V: a plane facing +Z at z = 0."""
    ys, xs = np.mgrid[0:h, 0:w].astype(np.float32)
    return {
        "P": np.stack([xs, ys, np.zeros_like(xs)], axis=-1),
        "N": np.broadcast_to(np.float32([0, 0, 1]), (h, w, 3)).copy(),
        "baseColor": np.full((h, w, 3), 0.5, np.float32),
        "metallic": np.zeros((h, w), np.float32),
        "roughness": np.full((h, w), 0.5, np.float32),
        "mask": np.ones((h, w), np.float32),
    }


@pytest.mark.parametrize("channel, pixel, value", [
    ("baseColor", (1, 2, 1), 1.5),   # a factor above 1
    ("roughness", (3, 0), -0.25),    # below 0
    ("N", (0, 4, 0), 0.5),           # a normal of length sqrt(1.25)
])
def test_dict_range_check_same_message_as_file(tmp_path, channel, pixel, value):
    g = gbuffer()
    g[channel][pixel] = value
    path = tmp_path / "g.exr"
    brdfcl.write_gbuffer(path, g)
    with pytest.raises(brdfcl.Error) as from_file:
        brdfcl.read_gbuffer(path)
    with pytest.raises(brdfcl.Error) as from_dict:
        brdfcl.shade(g, SCENE)
    assert "--" not in str(from_file.value)  # a Python caller's message names check=False, not --no-check
    expected = str(from_file.value).replace(str(path), "<gbuffer>")
    assert str(from_dict.value) == expected
    assert str(from_dict.value).startswith(f"<gbuffer>: pixel ({pixel[1]}, {pixel[0]}): ")
    # A pixel the mask leaves uncovered is not checked; check=False skips the check.
    g["mask"][pixel[:2]] = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", brdfcl.BrdfclWarning)
        brdfcl.shade(g, SCENE, ibl_samples=16)
        g["mask"][pixel[:2]] = 1
        assert brdfcl.shade(g, SCENE, check=False).shape == (4, 6, 3)


def test_camera_warning_as_cli(cli, tmp_path):
    g = gbuffer()
    brdfcl.write_gbuffer(tmp_path / "g.exr", g)
    (tmp_path / "scene.json").write_text(json.dumps(SCENE))
    r = subprocess.run([str(cli.path), "shade", "--gbuffer", str(tmp_path / "g.exr"), "--scene",
                        str(tmp_path / "scene.json"), "--out", str(tmp_path / "s.exr")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    cli_warnings = [ln[len("brdfcl: warning: "):] for ln in r.stderr.splitlines() if ln.startswith("brdfcl: warning: ")]
    assert len(cli_warnings) == 1 and "has a camera" in cli_warnings[0]
    with pytest.warns(brdfcl.BrdfclWarning) as from_paths:
        brdfcl.shade(tmp_path / "g.exr", tmp_path / "scene.json")
    assert [str(w.message) for w in from_paths] == cli_warnings
    with pytest.warns(brdfcl.BrdfclWarning) as from_dicts:
        brdfcl.shade(g, SCENE)
    expected = cli_warnings[0].replace(str(tmp_path / "scene.json"), "<scene>").replace(str(tmp_path / "g.exr"),
                                                                                         "<gbuffer>")
    assert [str(w.message) for w in from_dicts] == [expected]
    # With a per-pixel V there is nothing to warn about.
    g["V"] = g["N"].copy()
    with warnings.catch_warnings():
        warnings.simplefilter("error", brdfcl.BrdfclWarning)
        brdfcl.shade(g, SCENE)
