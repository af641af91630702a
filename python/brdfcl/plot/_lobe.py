"""brdfcl.plot.lobe: in-plane f·cosθ_L as polar plots, the lobes stacked, on a linear or log
radius (_radial_scale)."""
from __future__ import annotations

import math
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, cast

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from .. import evaluate as _evaluate
from .. import InputError, LOBES, MaterialsLike
from ._common import _LOBE_COLOURS, Device, Plot, _channel, _figure, _options_text, _resolution, _select


# ---- lobe: the in-plane polar plot ----

def lobe(materials: MaterialsLike, material: int = 0, *, view_angles: Sequence[float] = (0, 30, 60, 80),
         resolution: int = 361, channel: str = "luminance", radius: str = "linear", decades: float = 4,
         sheen_visibility: str = "charlie",
         sheen_distribution: str = "charlie", sheen_scaling: str = "min", profile: str = "spec",
         strict: bool = False, figsize: Tuple[float, float] = (9, 6), dpi: float = 100, ax: Optional[Axes] = None,
         device: Device = None) -> Plot:
    """In-plane f·cosθ_L for each view angle, as a polar plot (normal up): the diffuse, specular,
    sheen and clearcoat lobes as stacked filled areas, which add up to the total (lobe all, black).

    The plane is XZ: V = (sin θ_V, 0, cos θ_V) on the right, L = (sin θ_L, 0, cos θ_L) for θ_L
    from -90° (left, where the mirror direction θ_L = -θ_V lies) to 90°. The radius is
    f·cosθ_L (luminance or one channel, 1/sr), on a log scale from `decades` decades below the
    peak (radius="log": a smooth coat's spike and the diffuse lobe both show) or linear (the
    default, where the bands' areas compare honestly). One
    polar axes per view angle, each scaled to its peak; ax (a polar axes) with one view angle.

    arrays: theta_l_deg (n,), theta_v_deg (k,), L, V float32 (k, n, 3) as passed to
    brdfcl.evaluate, f_<lobe> float32 (k, n, 3) for each of LOBES (its result), r_<lobe> (k, n)
    the radii drawn.
    """
    m, name = _select(materials, material, strict)
    n = _resolution(resolution, 3, 10000)
    try:
        views = [float(a) for a in np.atleast_1d(np.asarray(view_angles, dtype=np.float64))]
    except (TypeError, ValueError):
        raise InputError(f"view_angles must be numbers of degrees in [0, 90), got {view_angles!r}") from None
    if not views or len(views) > 12 or not all(0 <= a < 90 for a in views):
        raise InputError(f"view_angles must be 1 to 12 angles in degrees in [0, 90), got {view_angles!r}")
    if radius not in ("log", "linear"):
        raise InputError(f"radius must be log or linear, got {radius!r}")
    if not (isinstance(decades, (int, float)) and 0.5 <= decades <= 12):
        raise InputError(f"decades must be a number from 0.5 to 12, got {decades!r}")
    if ax is not None and len(views) != 1:
        raise InputError(f"ax holds one polar plot; give one view angle with it, not {len(views)}")
    theta_l = np.linspace(-90.0, 90.0, n)
    tl = np.radians(theta_l)
    L1 = np.stack([np.sin(tl), np.zeros(n), np.cos(tl)], axis=-1)
    tv = np.radians(np.asarray(views))
    V1 = np.stack([np.sin(tv), np.zeros(len(views)), np.cos(tv)], axis=-1)
    L = np.broadcast_to(L1, (len(views), n, 3)).astype(np.float32)
    V = np.broadcast_to(V1[:, None, :], (len(views), n, 3)).astype(np.float32)
    arrays: Dict[str, Any] = {"theta_l_deg": theta_l, "theta_v_deg": np.asarray(views), "L": L, "V": V}
    cos_l = np.clip(np.cos(tl), 0.0, None)
    for lb in LOBES:
        f = _evaluate(m, L.reshape(-1, 3), V.reshape(-1, 3), lobe=lb, sheen_visibility=sheen_visibility,
                      sheen_distribution=sheen_distribution, sheen_scaling=sheen_scaling, profile=profile,
                      device=device).reshape(len(views), n, 3)
        arrays[f"f_{lb}"] = f
        arrays[f"r_{lb}"] = _channel(f, channel) * cos_l

    axes: List[Any]  # PolarAxes
    if ax is not None:
        fig, axes = cast(Figure, ax.figure), [ax]
    else:
        fig = _figure(figsize, dpi)
        cols = min(len(views), 2 if len(views) == 4 else 3)
        rows = math.ceil(len(views) / cols)
        axes = [fig.add_subplot(rows, cols, i + 1, projection="polar") for i in range(len(views))]
    what = "f·cosθ_L" + (", luminance" if channel == "luminance" else f", channel {channel.upper()}")
    for k, (a, view) in enumerate(zip(axes, views)):
        _draw_view(a, arrays, k, view, tl, radius, decades)
    handles, labels = axes[0].get_legend_handles_labels()
    for a in axes[1:]:
        for h, lab in zip(*a.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="outside lower center", ncols=len(labels), fontsize=8, frameon=False)
    scale = "linear radius" if radius == "linear" else f"log radius, {decades:g} decades below each peak"
    fig.suptitle(f"{name}: in-plane {what}, lobes stacked, {scale}\n"
                 f"{_options_text(profile, sheen_visibility, sheen_distribution, sheen_scaling)}", fontsize=10)
    return Plot(fig, arrays)


def _draw_view(a: Any, arrays: Dict[str, Any], k: int, view: float, tl: np.ndarray, radius: str,
               decades: float) -> None:
    """One view angle's polar axes: the stacked lobes, the total, the radial ticks and V."""
    n = len(tl)
    a.set_theta_zero_location("N")
    a.set_theta_direction(-1)  # positive θ_L to the right, V's side
    a.set_thetamin(-90)
    a.set_thetamax(90)
    peak = float(np.nanmax(arrays["r_all"][k])) if np.any(arrays["r_all"][k] > 0) else 1.0
    to_radius, ticks, tick_labels = _radial_scale(radius, peak, decades)
    bottom = np.zeros(n)
    for lb in LOBES[1:]:
        r = arrays[f"r_{lb}"][k]
        if not np.any(r > 0):
            continue
        # The bands are stacked in f·cosθ_L and only then mapped to the radius: each band's
        # outer edge is the sum of the lobes so far, also on the log scale.
        a.fill_between(tl, to_radius(bottom), to_radius(bottom + r), color=_LOBE_COLOURS[lb], alpha=0.8,
                       linewidth=0, label=lb)
        bottom = bottom + r
    a.plot(tl, to_radius(arrays["r_all"][k]), color="black", linewidth=1.0, label="total")
    top = float(to_radius(np.array([peak]))[0])
    a.set_rmax(top * 1.04)
    a.set_rmin(0)
    if ticks is not None and tick_labels is not None:
        a.set_rticks(ticks)
        a.set_yticklabels(tick_labels)
    else:
        a.yaxis.set_major_locator(MaxNLocator(3))  # labels along the baseline: few fit
    a.set_xlabel("θ_L (degrees); radius f·cosθ_L (1/sr)", fontsize=7, labelpad=-8)
    a.annotate("V", xy=(math.radians(view), top * 1.04), xytext=(math.radians(view), top * 0.55),
               ha="center", va="center", arrowprops={"arrowstyle": "<-", "color": "0.3"}, color="0.3")
    a.set_title(f"θ_V = {view:g}°", fontsize=9, pad=2)
    a.tick_params(labelsize=7, pad=1)


def _radial_scale(radius: str, peak: float, decades: float) -> Tuple[Callable[[np.ndarray], np.ndarray],
                                                                        Optional[List[float]], Optional[List[str]]]:
    """The map from f·cosθ_L to the polar radius, and the radial ticks (None: matplotlib's)."""
    if radius == "linear":
        return (lambda r: r), None, None
    lo = peak * 10.0 ** -decades
    ticks = [float(decades - t) for t in range(0, int(decades), 2)][::-1]  # every other decade
    return (lambda r: np.log10(np.maximum(r, lo) / lo)), ticks, [_short(lo * 10 ** t) for t in ticks]


def _short(v: float) -> str:
    """2 significant digits in few characters: 0.032, 3.2, 190, 1.9e3."""
    text = f"{v:.2g}"
    if "e" in text:
        mantissa, exponent = text.split("e")
        text = f"{mantissa}e{int(exponent)}"
    return text
