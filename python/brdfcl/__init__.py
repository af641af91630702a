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

This file is the pure-Python front (argument checks and conversions, docstrings); the work is
done by brdfcl._core, the nanobind module on the C++ host library. Plots (matplotlib) live in
brdfcl.plot, imported on first use so that `import brdfcl` needs no matplotlib.
"""
from __future__ import annotations

import importlib
import json
import math
import os
import threading
import warnings
from typing import TYPE_CHECKING, Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._core import DeviceError, EnvironmentError, Error, InputError, InternalError, OutOfMemoryError

if TYPE_CHECKING:
    from . import plot as plot

__all__ = [
    "Error", "InputError", "DeviceError", "OutOfMemoryError", "InternalError", "BrdfclWarning", "Options", "Evaluator", "DeviceArray",
    "devices", "evaluate", "evaluate_grid", "albedo", "lut", "sample", "pdf",
    "render", "shade", "read_gbuffer", "write_gbuffer", "read_exr", "LOBES", "PROFILES", "LUT_KINDS",
]
__version__ = "0.1.0"

LOBES = ("all", "diffuse", "specular", "sheen", "clearcoat")
PROFILES = ("spec", "khronos", "threejs", "filament", "babylon", "materialx")
LUT_KINDS = ("sheen-e", "ggx-dfg", "charlie-dfg")

PathLike = Union[str, "os.PathLike[str]"]
MaterialsLike = Union[PathLike, Mapping[str, Any], Sequence[Mapping[str, Any]], "_core.Materials"]


class Options:
    """The model options, checked when made (an unknown value, or a sheen variant under an engine
    profile, raises InputError naming the keyword):

    lobe: all|diffuse|specular|sheen|clearcoat. profile: spec|khronos|threejs|filament|babylon|
    materialx (docs/profiles.md). sheen_visibility, sheen_distribution: charlie|ashikhmin;
    sheen_scaling: min|view|none (spec profile only).

    Immutable and hashable; replace(**changes) makes a changed copy. Pass it as options= to any
    function or Evaluator method, or to Evaluator(options=) as that evaluator's default.
    """

    __slots__ = ("lobe", "profile", "sheen_visibility", "sheen_distribution", "sheen_scaling", "_core")
    _NAMES = ("lobe", "profile", "sheen_visibility", "sheen_distribution", "sheen_scaling")

    def __init__(self, *, lobe: str = "all", profile: str = "spec", sheen_visibility: str = "charlie",
                 sheen_distribution: str = "charlie", sheen_scaling: str = "min"):
        values = (lobe, profile, sheen_visibility, sheen_distribution, sheen_scaling)
        for name, value in zip(self._NAMES, values):
            if not isinstance(value, str):
                raise InputError(f"{name}= must be a str, got {type(value).__name__}")
            object.__setattr__(self, name, value)
        object.__setattr__(self, "_core", _core.eval_options(lobe, sheen_visibility, sheen_distribution, sheen_scaling,
                                                             profile))

    def replace(self, **changes: str) -> "Options":
        """A copy with the given options changed."""
        unknown = sorted(set(changes) - set(self._NAMES))
        if unknown:
            raise TypeError(f"unknown option {unknown[0]!r}; the options are " + ", ".join(self._NAMES))
        return Options(**{**{n: getattr(self, n) for n in self._NAMES}, **changes})

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("brdfcl.Options is immutable; use replace()")

    def _key(self) -> Tuple[str, ...]:
        return tuple(getattr(self, n) for n in self._NAMES)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Options) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def __repr__(self) -> str:
        return "brdfcl.Options(" + ", ".join(f"{n}={getattr(self, n)!r}" for n in self._NAMES) + ")"


_DEFAULT_OPTIONS = Options()


def _options(options: Optional[Options], default: Options, **keywords: Optional[str]) -> Options:
    """`options` (or `default`) with the keywords given (not None) applied."""
    if options is None:
        options = default
    elif not isinstance(options, Options):
        raise InputError(f"options= must be a brdfcl.Options, got {type(options).__name__}")
    given = {k: v for k, v in keywords.items() if v is not None}
    return options.replace(**given) if given else options


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


class DeviceArray:
    """An array kept in an Evaluator's device memory: float32 rows of shape (N, 3) (directions or
    results) or uint32 material indices of shape (N,). Evaluator.to_device and
    Evaluator.device_array make them; Evaluator.evaluate takes them for L, V, material_index and
    out and returns its results as one, so chained calls keep their data on the device. numpy()
    copies the array back to the host."""

    __slots__ = ("_core", "shape", "dtype", "_evaluator")

    def __init__(self, evaluator: "Evaluator", shape: Tuple[int, ...], dtype: Any):
        dtype = np.dtype(dtype)
        if dtype not in (np.dtype(np.float32), np.dtype(np.uint32)):
            raise InputError(f"device arrays hold float32 or uint32, got dtype {dtype}")
        self._core = _core.DeviceArray(evaluator._device, dtype == np.uint32, int(np.prod(shape, dtype=np.int64)))
        self.shape = tuple(int(x) for x in shape)
        self.dtype = dtype
        self._evaluator = evaluator

    def __len__(self) -> int:
        return self.shape[0]

    def __repr__(self) -> str:
        return f"brdfcl.DeviceArray(shape={self.shape}, dtype={self.dtype.name})"

    def numpy(self) -> np.ndarray:
        """A fresh host copy of the array."""
        out = np.empty(self.shape, dtype=self.dtype)
        self._core.download(out)
        return out


class Evaluator:
    """One OpenCL device and the programs compiled for it (kept between calls).

    device: None ($BRDFCL_DEVICE, then device 0), an index into brdfcl.devices(), or a
    substring of a device name, as the CLI's --device. The methods are the module-level
    functions without their `device` argument; one Evaluator may be used from several threads.
    Conventions: N = +Z, L towards the light, V towards the viewer, f without the cosine.
    """

    def __init__(self, device: Union[None, int, str] = None, *, options: Optional[Options] = None):
        self._device = _core.Device("" if device is None else str(device))
        self.options = _options(options, _DEFAULT_OPTIONS)
        """The options of every call that gives no options= of its own."""

    @property
    def device(self) -> Dict[str, Any]:
        """The device's description (the keys of brdfcl.devices())."""
        return self._device.info

    def __repr__(self) -> str:
        return f"brdfcl.Evaluator({self.device['name']!r})"

    def evaluate(self, materials: MaterialsLike, L: Any, V: Any, material_index: Any = None, *,
                 options: Optional[Options] = None, lobe: Optional[str] = None, sheen_visibility: Optional[str] = None,
                 sheen_distribution: Optional[str] = None, sheen_scaling: Optional[str] = None,
                 profile: Optional[str] = None, strict: bool = False, out: Any = None) -> Any:
        """f(L, V) per sample: float32 (N, 3) rgb in 1/sr, no cosine. See brdfcl.evaluate.

        With DeviceArrays for L and V (and material_index and out, if given), the rows stay in
        device memory: the result is a DeviceArray, the same bytes as the numpy call's."""
        opts = _options(options, self.options, lobe=lobe, sheen_visibility=sheen_visibility,
                        sheen_distribution=sheen_distribution, sheen_scaling=sheen_scaling, profile=profile)._core
        m = _materials(materials, strict)
        if any(isinstance(a, DeviceArray) for a in (L, V, material_index, out)):
            return self._evaluate_device(m, L, V, material_index, out, opts)
        Ld, Vd = _directions(L, "L"), _directions(V, "V")
        if Ld.shape[0] != Vd.shape[0]:
            raise InputError(f"L and V must have the same number of rows, got {Ld.shape[0]} and {Vd.shape[0]}")
        idx = _index(material_index, Ld.shape[0], len(m))
        if idx is not None and idx.shape[0] != Ld.shape[0]:
            raise InputError(f"material_index must have one entry per sample: {idx.shape[0]} for {Ld.shape[0]} samples")
        out = _output(out, (Ld.shape[0], 3), Ld, Vd)
        self._device.evaluate(m, Ld, Vd, idx, out, opts)
        return out

    def device_array(self, shape: Union[int, Tuple[int, ...]], dtype: Any = np.float32) -> DeviceArray:
        """A zero-filled DeviceArray in this evaluator's device memory: float32 (N, 3) or uint32 (N,)."""
        return DeviceArray(self, (shape,) if isinstance(shape, (int, np.integer)) else tuple(shape), dtype)

    def to_device(self, a: Any) -> DeviceArray:
        """A copy of `a` in this evaluator's device memory: (N, 3) directions as float32, or (N,)
        material indices as uint32."""
        arr = np.asarray(a)
        if arr.ndim == 2 and arr.shape[1] == 3 and arr.dtype.kind in "fiu":
            host = np.ascontiguousarray(arr, dtype=np.float32)
        elif arr.ndim == 1 and arr.dtype.kind in "iu":
            if arr.size and (arr.min() < 0 or arr.max() > np.iinfo(np.uint32).max):
                row = int(np.argmax((arr < 0) | (arr > np.iinfo(np.uint32).max)))
                raise InputError(f"row {row}: material index {int(arr[row])} does not fit a uint32")
            host = np.ascontiguousarray(arr, dtype=np.uint32)
        else:
            raise InputError(f"to_device takes (N, 3) directions or (N,) integer material indices, got shape "
                             f"{tuple(arr.shape)} and dtype {arr.dtype}")
        d = DeviceArray(self, host.shape, host.dtype)
        d._core.upload(host)
        return d

    def _device_rows(self, a: Any, name: str, dtype: Any, rows: Optional[int]) -> DeviceArray:
        if not isinstance(a, DeviceArray):
            raise InputError(f"{name} must be a brdfcl.DeviceArray when the other inputs are (see Evaluator.to_device), "
                             f"got {type(a).__name__}")
        if a._evaluator is not self:
            raise InputError(f"{name} lives on another Evaluator's device; make it with this Evaluator's to_device")
        shape = (a.shape[0], 3) if dtype == np.float32 else (a.shape[0],)
        if a.dtype != dtype or a.shape != shape or (rows is not None and a.shape[0] != rows):
            want = f"({rows if rows is not None else 'N'}{', 3' if dtype == np.float32 else ''})"
            raise InputError(f"{name} must be a {np.dtype(dtype).name} device array of shape {want}, got "
                             f"{a.dtype.name} {a.shape}")
        return a

    def _evaluate_device(self, m: "_core.Materials", L: Any, V: Any, material_index: Any, out: Any,
                         opts: "_core.EvalOptions") -> DeviceArray:
        Ld = self._device_rows(L, "L", np.float32, None)
        n = Ld.shape[0]
        Vd = self._device_rows(V, "V", np.float32, n)
        if material_index is None:
            if len(m) != 1:
                raise InputError(f"{len(m)} materials but no material_index; give one index per sample "
                                 "(a uint32 device array of shape (N,))")
            idx = None
        else:
            idx = self._device_rows(material_index, "material_index", np.uint32, n)._core
        o = self.device_array((n, 3)) if out is None else self._device_rows(out, "out", np.float32, n)
        if o._core is Ld._core or o._core is Vd._core:
            raise InputError("out must not be L or V; pass a separate device array")
        self._device.evaluate_device(m, Ld._core, Vd._core, idx, o._core, True, opts)
        return o

    def evaluate_grid(self, materials: MaterialsLike, L: Any, V: Any, *, options: Optional[Options] = None,
                      lobe: Optional[str] = None, sheen_visibility: Optional[str] = None,
                      sheen_distribution: Optional[str] = None, sheen_scaling: Optional[str] = None,
                      profile: Optional[str] = None, strict: bool = False,
                      out: Optional[np.ndarray] = None) -> np.ndarray:
        """Every material x every direction pair: float32 (M, N, 3). See brdfcl.evaluate_grid."""
        opts = _options(options, self.options, lobe=lobe, sheen_visibility=sheen_visibility,
                        sheen_distribution=sheen_distribution, sheen_scaling=sheen_scaling, profile=profile)._core
        m = _materials(materials, strict)
        Ld, Vd = _directions(L, "L"), _directions(V, "V")
        if Ld.shape[0] != Vd.shape[0]:
            raise InputError(f"L and V must have the same number of rows, got {Ld.shape[0]} and {Vd.shape[0]}")
        out = _output(out, (len(m), Ld.shape[0], 3), Ld, Vd)
        self._device.evaluate_grid(m, Ld, Vd, out, opts)
        return out

    def albedo(self, material: MaterialsLike, cos_theta_v: Any, *, options: Optional[Options] = None,
               sheen_visibility: Optional[str] = None, sheen_distribution: Optional[str] = None,
               sheen_scaling: Optional[str] = None, profile: Optional[str] = None,
               strict: bool = False) -> Dict[str, np.ndarray]:
        """Directional albedo per lobe. See brdfcl.albedo."""
        # Every lobe is integrated, so the options' lobe plays no part.
        opts = _options(options, self.options, lobe="all", sheen_visibility=sheen_visibility,
                        sheen_distribution=sheen_distribution, sheen_scaling=sheen_scaling, profile=profile)._core
        single = isinstance(material, Mapping) and "materials" not in material
        m = _materials(material, strict)
        if len(m) == 0:
            raise InputError("albedo: no materials given")
        mus = np.atleast_1d(np.asarray(cos_theta_v, dtype=np.float64))
        if mus.ndim != 1 or mus.size == 0:
            raise InputError(f"cos_theta_v must be a number or a 1-D array of numbers, got shape {tuple(mus.shape)}")
        bad = ~(np.isfinite(mus) & (mus >= 0.0) & (mus <= 1.0))
        if bad.any():
            raise InputError(f"cos_theta_v must lie in [0, 1] (N.V), got {float(mus[int(np.argmax(bad))]):g}")
        out = self._device.albedo(m, mus.astype(np.float32).tolist(), opts)
        scalar = np.ndim(cos_theta_v) == 0
        result = {}
        for name, a in out.items():
            if single:
                a = a[0]
            if scalar:
                a = a[..., 0, :]
            result[name] = a
        return result

    def lut(self, kind: str, size: int = 128, *, sheen_visibility: Optional[str] = None,
            sheen_distribution: Optional[str] = None) -> np.ndarray:
        """A baked look-up table. See brdfcl.lut."""
        if kind in ("ggx-dfg", "charlie-dfg"):
            for name, value in (("sheen_visibility", sheen_visibility), ("sheen_distribution", sheen_distribution)):
                if value is not None:
                    raise InputError(f"{name} applies to kind 'sheen-e' only; drop it for kind '{kind}'")
        if isinstance(size, bool) or not isinstance(size, (int, np.integer)):
            raise InputError(f"size must be an integer from 2 to 4096, got {size!r}")
        return self._device.lut(kind, int(size), sheen_visibility or "charlie", sheen_distribution or "charlie")

    def render(self, gltf: Optional[PathLike] = None, scene: Optional[str] = None, *,
               size: Optional[Tuple[int, int]] = None, camera: Union[None, int, str] = None,
               spp: Optional[int] = None, environment: Optional[PathLike] = None,
               env_intensity: Optional[float] = None, env_rotation: Optional[float] = None,
               lights: PathLike = "gltf", options: Optional[Options] = None, profile: Optional[str] = None,
               ibl: str = "split-sum",
               ibl_samples: Optional[int] = None, gltf_scene: Optional[int] = None,
               variant: Optional[str] = None, strict: bool = False,
               allow_outside_uris: bool = False) -> np.ndarray:
        """A rendered image, float32 (H, W, 3) linear radiance. See brdfcl.render."""
        job = _core.RenderJob()
        if gltf is not None:
            if scene is not None:
                raise InputError("scene and gltf are alternatives; give one")
            job.gltf = os.fspath(gltf)
        else:
            job.scene = "spheres" if scene is None else str(scene)
        if size is not None:
            try:
                w, h = size
                job.width, job.height = _int(w, "size"), _int(h, "size")
            except (TypeError, ValueError):
                raise InputError(f"size must be (width, height) with sides 1 to 16384, e.g. (768, 768), got {size!r}") from None
            if not (1 <= job.width <= 16384 and 1 <= job.height <= 16384):
                raise InputError(f"size must be (width, height) with sides 1 to 16384, e.g. (768, 768), got {size!r}")
        if camera is not None:
            job.camera = str(camera)
        if spp is not None:
            job.spp = _int(spp, "spp")
            job.spp_given = True
        job.environment_given = environment is not None or env_intensity is not None or env_rotation is not None
        if environment is not None:
            job.environment = os.fspath(environment)
        if env_intensity is not None:
            job.env_intensity = float(env_intensity)
        if env_rotation is not None:
            job.env_rotation = float(env_rotation)
        job.lights = os.fspath(lights)
        if gltf_scene is not None:
            job.gltf_scene = _int(gltf_scene, "gltf_scene")
        if variant is not None:
            job.variant = str(variant)
        job.strict = bool(strict)
        job.allow_outside_uris = bool(allow_outside_uris)
        job.set_profile(_options(options, self.options, profile=profile).profile)
        image, warns = self._device.render(job, ibl, 1024 if ibl_samples is None else _int(ibl_samples, "ibl_samples"),
                                           ibl_samples is not None)
        _warn(warns)
        return image

    def shade(self, gbuffer: Union[PathLike, Mapping[str, Any]], scene: Union[PathLike, Mapping[str, Any]], *,
              options: Optional[Options] = None, profile: Optional[str] = None, ibl: str = "split-sum", ibl_samples: int = 1024,
              check: bool = True, allow_outside_uris: bool = False) -> np.ndarray:
        """Deferred shading of a G-buffer: float32 (H, W, 3) linear radiance. See brdfcl.shade."""
        g = _gbuffer(gbuffer, check)
        if isinstance(scene, Mapping):
            scene_name = "<scene>"
            # The caller's own data, as trusted as a path the caller passes: not confined.
            s = _core.parse_scene(json.dumps(scene, default=_json_default), scene_name, os.getcwd(), True)
        elif isinstance(scene, (str, os.PathLike)):
            scene_name = os.fspath(scene)
            s = _core.read_scene(scene_name, bool(allow_outside_uris))
        else:
            raise InputError(f"scene must be a path to a scene JSON file or a dict (docs/gbuffer.md), got {type(scene).__name__}")
        # `brdfcl shade`'s warning about which camera shades (or that neither file has one).
        gbuffer_name = os.fspath(gbuffer) if isinstance(gbuffer, (str, os.PathLike)) else _GBUFFER_NAME
        camera_warning = _core.shade_camera_warning(scene_name, s, gbuffer_name, g)
        if camera_warning:
            _warn([camera_warning])
        profile = _options(options, self.options, profile=profile).profile
        return self._device.shade(g, s, profile, ibl, _int(ibl_samples, "ibl_samples"))


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


_default_lock = threading.Lock()
_evaluators: Dict[str, Evaluator] = {}


def _evaluator(device: Union[None, int, str, Evaluator]) -> Evaluator:
    """The Evaluator of `device`, created on first use and kept (programs are compiled once)."""
    if isinstance(device, Evaluator):
        return device
    key = "" if device is None else str(device)
    with _default_lock:
        ev = _evaluators.get(key)
        if ev is None:
            ev = _evaluators[key] = Evaluator(device)
        return ev


def devices() -> List[Dict[str, Any]]:
    """The OpenCL devices of every platform, as `brdfcl devices` lists them: dicts with index,
    name, platform, type, compute_units, opencl_c, max_alloc and global_mem (bytes)."""
    return _core.devices()


def evaluate(materials: MaterialsLike, L: Any, V: Any, material_index: Any = None, *,
             options: Optional[Options] = None, lobe: Optional[str] = None,
             sheen_visibility: Optional[str] = None, sheen_distribution: Optional[str] = None,
             sheen_scaling: Optional[str] = None, profile: Optional[str] = None, strict: bool = False,
             device: Union[None, int, str, Evaluator] = None, out: Optional[np.ndarray] = None) -> np.ndarray:
    """f(L, V) of glTF materials per sample: float32 array (N, 3), rgb in 1/sr, without the cosine.

    Conventions: shading frame N = +Z, T = +X, B = +Y; L (N, 3) points towards the light, V (N, 3)
    towards the viewer; rows need not be unit length (normalized as `brdfcl eval` does)
    but must be finite and non-zero. C-contiguous float32 or float64 arrays are read in place (no
    copy, whatever N); other number types are converted. Results equal `brdfcl eval` on the same
    numbers bit for bit.

    materials: one glTF material dict, a list of them, a dict with "materials" (a glTF document),
      or a path to a .gltf/.glb/JSON file, read by the CLI's --materials reader
      (pbrMetallicRoughness, KHR_materials_sheen, _clearcoat, _anisotropy, _ior). Unknown keys
      warn (BrdfclWarning); strict=True makes them errors.
    material_index: int array (N,) of indices into materials; required with more than one.
    options: a brdfcl.Options (default: the Evaluator's, else brdfcl.Options()); lobe, profile,
      sheen_visibility, sheen_distribution, sheen_scaling: the same options as keywords, which
      override it (lobe: all|diffuse|specular|sheen|clearcoat; profile: spec|khronos|threejs|
      filament|babylon|materialx, docs/profiles.md; the sheen variants: spec profile only).
    device: None (the default device, $BRDFCL_DEVICE then 0), an index, a name substring or an
      Evaluator. Raises brdfcl.Error on a bad material, direction or option, naming it.
    out: an existing C-contiguous float32 array of shape (N, 3) to write f into and return, as
      numpy's out=: a loop that reuses it skips the page faults of a fresh result array.
    """
    return _evaluator(device).evaluate(materials, L, V, material_index, options=options, lobe=lobe,
                                       sheen_visibility=sheen_visibility,
                                       sheen_distribution=sheen_distribution, sheen_scaling=sheen_scaling,
                                       profile=profile, strict=strict, out=out)


def evaluate_grid(materials: MaterialsLike, L: Any, V: Any, *,
                  options: Optional[Options] = None, lobe: Optional[str] = None,
                  sheen_visibility: Optional[str] = None, sheen_distribution: Optional[str] = None,
                  sheen_scaling: Optional[str] = None, profile: Optional[str] = None, strict: bool = False,
                  device: Union[None, int, str, Evaluator] = None, out: Optional[np.ndarray] = None) -> np.ndarray:
    """f(L, V) of every material at every direction pair: float32 array (M, N, 3), rgb in 1/sr,
    without the cosine; out[m, i] is material m at pair i (`brdfcl eval --grid`, bit for bit).

    Conventions and arguments as brdfcl.evaluate (N = +Z, L towards the light, V towards the
    viewer, f without the cosine); there is no material_index. out: an existing C-contiguous
    float32 (M, N, 3) array to fill and return.
    """
    return _evaluator(device).evaluate_grid(materials, L, V, options=options, lobe=lobe, sheen_visibility=sheen_visibility,
                                            sheen_distribution=sheen_distribution, sheen_scaling=sheen_scaling,
                                            profile=profile, strict=strict, out=out)


def albedo(material: MaterialsLike, cos_theta_v: Any, *, options: Optional[Options] = None,
           sheen_visibility: Optional[str] = None, sheen_distribution: Optional[str] = None,
           sheen_scaling: Optional[str] = None, profile: Optional[str] = None, strict: bool = False,
           device: Union[None, int, str, Evaluator] = None) -> Dict[str, np.ndarray]:
    """Directional albedo per lobe, as `brdfcl albedo`: the integral over the hemisphere of L of
    f(L, V) N.L, by deterministic quadrature on the device.

    Conventions: N = +Z, V in the XZ plane with N.V = cos_theta_v (a number or a 1-D array in
    [0, 1]), L towards the light, f without the cosine (the integral applies N.L).
    Returns {"diffuse", "specular", "sheen", "clearcoat", "all"} -> float32 RGB albedo of shape
    (K, 3) for one material dict (K = len(cos_theta_v); (3,) for a scalar), (M, K, 3) for a list
    or a file of M materials. Options as brdfcl.evaluate; every lobe is integrated, whatever
    the options' lobe.
    """
    return _evaluator(device).albedo(material, cos_theta_v, options=options, sheen_visibility=sheen_visibility,
                                     sheen_distribution=sheen_distribution, sheen_scaling=sheen_scaling,
                                     profile=profile, strict=strict)


def lut(kind: str, size: int = 128, *, sheen_visibility: Optional[str] = None,
        sheen_distribution: Optional[str] = None, device: Union[None, int, str, Evaluator] = None) -> np.ndarray:
    """A look-up table for engines, baked on the device as `brdfcl lut --kind KIND --size SIZE`.

    kind: "sheen-e" (E of the white sheen lobe; sheen_visibility/sheen_distribution choose it),
    "ggx-dfg" (A, B with F0 A + B the GGX directional albedo), "charlie-dfg". Returns float32
    (size, size) for one channel, (size, size, 2) for ggx-dfg: lut[j, i] is the texel at
    N.V = max(i / (size - 1), 1e-4), roughness = j / (size - 1), equal to the CLI's .npy.
    Conventions: N = +Z, L towards the light, f without the cosine (the albedo integrals apply N.L).
    """
    return _evaluator(device).lut(kind, size, sheen_visibility=sheen_visibility,
                                  sheen_distribution=sheen_distribution)


def render(gltf: Optional[PathLike] = None, scene: Optional[str] = None, *, size: Optional[Tuple[int, int]] = None,
           camera: Union[None, int, str] = None, spp: Optional[int] = None, environment: Optional[PathLike] = None,
           env_intensity: Optional[float] = None, env_rotation: Optional[float] = None, lights: PathLike = "gltf",
           options: Optional[Options] = None, profile: Optional[str] = None, ibl: str = "split-sum", ibl_samples: Optional[int] = None,
           gltf_scene: Optional[int] = None, variant: Optional[str] = None, strict: bool = False,
           allow_outside_uris: bool = False, device: Union[None, int, str, Evaluator] = None) -> np.ndarray:
    """Renders a glTF asset (gltf=PATH) or the built-in scene (scene="spheres", the default):
    float32 (H, W, 3) linear radiance, rows from the top, equal to `brdfcl render --out x.exr`.

    size: (width, height) (default 768x768 for the spheres; glTF: 1280x720 or the camera's aspect
    at 720 rows). camera: glTF camera index or "auto". spp: glTF sub-pixel samples (default 4).
    environment: builtin|sky|studio|uniform|FILE.hdr|FILE.exr, env_intensity, env_rotation
    (radians about +Y). lights: gltf|none|SCENE.json. options, profile: as brdfcl.evaluate (a
    render uses the profile; the options' lobe and sheen variants play no part). ibl: split-sum
    or exact (Monte Carlo, ibl_samples per pixel). gltf_scene, variant, strict: as the CLI's
    --gltf-scene, --variant, --strict. allow_outside_uris: as --allow-outside-uris, lets the asset's
    URIs and a lights scene's environment path name files outside their folders (docs/gltf.md,
    "Files an asset names"). The BRDF follows the conventions of brdfcl.evaluate
    (N = +Z in each surface's frame, L towards the light, f without the cosine; the renderer
    applies N.L).
    """
    return _evaluator(device).render(gltf, scene, size=size, camera=camera, spp=spp, environment=environment,
                                     env_intensity=env_intensity, env_rotation=env_rotation, lights=lights,
                                     options=options, profile=profile, ibl=ibl, ibl_samples=ibl_samples, gltf_scene=gltf_scene,
                                     variant=variant, strict=strict, allow_outside_uris=allow_outside_uris)


def shade(gbuffer: Union[PathLike, Mapping[str, Any]], scene: Union[PathLike, Mapping[str, Any]], *,
          options: Optional[Options] = None, profile: Optional[str] = None, ibl: str = "split-sum",
          ibl_samples: int = 1024, check: bool = True,
          allow_outside_uris: bool = False, device: Union[None, int, str, Evaluator] = None) -> np.ndarray:
    """Deferred shading of a G-buffer under a scene's lights and environment, as `brdfcl shade`:
    float32 (H, W, 3) linear radiance.

    gbuffer: a G-buffer EXR path or a dict of channel arrays as brdfcl.read_gbuffer returns
    (docs/gbuffer.md names: P, N, baseColor, metallic, roughness, mask required; (H, W, 3)
    vectors, (H, W) scalars; optional "camera"); either is range-checked as the CLI checks a file
    (factors in [0, 1], unit normals on covered pixels) unless check=False.
    scene: a scene JSON path or the same JSON as a dict (docs/gbuffer.md, "Scene JSON"). A scene
    file's environment path stays in the file's folder unless allow_outside_uris=True; a dict's is
    the caller's own and taken as it is (relative to the working directory).
    Warns (BrdfclWarning) as the CLI does when the scene's camera differs from the G-buffer's, or
    neither has one and the G-buffer no V.
    options, profile: as brdfcl.render.
    Conventions: world-space N per pixel, L towards the light, V towards the viewer, f without
    the cosine (the shader applies N.L).
    """
    return _evaluator(device).shade(gbuffer, scene, options=options, profile=profile, ibl=ibl, ibl_samples=ibl_samples, check=check,
                                    allow_outside_uris=allow_outside_uris)


def read_gbuffer(path: PathLike, *, check: bool = True) -> Dict[str, Any]:
    """Reads a G-buffer EXR (docs/gbuffer.md) into {channel: float32 array}: (H, W, 3) for the
    vectors (P, N, T, V, clearcoatN, baseColor, emissive, sheenColor), (H, W) for the scalars, and
    "camera" (a dict) when the file has one. N is the world-space normal (the +Z of each pixel's
    shading frame); V points towards the viewer. check: the CLI's range checks."""
    return _core.gbuffer_to_dict(_core.read_gbuffer(os.fspath(path), bool(check)))


def read_exr(path: PathLike) -> np.ndarray:
    """Reads an RGB OpenEXR image (e.g. `brdfcl render --out x.exr`) as float32 (H, W, 3)
    linear values, rows from the top."""
    return _core.read_exr(os.fspath(path))


def write_gbuffer(path: PathLike, channels: Mapping[str, Any], *, half: bool = False) -> None:
    """Writes {channel: array} (as read_gbuffer returns) as a G-buffer EXR, FLOAT (or HALF)
    channels under their docs/gbuffer.md names, atomically. Conventions as read_gbuffer."""
    _core.write_gbuffer(os.fspath(path), _gbuffer(channels, False), bool(half))



# ---- Importance sampling (docs/sampling.md) ----

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
    if Ld.shape[0] != Vd.shape[0]:
        raise InputError(f"L and V must have the same number of rows, got {Ld.shape[0]} and {Vd.shape[0]}")
    idx = _index32(material_index, Ld.shape[0], len(m))
    o = _output(out, (Ld.shape[0],), Ld, Vd)
    _core.pdf(ev._device, m, Ld, Vd, idx, o, opts)
    return o

def __getattr__(name: str) -> Any:
    # brdfcl.plot on first use: matplotlib is needed by the plots only.
    if name == "plot":
        return importlib.import_module(".plot", __name__)
    raise AttributeError(f"module 'brdfcl' has no attribute {name!r}")


def __dir__() -> List[str]:
    return sorted(list(globals()) + ["plot"])
