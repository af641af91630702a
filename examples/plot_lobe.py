"""Plot: the in-plane lobe of a velvet, f·cosθ_L as a polar plot per view angle, the diffuse,
specular and sheen lobes stacked under the total. Writes out/lobe.png (9 x 4.5 in at 100 dpi).
The same from the shell: python -m brdfcl plot lobe --materials M.json --out out/lobe.png"""
import os

from brdfcl import plot

velvet = {"name": "velvet",
          "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.1, 0.4, 1], "metallicFactor": 0, "roughnessFactor": 0.8},
          "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 0.6, 0.8], "sheenRoughnessFactor": 0.4}}}
os.makedirs("out", exist_ok=True)
fig, arrays = plot.lobe(velvet, view_angles=(0, 30, 60, 80), figsize=(9, 4.5))
fig.savefig("out/lobe.png")
print("out/lobe.png; peak f·cosθ_L per view angle:", arrays["r_all"].max(axis=1))
