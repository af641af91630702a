"""Plot: the sheen E table (the white sheen lobe's directional albedo over N·V and sheen
roughness) with its E = 1 contour, for the Charlie and the Ashikhmin visibility. Writes
out/sheen_e_charlie.png and out/sheen_e_ashikhmin.png.
The same from the shell: python -m brdfcl plot sheen-e --sheen-visibility ashikhmin --out out/e.png"""
import os

from brdfcl import plot

os.makedirs("out", exist_ok=True)
for visibility in ("charlie", "ashikhmin"):
    fig, arrays = plot.sheen_e(size=64, sheen_visibility=visibility)
    fig.savefig(f"out/sheen_e_{visibility}.png")
    print(f"out/sheen_e_{visibility}.png; E from {arrays['E'].min():.3g} to {arrays['E'].max():.3g}")
