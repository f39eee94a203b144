"""Checks that each file named is a PNG plot with something drawn in it (not blank, not tiny)."""

import sys

import matplotlib.image

for path in sys.argv[1:]:
    with open(path, "rb") as file:
        assert file.read(8) == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    image = matplotlib.image.imread(path)
    height, width = image.shape[:2]
    assert width >= 300 and height >= 200, f"{path}: {width}x{height} is too small for a plot"
    # A plot has lines and text: many pixels differ from the background.
    background = image[0, 0]
    drawn = (abs(image[..., :3] - background[:3]).sum(axis=-1) > 0.1).mean()
    assert drawn > 0.01, f"{path}: only {drawn:.2%} of the pixels are drawn"
    print(f"{path}: {width}x{height} PNG, {drawn:.1%} of pixels drawn")
