"""brdfcl.plot: matplotlib figures of brdfcl's results (lobe, halfdiff, albedo, sheen_e, compare,
image, diff, samples): the labelled figures of everything the CLI writes as data or text-free pictures.
Each function returns a Plot: the figure and the numpy arrays it drew, which are exactly what
brdfcl.evaluate / albedo / lut / render returned for them. `python -m brdfcl plot` runs them.

Conventions are brdfcl's: N = +Z, T = +X, B = +Y; L towards the light, V towards the viewer; f in
1/sr without the cosine. "Luminance" is Rec. 709's Y = 0.2126 R + 0.7152 G + 0.0722 B.
"""
from __future__ import annotations

import io
import math
import os
from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence, Tuple, Union, cast

import numpy as np

try:
    from matplotlib.axes import Axes
    from matplotlib.colors import LogNorm, Normalize
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator
except ImportError as e:  # the rest of brdfcl works without it
    raise ImportError("brdfcl.plot needs matplotlib 3.7 or newer: pip install 'brdfcl[plot]' "
                      "(or pip install matplotlib)") from e

from . import _core, _materials, albedo as _albedo, evaluate as _evaluate, lut as _lut, pdf as _pdf, render as _render
from . import sample as _sample
from . import Error, Evaluator, InputError, LOBES, MaterialsLike

__all__ = ["Plot", "lobe", "halfdiff", "halfdiff_directions", "albedo", "sheen_e", "compare", "image", "diff",
           "tone_map", "samples", "KINDS"]

KINDS = ("lobe", "halfdiff", "albedo", "sheen-e", "compare", "image", "diff", "samples")
CHANNELS = ("luminance", "r", "g", "b")
Device = Union[None, int, str, Evaluator]
_REC709 = np.array([0.2126, 0.7152, 0.0722])
_LOBE_COLOURS = {"diffuse": "#4c72b0", "specular": "#dd8452", "sheen": "#c44e9c", "clearcoat": "#55a868"}


class Plot:
    """A figure and the arrays drawn in it. Unpacks as `figure, arrays = brdfcl.plot.lobe(...)`;
    shows itself inline in a notebook (as a PNG); save(path) writes .png, .svg or .pdf."""

    def __init__(self, figure: Figure, arrays: Dict[str, Any]):
        self.figure = figure
        self.arrays = arrays

    def __iter__(self) -> Iterator[Any]:
        return iter((self.figure, self.arrays))

    def __repr__(self) -> str:
        w, h = self.figure.get_size_inches()
        return f"<brdfcl.plot.Plot {w:g}x{h:g} in, arrays {sorted(self.arrays)}>"

    def save(self, path: Union[str, "os.PathLike[str]"], dpi: Optional[float] = None) -> None:
        """Writes the figure (format from the extension); the size is figsize x dpi pixels."""
        self.figure.savefig(path, dpi=dpi if dpi is not None else self.figure.dpi)

    def _repr_png_(self) -> bytes:
        buf = io.BytesIO()
        self.figure.savefig(buf, format="png")
        return buf.getvalue()


# ---- Shared helpers ----

def _figure(figsize: Tuple[float, float], dpi: float) -> Figure:
    # A Figure made without pyplot: no global figure list to leak from in loops, no GUI backend.
    try:
        w, h = (float(v) for v in figsize)
    except (TypeError, ValueError):
        raise InputError(f"figsize must be (width, height) in inches, e.g. (9, 4.5), got {figsize!r}") from None
    if not (0 < w <= 100 and 0 < h <= 100):
        raise InputError(f"figsize must be (width, height) in inches from 0 to 100, got {figsize!r}")
    if not (isinstance(dpi, (int, float)) and 1 <= dpi <= 1000):
        raise InputError(f"dpi must be a number from 1 to 1000, got {dpi!r}")
    return Figure(figsize=(w, h), dpi=dpi, layout="constrained")


def _select(materials: MaterialsLike, material: int, strict: bool) -> Tuple["_core.Materials", str]:
    """One material of `materials` (read as brdfcl.evaluate reads them) and its name for titles."""
    m = materials if isinstance(materials, _core.Materials) else _materials(materials, strict)
    count = len(m)
    if isinstance(material, bool) or not isinstance(material, (int, np.integer)):
        raise InputError(f"material must be an integer index, got {material!r}")
    if not 0 <= material < count:
        raise InputError(f"material {material} is out of range: there {'is' if count == 1 else 'are'} {count} "
                    f"material{'' if count == 1 else 's'}; use 0 to {count - 1}")
    name = _plain(m.names[int(material)] or "unnamed")
    return _core.select_material(m, int(material)), f"[{int(material)}] {name}"


def _plain(text: str) -> str:
    """A name from a file, drawn as it is: matplotlib would read "$...$" in it as mathematics."""
    return text.replace("$", r"\$")


def _channel(f: np.ndarray, channel: str) -> np.ndarray:
    """The value drawn of RGB f (..., 3): luminance (float64) or one channel."""
    if channel == "luminance":
        return f.astype(np.float64) @ _REC709
    if channel in ("r", "g", "b"):
        return f[..., "rgb".index(channel)].astype(np.float64)
    raise InputError(f"channel must be one of {', '.join(CHANNELS)}, got {channel!r}")


def _options_text(profile: str, sheen_visibility: str, sheen_distribution: str, sheen_scaling: str,
                  lobe: Optional[str] = None) -> str:
    parts = [] if lobe is None else [f"lobe {lobe}"]
    parts.append(f"profile {profile}")
    parts.append(f"sheen V {sheen_visibility}, D {sheen_distribution}, scaling {sheen_scaling}")
    return ", ".join(parts)


def _resolution(n: int, lo: int, hi: int) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not lo <= n <= hi:
        raise InputError(f"resolution must be an integer from {lo} to {hi}, got {n!r}")
    return int(n)


def _cell_centres_deg(n: int) -> np.ndarray:
    # (i + 0.5) 90 / n: never 0 or 90 degrees, as `brdfcl compare`'s grids.
    return (np.arange(n) + 0.5) * (90.0 / n)


def _single_axes(ax: Optional[Axes], figsize: Tuple[float, float], dpi: float, **kw: Any) -> Tuple[Figure, Axes]:
    if ax is not None:
        return cast(Figure, ax.figure), ax
    fig = _figure(figsize, dpi)
    return fig, fig.add_subplot(**kw)


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


# ---- halfdiff: the MERL / BRDF Explorer slice ----

def halfdiff_directions(theta_h_deg: np.ndarray, theta_d_deg: np.ndarray, phi_d_deg: float = 90.0,
                        phi_h_deg: float = 0.0) -> Tuple[np.ndarray, np.ndarray]:
    """L and V (float64, shape (len(theta_d), len(theta_h), 3)) of Rusinkiewicz's half/difference
    angles. The half vector H = (sin θ_h cos φ_h, sin θ_h sin φ_h, cos θ_h); the difference vector
    D = (sin θ_d cos φ_d, sin θ_d sin φ_d, cos θ_d) is L in the frame where H is the pole:
    L = R_z(φ_h) R_y(θ_h) D, and V is D mirrored about H's pole, V = R_z(φ_h) R_y(θ_h)
    (-D_x, -D_y, D_z). At φ_d = 90° and φ_h = 0 this is L = (cos θ_d sin θ_h, sin θ_d,
    cos θ_d cos θ_h), V = (cos θ_d sin θ_h, -sin θ_d, cos θ_d cos θ_h): both above the horizon
    for every θ_h, θ_d in [0, 90°) (the slice `brdfcl compare` draws)."""
    th, td = np.meshgrid(np.radians(theta_h_deg), np.radians(theta_d_deg))
    pd, ph = math.radians(phi_d_deg), math.radians(phi_h_deg)
    d = np.stack([np.sin(td) * math.cos(pd), np.sin(td) * math.sin(pd), np.cos(td)], axis=-1)

    def to_world(v: np.ndarray) -> np.ndarray:
        # R_y(θ_h) then R_z(φ_h), applied to vectors in the H frame.
        x = v[..., 0] * np.cos(th) + v[..., 2] * np.sin(th)
        z = -v[..., 0] * np.sin(th) + v[..., 2] * np.cos(th)
        y = v[..., 1]
        return np.stack([x * math.cos(ph) - y * math.sin(ph), x * math.sin(ph) + y * math.cos(ph), z], axis=-1)

    mirrored = d * np.array([-1.0, -1.0, 1.0])
    return to_world(d), to_world(mirrored)


def halfdiff(materials: MaterialsLike, material: int = 0, *, resolution: int = 90, lobe: str = "all",
             channel: str = "luminance", vmin: Optional[float] = None, vmax: Optional[float] = None,
             sheen_visibility: str = "charlie", sheen_distribution: str = "charlie", sheen_scaling: str = "min",
             profile: str = "spec", strict: bool = False, figsize: Tuple[float, float] = (6, 5), dpi: float = 100,
             ax: Optional[Axes] = None, device: Device = None) -> Plot:
    """f over (θ_h, θ_d) at φ_d = 90°, φ_h = 0 (Rusinkiewicz's half/difference angles, see
    halfdiff_directions): an image on a logarithmic colour scale, as MERL and BRDF Explorer show
    BRDFs. Cells are resolution x resolution centres in [0, 90)°; cells where f is 0 are grey.
    The colour scale spans the smallest positive value (at least 1e-8 of the largest) to the
    largest unless vmin, vmax say otherwise.

    arrays: theta_h_deg (n,), theta_d_deg (n,), L, V float32 (n, n, 3) ([θ_d index, θ_h index]),
    f float32 (n, n, 3) (brdfcl.evaluate's result), value (n, n) the luminance or channel drawn.
    """
    m, name = _select(materials, material, strict)
    n = _resolution(resolution, 2, 1024)
    theta = _cell_centres_deg(n)
    Ld, Vd = halfdiff_directions(theta, theta)
    L: np.ndarray = Ld.astype(np.float32)
    V: np.ndarray = Vd.astype(np.float32)
    f = _evaluate(m, L.reshape(-1, 3), V.reshape(-1, 3), lobe=lobe, sheen_visibility=sheen_visibility,
                  sheen_distribution=sheen_distribution, sheen_scaling=sheen_scaling, profile=profile,
                  device=device).reshape(n, n, 3)
    value = _channel(f, channel)
    arrays = {"theta_h_deg": theta, "theta_d_deg": theta, "L": L, "V": V, "f": f, "value": value}
    fig, a = _single_axes(ax, figsize, dpi)
    shown = np.ma.masked_where(~(value > 0) | ~np.isfinite(value), value)
    top = float(shown.max()) if shown.count() else 1.0
    low = max(float(shown.min()), top * 1e-8) if shown.count() else top * 1e-4
    norm = LogNorm(vmin=vmin if vmin is not None else low, vmax=vmax if vmax is not None else top, clip=True)
    cmap = _cmap("viridis", bad="0.75")
    im = a.imshow(shown, origin="lower", extent=(0, 90, 0, 90), norm=norm, cmap=cmap, interpolation="nearest",
                  aspect="equal")
    a.set_xlabel("θ_h (degrees)")
    a.set_ylabel("θ_d (degrees)")
    what = "luminance" if channel == "luminance" else f"channel {channel.upper()}"
    fig.colorbar(im, ax=a, label=f"f, {what} (1/sr, log scale)")
    a.set_title(f"{name}: f over (θ_h, θ_d), φ_d = 90°, φ_h = 0\n"
                f"{_options_text(profile, sheen_visibility, sheen_distribution, sheen_scaling, lobe)}", fontsize=9)
    return Plot(fig, arrays)


def _cmap(name: str, bad: str) -> Any:
    import matplotlib

    cmap = matplotlib.colormaps[name].copy()
    cmap.set_bad(bad)
    return cmap


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


# ---- compare: two profiles as a ratio heat map ----

def compare(materials: MaterialsLike, material: int = 0, *, profile: str = "khronos", against: str = "spec",
            plane: str = "inplane", lobe: str = "all", resolution: int = 90, sheen_visibility: str = "charlie",
            sheen_distribution: str = "charlie", sheen_scaling: str = "min", strict: bool = False,
            figsize: Tuple[float, float] = (6, 5), dpi: float = 100, ax: Optional[Axes] = None,
            device: Device = None) -> Plot:
    """log2 of f under `profile` over f under `against` (luminance), as `brdfcl compare`'s heat
    maps: plane="inplane", the incidence plane over (θ_L, θ_V) cell centres in [0, 90)°:
    V = (sin θ_V, 0, cos θ_V), L = (-sin θ_L, 0, cos θ_L) (the mirror azimuth); plane="halfdiff",
    (θ_h, θ_d) cell centres at φ_h = 0, φ_d = 90° (halfdiff_directions). Both luminances are floored at
    1e-3 ρ₀/π (ρ₀ the largest channel of the lobe-all albedo at normal view under either profile)
    so that 0/0 never occurs; a diverging map centred on 0 (equal) over ±R, R the first of 0.25,
    0.5, 1, 2, 4, 8 that holds the largest |log2| (beyond 8, the end colours); cells where either
    f is not finite are magenta.

    arrays: theta_l_deg, theta_v_deg (n,) (inplane) or theta_h_deg, theta_d_deg (n,)
    (halfdiff), L, V float32 (n, n, 3) ([θ_V or θ_d index, θ_L or θ_h index]), f_a, f_b float32
    (n, n, 3) (brdfcl.evaluate under profile and against), floor, log2_ratio (n, n).
    """
    if plane not in ("inplane", "halfdiff"):
        raise InputError(f"plane must be inplane or halfdiff, got {plane!r}")
    m, name = _select(materials, material, strict)
    n = _resolution(resolution, 2, 1024)
    theta = _cell_centres_deg(n)
    if plane == "inplane":
        tl, tv = np.meshgrid(np.radians(theta), np.radians(theta))
        L = np.stack([-np.sin(tl), np.zeros_like(tl), np.cos(tl)], axis=-1).astype(np.float32)
        V = np.stack([np.sin(tv), np.zeros_like(tv), np.cos(tv)], axis=-1).astype(np.float32)
    else:
        Ld, Vd = halfdiff_directions(theta, theta)
        L, V = Ld.astype(np.float32), Vd.astype(np.float32)
    opts: Dict[str, Any] = dict(sheen_visibility=sheen_visibility, sheen_distribution=sheen_distribution,
                sheen_scaling=sheen_scaling, device=device)
    fa = _evaluate(m, L.reshape(-1, 3), V.reshape(-1, 3), lobe=lobe, profile=profile, **opts).reshape(n, n, 3)
    fb = _evaluate(m, L.reshape(-1, 3), V.reshape(-1, 3), lobe=lobe, profile=against, **opts).reshape(n, n, 3)
    rho = [_albedo(m, 1.0, profile=p, **opts)["all"][0] for p in (profile, against)]
    finite = np.concatenate([r[np.isfinite(r)] for r in rho])
    rho0 = float(finite.max()) if finite.size else 0.0
    floor = max(1e-3 * rho0 / math.pi, float(np.finfo(np.float32).tiny))
    ya, yb = _channel(fa, "luminance"), _channel(fb, "luminance")
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        ratio = np.log2(np.maximum(ya, floor) / np.maximum(yb, floor))
    bad = ~(np.isfinite(ya) & np.isfinite(yb))
    ratio[bad] = np.nan
    axes = ("theta_l_deg", "theta_v_deg") if plane == "inplane" else ("theta_h_deg", "theta_d_deg")
    arrays = {axes[0]: theta, axes[1]: theta, "L": L, "V": V, "f_a": fa, "f_b": fb, "floor": floor,
              "log2_ratio": ratio}
    max_abs = float(np.nanmax(np.abs(ratio))) if np.any(~bad) else 0.0
    limit = next((r for r in (0.25, 0.5, 1.0, 2.0, 4.0, 8.0) if max_abs <= r), 8.0)
    fig, a = _single_axes(ax, figsize, dpi)
    im = a.imshow(np.ma.masked_invalid(ratio), origin="lower", extent=(0, 90, 0, 90), cmap=_cmap("RdBu_r", "magenta"),
                  norm=Normalize(-limit, limit, clip=True), interpolation="nearest", aspect="equal")
    fig.colorbar(im, ax=a, label=f"log2(f_{profile} / f_{against}), luminance (unitless)")
    if plane == "inplane":
        a.set_xlabel("θ_L (degrees), L at φ = 180°")
        a.set_ylabel("θ_V (degrees), V at φ = 0")
    else:
        a.set_xlabel("θ_h (degrees), φ_h = 0")
        a.set_ylabel("θ_d (degrees), φ_d = 90°")
    extra = f"; magenta: {int(bad.sum())} cell(s) not finite" if bad.any() else ""
    where = "in-plane" if plane == "inplane" else "half/difference angles"
    a.set_title(f"{name}: {profile} vs {against}, {where}, max |log2| {max_abs:.3g}{extra}\n"
                f"lobe {lobe}, sheen V {sheen_visibility}, D {sheen_distribution}, scaling {sheen_scaling}, "
                f"floor {floor:.3g} 1/sr", fontsize=9)
    return Plot(fig, arrays)


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


# ---- samples: the sampler's histogram against its pdf ----

def samples(materials: MaterialsLike, material: int = 0, *, view: Tuple[float, float] = (45.0, 0.0),
            lobe: str = "all", count: int = 200000, seed: int = 0, bins: Tuple[int, int] = (18, 36),
            quadrature: int = 4, sheen_visibility: str = "charlie", sheen_distribution: str = "charlie",
            sheen_scaling: str = "min", profile: str = "spec", strict: bool = False,
            figsize: Tuple[float, float] = (14, 5), dpi: float = 100, device: Device = None) -> Plot:
    """The directions brdfcl.sample draws for one material and view, binned on the hemisphere in
    (θ_L, φ_L), against the density brdfcl.pdf gives them: three polar panels seen from above the
    surface (radius θ_L, angle φ_L), the histogram and the pdf integrated over each bin, both as a
    mean density in 1/sr on one log colour scale, and their difference in standard deviations,
    (observed − expected) / √expected (Pearson's residual: about ±1 everywhere when sampler and pdf
    agree, whatever a bin's count).

    view: (θ_V, φ_V) in degrees, V = (sin θ_V cos φ_V, sin θ_V sin φ_V, cos θ_V), θ_V in [0, 90).
    lobe: all (the one-sample mixture) or one lobe's sampler alone. count samples from the
    counter-based generator with seed (those of `brdfcl sample --count --seed`). bins: (θ bins
    over [0, 90°], φ bins over [0, 360°)). Each bin's pdf integral is a quadrature x quadrature
    Gauss-Legendre rule in (θ, φ) of pdf sin θ: a lobe narrower than the nodes' spacing (a smooth
    coat, α ≲ 0.05) needs more bins or nodes before the residuals and χ² mean anything. Bins
    expecting fewer than 5 samples stay out of the residual panel and the χ² of the title (their
    expected mass is summed into one pooled bin).

    arrays: theta_edges_deg (nθ+1,), phi_edges_deg (nφ+1,), V (3,), L float32 (count, 3), pdf
    float32 (count,), weight float32 (count, 3) (brdfcl.sample's result), counts (nθ, nφ) of the
    kept samples, expected (nθ, nφ) = count x the integral of the pdf over each bin, ratio and
    residual (nθ, nφ) (observed / expected and (observed − expected) / √expected, NaN where a bin
    expects fewer than 5), solid_angle (nθ, nφ) in sr, kept (the fraction of samples with a direction), pdf_mass (the pdf's integral
    over the hemisphere), chi2 and dof (Pearson's statistic over the bins expecting 5 or more, with
    one pooled bin for the rest and one for the samples without a direction).
    """
    m, name = _select(materials, material, strict)
    if lobe not in LOBES:
        raise InputError(f"lobe must be one of {', '.join(LOBES)}, got {lobe!r}")
    try:
        theta_v, phi_v = (float(v) for v in view)
    except (TypeError, ValueError):
        raise InputError(f"view must be (theta, phi) in degrees, e.g. (45, 0), got {view!r}") from None
    if not (0.0 <= theta_v < 90.0 and math.isfinite(phi_v)):
        raise InputError(f"view must be (theta, phi) in degrees with theta in [0, 90), got {view!r}")
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or not 100 <= count <= 100_000_000:
        raise InputError(f"count must be an integer from 100 to 100000000, got {count!r}")
    try:
        n_theta, n_phi = (int(b) for b in bins)
    except (TypeError, ValueError):
        raise InputError(f"bins must be (theta bins, phi bins), e.g. (18, 36), got {bins!r}") from None
    if not (2 <= n_theta <= 360 and 4 <= n_phi <= 720):
        raise InputError(f"bins must be 2 to 360 theta bins and 4 to 720 phi bins, got {bins!r}")
    if isinstance(quadrature, bool) or not isinstance(quadrature, (int, np.integer)) or not 1 <= quadrature <= 16:
        raise InputError(f"quadrature must be an integer from 1 to 16, got {quadrature!r}")
    opts: Dict[str, Any] = dict(sheen_visibility=sheen_visibility, sheen_distribution=sheen_distribution,
                                sheen_scaling=sheen_scaling, profile=profile, device=device)
    tv, pv = math.radians(theta_v), math.radians(phi_v)
    V = np.array([math.sin(tv) * math.cos(pv), math.sin(tv) * math.sin(pv), math.cos(tv)])
    L, pdf, weight = _sample(m, V[None, :], count=int(count), seed=seed, lobe=lobe, **opts)

    theta_edges = np.linspace(0.0, 90.0, n_theta + 1)
    phi_edges = np.linspace(0.0, 360.0, n_phi + 1)
    kept = pdf > 0
    lk = L[kept].astype(np.float64)
    theta_l = np.degrees(np.arccos(np.clip(lk[:, 2], -1.0, 1.0)))
    phi_l = np.degrees(np.arctan2(lk[:, 1], lk[:, 0])) % 360.0
    counts, _, _ = np.histogram2d(theta_l, phi_l, bins=(theta_edges, phi_edges))

    # Gauss-Legendre nodes in each bin: pdf x sin θ over (θ, φ) in radians.
    x, w = np.polynomial.legendre.leggauss(int(quadrature))
    th_lo, dth = np.radians(theta_edges[:-1]), math.radians(90.0 / n_theta)
    ph_lo, dph = np.radians(phi_edges[:-1]), math.radians(360.0 / n_phi)
    th = (th_lo[:, None] + dth * (x[None, :] + 1) / 2).reshape(-1)  # (nθ q,)
    ph = (ph_lo[:, None] + dph * (x[None, :] + 1) / 2).reshape(-1)  # (nφ q,)
    T, P = np.meshgrid(th, ph, indexing="ij")
    Lq = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], axis=-1).reshape(-1, 3)
    Vq = np.broadcast_to(V.astype(np.float32), Lq.shape)
    pq = _pdf(m, Lq, Vq, lobe=lobe, **opts).astype(np.float64).reshape(T.shape) * np.sin(T)
    q = int(quadrature)
    wq = np.outer(w, w) * (dth / 2) * (dph / 2)
    integral = (pq.reshape(n_theta, q, n_phi, q) * wq[None, :, None, :]).sum(axis=(1, 3))
    solid = np.outer(np.cos(th_lo) - np.cos(th_lo + dth), np.full(n_phi, dph))
    expected = count * integral
    kept_fraction = float(kept.mean())
    pdf_mass = float(integral.sum())

    # Pearson's χ² over the bins expecting 5 or more, the rest pooled, and the "no direction" cell
    # (expected: what the pdf leaves of 1).
    big = expected >= 5
    obs = [counts[big]]
    exp = [expected[big]]
    if (~big).any() and expected[~big].sum() > 0:
        obs.append(np.array([counts[~big].sum()]))
        exp.append(np.array([expected[~big].sum()]))
    missing = count * max(1.0 - pdf_mass, 0.0)
    if missing >= 5:
        obs.append(np.array([float(count - kept.sum())]))
        exp.append(np.array([missing]))
    o, e = np.concatenate(obs), np.concatenate(exp)
    chi2 = float(((o - e) ** 2 / e).sum())
    dof = max(len(o) - 1, 1)

    with np.errstate(invalid="ignore", divide="ignore"):
        density_obs = counts / (count * solid)
        density_exp = integral / solid
        ratio = np.where(big, counts / expected, np.nan)
        residual = np.where(big, (counts - expected) / np.sqrt(expected), np.nan)
    arrays: Dict[str, Any] = {"theta_edges_deg": theta_edges, "phi_edges_deg": phi_edges, "V": V, "L": L,
                              "pdf": pdf, "weight": weight, "counts": counts, "expected": expected,
                              "ratio": ratio, "residual": residual, "solid_angle": solid, "kept": kept_fraction,
                              "pdf_mass": pdf_mass, "chi2": chi2, "dof": dof}

    fig = _figure(figsize, dpi)
    axes = [fig.add_subplot(1, 3, i + 1, projection="polar") for i in range(3)]
    positive = np.concatenate([density_obs[density_obs > 0], density_exp[density_exp > 0]])
    top = float(positive.max()) if positive.size else 1.0
    norm = LogNorm(vmin=top * 1e-4, vmax=top, clip=True)
    PH, TH = np.meshgrid(np.radians(phi_edges), theta_edges)
    cmap = _cmap("viridis", "white")
    for a, data, title in ((axes[0], density_obs, f"histogram of {count} samples"),
                           (axes[1], density_exp, "pdf integrated over each bin")):
        im = a.pcolormesh(PH, TH, np.ma.masked_less_equal(data, 0), cmap=cmap, norm=norm, shading="flat")
        a.set_title(f"{title} (1/sr)", fontsize=9)
    fig.colorbar(im, ax=axes[:2], label="mean density over the bin (1/sr), log scale", shrink=0.8)
    im = axes[2].pcolormesh(PH, TH, np.ma.masked_invalid(residual), cmap=_cmap("RdBu_r", "0.85"),
                            norm=Normalize(-4.0, 4.0, clip=True), shading="flat")
    fig.colorbar(im, ax=axes[2], label="(observed − expected) / √expected", shrink=0.8, extend="both")
    axes[2].set_title("residual; grey: bins expecting < 5", fontsize=9)
    mirror = (math.radians(phi_v + 180.0), theta_v)
    for a in axes:
        a.set_ylim(0, 90)
        a.set_yticks([30, 60, 90])
        a.set_yticklabels(["30°", "60°", "90°"], fontsize=7)
        a.tick_params(labelsize=7, pad=1)
        a.plot([math.radians(phi_v)], [theta_v], marker="o", color="red", markersize=5, linestyle="none",
               label="V")
        a.plot([mirror[0]], [mirror[1]], marker="x", color="red", markersize=6, linestyle="none",
               label="mirror of V")
    axes[0].legend(loc="lower left", bbox_to_anchor=(-0.15, -0.15), fontsize=7, frameon=False)
    fig.suptitle(f"{name}: lobe {lobe}, θ_V = {theta_v:g}°, φ_V = {phi_v:g}°; radius θ_L, angle φ_L\n"
                 f"kept {100 * kept_fraction:.2f} % of samples, ∫pdf = {pdf_mass:.4f}, "
                 f"χ² = {chi2:.1f} over {dof} degrees of freedom; "
                 f"{_options_text(profile, sheen_visibility, sheen_distribution, sheen_scaling)}", fontsize=10)
    return Plot(fig, arrays)
