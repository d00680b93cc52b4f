"""Exit non-zero unless IMAGE exists and is not blank (for .ci/run).

Not blank: at least 16 distinct colours and both dark and bright pixels, which the
shadow scene has (floor, lit faces, shadows) and a failed or empty render does not.
"""

from __future__ import annotations

import sys

import imageio.v3 as iio
import numpy as np


def main(path: str) -> int:
    try:
        img = np.asarray(iio.imread(path))
    except (OSError, ValueError) as exc:
        print(f"{path}: cannot read the image the main job should have written ({exc})")
        return 1
    rgb = img[..., :3].reshape(-1, 3) if img.ndim == 3 else img.reshape(-1, 1)
    colours = np.unique(rgb, axis=0).shape[0]
    lum = rgb.astype(np.float64).mean(axis=1)
    if colours < 16 or lum.max() - lum.min() < 64:
        print(f"{path}: looks blank ({colours} colours, "
              f"luminance {lum.min():.0f}..{lum.max():.0f})")
        return 1
    print(f"{path}: {img.shape[1]}x{img.shape[0]}, {colours} colours: not blank")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
