"""Images: brdfcl.plot.tone_map (`brdfcl render`'s PNG pipeline), image (a tone-mapped render)
and diff (two renders' relative luminance difference, as `brdfcl diff`)."""
from __future__ import annotations

import math
import os
from typing import Any, Optional, Tuple, Union

import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import Normalize

from .. import _core, render as _render
from .. import InputError
from ._common import Device, Plot, _cmap, _plain, _single_axes


# ---- image: a tone-mapped render ----

def tone_map(radiance: Any, exposure: float = 0.0) -> np.ndarray:
    """`brdfcl render`'s PNG pipeline on linear float RGB (H, W, 3): times 2^exposure, Khronos PBR
    Neutral, the sRGB OETF, 8-bit rounding; returned as float32 in [0, 1] (the 8-bit value / 255)."""
    if not (isinstance(exposure, (int, float, np.floating)) and math.isfinite(exposure)):
        raise InputError(f"exposure must be a finite number of stops, got {exposure!r}")
    rgb = np.asarray(radiance)
    if rgb.ndim != 3 or rgb.shape[2] != 3:
        raise InputError(f"the image must have shape (H, W, 3), got {tuple(rgb.shape)}")
    # The library's own pipeline (the bytes `brdfcl render --out x.png` writes), not a copy of it.
    rgb8 = _core.tone_map(np.ascontiguousarray(rgb, dtype=np.float32), float(exposure))
    return (rgb8 / np.float32(255)).astype(np.float32)


def image(radiance: Any = None, *, exposure: float = 0.0, gltf: Optional[Union[str, "os.PathLike[str]"]] = None,
          scene: Optional[str] = None, size: Optional[Tuple[int, int]] = None, profile: str = "spec",
          title: Optional[str] = None, figsize: Optional[Tuple[float, float]] = None, dpi: float = 100,
          ax: Optional[Axes] = None, device: Device = None, **render_options: Any) -> Plot:
    """A tone-mapped render (tone_map: exposure in stops, PBR Neutral, sRGB), without ticks, with a
    title. radiance: a float (H, W, 3) linear image (brdfcl.render, read_exr or shade); without it,
    brdfcl.render(gltf=..., scene=..., size=..., profile=..., **render_options) makes one.
    figsize defaults to the image's aspect, 6 inches wide. In a notebook the Plot shows inline.

    arrays: radiance float32 (H, W, 3) (brdfcl.render's result, or the array given), display
    float32 (H, W, 3) in [0, 1] (what imshow drew: the same values as `brdfcl render`'s PNG).
    """
    if radiance is None:
        rad = _render(gltf=gltf, scene=scene, size=size, profile=profile, device=device, **render_options)
        what = os.path.basename(os.fspath(gltf)) if gltf is not None else f"scene {scene or 'spheres'}"
        caption = f"{what}: profile {profile}"
    else:
        if gltf is not None or scene is not None or size is not None or render_options:
            raise InputError("image: give a radiance array or render options (gltf, scene, size, ...), not both")
        rad = np.asarray(radiance)
        caption = "image"
    display = tone_map(rad, exposure)
    h, w = display.shape[:2]
    if figsize is None:
        figsize = (6.0, max(1.0, 6.0 * h / w))
    fig, a = _single_axes(ax, figsize, dpi)
    a.imshow(display)
    a.set_xticks([])
    a.set_yticks([])
    a.set_xlabel(f"{w} x {h} pixels")
    a.set_title(title if title is not None else f"{caption}, exposure {exposure:+g} stops (PBR Neutral, sRGB)",
                fontsize=9)
    return Plot(fig, {"radiance": rad, "display": display})


# ---- diff: two renders' relative luminance difference ----

def diff(a: Any, b: Any, *, threshold: float = 0.01, floor: Optional[float] = None, range: Optional[float] = None,
         names: Optional[Tuple[str, str]] = None, figsize: Optional[Tuple[float, float]] = None, dpi: float = 100,
         ax: Optional[Axes] = None) -> Plot:
    """`brdfcl diff A B`'s picture with its legend: d = (Y_A - Y_B) / max(Y_B, floor) per pixel
    (Y the Rec. 709 luminance, B the reference) in a diverging map over ±range (default: the
    99th percentile of |d|, as the CLI), magenta where a pixel is not finite in A or B, titled
    with the statistics the CLI prints. a, b: EXR paths (read and checked as the CLI reads them)
    or float (H, W, 3) linear images of one shape. threshold, floor: as --threshold, --floor.
    names: how the title names a and b (default: the paths, or "A" and "B" for arrays).

    arrays: relative (H, W) float32 (d; NaN where not compared), stats (the dict `brdfcl diff
    --json` prints, "range" the colour range drawn).
    """
    import json

    for name, v, positive in (("threshold", threshold, False), ("floor", floor, True), ("range", range, True)):
        if v is None:
            continue
        if isinstance(v, bool) or not isinstance(v, (int, float, np.floating)) or not math.isfinite(v) or v < 0 \
                or (positive and v == 0):
            raise InputError(f"{name} must be a finite number {'> 0' if positive else '>= 0'}, got {v!r}")
    paths = [isinstance(x, (str, os.PathLike)) for x in (a, b)]
    if all(paths):
        name_a, name_b = os.fspath(a), os.fspath(b)
        relative, report, default_range = _core.image_diff_files(name_a, name_b, float(threshold), float(floor or 0))
    elif not any(paths):
        name_a, name_b = ("A", "B") if names is None else (str(n) for n in names)
        arrs = [np.ascontiguousarray(x, dtype=np.float32) for x in (a, b)]
        for label, x in zip(("A", "B"), arrs):
            if x.ndim != 3 or x.shape[2] != 3:
                raise InputError(f"{label} must have shape (H, W, 3), got {tuple(x.shape)}")
        if arrs[0].shape != arrs[1].shape:
            raise InputError(f"the images differ in shape: A is {arrs[0].shape}, B is {arrs[1].shape}; "
                             "compare renders of the same size")
        relative, report, default_range = _core.image_diff_arrays(arrs[0], arrs[1], float(threshold),
                                                                  float(floor or 0), name_a, name_b)
    else:
        raise InputError("a and b must both be EXR paths or both be image arrays")
    if names is not None:
        name_a, name_b = (str(n) for n in names)
    stats = json.loads(report)
    limit = float(range) if range is not None else float(default_range)
    stats["range"] = limit
    h, w = relative.shape
    if figsize is None:
        figsize = (7.0, max(2.5, 7.0 * h / w * 0.8 + 1.2))
    fig, axes = _single_axes(ax, figsize, dpi)
    im = axes.imshow(np.ma.masked_invalid(relative), cmap=_cmap("RdBu_r", "magenta"),
                     norm=Normalize(-limit, limit, clip=True), interpolation="nearest")
    fig.colorbar(im, ax=axes, label=f"d, clipped at |d| = {limit:.4g}")
    axes.set_xlabel("x (pixels)")
    axes.set_ylabel("y (pixels)")
    rel = stats["relative"]
    lines = [f"A: {_plain(name_a)}", f"B: {_plain(name_b)}", f"d = (Y_A - Y_B) / max(Y_B, {stats['floor']:.4g})"]
    if stats["compared"] > 0:
        lines.append(f"max |d| {rel['max_abs']:.4g} at ({rel['max_x']}, {rel['max_y']}), mean |d| {rel['mean_abs']:.4g}, "
                     f"p99 {rel['p99']:.4g}")
    if stats["compared"] < stats["pixels"]:
        lines.append(f"magenta: {stats['pixels'] - stats['compared']} pixels not finite in A or B")
    axes.set_title("Relative luminance difference of A and B\n" + "\n".join(lines), fontsize=8)
    return Plot(fig, {"relative": relative, "stats": stats})
