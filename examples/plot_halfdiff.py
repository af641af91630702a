"""Plot: f of a clear-coated paint over Rusinkiewicz's (θ_h, θ_d) at φ_d = 90°, on a log colour
scale (the MERL / BRDF Explorer slice). Writes out/halfdiff.png.
The same from the shell: python -m brdfcl plot halfdiff --materials M.json --out out/halfdiff.png"""
import os

from brdfcl import plot

paint = {"name": "car paint",
         "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.05, 0.05, 1], "metallicFactor": 0, "roughnessFactor": 0.4},
         "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 0.05}}}
os.makedirs("out", exist_ok=True)
result = plot.halfdiff(paint, resolution=90)
result.save("out/halfdiff.png")
print("out/halfdiff.png; f luminance from", result.arrays["value"].min(), "to", result.arrays["value"].max(), "1/sr")
