# Shared fixtures of the Python tests: the CLI binary the Makefile built (build/bin/brdfcl, or
# $BRDFCL_CLI) to compare against, and a runner that fails with the CLI's stderr.
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli():
    path = Path(os.environ.get("BRDFCL_CLI", ROOT / "build" / "bin" / "brdfcl"))
    if not path.exists():
        pytest.skip(f"{path} not built; run `make build` (or set BRDFCL_CLI)")

    def run(*args):
        r = subprocess.run([str(path), *map(str, args)], capture_output=True, text=True)
        assert r.returncode == 0, f"brdfcl {' '.join(map(str, args))}: {r.stderr}"
        return r.stdout

    run.path = path  # for tests that read the CLI's stderr
    return run


# Materials that reach every lobe: sheen, clearcoat, anisotropy, metal, and KHR_materials_ior.
MATERIALS = [
    {"name": "velvet", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.1, 0.4, 1], "metallicFactor": 0,
                                                 "roughnessFactor": 0.8},
     "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 0.6, 0.8], "sheenRoughnessFactor": 0.4}}},
    {"name": "coat", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.1, 1], "metallicFactor": 0,
                                               "roughnessFactor": 0.5},
     "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 0.1},
                    "KHR_materials_ior": {"ior": 1.4}}},
    {"name": "brushed", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1], "metallicFactor": 1,
                                                  "roughnessFactor": 0.3},
     "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.7, "anisotropyRotation": 0.5}}},
]
