"""Importance sampling (docs/sampling.md): brdfcl.sample draws directions with their pdf and
weight, brdfcl.pdf gives the density; the row and index checks they share."""
from __future__ import annotations

from typing import Any, Optional, Tuple, Union

import numpy as np

from . import _core
from ._core import InputError
from ._device import Evaluator, _evaluator
from ._inputs import MaterialsLike, _directions, _index, _materials, _output, _same_rows
from ._options import Options, _options


def _unit_rows(a: Any, name: str) -> np.ndarray:
    """(N, 3) float32 C-contiguous rows, finite and non-zero, as the sampling kernels read them."""
    arr = _directions(a, name).astype(np.float32, copy=False)
    bad = ~np.isfinite(arr).all(axis=1) | ~(arr != 0).any(axis=1)
    if bad.any():
        row = int(np.argmax(bad))
        raise InputError(f"{name} row {row} is not a finite non-zero direction: {arr[row].tolist()}")
    return np.ascontiguousarray(arr)


def _index32(material_index: Any, n: int, count: int) -> Optional[np.ndarray]:
    idx = _index(material_index, n, count)
    if idx is None:
        return None
    if idx.shape[0] != n:
        raise InputError(f"material_index must have one entry per row: {idx.shape[0]} for {n} rows")
    bad = (idx < 0) | (idx >= count)
    if bad.any():
        row = int(np.argmax(bad))
        raise InputError(f"row {row}: material index {int(idx[row])} out of range ({count} materials)")
    return idx.astype(np.uint32)


def sample(materials: MaterialsLike, V: Any, u: Any = None, *, material: Any = None, count: Optional[int] = None,
           seed: int = 0, options: Optional[Options] = None, lobe: Optional[str] = None,
           sheen_visibility: Optional[str] = None, sheen_distribution: Optional[str] = None,
           sheen_scaling: Optional[str] = None, profile: Optional[str] = None, strict: bool = False,
           device: Union[None, int, str, Evaluator] = None,
           out: Optional[np.ndarray] = None) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Importance-sampled directions, as `brdfcl sample`: returns (L, pdf, weight), float32 arrays
    of shapes (R, 3), (R,) and (R, 3). pdf is the mixture's density of L in solid angle and weight is
    f(L, V) N.L / pdf; all three are 0 in a row where no direction came out.

    V: (N, 3) views (N = +Z). u: (N, 3) uniforms in [0, 1) (u3 picks the lobe, u1 and u2 drive its
    sampler); or None with count=K: K rows per view (R = N K, each view repeated K times) from the
    counter-based generator with `seed`, the numbers `brdfcl sample --count K --seed S` uses.
    material: indices (N,) into materials (required with more than one). options and the option
    keywords as brdfcl.evaluate: lobe samples one lobe alone; profile changes the f of the weight only. out: a C-contiguous float32 (R, 7) array
    (Lx Ly Lz pdf wr wg wb) to fill; the returned arrays are views of it.
    """
    ev = _evaluator(device)
    opts = _options(options, ev.options, lobe=lobe, sheen_visibility=sheen_visibility,
                    sheen_distribution=sheen_distribution, sheen_scaling=sheen_scaling, profile=profile)._core
    m = _materials(materials, strict)
    Vd = _unit_rows(V, "V")
    idx = _index32(material, Vd.shape[0], len(m))
    if u is None:
        if count is None or isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
            raise InputError(f"give u (N, 3) uniforms, or count=K (a positive integer) to draw them; got count={count!r}")
        Vd = np.ascontiguousarray(np.repeat(Vd, int(count), axis=0))
        idx = None if idx is None else np.ascontiguousarray(np.repeat(idx, int(count)))
        ud = _core.draw_uniforms(int(seed), Vd.shape[0])
    else:
        if count is not None:
            raise InputError("count draws the uniforms, but u was given; give one or the other")
        ud = np.ascontiguousarray(np.asarray(u, dtype=np.float32))
        if ud.shape != Vd.shape:
            raise InputError(f"u must have shape {Vd.shape} (one row of u1 u2 u3 per view), got {ud.shape}")
        bad = ~((ud >= 0) & (ud < 1)).all(axis=1)
        if bad.any():
            row = int(np.argmax(bad))
            raise InputError(f"u row {row} must lie in [0, 1), got {ud[row].tolist()}")
    o = _output(out, (Vd.shape[0], 7), Vd, ud)
    _core.sample(ev._device, m, Vd, idx, ud, o, opts)
    return o[:, :3], o[:, 3], o[:, 4:]


def pdf(materials: MaterialsLike, L: Any, V: Any, material_index: Any = None, *,
        options: Optional[Options] = None, lobe: Optional[str] = None, sheen_visibility: Optional[str] = None,
        sheen_distribution: Optional[str] = None, sheen_scaling: Optional[str] = None,
        profile: Optional[str] = None, strict: bool = False, device: Union[None, int, str, Evaluator] = None,
        out: Optional[np.ndarray] = None) -> np.ndarray:
    """The density brdfcl.sample draws L with at V (solid angle of L), float32 (N,); 0 where N.L or
    N.V <= 0. Arguments as brdfcl.evaluate; out: a C-contiguous float32 (N,) array to fill."""
    ev = _evaluator(device)
    opts = _options(options, ev.options, lobe=lobe, sheen_visibility=sheen_visibility,
                    sheen_distribution=sheen_distribution, sheen_scaling=sheen_scaling, profile=profile)._core
    m = _materials(materials, strict)
    Ld, Vd = _unit_rows(L, "L"), _unit_rows(V, "V")
    _same_rows(Ld, Vd)
    idx = _index32(material_index, Ld.shape[0], len(m))
    o = _output(out, (Ld.shape[0],), Ld, Vd)
    _core.pdf(ev._device, m, Ld, Vd, idx, o, opts)
    return o
