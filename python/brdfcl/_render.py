"""Images: brdfcl.render (glTF or the built-in spheres) and shade (a G-buffer), and the EXR
readers and writer read_gbuffer, read_exr, write_gbuffer."""
from __future__ import annotations

import os
from typing import Any, Dict, Mapping, Optional, Tuple, Union

import numpy as np

from . import _core
from ._device import Evaluator, _evaluator
from ._inputs import PathLike, _gbuffer
from ._options import Options


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
