"""Plot: a render, tone-mapped as `brdfcl render` writes its PNG (exposure in stops, PBR Neutral,
sRGB), drawn by matplotlib with a title. In a notebook, `plot.image(...)` alone shows inline.
Usage: python plot_image.py [asset.gltf|asset.glb]; writes out/image.png.
The same from the shell: python -m brdfcl plot image [--gltf asset.glb] --exposure 0.5 --out out/i.png"""
import os
import sys

from brdfcl import plot

os.makedirs("out", exist_ok=True)
if len(sys.argv) > 1:
    result = plot.image(gltf=sys.argv[1], size=(640, 360), exposure=0.5, environment="studio")
else:
    result = plot.image(size=(384, 384), exposure=0.5)  # the built-in sphere sweep
result.save("out/image.png")
print("out/image.png;", result.arrays["radiance"].shape, "linear radiance, max", result.arrays["radiance"].max())
