"""Plot: how three.js's BRDF differs from the spec's for a velvet, as log2 of the ratio of f over
(θ_L, θ_V) in the incidence plane (0: equal). Writes out/compare_threejs_spec.png.
The same from the shell: python -m brdfcl plot compare --materials M.json --profile threejs --out out/c.png"""
import os

import numpy as np

from brdfcl import plot

velvet = {"name": "velvet",
          "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.1, 0.4, 1], "metallicFactor": 0, "roughnessFactor": 0.8},
          "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 0.6, 0.8], "sheenRoughnessFactor": 0.4}}}
os.makedirs("out", exist_ok=True)
fig, arrays = plot.compare(velvet, profile="threejs", against="spec")
fig.savefig("out/compare_threejs_spec.png")
print("out/compare_threejs_spec.png; largest |log2 ratio|:", np.nanmax(np.abs(arrays["log2_ratio"])))
