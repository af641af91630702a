"""brdfcl: f(L, V) of glTF 2.0 materials (metallic-roughness + KHR sheen, clearcoat, anisotropy)
on an OpenCL device, for numpy arrays; look-up tables and renders as arrays.

Conventions (every function): directions live in the shading frame N = +Z, T = +X, B = +Y;
L points from the surface towards the light, V towards the viewer; f is the BRDF in 1/sr
*without* the cosine N.L. Directions need not be unit length: each row is normalized as
`brdfcl eval` normalizes its samples (x / sqrt(x*x + y*y + z*z) in float32, with an exact
power-of-two rescaling of vectors beyond float's range), so the results equal the CLI's bit for bit. A direction at or below the
horizon gives f = 0.

The model options (lobe, profile, sheen_visibility, sheen_distribution, sheen_scaling) are one
brdfcl.Options object, checked once when made; every function and Evaluator method takes it as
options=, or the same names as keywords, which override it.

Errors raise a subclass of brdfcl.Error carrying the CLI's message (options named as Python
keywords: lobe=, not --lobe), by kind: InputError (a
ValueError), EnvironmentError (an OSError: no OpenCL platform or device, cache folder),
DeviceError (a RuntimeError), OutOfMemoryError (a MemoryError), InternalError (a RuntimeError). The GIL is released while
the device works; calls from several threads are safe.

This package is the pure-Python front (argument checks and conversions, docstrings); the work is
done by brdfcl._core, the nanobind module on the C++ host library. This file re-exports the
public names from _options (Options), _inputs (checks, BrdfclWarning), _device (Evaluator,
DeviceArray), _eval (evaluate, evaluate_grid, albedo, lut, devices), _render (render, shade, EXR
files) and _sample (sample, pdf). Plots (matplotlib) live in brdfcl.plot, imported on first use
so that `import brdfcl` needs no matplotlib.
"""
from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any, List

from . import _core
from ._core import DeviceError, EnvironmentError, Error, InputError, InternalError, OutOfMemoryError
from ._options import LOBES, LUT_KINDS, PROFILES, Options
from ._inputs import BrdfclWarning, MaterialsLike, PathLike, _materials
from ._device import DeviceArray, Evaluator
from ._eval import albedo, devices, evaluate, evaluate_grid, lut
from ._render import read_exr, read_gbuffer, render, shade, write_gbuffer
from ._sample import pdf, sample

if TYPE_CHECKING:
    from . import plot as plot


__all__ = [
    "Error", "InputError", "DeviceError", "OutOfMemoryError", "InternalError", "BrdfclWarning", "Options", "Evaluator", "DeviceArray",
    "devices", "evaluate", "evaluate_grid", "albedo", "lut", "sample", "pdf",
    "render", "shade", "read_gbuffer", "write_gbuffer", "read_exr", "LOBES", "PROFILES", "LUT_KINDS",
]
__version__ = "0.1.0"

# The classes and functions above are brdfcl's wherever they are defined: repr, help() and
# pickling name them brdfcl.X, as before the package was split into modules.
for _name in __all__:
    _obj = globals()[_name]
    if getattr(_obj, "__module__", "").startswith(__name__ + "._") and _obj.__module__ != _core.__name__:
        _obj.__module__ = __name__
del _name, _obj


def __getattr__(name: str) -> Any:
    # brdfcl.plot on first use: matplotlib is needed by the plots only.
    if name == "plot":
        return importlib.import_module(".plot", __name__)
    raise AttributeError(f"module 'brdfcl' has no attribute {name!r}")


def __dir__() -> List[str]:
    return sorted(list(globals()) + ["plot"])
