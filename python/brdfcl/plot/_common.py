"""What the brdfcl.plot figures share: Plot (a figure and its arrays), the constants (KINDS,
CHANNELS, lobe colours) and helpers (figures, material selection, channels, colour maps)."""
from __future__ import annotations

import io
import os
from typing import Any, Dict, Iterator, Optional, Tuple, Union, cast

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from .. import _core, _materials
from .. import Evaluator, InputError, MaterialsLike


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


def _cmap(name: str, bad: str) -> Any:
    import matplotlib

    cmap = matplotlib.colormaps[name].copy()
    cmap.set_bad(bad)
    return cmap
