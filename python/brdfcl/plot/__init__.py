"""brdfcl.plot: matplotlib figures of brdfcl's results (lobe, halfdiff, albedo, sheen_e, compare,
image, diff, samples): the labelled figures of everything the CLI writes as data or text-free pictures.
Each function returns a Plot: the figure and the numpy arrays it drew, which are exactly what
brdfcl.evaluate / albedo / lut / render returned for them. `python -m brdfcl plot` runs them.

Conventions are brdfcl's: N = +Z, T = +X, B = +Y; L towards the light, V towards the viewer; f in
1/sr without the cosine. "Luminance" is Rec. 709's Y = 0.2126 R + 0.7152 G + 0.0722 B.

The figures are defined in _lobe (lobe), _halfdiff (halfdiff, halfdiff_directions, compare),
_albedo (albedo, sheen_e), _image (image, tone_map, diff) and _samples (samples); Plot and the
helpers they share in _common. This file checks for matplotlib and re-exports them.
"""
from __future__ import annotations

# matplotlib first, for this message when it is missing; the figure modules import what they use.
try:
    from matplotlib.axes import Axes
    from matplotlib.colors import LogNorm, Normalize
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator
except ImportError as e:  # the rest of brdfcl works without it
    raise ImportError("brdfcl.plot needs matplotlib 3.7 or newer: pip install 'brdfcl[plot]' "
                      "(or pip install matplotlib)") from e

from ._common import CHANNELS, KINDS, Device, Plot
from ._lobe import lobe
from ._halfdiff import compare, halfdiff, halfdiff_directions
from ._albedo import albedo, sheen_e
from ._image import diff, image, tone_map
from ._samples import samples

__all__ = ["Plot", "lobe", "halfdiff", "halfdiff_directions", "albedo", "sheen_e", "compare", "image", "diff",
           "tone_map", "samples", "KINDS"]

# The classes and functions above are brdfcl.plot's wherever they are defined: repr, help() and
# pickling name them brdfcl.plot.X, as before the package was split into modules.
for _name in __all__:
    _obj = globals()[_name]
    if getattr(_obj, "__module__", "").startswith(__name__ + "._"):
        _obj.__module__ = __name__
del _name, _obj
