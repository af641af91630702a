"""Albedo figures: brdfcl.plot.albedo (directional albedo per lobe against θ_V) and sheen_e
(the sheen E table with its E = 1 contour)."""
from __future__ import annotations

from typing import Any, Dict, Optional, Tuple

import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import Normalize

from .. import albedo as _albedo, lut as _lut
from .. import InputError, LOBES, MaterialsLike
from ._common import _LOBE_COLOURS, Device, Plot, _channel, _options_text, _resolution, _select, _single_axes


# ---- albedo: per lobe against the view angle ----

def albedo(materials: MaterialsLike, material: int = 0, *, resolution: int = 46, channel: str = "luminance",
           sheen_visibility: str = "charlie", sheen_distribution: str = "charlie", sheen_scaling: str = "min",
           profile: str = "spec", strict: bool = False, figsize: Tuple[float, float] = (7, 4.5), dpi: float = 100,
           ax: Optional[Axes] = None, device: Device = None) -> Plot:
    """The directional albedo ∫ f N·L dω_L of each lobe against θ_V, from 0 to 89° in
    `resolution` steps (brdfcl.albedo, V in the XZ plane).

    arrays: theta_v_deg (k,), cos_theta_v (k,) as passed to brdfcl.albedo, albedo_<lobe> float32
    (k, 3) (its result for the material) and value_<lobe> (k,) the luminance or channel drawn.
    """
    m, name = _select(materials, material, strict)
    k = _resolution(resolution, 2, 1000)
    theta_v = np.linspace(0.0, 89.0, k)
    mus = np.cos(np.radians(theta_v))
    result = _albedo(m, mus, sheen_visibility=sheen_visibility, sheen_distribution=sheen_distribution,
                     sheen_scaling=sheen_scaling, profile=profile, device=device)
    arrays: Dict[str, Any] = {"theta_v_deg": theta_v, "cos_theta_v": mus}
    fig, a = _single_axes(ax, figsize, dpi)
    for lb in LOBES[1:] + LOBES[:1]:
        arrays[f"albedo_{lb}"] = result[lb][0]
        arrays[f"value_{lb}"] = _channel(result[lb][0], channel)
        # A metal's specular lobe is its total: the total is dashed and thinner, drawn over the
        # lobes, whose markers show where a lobe runs under it.
        if lb == "all":
            a.plot(theta_v, arrays[f"value_{lb}"], color="black", linewidth=1.2, linestyle=(0, (4, 3)),
                   label="total (all)", zorder=3)
        else:
            a.plot(theta_v, arrays[f"value_{lb}"], color=_LOBE_COLOURS[lb], linewidth=2, label=lb, zorder=2,
                   marker="o", markersize=3, markevery=max(1, k // 12))
    what = "luminance" if channel == "luminance" else f"channel {channel.upper()}"
    a.set_xlabel("θ_V (degrees)")
    a.set_ylabel(f"directional albedo, {what} (unitless)")
    a.set_xlim(0, 90)
    a.set_ylim(bottom=0)
    a.grid(True, alpha=0.3)
    a.legend(fontsize=8)
    a.set_title(f"{name}: directional albedo per lobe\n"
                f"{_options_text(profile, sheen_visibility, sheen_distribution, sheen_scaling)}", fontsize=9)
    return Plot(fig, arrays)


# ---- sheen_e: the albedo-scaling table ----

def sheen_e(*, size: int = 64, sheen_visibility: Optional[str] = None, sheen_distribution: Optional[str] = None,
            figsize: Tuple[float, float] = (6, 5), dpi: float = 100, ax: Optional[Axes] = None,
            device: Device = None) -> Plot:
    """The sheen E table (brdfcl.lut("sheen-e")): E(N·V, sheen roughness), the white sheen lobe's
    directional albedo, as a heat map (colours capped at E = 2) with its E = 1 contour (where it
    reaches 1; the title says when it does not). Texel (i, j) is at N·V = max(i / (size - 1), 1e-4), roughness
    j / (size - 1), as docs/cli.md's "Look-up tables" says.

    arrays: cos_theta_v (size,), roughness (size,), E float32 (size, size) (brdfcl.lut's result,
    [roughness index, N·V index]).
    """
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or not 2 <= size <= 1024:
        raise InputError(f"size must be an integer from 2 to 1024, got {size!r}")
    e = _lut("sheen-e", int(size), sheen_visibility=sheen_visibility, sheen_distribution=sheen_distribution,
             device=device)
    x = np.maximum(np.arange(size) / (size - 1), 1e-4)
    y = np.arange(size) / (size - 1)
    arrays = {"cos_theta_v": x, "roughness": y, "E": e}
    fig, a = _single_axes(ax, figsize, dpi)
    half = 0.5 / (size - 1)
    emax = float(np.nanmax(e))
    # Capped at 2, so that the grazing, smooth corner (E up to ~6 for Charlie) leaves the rest
    # of the table, and E = 1, readable; the colour bar's arrow marks the cap.
    top = min(emax, 2.0)
    im = a.imshow(e, origin="lower", extent=(-half, 1 + half, -half, 1 + half), cmap="magma", aspect="auto",
                  interpolation="nearest", norm=Normalize(0.0, top))
    fig.colorbar(im, ax=a, label="E (directional albedo, unitless)", extend="max" if emax > top else "neither")
    if float(np.nanmin(e)) < 1.0 < emax:
        cs = a.contour(x, y, e, levels=[1.0], colors="cyan", linewidths=1.5)
        a.clabel(cs, fmt="E = 1", fontsize=8)
        note = "cyan: E = 1"
    else:
        note = f"E {'<' if emax < 1 else '>'} 1 everywhere (max {emax:.3g}): no E = 1 contour"
    a.set_xlabel("N·V = cos θ_V (unitless)")
    a.set_ylabel("sheen roughness r (unitless)")
    a.set_title(f"sheen E table, {size}x{size}: visibility {sheen_visibility or 'charlie'}, "
                f"distribution {sheen_distribution or 'charlie'}\n{note}", fontsize=9)
    return Plot(fig, arrays)
