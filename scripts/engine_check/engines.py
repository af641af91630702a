# The engine registry: profile -> (checkout folder, builder) for the direct light, and
# profile -> builder for the image-based light. Each builder builds an evaluator from a checkout
# and names the files it read.
from .khronos import build_khronos, build_khronos_ibl
from .filament import build_filament, build_filament_ibl
from .threejs import build_threejs, build_threejs_ibl
from .materialx import build_materialx, build_materialx_ibl
from .babylon import build_babylon, build_babylon_ibl


ENGINES = {
    # profile: (checkout folder, builder)
    "khronos": ("glTF-Sample-Renderer", build_khronos),
    "filament": ("filament", build_filament),
    "threejs": ("three.js", build_threejs),
    "materialx": ("MaterialX", build_materialx),
    "babylon": ("Babylon.js", build_babylon),
}


# profile -> builder of its image-based-light evaluator (the checkout folder is ENGINES').
IBL_ENGINES = {
    "khronos": build_khronos_ibl,
    "filament": build_filament_ibl,
    "threejs": build_threejs_ibl,
    "materialx": build_materialx_ibl,
    "babylon": build_babylon_ibl,
}
