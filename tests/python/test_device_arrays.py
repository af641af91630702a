# brdfcl.DeviceArray: rows kept in device memory between calls give the numpy call's bytes, chain
# from one call to the next, and are refused with a clear message when they are of the wrong
# shape, dtype or device; the pinned staging path (BRDFCL_STAGING=1) gives the same bytes as the
# in-place one at chunk boundaries.
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import brdfcl
from conftest import MATERIALS, ROOT


def rows(n, seed=3):
    rng = np.random.default_rng(seed)
    L = (rng.random((n, 3), dtype=np.float32) - np.float32(0.5)) * 3
    V = (rng.random((n, 3), dtype=np.float32) - np.float32(0.5)) * 3
    L[:, 2] = np.abs(L[:, 2]) + np.float32(0.01)
    V[:, 2] = np.abs(V[:, 2]) + np.float32(0.01)
    return L, V, rng.integers(0, len(MATERIALS), size=n)


@pytest.fixture(scope="module")
def ev():
    return brdfcl.Evaluator()


@pytest.mark.parametrize("n", [0, 1, 17, 5000])
def test_device_rows_give_the_numpy_calls_bytes(ev, n):
    L, V, idx = rows(n)
    want = ev.evaluate(MATERIALS, L, V, idx)
    got = ev.evaluate(MATERIALS, ev.to_device(L), ev.to_device(V), ev.to_device(idx))
    assert isinstance(got, brdfcl.DeviceArray)
    assert got.shape == (n, 3) and got.dtype == np.float32
    assert np.array_equal(got.numpy().view(np.uint32), want.view(np.uint32))


def test_results_chain_on_the_device_and_fill_out(ev):
    L, V, _ = rows(1000)
    m = MATERIALS[:1]
    Ld, Vd = ev.to_device(L), ev.to_device(V)
    first = ev.evaluate(m, Ld, Vd)
    out = ev.device_array((1000, 3))
    assert ev.evaluate(m, Ld, first, out=out) is out
    want = ev.evaluate(m, L, ev.evaluate(m, L, V))
    assert np.array_equal(out.numpy().view(np.uint32), want.view(np.uint32))


def test_refusals_name_the_argument(ev):
    L, V, idx = rows(10)
    Ld, Vd = ev.to_device(L), ev.to_device(V)
    with pytest.raises(brdfcl.InputError, match=r"^V must be a brdfcl.DeviceArray when the other inputs are"):
        ev.evaluate(MATERIALS[:1], Ld, V)
    with pytest.raises(brdfcl.InputError, match=r"^3 materials but no material_index"):
        ev.evaluate(MATERIALS, Ld, Vd)
    with pytest.raises(brdfcl.InputError, match=r"^material_index must be a uint32 device array of shape \(10\), got float32 \(10, 3\)"):
        ev.evaluate(MATERIALS, Ld, Vd, Vd)
    with pytest.raises(brdfcl.InputError, match=r"^out must not be L or V"):
        ev.evaluate(MATERIALS[:1], Ld, Vd, out=Vd)
    with pytest.raises(brdfcl.InputError, match=r"^V must be a float32 device array of shape \(10, 3\), got float32 \(9, 3\)"):
        ev.evaluate(MATERIALS[:1], Ld, ev.to_device(V[:9]))
    with pytest.raises(brdfcl.InputError, match=r"^to_device takes \(N, 3\) directions or \(N,\) integer material indices"):
        ev.to_device(np.zeros((4, 2)))
    with pytest.raises(brdfcl.InputError, match=r"^row 1: material index -1 does not fit a uint32"):
        ev.to_device(np.array([0, -1]))
    other = brdfcl.Evaluator()
    with pytest.raises(brdfcl.InputError, match=r"^L lives on another Evaluator's device"):
        ev.evaluate(MATERIALS[:1], other.to_device(L), Vd)


def test_bad_rows_are_worded_as_the_library_words_them(ev):
    L, V, idx = rows(50)
    idx[7] = 9
    with pytest.raises(brdfcl.InputError, match=r"^sample 7: material index 9 out of range \(3 materials\)$"):
        ev.evaluate(MATERIALS, ev.to_device(L), ev.to_device(V), ev.to_device(idx))


STAGED = textwrap.dedent("""
    import sys
    import numpy as np
    import brdfcl
    sys.path.insert(0, sys.argv[1])
    from conftest import MATERIALS
    rng = np.random.default_rng(9)
    out = []
    for n in (0, 1, 17, 300000):
        L = rng.random((n, 3), dtype=np.float32) + np.float32(0.01)
        V = rng.random((n, 3), dtype=np.float32) + np.float32(0.01)
        idx = rng.integers(0, len(MATERIALS), size=n)
        out.append(brdfcl.evaluate(MATERIALS, L, V, idx))
        out.append(brdfcl.evaluate_grid(MATERIALS, L[:1000], V[:1000]))
        u = rng.random((n, 3), dtype=np.float32) * np.float32(0.999)
        out.extend(brdfcl.sample(MATERIALS, V, u, material=idx))
        out.append(brdfcl.pdf(MATERIALS, L, V, idx))
    np.savez(sys.argv[2], *out)
""")


def test_staged_rows_give_the_in_place_bytes(tmp_path):
    results = []
    for staging in ("0", "1"):
        path = tmp_path / f"staging{staging}.npz"
        env = dict(os.environ, BRDFCL_STAGING=staging)
        r = subprocess.run([sys.executable, "-c", STAGED, str(ROOT / "tests" / "python"), str(path)], env=env,
                           capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, r.stderr
        results.append(np.load(path))
    for key in results[0].files:
        assert np.array_equal(results[0][key].view(np.uint32), results[1][key].view(np.uint32)), key
