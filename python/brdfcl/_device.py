"""brdfcl.Evaluator (one OpenCL device, its compiled programs and every method) and
brdfcl.DeviceArray (rows kept in device memory); _evaluator(), the shared Evaluator per device."""
from __future__ import annotations

import json
import os
import threading
from typing import Any, Dict, Mapping, Optional, Tuple, Union

import numpy as np

from . import _core
from ._core import InputError
from ._inputs import (_GBUFFER_NAME, MaterialsLike, PathLike, _directions, _gbuffer, _index, _int, _json_default,
                      _materials, _output, _same_rows, _warn)
from ._options import _DEFAULT_OPTIONS, Options, _options


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
        _same_rows(Ld, Vd)
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
        _same_rows(Ld, Vd)
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
