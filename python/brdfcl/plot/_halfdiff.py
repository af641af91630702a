"""Heat maps over angle pairs: brdfcl.plot.halfdiff (f over Rusinkiewicz's θ_h, θ_d, with
halfdiff_directions) and compare (log2 ratio of two profiles, in-plane or half/difference)."""
from __future__ import annotations

import math
from typing import Any, Dict, Optional, Tuple

import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import LogNorm, Normalize

from .. import albedo as _albedo, evaluate as _evaluate
from .. import InputError, MaterialsLike
from ._common import (Device, Plot, _cell_centres_deg, _channel, _cmap, _options_text, _resolution, _select,
                      _single_axes)


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
