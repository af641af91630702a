"""Batch evaluation from numpy: f(L, V) of two materials over a million random direction pairs.
Conventions: N = +Z, L towards the light, V towards the viewer, f in 1/sr without the cosine."""
import numpy as np

import brdfcl

materials = [
    {"name": "velvet", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.1, 0.4, 1], "metallicFactor": 0},
     "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 0.6, 0.8], "sheenRoughnessFactor": 0.4}}},
    {"name": "car paint", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.05, 0.05, 1], "metallicFactor": 0,
                                                    "roughnessFactor": 0.4},
     "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 0.05}}},
]
rng = np.random.default_rng(0)
n = 1_000_000
L = rng.normal(size=(n, 3)).astype(np.float32)  # need not be unit length: normalized as the CLI does
V = rng.normal(size=(n, 3)).astype(np.float32)
L[:, 2] = np.abs(L[:, 2])
V[:, 2] = np.abs(V[:, 2])
index = rng.integers(0, len(materials), size=n)

f = brdfcl.evaluate(materials, L, V, index)  # float32 (n, 3)
print(f"{n} samples on {brdfcl.devices()[0]['name']}: mean f {f.mean(axis=0)} 1/sr")
print("sheen lobe alone:", brdfcl.evaluate(materials, L[:4], V[:4], index[:4], lobe="sheen"))
