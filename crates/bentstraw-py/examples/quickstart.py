"""The README's calls as a script, type-checked in CI with ``mypy --strict``: what an editor or a
type checker says about them is what the package does.

Run it with ``python examples/quickstart.py``: it prints what each call gives.
"""

from typing import Tuple

import numpy as np

import bentstraw

# The assignment's glass by its numbers; a vector may be a tuple, a list or a numpy array.
sim = bentstraw.simulate(observer=np.array([0.1, 0.0, 0.1]), straw=(0, 0.02), water_height=0.1)
points: np.ndarray = sim.xyz
print(len(sim), "image points,", sim.path_keys)

# The picture: an (h, w, 3) array that knows its field of view.
picture = bentstraw.render(observer=(0.3, 0, 0.22), straw=[-0.02, 0.02], water_height=0.15,
                           size=(160, 120))
shape: Tuple[int, ...] = picture.shape
print("picture", shape, f"fov {picture.fov:.2f}°")

# With the per-pixel data too (`render --raw`): a pair.
picture, weights = bentstraw.render("leaning-straw", size=(80, 60), mode="course", weights=True)
print("colour codes", weights.shape)

# Another model of where the image is; a check of the points; one ray's path.
eye = bentstraw.simulate("leaning-straw", image_model="eye", points=2000)
report = bentstraw.check(sim.xyz, sim.color, observer=(0.1, 0, 0.1), straw=(0, 0.02),
                         water_height=0.1)
ray = bentstraw.trace(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1,
                      toward=(0, 0.02, 0.05))
print(eye.image_model, report["verdict"], ray["path"])
