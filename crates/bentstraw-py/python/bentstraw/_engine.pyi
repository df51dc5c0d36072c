"""Type stubs of the compiled engine (``bentstraw._engine``); use the functions of ``bentstraw``."""

from typing import Any, Dict, List, Optional, Tuple, final

import numpy as np
import numpy.typing as npt

__all__ = [
    "LoadedScene", "load", "read_scene", "check_scene", "gallery", "gallery_miss", "simulate", "light_paths", "save_points", "wavelength_rgb",
    "render", "pixel_direction", "check", "grade", "grade_points", "trace", "VERSION", "WATER_INDEX",
    "DEFAULT_MAX_EVENTS", "DEFAULT_TOLERANCE", "DEFAULT_MIN_COVERAGE", "DEFAULT_POINTS",
    "DEFAULT_PRUNE", "DEFAULT_SAMPLES", "DEFAULT_SIZE", "DEFAULT_MODE", "DEFAULT_BACKDROP",
    "COLOR_NAMES", "COLOR_RGB",
]

VERSION: str
WATER_INDEX: float
DEFAULT_MAX_EVENTS: int
DEFAULT_TOLERANCE: float
DEFAULT_MIN_COVERAGE: float
DEFAULT_POINTS: int
DEFAULT_PRUNE: float
DEFAULT_SAMPLES: int
DEFAULT_SIZE: Tuple[int, int]
DEFAULT_MODE: str
DEFAULT_BACKDROP: str
COLOR_NAMES: List[str]
COLOR_RGB: List[List[float]]

@final
class LoadedScene:
    """A scene loaded and checked, with its observer."""

    @property
    def observer(self) -> List[float]: ...
    @property
    def name(self) -> Optional[str]: ...
    @property
    def max_events(self) -> int: ...
    @property
    def color_names(self) -> List[str]: ...
    @property
    def hints(self) -> List[str]: ...

def load(
    path: Optional[str],
    text: Optional[Tuple[str, str]],
    observer: Optional[Tuple[float, ...]],
    straw: Optional[Tuple[float, ...]],
    water_height: Optional[float],
    n_water: Optional[float],
    max_events: int,
    wavelength: Optional[float],
) -> LoadedScene: ...
def read_scene(path: str) -> Tuple[str, str]: ...
def check_scene(name: str, text: str) -> None: ...
def gallery() -> List[Tuple[str, str]]: ...
def gallery_miss(name: str) -> str: ...
def simulate(scene: LoadedScene, points: int, image_model: str, light: str) -> Dict[str, Any]: ...
def save_points(scene: LoadedScene, points: int, image_model: str, light: str, path: str) -> None: ...
def light_paths(scene: LoadedScene, direction: npt.NDArray[np.float64],
                band: Optional[npt.NDArray[np.int64]] = None) -> Dict[str, Any]: ...
def wavelength_rgb(nm: float) -> List[float]: ...
def render(
    scene: LoadedScene,
    size: Optional[Tuple[int, int]],
    target: Optional[Tuple[float, ...]],
    fov: Optional[float],
    mode: str,
    prune: float,
    backdrop: str,
    samples: int,
    raw: bool,
    light: str,
    sampling: str,
) -> Dict[str, Any]: ...
def pixel_direction(
    forward: Any, right: Any, up: Any, tan_half_fov: float, size: Tuple[int, int], row: float,
    col: float,
) -> List[float]: ...
def check(
    scene: LoadedScene,
    xyz: npt.NDArray[np.float64],
    color: npt.NDArray[np.float64],
    tolerance: float,
    min_coverage: float,
    worst: int,
) -> str: ...
def grade(class_dir: str, out: str, assignment: Optional[str], lang: str) -> str: ...
def grade_points(
    scene: LoadedScene,
    xyz: npt.NDArray[np.float64],
    color: npt.NDArray[np.float64],
    tolerance: float,
    min_coverage: float,
    max_score: float,
    lang: str,
) -> str: ...
def trace(
    scene: LoadedScene,
    direction: Optional[Tuple[float, ...]],
    toward: Optional[Tuple[float, ...]],
) -> str: ...
