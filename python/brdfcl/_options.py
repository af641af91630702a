"""brdfcl.Options: the model options (lobe, profile, sheen variants) checked once when made, the
names LOBES, PROFILES, LUT_KINDS, and _options(), which applies keyword overrides to an Options."""
from __future__ import annotations

from typing import Any, Optional, Tuple

from . import _core
from ._core import InputError


LOBES = ("all", "diffuse", "specular", "sheen", "clearcoat")
PROFILES = ("spec", "khronos", "threejs", "filament", "babylon", "materialx")
LUT_KINDS = ("sheen-e", "ggx-dfg", "charlie-dfg")


class Options:
    """The model options, checked when made (an unknown value, or a sheen variant under an engine
    profile, raises InputError naming the keyword):

    lobe: all|diffuse|specular|sheen|clearcoat. profile: spec|khronos|threejs|filament|babylon|
    materialx (docs/profiles.md). sheen_visibility, sheen_distribution: charlie|ashikhmin;
    sheen_scaling: min|view|none (spec profile only).

    Immutable and hashable; replace(**changes) makes a changed copy. Pass it as options= to any
    function or Evaluator method, or to Evaluator(options=) as that evaluator's default.
    """

    __slots__ = ("lobe", "profile", "sheen_visibility", "sheen_distribution", "sheen_scaling", "_core")
    _NAMES = ("lobe", "profile", "sheen_visibility", "sheen_distribution", "sheen_scaling")

    def __init__(self, *, lobe: str = "all", profile: str = "spec", sheen_visibility: str = "charlie",
                 sheen_distribution: str = "charlie", sheen_scaling: str = "min"):
        values = (lobe, profile, sheen_visibility, sheen_distribution, sheen_scaling)
        for name, value in zip(self._NAMES, values):
            if not isinstance(value, str):
                raise InputError(f"{name}= must be a str, got {type(value).__name__}")
            object.__setattr__(self, name, value)
        object.__setattr__(self, "_core", _core.eval_options(lobe, sheen_visibility, sheen_distribution, sheen_scaling,
                                                             profile))

    def replace(self, **changes: str) -> "Options":
        """A copy with the given options changed."""
        unknown = sorted(set(changes) - set(self._NAMES))
        if unknown:
            raise TypeError(f"unknown option {unknown[0]!r}; the options are " + ", ".join(self._NAMES))
        return Options(**{**{n: getattr(self, n) for n in self._NAMES}, **changes})

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("brdfcl.Options is immutable; use replace()")

    def _key(self) -> Tuple[str, ...]:
        return tuple(getattr(self, n) for n in self._NAMES)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Options) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def __repr__(self) -> str:
        return "brdfcl.Options(" + ", ".join(f"{n}={getattr(self, n)!r}" for n in self._NAMES) + ")"


_DEFAULT_OPTIONS = Options()


def _options(options: Optional[Options], default: Options, **keywords: Optional[str]) -> Options:
    """`options` (or `default`) with the keywords given (not None) applied."""
    if options is None:
        options = default
    elif not isinstance(options, Options):
        raise InputError(f"options= must be a brdfcl.Options, got {type(options).__name__}")
    given = {k: v for k, v in keywords.items() if v is not None}
    return options.replace(**given) if given else options
