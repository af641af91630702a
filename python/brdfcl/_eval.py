"""The module-level BRDF functions: brdfcl.devices, evaluate, evaluate_grid, albedo and lut, each
the shared Evaluator's method of the same name (brdfcl._device)."""
from __future__ import annotations

from typing import Any, Dict, List, Optional, Union

import numpy as np

from . import _core
from ._device import Evaluator, _evaluator
from ._inputs import MaterialsLike
from ._options import Options


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
