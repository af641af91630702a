"""`python -m brdfcl plot KIND --materials M.json [--material I] [options] --out FILE.png|.svg|.pdf`:
the brdfcl.plot figures from the shell. Bad input: one line `brdfcl: error: ...` on stderr, exit
status 2, and no output file (the figure is written to a temporary file, then renamed).
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import warnings
from typing import Any, Callable, Dict, List, NoReturn, Optional, Sequence, Tuple

FORMATS = (".png", ".svg", ".pdf")


class _Parser(argparse.ArgumentParser):
    """argparse with the CLI's one-line errors instead of a usage block."""

    def error(self, message: str) -> NoReturn:
        _fail(message)


class _UsageError(Exception):
    pass


def _fail(message: str) -> NoReturn:
    raise _UsageError(message)


def _pair(text: str, what: str, cast: Callable[[str], Any]) -> Tuple[Any, Any]:
    try:
        w, h = (cast(v) for v in text.lower().split("x"))
    except ValueError:
        _fail(f"{what} '{text}' must be WIDTHxHEIGHT, e.g. 9x4.5")
    return w, h


def _bins(text: str) -> Tuple[int, int]:
    try:
        t, p = (int(v) for v in text.lower().split("x"))
    except ValueError:
        _fail(f"--bins '{text}' must be THETAxPHI bin counts, e.g. 18x36")
    return t, p


def _angles(text: str, option: str = "--view-angles") -> List[float]:
    try:
        return [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        _fail(f"{option} '{text}' must be degrees separated by commas, e.g. 0,30,60")


def _common(p: argparse.ArgumentParser, materials: bool, figsize: str) -> None:
    if materials:
        p.add_argument("--materials", required=True, metavar="M.json",
                       help="glTF materials: a .gltf/.glb or a JSON file, as `brdfcl eval --materials`")
        p.add_argument("--material", type=int, default=0, metavar="I", help="index of the material (default 0)")
        p.add_argument("--strict", action="store_true", help="unknown keys in the materials file are errors")
    p.add_argument("--out", required=True, metavar="FILE", help="the figure: .png, .svg or .pdf")
    p.add_argument("--figsize", default=figsize, metavar="WxH", help=f"figure size in inches (default {figsize})")
    p.add_argument("--dpi", type=float, default=100, help="pixels per inch (default 100): PNG size = figsize x dpi")
    p.add_argument("--device", help="OpenCL device index or name substring")


def _model(p: argparse.ArgumentParser, profile: bool = True) -> None:
    if profile:
        p.add_argument("--profile", default="spec", help="spec|khronos|threejs|filament|babylon|materialx")
    p.add_argument("--sheen-visibility", default="charlie", help="charlie|ashikhmin")
    p.add_argument("--sheen-distribution", default="charlie", help="charlie|ashikhmin")
    p.add_argument("--sheen-scaling", default="min", help="min|view|none")


def _parser() -> argparse.ArgumentParser:
    top = _Parser(prog="python -m brdfcl", description="brdfcl's Python command line")
    commands = top.add_subparsers(dest="command", metavar="COMMAND", required=True)
    plot = commands.add_parser("plot", help="draw a brdfcl.plot figure into a file",
                               description="Draw a brdfcl.plot figure into .png, .svg or .pdf")
    kinds = plot.add_subparsers(dest="kind", metavar="KIND", required=True)

    p = kinds.add_parser("lobe", help="in-plane f·cosθ_L, polar, stacked lobes")
    _common(p, True, "9x6")
    _model(p)
    p.add_argument("--view-angles", default="0,30,60,80", metavar="A,B,...", help="θ_V in degrees (default 0,30,60,80)")
    p.add_argument("--resolution", type=int, default=361, help="θ_L samples from -90 to 90° (default 361)")
    p.add_argument("--channel", default="luminance", help="luminance|r|g|b")
    p.add_argument("--radius", default="linear", help="linear|log (default linear)")
    p.add_argument("--decades", type=float, default=4, help="log radius: decades shown below the peak (default 4)")

    p = kinds.add_parser("halfdiff", help="f over (θ_h, θ_d) at φ_d = 90°, log colour scale")
    _common(p, True, "6x5")
    _model(p)
    p.add_argument("--lobe", default="all", help="all|diffuse|specular|sheen|clearcoat")
    p.add_argument("--resolution", type=int, default=90, help="cells per side (default 90)")
    p.add_argument("--channel", default="luminance", help="luminance|r|g|b")

    p = kinds.add_parser("albedo", help="directional albedo per lobe against θ_V")
    _common(p, True, "7x4.5")
    _model(p)
    p.add_argument("--resolution", type=int, default=46, help="view angles from 0 to 89° (default 46)")
    p.add_argument("--channel", default="luminance", help="luminance|r|g|b")

    p = kinds.add_parser("sheen-e", help="the sheen E table with its E = 1 contour")
    _common(p, False, "6x5")
    p.add_argument("--size", type=int, default=64, help="table size N (default 64)")
    p.add_argument("--sheen-visibility", help="charlie|ashikhmin (default charlie)")
    p.add_argument("--sheen-distribution", help="charlie|ashikhmin (default charlie)")

    p = kinds.add_parser("compare", help="log2 ratio of two profiles, heat map (`brdfcl compare --out`)")
    _common(p, True, "6x5")
    _model(p, profile=False)
    p.add_argument("--profile", default="khronos", help="profile A (default khronos)")
    p.add_argument("--against", default="spec", help="profile B (default spec)")
    p.add_argument("--plane", default="inplane", help="inplane|halfdiff (default inplane)")
    p.add_argument("--lobe", default="all", help="all|diffuse|specular|sheen|clearcoat")
    p.add_argument("--resolution", type=int, default=90, help="cells per side (default 90)")

    p = kinds.add_parser("image", help="a tone-mapped render")
    _common(p, False, "")
    p.add_argument("--gltf", metavar="FILE", help="a .gltf/.glb asset (default: the built-in spheres)")
    p.add_argument("--scene", help="built-in scene (spheres)")
    p.add_argument("--exr", metavar="FILE", help="draw this linear RGB EXR instead of rendering")
    p.add_argument("--size", metavar="WxH", help="render size in pixels, e.g. 384x384")
    p.add_argument("--exposure", type=float, default=0.0, help="exposure in stops (default 0)")
    p.add_argument("--profile", default="spec", help="spec|khronos|threejs|filament|babylon|materialx")
    p.add_argument("--spp", type=int, help="glTF sub-pixel samples (default 4)")
    p.add_argument("--camera", help="glTF camera index or auto")
    p.add_argument("--environment", help="builtin|sky|studio|uniform|FILE.hdr|FILE.exr")

    p = kinds.add_parser("diff", help="relative luminance difference of two EXR renders (`brdfcl diff`)")
    p.add_argument("a", metavar="A.exr", help="first image")
    p.add_argument("b", metavar="B.exr", help="second image, the reference")
    p.add_argument("--out", required=True, metavar="FILE", help="the figure: .png, .svg or .pdf")
    p.add_argument("--figsize", default="", metavar="WxH", help="figure size in inches (default: the images' aspect)")
    p.add_argument("--dpi", type=float, default=100, help="pixels per inch (default 100): PNG size = figsize x dpi")
    p.add_argument("--threshold", type=float, default=0.01, help="as brdfcl diff --threshold (default 0.01)")
    p.add_argument("--floor", type=float, help="as brdfcl diff --floor (default 1e-3 x mean luminance of B)")
    p.add_argument("--range", type=float, help="colour range +-R (default: p99 of |d|)")

    p = kinds.add_parser("samples", help="brdfcl.sample's histogram against brdfcl.pdf on the hemisphere")
    _common(p, True, "14x5")
    _model(p)
    p.add_argument("--lobe", default="all", help="all (the mixture)|diffuse|specular|sheen|clearcoat")
    p.add_argument("--view", default="45,0", metavar="THETA,PHI", help="θ_V and φ_V in degrees (default 45,0)")
    p.add_argument("--count", type=int, default=200000, help="samples (default 200000)")
    p.add_argument("--seed", type=int, default=0, help="seed of the counter-based generator (default 0)")
    p.add_argument("--bins", default="18x36", metavar="NTHETAxNPHI", help="θ and φ bins (default 18x36)")
    return top


def _plot(kind: str, a: argparse.Namespace) -> Any:
    from . import plot  # matplotlib is imported here, after the backend is chosen

    figsize = _pair(a.figsize, "--figsize", float) if a.figsize else None
    if kind == "diff":
        extra = {} if figsize is None else {"figsize": figsize}
        return plot.diff(a.a, a.b, threshold=a.threshold, floor=a.floor, range=a.range, dpi=a.dpi, **extra)
    common: Dict[str, Any] = {"dpi": a.dpi, "device": a.device}
    if figsize is not None:
        common["figsize"] = figsize
    if kind == "sheen-e":
        return plot.sheen_e(size=a.size, sheen_visibility=a.sheen_visibility,
                            sheen_distribution=a.sheen_distribution, **common)
    if kind == "image":
        if a.exr is not None:
            if a.gltf or a.scene or a.size or a.spp is not None or a.camera or a.environment:
                _fail("--exr draws a file as it is; drop the render options (--gltf, --scene, --size, ...)")
            from . import read_exr
            return plot.image(read_exr(a.exr), exposure=a.exposure, **common)
        render: Dict[str, Any] = {"gltf": a.gltf, "scene": a.scene, "profile": a.profile, "spp": a.spp,
                                  "camera": a.camera, "environment": a.environment}
        if a.size:
            render["size"] = _pair(a.size, "--size", int)
        return plot.image(exposure=a.exposure, **render, **common)
    model: Dict[str, Any] = {"sheen_visibility": a.sheen_visibility, "sheen_distribution": a.sheen_distribution,
                             "sheen_scaling": a.sheen_scaling, "strict": a.strict}
    if kind == "lobe":
        return plot.lobe(a.materials, a.material, view_angles=_angles(a.view_angles), resolution=a.resolution,
                         channel=a.channel, radius=a.radius, decades=a.decades, profile=a.profile, **model,
                         **common)
    if kind == "halfdiff":
        return plot.halfdiff(a.materials, a.material, lobe=a.lobe, resolution=a.resolution, channel=a.channel,
                             profile=a.profile, **model, **common)
    if kind == "albedo":
        return plot.albedo(a.materials, a.material, resolution=a.resolution, channel=a.channel, profile=a.profile,
                           **model, **common)
    if kind == "samples":
        view = _angles(a.view, "--view")
        if len(view) != 2:
            _fail(f"--view '{a.view}' must be THETA,PHI in degrees, e.g. 45,0")
        return plot.samples(a.materials, a.material, view=(view[0], view[1]), lobe=a.lobe, count=a.count,
                            seed=a.seed, bins=_bins(a.bins), profile=a.profile, **model, **common)
    if kind == "compare":
        return plot.compare(a.materials, a.material, profile=a.profile, against=a.against, plane=a.plane, lobe=a.lobe,
                            resolution=a.resolution, **model, **common)
    raise AssertionError(kind)


def _write(fig: Any, out: str, dpi: float) -> None:
    """The figure into `out` atomically: a temporary file beside it, renamed when complete."""
    ext = os.path.splitext(out)[1].lower()
    directory = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(directory):
        _fail(f"--out '{out}': the directory {directory} does not exist; create it first")
    fd, tmp = tempfile.mkstemp(prefix=".brdfcl-plot-", suffix=ext, dir=directory)
    try:
        with os.fdopen(fd, "wb") as f:
            fig.savefig(f, format=ext[1:], dpi=dpi)
        # mkstemp makes the file private (0600); the figure gets the mode any new file would.
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, out)
    except BaseException:
        os.unlink(tmp)
        raise


def _show_warning(message: Any, category: Any, filename: str, lineno: int, file: Any = None,
                  line: Optional[str] = None) -> None:
    # The C++ CLI's form, one line, rather than Python's file:line report.
    print("brdfcl: warning: " + " ".join(str(message).split()), file=sys.stderr)


def main(argv: Optional[Sequence[str]] = None) -> int:
    warnings.showwarning = _show_warning
    # A command line: the library's messages name options as --profile, as `brdfcl`'s do.
    from . import _core
    _core.set_cli_option_style()
    try:
        a = _parser().parse_args(argv)
        ext = os.path.splitext(a.out)[1].lower()
        if ext not in FORMATS:
            _fail(f"--out '{a.out}' must end in .png, .svg or .pdf")
        if os.path.isdir(a.out):
            _fail(f"--out '{a.out}' is a directory; name a file")
        try:
            import matplotlib
        except ImportError:
            _fail("python -m brdfcl plot needs matplotlib 3.7 or newer; pip install matplotlib")
        matplotlib.use("Agg")  # files only: no display needed, none opened
        from . import Error

        try:
            result = _plot(a.kind, a)
            _write(result.figure, a.out, a.dpi)
        except Error as e:
            _fail(str(e))
        except OSError as e:
            _fail(f"--out '{a.out}': {e.strerror or e}")
    except _UsageError as e:
        print("brdfcl: error: " + " ".join(str(e).split()), file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
