"""The argument checks and conversions of brdfcl's functions: materials (dicts, lists, files),
direction rows, out arrays, material indices, integers and G-buffers; BrdfclWarning and _warn."""
from __future__ import annotations

import json
import os
import warnings
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._core import InputError


PathLike = Union[str, "os.PathLike[str]"]
MaterialsLike = Union[PathLike, Mapping[str, Any], Sequence[Mapping[str, Any]], "_core.Materials"]


class BrdfclWarning(UserWarning):
    """A warning of the materials or glTF reader (an unknown key, an ignored extension): the
    CLI prints these as "brdfcl: warning: ..."."""


def _warn(lines: Sequence[str]) -> None:
    for line in lines:
        warnings.warn(line, BrdfclWarning, stacklevel=4)


def _materials(materials: Any, strict: bool) -> "_core.Materials":
    """The materials as the CLI's --materials reader reads them (KHR_materials_ior included)."""
    if isinstance(materials, _core.Materials):
        return materials
    if isinstance(materials, (str, os.PathLike)):
        m = _core.read_materials(os.fspath(materials), bool(strict))
    else:
        if isinstance(materials, Mapping):
            doc = materials if "materials" in materials else {"materials": [materials]}
        elif isinstance(materials, (list, tuple)):
            doc = {"materials": list(materials)}
        else:
            raise InputError(
                "materials must be a glTF material dict, a list of them, a dict with \"materials\" or a "
                f"path to a JSON file, got {type(materials).__name__}")
        try:
            text = json.dumps(doc, allow_nan=False, default=_json_default)
        except ValueError:
            raise InputError("<materials>: NaN and infinities are not valid material values (JSON has none); "
                        "use numbers in the glTF ranges") from None
        m = _core.parse_materials(text, "<materials>", bool(strict))
    _warn(m.warnings)
    return m


def _json_default(o: Any) -> Any:
    # numpy scalars and arrays in material dicts (np.float32(0.5), np.array([1, 0, 0])).
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    raise TypeError(f"{type(o).__name__} is not a JSON value")


def _directions(a: Any, name: str) -> np.ndarray:
    """(N, 3) float32 or float64, C-contiguous and native: such arrays are used as they are (no
    copy); other number types are converted to float64 (exact for every integer up to 2**53)."""
    arr = np.asarray(a)
    if arr.dtype != np.float32 and arr.dtype != np.float64:
        if arr.dtype.kind not in "fiu":
            raise InputError(f"{name} must hold real numbers (float32 or float64), got dtype {arr.dtype}")
        arr = arr.astype(np.float64)
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise InputError(f"{name} must have shape (N, 3), got {tuple(arr.shape)}")
    return np.ascontiguousarray(arr)


def _same_rows(L: np.ndarray, V: np.ndarray) -> None:
    """L and V hold one direction pair a row."""
    if L.shape[0] != V.shape[0]:
        raise InputError(f"L and V must have the same number of rows, got {L.shape[0]} and {V.shape[0]}")


def _output(out: Optional[np.ndarray], shape: Tuple[int, ...], L: np.ndarray, V: np.ndarray) -> np.ndarray:
    """A fresh float32 result array of `shape`, or the caller's `out` once it is checked to be one
    that does not overlap the directions (the device reads them while it writes out)."""
    if out is None:
        return np.empty(shape, dtype=np.float32)
    if not isinstance(out, np.ndarray):
        raise InputError(f"out must be a numpy array, got {type(out).__name__}")
    if out.dtype != np.float32 or not out.flags.c_contiguous or not out.flags.writeable:
        raise InputError(f"out must be a writeable C-contiguous float32 array, got {out.dtype} "
                    f"({'C-contiguous' if out.flags.c_contiguous else 'not C-contiguous'}"
                    f"{'' if out.flags.writeable else ', read-only'})")
    if out.shape != tuple(shape):
        raise InputError(f"out must have shape {tuple(shape)}, got {out.shape}")
    if np.may_share_memory(out, L) or np.may_share_memory(out, V):
        raise InputError("out must not overlap L or V; pass a separate array")
    return out


def _index(material_index: Any, n: int, count: int) -> Optional[np.ndarray]:
    if material_index is None:
        if count != 1:
            raise InputError(f"{count} materials but no material_index; give one index per sample "
                        "(an int array of shape (N,))")
        return None
    idx = np.asarray(material_index)
    if idx.ndim != 1:
        raise InputError(f"material_index must have shape (N,), got {tuple(idx.shape)}")
    if idx.dtype.kind == "f":
        bad = ~(np.isfinite(idx) & (np.floor(idx) == idx) & (idx >= 0))
        if bad.any():
            row = int(np.argmax(bad))
            raise InputError(f"row {row}: material index {float(idx[row]):g} is not a non-negative integer")
        idx = idx.astype(np.int64)
    elif idx.dtype.kind == "u":
        if idx.size and idx.max() > np.iinfo(np.int64).max:
            row = int(np.argmax(idx > np.iinfo(np.int64).max))
            raise InputError(f"row {row}: material index {int(idx[row])} out of range ({count} materials)")
        idx = idx.astype(np.int64)
    elif idx.dtype.kind != "i":
        raise InputError(f"material_index must hold integers, got dtype {idx.dtype}")
    return np.ascontiguousarray(idx, dtype=np.int64)


def _int(v: Any, name: str) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
        raise InputError(f"{name} must be an integer, got {v!r}")
    return int(v)


_GBUFFER_NAME = "<gbuffer>"  # how messages name a G-buffer given as a dict


def _gbuffer(gbuffer: Any, check: bool) -> "_core.GBuffer":
    if isinstance(gbuffer, (str, os.PathLike)):
        return _core.read_gbuffer(os.fspath(gbuffer), bool(check))
    if isinstance(gbuffer, Mapping):
        channels: Dict[str, Any] = {}
        for k, v in gbuffer.items():
            channels[str(k)] = v if k == "camera" else np.ascontiguousarray(v, dtype=np.float32)
        g = _core.gbuffer_from_dict(channels)
        if check:
            # The range checks a G-buffer file gets (factors in [0, 1], unit normals), same words.
            _core.check_gbuffer(g, _GBUFFER_NAME)
        return g
    raise InputError(f"gbuffer must be a path to a G-buffer EXR or a dict of channel arrays, got {type(gbuffer).__name__}")
