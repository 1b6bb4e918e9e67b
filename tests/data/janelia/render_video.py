"""A synthetic whisker video for the Janelia tracker (whisk's `trace`): a dark, tapering quadratic curve on a
light background, one whisker per frame, moving a little between frames. Writes video.tif (multi-page, 8-bit)
and truth.json (the drawn centre lines in pixels)."""
import json

import numpy as np
from PIL import Image
from scipy.spatial import cKDTree

W, H, FRAMES = 320, 240, 6
centres = np.stack(np.mgrid[0:H, 0:W][::-1], -1).reshape(-1, 2).astype(float)  # (x, y) of every pixel
pages, truth = [], []
for f in range(FRAMES):
    s = np.linspace(0.0, 220.0, 4401)
    x0, y0, slope, c = 40.0, 100.0 + 3.0 * f, -0.2 + 0.04 * f, 0.0012
    line = np.stack([x0 + s, y0 + slope * s + c * s * s], 1)
    half_width = 2.0 - 1.5 * s / s[-1]  # tapering from 4 px to 1 px
    dist, idx = cKDTree(line).query(centres)
    ink = np.clip(half_width[idx] + 0.5 - dist, 0.0, 1.0)  # anti-aliased edge
    img = (215.0 - 170.0 * ink).reshape(H, W)
    img[:, :20] = 40.0  # a dark face on the left, the whiskers' base side
    pages.append(Image.fromarray(np.round(img).astype(np.uint8)))
    truth.append({"frame": f, "x_px": line[::20, 0].tolist(), "y_px": line[::20, 1].tolist()})
pages[0].save("video.tif", save_all=True, append_images=pages[1:], compression=None)
json.dump(truth, open("truth.json", "w"))
