"""Plot: the directional albedo of each lobe of a velvet against the view angle θ_V (the sheen
rises towards grazing, the diffuse falls). Writes out/albedo.png.
The same from the shell: python -m brdfcl plot albedo --materials M.json --out out/albedo.png"""
import os

from brdfcl import plot

velvet = {"name": "velvet",
          "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.1, 0.4, 1], "metallicFactor": 0, "roughnessFactor": 0.8},
          "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 0.6, 0.8], "sheenRoughnessFactor": 0.4}}}
os.makedirs("out", exist_ok=True)
fig, arrays = plot.albedo(velvet)
fig.savefig("out/albedo.png")
print("out/albedo.png; total albedo (luminance) at 0° and 89°:", arrays["value_all"][[0, -1]])
