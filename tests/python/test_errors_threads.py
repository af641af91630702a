# Bad input raises brdfcl.InputError (a brdfcl.Error and a ValueError) with the documented one-line message
# (docs/errors.md), and four threads evaluating at once give the serial results.
import threading

import numpy as np
import pytest

import brdfcl
from conftest import MATERIALS

M = {"pbrMetallicRoughness": {"roughnessFactor": 0.5}}
L = np.array([[0, 0, 1], [1, 0, 1]], np.float32)
V = np.array([[0, 0.5, 1], [0, 0, 1]], np.float32)


def raises(match, fn, *a, **k):
    with pytest.raises(brdfcl.Error, match=match) as e:
        fn(*a, **k)
    assert isinstance(e.value, ValueError)


def test_nan_and_zero_directions():
    raises(r"^row 1: field 'Vy' is not finite: nan$", brdfcl.evaluate, M, L, [[0, 0, 1], [0, np.nan, 1]])
    raises(r"^row 0: L has zero length$", brdfcl.evaluate, M, [[0, 0, 0]], [[0, 0, 1]])


def test_shape_and_dtype():
    raises(r"^L must have shape \(N, 3\), got \(2, 4\)$", brdfcl.evaluate, M, np.zeros((2, 4)), V)
    raises(r"^V must have shape \(N, 3\), got \(3,\)$", brdfcl.evaluate, M, L[:1], [0, 0, 1])
    raises(r"^L must hold real numbers \(float32 or float64\), got dtype complex128$", brdfcl.evaluate, M,
           L.astype(complex), V)
    raises(r"^L and V must have the same number of rows, got 2 and 1$", brdfcl.evaluate, M, L, V[:1])


def test_out_array():
    """out= is filled and returned, with the bits of a fresh result; a wrong array is refused."""
    rng = np.random.default_rng(3)
    Ls = rng.random((1000, 3), dtype=np.float32) + np.float32(0.01)
    Vs = rng.random((1000, 3), dtype=np.float32) + np.float32(0.01)
    idx = rng.integers(0, len(MATERIALS), 1000)
    out = np.full((1000, 3), -1, np.float32)
    assert brdfcl.evaluate(MATERIALS, Ls, Vs, idx, out=out) is out
    assert np.array_equal(out.view(np.uint32), brdfcl.evaluate(MATERIALS, Ls, Vs, idx).view(np.uint32))
    grid = np.empty((len(MATERIALS), 1000, 3), np.float32)
    assert brdfcl.evaluate_grid(MATERIALS, Ls, Vs, out=grid) is grid
    assert np.array_equal(grid.view(np.uint32), brdfcl.evaluate_grid(MATERIALS, Ls, Vs).view(np.uint32))
    raises(r"^out must have shape \(2, 3\), got \(3, 3\)$", brdfcl.evaluate, M, L, V, out=np.empty((3, 3), np.float32))
    raises(r"^out must be a writeable C-contiguous float32 array, got float64", brdfcl.evaluate, M, L, V,
           out=np.empty((2, 3)))
    raises(r"^out must be a writeable C-contiguous float32 array, got float32 \(not C-contiguous\)$",
           brdfcl.evaluate, M, L, V, out=np.empty((3, 2), np.float32).T)
    raises(r"^out must be a numpy array, got list$", brdfcl.evaluate, M, L, V, out=[[0, 0, 0], [0, 0, 0]])
    both = np.array([[0, 0, 1], [1, 0, 1]], np.float32)
    raises(r"^out must not overlap L or V; pass a separate array$", brdfcl.evaluate, M, both, V, out=both)


def test_material_index():
    raises(r"^3 materials but no material_index", brdfcl.evaluate, MATERIALS, L, V)
    raises(r"^row 1: material index 3 out of range \(3 materials\)$", brdfcl.evaluate, MATERIALS, L, V, [0, 3])
    raises(r"^row 0: material index -1 is not a non-negative integer$", brdfcl.evaluate, MATERIALS, L, V, [-1, 0])
    raises(r"^row 1: material index 0.5 is not a non-negative integer$", brdfcl.evaluate, MATERIALS, L, V, [0, 0.5])


def test_bad_material_key_and_value():
    bad_key = {"pbrMetallicRoughness": {"roughnesFactor": 0.5}}
    with pytest.warns(brdfcl.BrdfclWarning, match="did you mean roughnessFactor"):
        brdfcl.evaluate(bad_key, L, V)
    raises(r"^<materials>: materials\[0\]\.pbrMetallicRoughness\.roughnesFactor: .*did you mean roughnessFactor",
           brdfcl.evaluate, bad_key, L, V, strict=True)
    raises(r"^<materials>: materials\[0\]\.pbrMetallicRoughness\.roughnessFactor: ", brdfcl.evaluate,
           {"pbrMetallicRoughness": {"roughnessFactor": 2}}, L, V)
    raises(r"^<materials>: NaN and infinities are not valid material values", brdfcl.evaluate,
           {"pbrMetallicRoughness": {"roughnessFactor": float("nan")}}, L, V)
    raises(r"^materials must be a glTF material dict", brdfcl.evaluate, 3, L, V)


def test_unknown_option_values():
    raises(r"^unknown lobe= value 'specularr'; use all, diffuse, specular, sheen or clearcoat$", brdfcl.evaluate, M, L,
           V, lobe="specularr")
    raises(r"^unknown profile= value 'unreal'", brdfcl.evaluate, M, L, V, profile="unreal")
    raises(r"^unknown sheen_scaling= value 'max'", brdfcl.evaluate, M, L, V, sheen_scaling="max")
    raises(r"^sheen_visibility= applies to profile='spec' only; profile='threejs' uses its engine's own sheen",
           brdfcl.evaluate, M, L, V, profile="threejs", sheen_visibility="ashikhmin")
    raises(r"^unknown kind= value 'dfg'", brdfcl.lut, "dfg")
    raises(r"^sheen_visibility applies to kind 'sheen-e' only", brdfcl.lut, "ggx-dfg", sheen_visibility="charlie")
    raises(r"out of range; use 2 to 4096", brdfcl.lut, "ggx-dfg", 1)
    raises(r"^unknown built-in scene 'cubes'; use spheres$", brdfcl.render, scene="cubes", size=(8, 8))
    raises(r"^spp= applies to glTF assets \(the spheres are shaded at pixel centres\); add gltf=FILE$", brdfcl.render,
           size=(8, 8), spp=2)


def test_four_threads_equal_serial():
    rng = np.random.default_rng(7)
    n = 200_000
    Ls = [rng.normal(size=(n, 3)).astype(np.float32) for _ in range(4)]
    Vs = [np.abs(rng.normal(size=(n, 3))).astype(np.float32) for _ in range(4)]
    idx = [rng.integers(0, len(MATERIALS), size=n) for _ in range(4)]
    profiles = ["spec", "filament", "spec", "threejs"]
    serial = [brdfcl.evaluate(MATERIALS, Ls[k], Vs[k], idx[k], profile=profiles[k]) for k in range(4)]
    results = [None] * 4
    errors = []

    def work(k):
        try:
            results[k] = brdfcl.evaluate(MATERIALS, Ls[k], Vs[k], idx[k], profile=profiles[k])
        except Exception as e:  # noqa: BLE001 -- reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    for k in range(4):
        assert np.array_equal(results[k].view(np.uint32), serial[k].view(np.uint32))
