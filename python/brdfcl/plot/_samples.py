"""brdfcl.plot.samples: brdfcl.sample's histogram on the hemisphere against brdfcl.pdf integrated
over each bin, their Pearson residuals and χ²."""
from __future__ import annotations

import math
from typing import Any, Dict, Tuple

import numpy as np
from matplotlib.colors import LogNorm, Normalize

from .. import pdf as _pdf, sample as _sample
from .. import InputError, LOBES, MaterialsLike
from ._common import Device, Plot, _cmap, _figure, _options_text, _select


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
    theta_v, phi_v, n_theta, n_phi = _check_arguments(lobe, view, count, bins, quadrature)
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

    integral, solid = _bin_integrals(m, V, lobe, opts, theta_edges, phi_edges, int(quadrature))
    expected = count * integral
    kept_fraction = float(kept.mean())
    pdf_mass = float(integral.sum())

    big = expected >= 5
    chi2, dof = _chi2(counts, expected, big, count, kept, pdf_mass)
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
    _draw(fig, phi_edges, theta_edges, density_obs, density_exp, residual, count, theta_v, phi_v)
    fig.suptitle(f"{name}: lobe {lobe}, θ_V = {theta_v:g}°, φ_V = {phi_v:g}°; radius θ_L, angle φ_L\n"
                 f"kept {100 * kept_fraction:.2f} % of samples, ∫pdf = {pdf_mass:.4f}, "
                 f"χ² = {chi2:.1f} over {dof} degrees of freedom; "
                 f"{_options_text(profile, sheen_visibility, sheen_distribution, sheen_scaling)}", fontsize=10)
    return Plot(fig, arrays)


def _check_arguments(lobe: str, view: Tuple[float, float], count: int, bins: Tuple[int, int],
                     quadrature: int) -> Tuple[float, float, int, int]:
    """samples()'s arguments checked: (θ_V, φ_V) in degrees and the bin counts."""
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
    return theta_v, phi_v, n_theta, n_phi


def _bin_integrals(m: Any, V: np.ndarray, lobe: str, opts: Dict[str, Any], theta_edges: np.ndarray,
                   phi_edges: np.ndarray, quadrature: int) -> Tuple[np.ndarray, np.ndarray]:
    """The pdf integrated over each (θ, φ) bin, and the bins' solid angles in sr."""
    n_theta, n_phi = len(theta_edges) - 1, len(phi_edges) - 1
    # Gauss-Legendre nodes in each bin: pdf x sin θ over (θ, φ) in radians.
    x, w = np.polynomial.legendre.leggauss(quadrature)
    th_lo, dth = np.radians(theta_edges[:-1]), math.radians(90.0 / n_theta)
    ph_lo, dph = np.radians(phi_edges[:-1]), math.radians(360.0 / n_phi)
    th = (th_lo[:, None] + dth * (x[None, :] + 1) / 2).reshape(-1)  # (nθ q,)
    ph = (ph_lo[:, None] + dph * (x[None, :] + 1) / 2).reshape(-1)  # (nφ q,)
    T, P = np.meshgrid(th, ph, indexing="ij")
    Lq = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], axis=-1).reshape(-1, 3)
    Vq = np.broadcast_to(V.astype(np.float32), Lq.shape)
    pq = _pdf(m, Lq, Vq, lobe=lobe, **opts).astype(np.float64).reshape(T.shape) * np.sin(T)
    q = quadrature
    wq = np.outer(w, w) * (dth / 2) * (dph / 2)
    integral = (pq.reshape(n_theta, q, n_phi, q) * wq[None, :, None, :]).sum(axis=(1, 3))
    solid = np.outer(np.cos(th_lo) - np.cos(th_lo + dth), np.full(n_phi, dph))
    return integral, solid


def _chi2(counts: np.ndarray, expected: np.ndarray, big: np.ndarray, count: int, kept: np.ndarray,
          pdf_mass: float) -> Tuple[float, int]:
    """Pearson's χ² and its degrees of freedom."""
    # Pearson's χ² over the bins expecting 5 or more, the rest pooled, and the "no direction" cell
    # (expected: what the pdf leaves of 1).
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
    return chi2, dof


def _draw(fig: Any, phi_edges: np.ndarray, theta_edges: np.ndarray, density_obs: np.ndarray,
          density_exp: np.ndarray, residual: np.ndarray, count: int, theta_v: float, phi_v: float) -> None:
    """The three polar panels: histogram, integrated pdf and residual, with V and its mirror marked."""
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
