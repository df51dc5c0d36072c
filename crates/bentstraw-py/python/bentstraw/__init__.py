"""bentstraw: see what refraction does to what we see.

A five-colour straw stands in a glass of water; you look at it from anywhere. bentstraw traces
rays from your eye through the water (Snell's law, total internal reflection, at most 10 events
by default) and gives the straw's *virtual image*: image points, the picture your eye gets, a
check of anyone's image points, and the light path of any one ray. The numbers are exactly those
of the command line ``bentstraw`` with the same inputs: the same engine, called the same way.

All lengths are in metres. A scene is either the assignment's glass given by its numbers::

    import bentstraw
    sim = bentstraw.simulate(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
    sim.xyz        # (N, 3) image points
    sim.color      # (N,) colour codes, 1 red ... 5 blue

or a scene file (a path, a gallery name such as ``"leaning-straw"``, or a :class:`Scene`)::

    sim = bentstraw.simulate("leaning-straw")

The calls: :func:`simulate` (image points), :func:`sweep` (one keyword varied), :func:`render`
(the eye's picture), :func:`check` and :func:`assert_solution` (someone's image points judged),
:func:`grade` (a class's solutions), :func:`trace` and :func:`ray_diagram` (one ray's light path),
:func:`explore` (the live page in a notebook) and :func:`gallery` (the demonstrations' names).

What they return, each with its own ``help``: :class:`Simulation`, :class:`Picture`,
:class:`CheckReport`, :class:`Ray`, :class:`Explorer`; and :class:`Scene`, a scene file checked,
:class:`SolutionError`, what :func:`assert_solution` raises. The defaults are ``DEFAULT_*`` and
``WATER_INDEX``; the colour codes' names and colours ``COLOR_NAMES`` and ``COLOR_RGB``.

The physics (how rays bend, what an image point is, the three apparent-position models) is
explained in the project's ``docs/physics.md``.
"""

from __future__ import annotations

import functools
import json
import os
import re
import warnings
from collections import abc
from typing import (TYPE_CHECKING, Any, Callable, Dict, List, Literal, Optional, Sequence, Tuple,
                    TypeVar, Union, cast, overload)

import numpy as np
import numpy.typing as npt

from . import _engine, _explore
from ._explore import Explorer

# The engine words its refusals as the command line does, naming its flags (`--points 0`); a
# Python caller reads them with the keywords it wrote (`points=0`).
_FLAG = re.compile(r"--([a-z][a-z0-9-]*)(?:[ =](?=[-+\d.(\"']))?")
_KEYWORD = {"raw": "weights"}


def _keywords(message: str) -> str:
    """``message`` with each command-line flag written as the Python keyword it stands for:
    ``--points 0`` as ``points=0``, a flag named without its value as the keyword alone."""

    def keyword(m: "re.Match[str]") -> str:
        name = _KEYWORD.get(m.group(1), m.group(1).replace("-", "_"))
        return name + "=" if m.group(0)[-1] in " =" else name

    return _FLAG.sub(keyword, message)


_F = TypeVar("_F", bound=Callable[..., Any])


def _keyworded(f: _F) -> _F:
    """``f``, its ``ValueError``s naming Python's keywords rather than the command line's flags."""

    @functools.wraps(f)
    def call(*args: Any, **kwargs: Any) -> Any:
        try:
            return f(*args, **kwargs)
        except ValueError as e:
            raise ValueError(_keywords(str(e))) from None

    return call  # type: ignore[return-value]

# What `help(bentstraw)` shows and `import *` gives: the calls. What they return and take
# (`Simulation`, `Picture`, `CheckReport`, `Ray`, `Scene`, `Explorer`, `SolutionError`), the
# defaults (`DEFAULT_*`, `WATER_INDEX`), the colours and the choices' types are public too, each
# with its own help, and listed in the module's docstring: printed whole here, with every method
# inherited from numpy, dict and AssertionError, they would bury the calls.
__all__ = [
    "simulate",
    "sweep",
    "render",
    "check",
    "grade",
    "assert_solution",
    "trace",
    "ray_diagram",
    "explore",
    "gallery",
]

__version__: str = _engine.VERSION
#: The refractive index of water when none is given.
WATER_INDEX: float = _engine.WATER_INDEX
#: Most events (refractions and total reflections) a ray may undergo, by default.
DEFAULT_MAX_EVENTS: int = _engine.DEFAULT_MAX_EVENTS
#: Largest error of a point's path length that :func:`check` still judges correct (m).
DEFAULT_TOLERANCE: float = _engine.DEFAULT_TOLERANCE
#: Smallest share of each colour's true image a complete solution covers.
DEFAULT_MIN_COVERAGE: float = _engine.DEFAULT_MIN_COVERAGE
#: Image points asked for when no number is given.
DEFAULT_POINTS: int = _engine.DEFAULT_POINTS
#: Fresnel branches lighter than this are abandoned, by default.
DEFAULT_PRUNE: float = _engine.DEFAULT_PRUNE
#: Samples per pixel side at a picture's edges, by default.
DEFAULT_SAMPLES: int = _engine.DEFAULT_SAMPLES
#: A picture's mode by default: ``"fresnel"`` (or ``"course"``).
DEFAULT_MODE: "Mode" = _engine.DEFAULT_MODE  # type: ignore[assignment]
#: A picture's backdrop by default: ``"checker"`` (or ``"none"``).
DEFAULT_BACKDROP: "Backdrop" = _engine.DEFAULT_BACKDROP  # type: ignore[assignment]
#: A picture's size ``(w, h)`` in pixels, by default.
DEFAULT_SIZE: Tuple[int, int] = tuple(_engine.DEFAULT_SIZE)  # type: ignore[assignment]
#: The names of the colour codes 1, 2, ...: a straw's five sections, then a coin, a card, an arrow.
COLOR_NAMES: Tuple[str, ...] = tuple(_engine.COLOR_NAMES)
#: The colours of the codes 1, 2, ... as RGB in 0..1, as the figures draw them: ``COLOR_RGB[code - 1]``.
COLOR_RGB: np.ndarray = np.array(_engine.COLOR_RGB, dtype=np.float64)
COLOR_RGB.flags.writeable = False

#: A point or direction: three numbers, as a tuple, a list or a numpy array.
Vector3 = Union[Sequence[float], "npt.NDArray[Any]"]
#: A point on the floor: two numbers, as a tuple, a list or a numpy array.
Vector2 = Union[Sequence[float], "npt.NDArray[Any]"]
#: Where an image point is placed: the course's convention, a small eye's foci, or two eyes.
ImageModel = Literal["course", "eye", "stereo"]
#: How a picture's rays are followed: one ray each (the course's law), or Fresnel's branches.
Mode = Literal["course", "fresnel"]
#: What lies behind the scene in a picture: the checkerboard wall and floor, or plain light.
Backdrop = Literal["checker", "none"]
#: The light a picture is drawn in: one wavelength (``wavelength=``), or white light.
Light = Literal["mono", "white"]
#: Where a picture takes its samples: at edges only (where neighbouring pixels differ), or at
#: every pixel.
Sampling = Literal["adaptive", "full"]

if TYPE_CHECKING:
    _PictureArray = np.ndarray[Any, np.dtype[np.uint8]]
else:
    _PictureArray = np.ndarray


class Picture(_PictureArray):
    """A picture as :func:`render` returns it: an ``(h, w, 3)`` uint8 array of sRGB pixels that
    also knows the camera it was drawn with: the ``eye``, the unit direction it looks along
    (``forward``, towards the target), and the vertical field of view ``fov`` (degrees), so
    that a picture framed by default can be drawn again with the same one, and
    :meth:`direction` maps a pixel to the direction its ray leaves the eye in."""

    _camera: Dict[str, Any]

    def __array_finalize__(self, obj: Any) -> None:
        # (A slice or a copy of a picture keeps its camera.)
        self._camera = getattr(obj, "_camera", {})

    @property
    def fov(self) -> float:
        """The vertical field of view of the picture (degrees)."""
        return float(self._camera.get("fov_deg", float("nan")))

    @property
    def eye(self) -> Tuple[float, ...]:
        """The eye, where every ray of the picture starts (m)."""
        return tuple(self._camera.get("eye", (float("nan"),) * 3))

    @property
    def forward(self) -> Tuple[float, ...]:
        """The unit direction the camera looks along (towards its target)."""
        return tuple(self._camera.get("forward", (float("nan"),) * 3))

    def direction(self, row: float, col: float) -> np.ndarray:
        """The unit direction of the ray through the centre of pixel ``(row, col)`` (row 0 at the
        top, column 0 at the left), the one the picture traced there: ``f + sx·r + sy·u``
        normalised, with ``sx = (2(col + ½)/w − 1)·tan(fov/2)·w/h`` and
        ``sy = (1 − 2(row + ½)/h)·tan(fov/2)``.

        >>> picture = bentstraw.render("leaning-straw", size=(80, 60))
        >>> ray = bentstraw.trace("leaning-straw", direction=picture.direction(30, 40))
        """
        # (The whole picture's size: a slice of a picture keeps its camera.)
        c = self._camera
        return np.asarray(_engine.pixel_direction(c["forward"], c["right"], c["up"],
                                                  c["tan_half_fov"], c["size"],
                                                  _real(row, "row"), _real(col, "col")))

    def __reduce__(self) -> Any:
        # Pickled with its camera (an array's own state does not hold it).
        reduced: Any = super().__reduce__()
        return reduced[0], reduced[1], (reduced[2], self._camera)

    def __setstate__(self, state: Any) -> None:
        array_state, self._camera = state
        super().__setstate__(array_state)

    def __repr__(self) -> str:
        eye = ", ".join(f"{v:g}" for v in self.eye)
        return (f"<Picture {self.shape[1]}x{self.shape[0]} seen from ({eye}), "
                f"field of view {self.fov:.2f}°>")

    def plot(self, ax: Any = None) -> Tuple[Any, Any]:
        """The picture drawn with matplotlib, pixel for pixel, its field of view in the title:
        ``(fig, ax)``, on ``ax`` if given (else a new figure).

        >>> fig, ax = bentstraw.render("leaning-straw", size=(80, 60)).plot()
        """
        fig, ax = _axes(ax, None)
        ax.imshow(np.asarray(self), interpolation="nearest")
        ax.set_axis_off()
        ax.set_title(f"what the eye sees (field of view {self.fov:.1f}°)")
        return fig, ax


class Scene:
    """A scene file's text, checked: glasses (straight or of any profile), tanks, liquids, straws,
    coins, cards and transparent solids.

    Make one with :meth:`Scene.load` (a file), :meth:`Scene.from_toml` (text) or
    :meth:`Scene.gallery` (one of the built-in demonstrations), and pass it as ``scene=`` to
    :func:`simulate`, :func:`render`, :func:`check` or :func:`trace`.

    >>> scene = bentstraw.Scene.gallery("leaning-straw")
    >>> scene.name
    'leaning-straw'
    """

    __slots__ = ("_name", "_text")

    @_keyworded
    def __init__(self, text: str, name: str = "scene.toml") -> None:
        """The scene file ``text`` (TOML), named ``name`` in messages; refused with a
        ``ValueError`` listing every broken rule."""
        _engine.check_scene(name, text)
        self._name = name
        self._text = text

    @classmethod
    @_keyworded
    def load(cls, path: Union[str, "os.PathLike[str]"]) -> "Scene":
        """The scene file at ``path`` (at most 1 MB of UTF-8 TOML), read and checked.

        >>> scene = bentstraw.Scene.load("scenes/leaning-straw.toml")
        """
        name, text = _engine.read_scene(os.fspath(path))
        scene = cls.__new__(cls)
        scene._name, scene._text = name, text
        return scene

    @classmethod
    @_keyworded
    def from_toml(cls, text: str, name: str = "scene.toml") -> "Scene":
        """The scene file whose text is ``text``, checked (``name`` names it in messages).

        >>> text = open("scenes/leaning-straw.toml").read().replace("tilt = 15.0", "tilt = 10.0")
        >>> bentstraw.Scene.from_toml(text, name="ten-degrees.toml")
        Scene('ten-degrees.toml')
        """
        return cls(text, name)

    @classmethod
    @_keyworded
    def gallery(cls, name: str) -> "Scene":
        """The gallery's demonstration ``name`` (see :func:`gallery` for the names).

        >>> bentstraw.Scene.gallery("reversing-arrow").name
        'reversing-arrow'
        """
        for stem, text in _engine.gallery():
            if stem == name or stem + ".toml" == name:
                scene = cls.__new__(cls)
                scene._name, scene._text = stem, text
                return scene
        raise ValueError(_engine.gallery_miss(name))

    @property
    def name(self) -> str:
        """The scene's name as messages show it."""
        return self._name

    @property
    def text(self) -> str:
        """The scene file's text (TOML)."""
        return self._text

    def __repr__(self) -> str:
        return f"Scene({self._name!r})"


def gallery() -> List[str]:
    """The names of the gallery's demonstrations, each usable as ``scene=NAME``.

    >>> "leaning-straw" in bentstraw.gallery()
    True
    """
    return [stem for stem, _ in _engine.gallery()]


SceneLike = Union[None, str, "os.PathLike[str]", Scene]


def _load(
    scene: SceneLike,
    observer: Optional[Vector3],
    straw: Optional[Vector2],
    water_height: Optional[float],
    n_water: Optional[float],
    max_events: int,
    wavelength: Optional[float] = None,
) -> Any:
    """The scene loaded by the engine as the command line's flags would give it; its hints
    (numbers that look like slips) as warnings."""
    path = text = None
    if isinstance(scene, Scene):
        text = (scene.name, scene.text)
    elif scene is not None:
        if not isinstance(scene, (str, os.PathLike)):
            raise TypeError(
                f"scene must be a path, a gallery name or a bentstraw.Scene, not {type(scene).__name__}"
            )
        path = os.fspath(scene)
    loaded = _engine.load(
        path,
        text,
        _vector(observer, 3, "observer"),
        _vector(straw, 2, "straw"),
        _number(water_height, "water_height"),
        _number(n_water, "n_water"),
        _count(max_events, "max_events"),
        _number(wavelength, "wavelength"),
    )
    for hint in loaded.hints:
        warnings.warn(hint, UserWarning, stacklevel=3)
    return loaded


def _real(x: Any, name: str) -> float:
    """One number given for ``name``: an int, a float or a numpy number (a bool or a string is
    not one: ``True`` or ``"0.15"`` are refused, not read as 1.0 or 0.15), else a TypeError
    naming it."""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a number, not {type(x).__name__} {x!r}")
    return float(x)


def _sequence(v: Any, name: str, of: str = "") -> None:
    """A TypeError naming ``name`` unless ``v`` is a sequence or an array (of ``of``): a string,
    a set (no order) or a dict is none."""
    if isinstance(v, (str, bytes, set, frozenset, dict)) or not isinstance(v, (abc.Sequence, np.ndarray)):
        raise TypeError(f"{name} must be a sequence or array{of}, not {type(v).__name__} {v!r}")


def _vector(v: Optional[Any], n: int, name: str) -> Optional[Tuple[float, ...]]:
    """``v`` as ``n`` floats (or None): a sequence or array of numbers. A string, a set (no
    order) or a dict is a TypeError naming ``name``; the wrong count a ValueError."""
    if v is None:
        return None
    _sequence(v, name, f" of {n} numbers")
    values = tuple(_real(x, name) for x in v)
    if len(values) != n:
        raise ValueError(f"{name} must be {n} numbers, not {len(values)}: {v!r}")
    return values


def _size(size: Sequence[int]) -> Tuple[int, int]:
    """``size`` as two whole numbers of pixels >= 0 (the engine checks the rest of the rule)."""
    w, h = _vector(size, 2, "size")  # type: ignore[misc]
    if not (w.is_integer() and h.is_integer() and 0 <= w < 2**31 and 0 <= h < 2**31):
        raise ValueError(
            f"size {tuple(size)!r} is not allowed: each side must be a whole number of pixels "
            "between 1 and 16384"
        )
    return int(w), int(h)


def _number(v: Optional[float], name: str) -> Optional[float]:
    """``v`` as a float (or None); a string or a bool is a TypeError naming ``name``."""
    if v is None:
        return None
    return _real(v, name)


def _count(v: int, name: str, most: int = 2**31 - 1) -> int:
    """``v`` as a whole number from 0 to ``most`` (the engine's own rules then apply): another
    type is a TypeError, a number out of that range a ValueError, both naming ``name``."""
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, np.integer)):
        raise TypeError(f"{name} must be a whole number, not {type(v).__name__} {v!r}")
    if not 0 <= v <= most:
        raise ValueError(f"{name} must be a whole number from 0 to {most}, not {v!r}")
    return int(v)


def _flag(v: bool, name: str) -> bool:
    """``v`` as True or False; anything else (``"no"``, 0) is a TypeError naming ``name``."""
    if not isinstance(v, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, not {type(v).__name__} {v!r}")
    return bool(v)


class Simulation:
    """The image points of a scene seen from one observer, as :func:`simulate` returns them.

    One row per point, in the order ``bentstraw simulate`` writes them:

    - ``xyz`` — ``(N, 3)`` float64: where the point appears in the chosen model (the course's
      ``O + L·u0``, the eye's or the stereo point); ``nan`` where the eye model places none.
    - ``color`` — ``(N,)`` int64: the colour code of the object the light came from (1 red,
      2 orange, 3 magenta, 4 green, 5 blue; 6 a coin, 7 a card, 8 the arrow on it;
      ``COLOR_RGB[color - 1]`` is each point's colour for a plot).
    - ``path`` — ``(N,)`` str: the kind of light path (``"direct"``, ``"top"``, ``"wall"``,
      ``"bottom"``, with ``"+k"`` for k total reflections); ``path_index`` indexes
      ``path_keys`` and ``path_words`` (the same in words). Found on first use: each point's
      ray traced once more.
    - ``wavelength`` — ``(N,)`` float64, in white light only: the wavelength (nm) of the band of
      the spectrum each point's ray carried (the middle of its band).
    - ``image_xyz``, ``direction``, ``path_length``, ``object_point``, ``events``: the course's
      image point (for the course model the very array ``xyz``, not a copy), the ray's first direction ``u0``, its broken length ``L``, the point of the
      object it reached and how many events it underwent.
    - eye model: ``s_h``, ``s_v`` (the two foci's signed distances, m), ``s_h_kind``,
      ``s_v_kind``, ``gap``; stereo model: ``disparity``, ``vertical_disparity``,
      ``miss_distance``, ``gap``, and ``skipped`` (points one eye only sees).

    >>> sim = bentstraw.simulate(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
    >>> sim.xyz.shape[1], sim.color.dtype
    (3, dtype('int64'))
    """

    #: ``(N, 3)`` float64: where each point appears in the chosen model (m); nan where none.
    xyz: np.ndarray
    #: ``(N,)`` int64: the colour code of the object each point's light came from.
    color: np.ndarray
    #: ``(N, 3)``: the course's image point ``O + L·u0`` of each point's ray (m).
    image_xyz: np.ndarray
    #: ``(N, 3)``: the unit direction ``u0`` in which the eye looks for each point.
    direction: np.ndarray
    #: ``(N,)``: the length ``L`` of each ray's broken path from the eye to the object (m).
    path_length: np.ndarray
    #: ``(N, 3)``: the point of the object each ray really reached (m).
    object_point: np.ndarray
    #: ``(N,)`` int64: the events (refractions and total reflections) on each ray's way.
    events: np.ndarray
    #: White light: ``(N,)`` float64, the wavelength (nm) each point's ray carried; else None.
    wavelength: Optional[np.ndarray] = None
    #: Rays traced in all, to find the points.
    rays_traced: int
    #: Angular spacing of the rays (≈ rad).
    spacing: float
    #: Share of the traced rays that reached an object.
    hit_ratio: float
    #: Image points traced (the stereo model keeps those both eyes see).
    image_points: int
    #: Eye model: the horizontal and vertical foci's signed distances from the eye (m; nan where
    #: not defined, inf at infinity), their kinds, and each point's gap to the course's point (m).
    s_h: Optional[np.ndarray] = None
    s_v: Optional[np.ndarray] = None
    s_h_kind: Optional[List[str]] = None
    s_v_kind: Optional[List[str]] = None
    gap: Optional[np.ndarray] = None
    #: Stereo model: the binocular and vertical disparities (rad), the lines of sight's closest
    #: distance (m), and how many points one eye only sees.
    disparity: Optional[np.ndarray] = None
    vertical_disparity: Optional[np.ndarray] = None
    miss_distance: Optional[np.ndarray] = None
    skipped: Optional[int] = None

    def __init__(self, fields: Dict[str, Any], scene: Any, image_model: ImageModel,
                 light: Light = "mono") -> None:
        self.__dict__.update(fields)
        self._read_only()
        self._scene = scene
        self._paths: Optional[Dict[str, Any]] = None
        self._points_asked = DEFAULT_POINTS
        observer = tuple(scene.observer)
        scene_name = scene.name
        #: The observer's eye (m).
        self.observer = observer
        #: The apparent-position model: ``"course"``, ``"eye"`` or ``"stereo"``.
        self.image_model = image_model
        #: The light the rays carried: ``"mono"`` (one wavelength) or ``"white"``.
        self.light = light
        #: The scene file's name, or None for the assignment's glass given by its numbers.
        self.scene_name = scene_name

    def _read_only(self) -> None:
        # The columns are results: read-only, so that editing one (the course's ``xyz`` is its
        # ``image_xyz``) cannot change another behind one's back. ``.copy()`` gives one to edit.
        for v in self.__dict__.values():
            if isinstance(v, np.ndarray):
                v.setflags(write=False)

    def __getstate__(self) -> Dict[str, Any]:
        # Pickled (multiprocessing, joblib, a cache) with its light paths, found now: the engine's
        # loaded scene they need does not travel.
        self._light_paths()
        return {k: v for k, v in self.__dict__.items() if k != "_scene"}

    def __setstate__(self, state: Dict[str, Any]) -> None:
        self.__dict__.update(state)
        self._scene = None
        self._read_only()

    @_keyworded
    def _light_paths(self) -> Dict[str, Any]:
        # Each point's ray traced once more, on first use (it costs about as much as the points).
        if self._paths is None:
            self._paths = _engine.light_paths(self._scene, self.direction,
                                              self.__dict__.get("_band"))
        return self._paths

    @property
    def path_index(self) -> np.ndarray:
        """``(N,)`` int64: each point's kind of light path, an index into ``path_keys``."""
        return cast(np.ndarray, self._light_paths()["path_index"])

    @property
    def path_keys(self) -> List[str]:
        """The kinds of light path present, as short keys (``"direct"``, ``"wall+1"``, ...),
        sorted: direct first, then by entry face and number of total reflections."""
        return cast(List[str], self._light_paths()["path_keys"])

    @property
    def path_words(self) -> List[str]:
        """The same kinds in words (``"through the side wall, 1 total reflection"``)."""
        return cast(List[str], self._light_paths()["path_words"])

    @property
    def path(self) -> np.ndarray:
        """``(N,)`` str: the kind of light path of each point, as its key."""
        if not self.path_keys:
            return np.empty(0, dtype=str)
        return cast(np.ndarray, np.asarray(self.path_keys, dtype=str)[self.path_index])

    def __len__(self) -> int:
        return len(self.color)

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the points to ``path`` exactly as ``bentstraw simulate --output PATH`` does
        for the same inputs: CSV, JSON (with the inputs) or PLY (a coloured point cloud) by the
        name's extension, byte for byte, all or nothing (a file already there stays until the
        new one is complete). The points are traced again to be written by the command line's
        own writers: tracing is deterministic, so they are these points.

        >>> sim = bentstraw.simulate(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
        >>> sim.save(tmp_path / "points.csv")
        """
        if self._scene is None:
            raise ValueError("a simulation read back from a pickle cannot be saved (its scene does "
                             "not travel): run simulate again with the same inputs")
        _engine.save_points(self._scene, self._points_asked, self.image_model, self.light,
                            os.fspath(path))

    def to_dataframe(self) -> Any:
        """The points as a pandas DataFrame, one row per point: ``x``, ``y``, ``z`` and
        ``color`` (the columns ``bentstraw simulate`` writes), then ``path`` (the kind of light
        path), ``path_length``, the object point ``object_x``, ``object_y``, ``object_z``, the
        first direction ``u0_x``, ``u0_y``, ``u0_z``, ``events``, and the model's own columns.
        Needs pandas (not required by the package otherwise).

        >>> sim = bentstraw.simulate(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
        >>> list(sim.to_dataframe().columns[:5])
        ['x', 'y', 'z', 'color', 'path']
        """
        try:
            import pandas as pd
        except ImportError as e:
            raise ImportError("to_dataframe needs pandas: pip install pandas") from e
        columns: Dict[str, Any] = {"x": self.xyz[:, 0], "y": self.xyz[:, 1], "z": self.xyz[:, 2],
                                   "color": self.color}
        if self.wavelength is not None:
            columns["wavelength"] = self.wavelength
        columns.update({"path": self.path, "path_length": self.path_length})
        for name, v in (("object", self.object_point), ("u0", self.direction)):
            for k, axis in enumerate("xyz"):
                columns[f"{name}_{axis}"] = v[:, k]
        columns["events"] = self.events
        for name in ("s_h", "s_v", "s_h_kind", "s_v_kind", "gap", "disparity",
                     "vertical_disparity", "miss_distance"):
            value = getattr(self, name)
            if value is not None:
                columns[name] = value
        return pd.DataFrame(columns)

    def plot(self, ax: Any = None, *,
             color_by: Optional[Literal["section", "path", "wavelength"]] = None,
             size: float = 1.0) -> Tuple[Any, Any]:
        """The image points in 3D with matplotlib, each in its object's colour (or, with
        ``color_by="path"``, coloured by kind of light path with a legend in words; with
        ``color_by="wavelength"``, the default in white light, in its wavelength's colour), on
        axes of equal scale so that the image's shape is true: ``(fig, ax)``, on ``ax`` if given
        (a 3D axes) else a new figure. Points the eye model places nowhere are left out.

        >>> sim = bentstraw.simulate(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
        >>> fig, ax = sim.plot(color_by="path")
        """
        if color_by is None:
            color_by = "section" if self.wavelength is None else "wavelength"
        if color_by not in ("section", "path", "wavelength"):
            raise ValueError(f"color_by={color_by!r}: it must be \"section\", \"path\" or "
                             "\"wavelength\"")
        if color_by == "wavelength" and self.wavelength is None:
            raise ValueError("color_by=\"wavelength\" needs a simulation in white light: "
                             "simulate(..., light=\"white\")")
        fig, ax = _axes(ax, "3d")
        shown = np.isfinite(self.xyz).all(axis=1)
        xyz = self.xyz[shown]
        # One set of points per colour (or kind of path), named in the legend.
        if color_by == "section":
            groups = [(self.color[shown] == code, COLOR_RGB[code - 1], COLOR_NAMES[code - 1])
                      for code in np.unique(self.color[shown])]
        elif color_by == "wavelength":
            nm = cast(np.ndarray, self.wavelength)[shown]
            groups = [(nm == w, _engine.wavelength_rgb(float(w)), f"{w:g} nm")
                      for w in np.unique(nm)]
        else:
            import matplotlib
            palette = matplotlib.colormaps["tab10"]
            index = self.path_index[shown]
            groups = [(index == k, palette(k % 10), words) for k, words in enumerate(self.path_words)]
        for chosen, colour, words in groups:
            ax.scatter(*xyz[chosen].T, color=colour, s=size, depthshade=False, label=words)
        ax.legend(loc="upper left", fontsize="small", markerscale=4)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_zlabel("z (m)")
        if len(xyz):
            # One scale on the three axes (the image's true shape), each axis at least 0.4 of the
            # longest so that a straw's tall, thin image stays readable.
            lo, hi = xyz.min(axis=0), xyz.max(axis=0)
            spans = np.maximum(hi - lo, 0.4 * (hi - lo).max() + 1e-9)
            for centre, span, limits in zip((lo + hi) / 2, spans,
                                            (ax.set_xlim, ax.set_ylim, ax.set_zlim)):
                limits(centre - span / 2, centre + span / 2)
            ax.set_box_aspect(spans)
            ax.locator_params(nbins=4)
        ax.set_title(f"{len(xyz)} image points ({self.image_model} model)")
        return fig, ax

    def __repr__(self) -> str:
        where = self.scene_name or "the glass"
        light = ", white light" if self.light == "white" else ""
        return (f"<Simulation of {where} from {self.observer}: {len(self)} points, "
                f"{self.image_model} model{light}>")


@_keyworded
def simulate(
    scene: SceneLike = None,
    *,
    observer: Optional[Vector3] = None,
    straw: Optional[Vector2] = None,
    water_height: Optional[float] = None,
    n_water: Optional[float] = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    wavelength: Optional[float] = None,
    points: int = DEFAULT_POINTS,
    image_model: ImageModel = "course",
    light: Light = "mono",
) -> Simulation:
    """The straw's virtual image: at least ``points`` image points seen from ``observer``.

    The scene is the assignment's glass given by ``straw=(xp, yp)``, ``water_height`` and
    ``n_water`` (default 1.333), or ``scene``: a scene file's path, a gallery name or a
    :class:`Scene` (its own ``[observer]`` unless ``observer`` is given; ``straw``,
    ``water_height`` and ``n_water`` change its one straw and liquid). ``image_model`` places
    each point by the course's convention (``"course"``: along the first ray, as far as the
    light travelled), by a small eye's astigmatic foci (``"eye"``) or by two eyes 65 mm apart
    (``"stereo"``). With ``light="white"`` each ray carries one band of the spectrum in turn (as
    many points, an eighth in each band, each traced at its band's wavelength) and the points
    have a ``wavelength``. The points are those ``bentstraw simulate`` writes for the same
    inputs, bit for bit. A broken rule raises ``ValueError`` with the command line's message.

    >>> sim = bentstraw.simulate(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
    >>> import matplotlib.pyplot as plt
    >>> ax = plt.figure().add_subplot(projection="3d")
    >>> _ = ax.scatter(*sim.xyz.T, c=sim.color, cmap="rainbow", s=1)
    """
    loaded = _load(scene, observer, straw, water_height, n_water, max_events, wavelength)
    fields = _engine.simulate(loaded, _count(points, "points", 2**63 - 1), image_model, light)
    simulation = Simulation(fields, loaded, image_model, light)
    simulation._points_asked = points
    return simulation


#: The keywords of :func:`simulate` a :func:`sweep` may vary.
_SWEPT = ("observer", "straw", "water_height", "n_water", "max_events", "wavelength", "points",
          "image_model", "light")


def _progress_bar(total: int, show: Optional[bool]) -> Any:
    """A progress bar for `total` steps that appears once a second has passed (tqdm's, a widget
    in a notebook), or None: without tqdm installed, or with ``show=False``."""
    if show is False:
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return tqdm(total=total, delay=0.0 if show else 1.0, desc="bentstraw.sweep")


def sweep(
    keyword: str,
    values: Sequence[Any],
    scene: SceneLike = None,
    *,
    progress: Optional[bool] = None,
    **shared: Any,
) -> List[Simulation]:
    """:func:`simulate` once for each of ``values`` of one of its keywords (``n_water``,
    ``water_height``, ``straw``, ``observer``, ``max_events``, ``wavelength``, ``points``,
    ``image_model``), the
    other keywords ``shared``: the simulations in the order of ``values``, each the one
    :func:`simulate` gives alone. A sweep that runs over a second shows a progress bar when tqdm
    is installed (a widget in a notebook); ``progress=True`` shows it at once, ``False`` never.
    Each value costs the call of :func:`simulate` (under a millisecond besides the tracing).

    >>> sims = bentstraw.sweep("n_water", [1.0, 1.2, 1.333], observer=(0.1, 0, 0.1),
    ...                        straw=(0, 0.02), water_height=0.1, points=2000)
    >>> len(sims), sims[0].image_model
    (3, 'course')
    """
    if keyword not in _SWEPT:
        raise TypeError(f"sweep cannot vary {keyword!r}: it varies one of {', '.join(_SWEPT)}")
    if keyword in shared:
        raise TypeError(f"{keyword} is both swept and shared: give it once, in values")
    _sequence(values, "values")
    bar = _progress_bar(len(values), progress)
    out = []
    try:
        for v in values:
            out.append(simulate(scene, **{keyword: v}, **shared))
            if bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()
    return out


@overload
def render(
    scene: SceneLike = ...,
    *,
    observer: Optional[Vector3] = ...,
    straw: Optional[Vector2] = ...,
    water_height: Optional[float] = ...,
    n_water: Optional[float] = ...,
    max_events: int = ...,
    wavelength: Optional[float] = ...,
    size: Tuple[int, int] = ...,
    target: Optional[Vector3] = ...,
    fov: Optional[float] = ...,
    mode: Mode = ...,
    prune: float = ...,
    backdrop: Backdrop = ...,
    samples: int = ...,
    light: Light = ...,
    sampling: Sampling = ...,
    weights: Literal[False] = ...,
) -> Picture: ...


@overload
def render(
    scene: SceneLike = ...,
    *,
    observer: Optional[Vector3] = ...,
    straw: Optional[Vector2] = ...,
    water_height: Optional[float] = ...,
    n_water: Optional[float] = ...,
    max_events: int = ...,
    wavelength: Optional[float] = ...,
    size: Tuple[int, int] = ...,
    target: Optional[Vector3] = ...,
    fov: Optional[float] = ...,
    mode: Mode = ...,
    prune: float = ...,
    backdrop: Backdrop = ...,
    samples: int = ...,
    light: Light = ...,
    sampling: Sampling = ...,
    weights: Literal[True],
) -> Tuple[Picture, np.ndarray]: ...


@overload
def render(
    scene: SceneLike = ...,
    *,
    observer: Optional[Vector3] = ...,
    straw: Optional[Vector2] = ...,
    water_height: Optional[float] = ...,
    n_water: Optional[float] = ...,
    max_events: int = ...,
    wavelength: Optional[float] = ...,
    size: Tuple[int, int] = ...,
    target: Optional[Vector3] = ...,
    fov: Optional[float] = ...,
    mode: Mode = ...,
    prune: float = ...,
    backdrop: Backdrop = ...,
    samples: int = ...,
    light: Light = ...,
    sampling: Sampling = ...,
    weights: bool = ...,
) -> Union[Picture, Tuple[Picture, np.ndarray]]: ...


@_keyworded
def render(
    scene: SceneLike = None,
    *,
    observer: Optional[Vector3] = None,
    straw: Optional[Vector2] = None,
    water_height: Optional[float] = None,
    n_water: Optional[float] = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    wavelength: Optional[float] = None,
    size: Tuple[int, int] = DEFAULT_SIZE,
    target: Optional[Vector3] = None,
    fov: Optional[float] = None,
    mode: Mode = DEFAULT_MODE,
    prune: float = DEFAULT_PRUNE,
    backdrop: Backdrop = DEFAULT_BACKDROP,
    samples: int = DEFAULT_SAMPLES,
    light: Light = "mono",
    sampling: Sampling = "adaptive",
    weights: bool = False,
) -> Union[Picture, Tuple[Picture, np.ndarray]]:
    """The picture the observer's eye gets: an ``(h, w, 3)`` uint8 array (a :class:`Picture`,
    which also holds its field of view ``fov`` in degrees), the pixels of the PNG
    ``bentstraw render`` writes for the same inputs.

    ``size=(w, h)`` in pixels; ``target`` the point looked at and ``fov`` the vertical field of
    view in degrees (both framed from the scene by default); ``mode="fresnel"`` shares each
    ray's light between reflection and refraction by Fresnel's equations (branches lighter than
    ``prune`` abandoned), ``"course"`` follows one ray; ``backdrop`` is ``"checker"`` or
    ``"none"``; ``samples`` per pixel side at edges (``sampling="full"``: at every pixel);
    ``light="white"`` draws it in white light (each band of the spectrum at its own wavelength,
    where an index depends on it). With
    ``weights=True`` returns
    ``(picture, raw)``: one ray per pixel centre as ``render --raw`` writes it, ``raw`` an
    ``(h, w)`` array of colour codes (course) or an ``(h, w, k)`` array of each colour code's
    weight (Fresnel).

    >>> picture = bentstraw.render(observer=(0.3, 0, 0.22), straw=(-0.02, 0.02), water_height=0.15)
    >>> import matplotlib.pyplot as plt
    >>> picture.shape
    (600, 800, 3)
    >>> round(picture.fov, 2)
    51.68
    >>> _ = plt.imshow(picture)
    """
    loaded = _load(scene, observer, straw, water_height, n_water, max_events, wavelength)
    size_ = None if size is None else _size(size)
    out = _engine.render(
        loaded, size_, _vector(target, 3, "target"), _number(fov, "fov"), mode,
        _real(prune, "prune"), backdrop, _count(samples, "samples"), _flag(weights, "weights"),
        light, sampling,
    )
    picture: Picture = out["pixels"].view(Picture)
    camera = {k: out[k] for k in ("fov_deg", "eye", "forward", "right", "up", "tan_half_fov")}
    camera["size"] = (picture.shape[1], picture.shape[0])
    picture._camera = camera
    if not weights:
        return picture
    return picture, out["codes"] if "codes" in out else out["weights"]


@_keyworded
def check(
    xyz: Any,
    color: Any,
    scene: SceneLike = None,
    *,
    observer: Optional[Vector3] = None,
    straw: Optional[Vector2] = None,
    water_height: Optional[float] = None,
    n_water: Optional[float] = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    wavelength: Optional[float] = None,
    tolerance: float = DEFAULT_TOLERANCE,
    min_coverage: float = DEFAULT_MIN_COVERAGE,
    worst: int = 10,
) -> CheckReport:
    """Judges image points ``xyz`` (``(N, 3)``, m) of colour codes ``color`` (``(N,)``) seen
    from ``observer``: a dict with the fields of ``bentstraw check --json`` and the same values
    (``"verdict"`` is ``"pass"`` or ``"fail"``; the counts per kind and per colour; the coverage
    of the true image; the missing regions; the worst points, their ``"line"`` being the row's
    index + 1; hints).

    >>> sim = bentstraw.simulate(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
    >>> bentstraw.check(sim.xyz, sim.color, observer=(0.1, 0, 0.1), straw=(0, 0.02),
    ...                 water_height=0.1)["verdict"]
    'pass'
    """
    points, codes = _points(xyz, color)
    loaded = _load(scene, observer, straw, water_height, n_water, max_events, wavelength)
    report = _engine.check(loaded, points, codes, _real(tolerance, "tolerance"),
                           _real(min_coverage, "min_coverage"), _count(worst, "worst"))
    return CheckReport(json.loads(report))


@_keyworded
def grade(
    class_dir: Union[str, "os.PathLike[str]"],
    out: Union[str, "os.PathLike[str]"],
    *,
    assignment: Optional[Union[str, "os.PathLike[str]"]] = None,
    lang: str = "en",
) -> List[Dict[str, Any]]:
    """Grades a whole class as ``bentstraw grade CLASS --out OUT`` does, and returns the
    gradebook's rows.

    ``class_dir`` is a folder with one sub-folder per student (Moodle's "download all
    submissions" layout included), or a zip of such folders. The cases are the assignment file's
    (``assignment``, TOML), else the four reference simulations (files ``sim1`` ... ``sim4``, 25
    points each). Into ``out`` go, all together or not at all, ``grades.csv``, the class's page
    ``index.html``, and per student their Gradescope ``results.json`` and feedback page with the
    check figures (in French with ``lang="fr"``). Each row is a dict with ``student``, ``case``,
    ``verdict`` (``"pass"``, ``"fail"``, ``"missing"`` or ``"unreadable"``), ``score``,
    ``max_score``, ``points``, ``correct``, ``coverage``, ``note`` and ``missing`` (the parts of
    the image the points miss, in words). A student's bad file is that case's verdict, with the
    reason; the rest of the class is graded.
    """
    rows = _engine.grade(os.fspath(class_dir), os.fspath(out),
                         None if assignment is None else os.fspath(assignment), lang)
    return cast(List[Dict[str, Any]], json.loads(rows))


class SolutionError(AssertionError):
    """Raised by :func:`assert_solution` when the points are not the image: the message names
    what is wrong and the parts of the image missed; ``score`` is the partial score out of
    ``max_score``, and ``row`` the whole grade (as :func:`grade` gives a row)."""

    def __init__(self, message: str, row: Dict[str, Any]):
        super().__init__(message)
        self.row = row
        self.score: float = row["score"]
        self.max_score: float = row["max_score"]


@_keyworded
def assert_solution(
    xyz: Any,
    color: Any,
    scene: SceneLike = None,
    *,
    observer: Optional[Vector3] = None,
    straw: Optional[Vector2] = None,
    water_height: Optional[float] = None,
    n_water: Optional[float] = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    wavelength: Optional[float] = None,
    tolerance: float = DEFAULT_TOLERANCE,
    min_coverage: float = DEFAULT_MIN_COVERAGE,
    points: float = 25.0,
    lang: str = "en",
) -> Dict[str, Any]:
    """Asserts that ``xyz`` (``(N, 3)``, m) with colour codes ``color`` (``(N,)``) are the image
    points of the scene seen from ``observer``, for notebook graders (nbgrader, Otter): passes
    silently with the grade (a dict, as a row of :func:`grade`) when every point is right and the
    image covered, as ``bentstraw check`` judges it; otherwise raises :class:`SolutionError` (an
    ``AssertionError``) naming what is wrong and the parts of the image missed, carrying the
    partial score out of ``points``.

    >>> sim = bentstraw.simulate(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
    >>> bentstraw.assert_solution(sim.xyz, sim.color, observer=(0.1, 0, 0.1), straw=(0, 0.02),
    ...                           water_height=0.1)["score"]
    25.0
    >>> try:
    ...     bentstraw.assert_solution(sim.xyz[::2], sim.color[::2] % 5 + 1,
    ...                               observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
    ... except AssertionError as e:
    ...     print(e.score < 25.0, str(e).split(":")[0])
    True xyz
    """
    pts, codes = _points(xyz, color)
    loaded = _load(scene, observer, straw, water_height, n_water, max_events, wavelength)
    row: Dict[str, Any] = json.loads(_engine.grade_points(loaded, pts, codes, _real(tolerance, "tolerance"),
                                          _real(min_coverage, "min_coverage"),
                                          _real(points, "points"), lang))
    if row["verdict"] != "pass":
        message = row["note"]
        if row["missing"]:
            message += "\n" + "\n".join(row["missing"])
        if lang == "fr":
            message += f"\nnote partielle : {row['score']} sur {row['max_score']}"
        else:
            message += f"\npartial score: {row['score']} of {row['max_score']}"
        raise SolutionError(message, row)
    return row


class CheckReport(Dict[str, Any]):
    """What :func:`check` says of a solution: a dict with the fields of ``bentstraw check
    --json`` (``report["verdict"]``, ``report["coverage"]``, ...), whose ``repr`` says the
    verdict, the points judged correct and the coverage of the true image; it pickles."""

    def __repr__(self) -> str:
        coverage = self.get("coverage") or {}
        least = min(coverage.values()) if coverage else float("nan")
        return (f"<CheckReport: {self.get('verdict')}, {self.get('correct')} of "
                f"{self.get('points')} points correct, least coverage of a colour {least:.0%}>")


class Ray(Dict[str, Any]):
    """One ray's light path, as :func:`trace` gives it: a dict (``ray["events"]``,
    ``ray["path"]``, ``ray["path_length"]``, ...), whose ``repr`` says its path and where it
    ends; it pickles; :meth:`plot` draws it."""

    def plot(self, ax: Any = None) -> Tuple[Any, Any]:
        """The ray's broken path in 3D with matplotlib: from the eye to each event (numbered, as
        in ``ray["events"]``) and on to the object it reaches ("really here"), or out of the
        scene; and, dashed, the straight line of sight along which the eye looks, to the image
        point where the object is seen ("seen here"). One scale on the three axes. Returns
        ``(fig, ax)``, on ``ax`` if given (a 3D axes), else a new figure.

        >>> ray = bentstraw.trace(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1,
        ...                       toward=(0, 0.02, 0.05))
        >>> fig, ax = ray.plot()
        """
        fig, ax = _axes(ax, "3d")
        path = [self["observer"]] + [e["point"] for e in self["events"]]
        if self.get("outcome") == "escaped":
            leaves = self["leaves"]
            reach = max(0.05, float(np.ptp(np.asarray(path), axis=0).max()) / 2)
            path.append(list(np.asarray(leaves["from"]) + reach * np.asarray(leaves["direction"])))
        else:
            path.append(self["straw_point"])
        line = np.asarray(path, dtype=float)
        ax.plot(*line.T, color="tab:orange", lw=1.5, label="the light's path")
        drawn = [line]
        for k, e in enumerate(self["events"], start=1):
            ax.text(*e["point"], f" {k}", color="tab:orange")
        ax.scatter(*np.asarray(self["observer"]), color="black", s=20)
        ax.text(*self["observer"], " eye")
        if self.get("outcome") != "escaped":
            seen = np.asarray([self["observer"], self["image_point"]], dtype=float)
            ax.plot(*seen.T, color="0.4", ls="--", lw=1, label="line of sight")
            ax.scatter(*seen[1], color="0.4", s=20)
            ax.text(*seen[1], " seen here", color="0.3")
            ax.scatter(*np.asarray(self["straw_point"]), color="tab:red", s=20)
            ax.text(*self["straw_point"], " really here", color="tab:red")
            drawn.append(seen)
        points = np.concatenate(drawn)
        lo, hi = points.min(axis=0), points.max(axis=0)
        span = float((hi - lo).max()) or 1.0
        for centre, limits in zip((lo + hi) / 2, (ax.set_xlim, ax.set_ylim, ax.set_zlim)):
            limits(centre - span / 2, centre + span / 2)
        ax.set_box_aspect((1, 1, 1))
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_zlabel("z (m)")
        ax.set_title(str(self.get("path")))
        ax.legend(loc="upper left", fontsize="small")
        return fig, ax

    def __repr__(self) -> str:
        events = len(self.get("events", []))
        if self.get("outcome") == "escaped":
            return f"<Ray: {self.get('path')}, {events} events, escapes>"
        return (f"<Ray: {self.get('path')}, {events} events, reaches {self.get('color_name')} "
                f"after L = {self.get('path_length', float('nan')):.4f} m>")


def _axes(ax: Any, projection: Optional[str]) -> Tuple[Any, Any]:
    """``ax`` and its figure, or a new figure's axes (``projection="3d"`` for points)."""
    if ax is not None:
        return ax.figure, ax
    import matplotlib.pyplot as plt
    fig = plt.figure()
    return fig, fig.add_subplot(projection=projection)


def _points(xyz: Any, color: Any) -> Tuple[np.ndarray, np.ndarray]:
    """``xyz`` and ``color`` as contiguous float arrays of shapes ``(N, 3)`` and ``(N,)``, or a
    ValueError naming the one that is not."""
    points = np.ascontiguousarray(np.asarray(xyz, dtype=np.float64))
    codes = np.ascontiguousarray(np.asarray(color, dtype=np.float64))
    if points.ndim != 2 or points.shape[1:] != (3,):
        raise ValueError(f"xyz has shape {points.shape}: it must be (N, 3), points x, y, z in metres")
    if codes.ndim != 1:
        raise ValueError(f"color has shape {codes.shape}: it must be (N,), one colour code per point")
    return points, codes


@_keyworded
def trace(
    scene: SceneLike = None,
    *,
    observer: Optional[Vector3] = None,
    straw: Optional[Vector2] = None,
    water_height: Optional[float] = None,
    n_water: Optional[float] = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    wavelength: Optional[float] = None,
    direction: Optional[Vector3] = None,
    toward: Optional[Vector3] = None,
) -> Ray:
    """The light path of one ray from the observer, along ``direction`` or toward the point
    ``toward``, as the explorer shows a clicked ray: a dict with its ``"events"`` (each with its
    point, face, ``"refraction"`` or ``"total reflection"``, the angles of incidence and of the
    outgoing ray in degrees, and the indices), the kind of ``"path"``, and where it ends: the
    ``"straw_point"`` reached, the ``"path_length"``, the ``"image_point"`` and the eye's and
    stereo points — or ``"outcome": "escaped"`` with where it ``"leaves"``.

    >>> sim = bentstraw.simulate(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
    >>> ray = bentstraw.trace(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1,
    ...                       direction=sim.direction[0])
    >>> ray["path"], [e["event"] for e in ray["events"]]
    ('through the side wall, 1 total reflection', ['refraction', 'total reflection'])
    >>> bool(ray["path_length"] == sim.path_length[0])
    True
    """
    loaded = _load(scene, observer, straw, water_height, n_water, max_events, wavelength)
    ray = _engine.trace(loaded, _vector(direction, 3, "direction"), _vector(toward, 3, "toward"))
    return Ray(json.loads(ray))


def ray_diagram(
    scene: SceneLike = None,
    *,
    observer: Optional[Vector3] = None,
    straw: Optional[Vector2] = None,
    water_height: Optional[float] = None,
    n_water: Optional[float] = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    wavelength: Optional[float] = None,
    direction: Optional[Vector3] = None,
    toward: Optional[Vector3] = None,
    ax: Any = None,
) -> Tuple[Any, Any]:
    """The ray of :func:`trace` (the same keywords) drawn by :meth:`Ray.plot`: its broken path,
    each event numbered, the object it reaches and, dashed, the line of sight to where the eye
    sees it. Returns ``(fig, ax)``.

    >>> fig, ax = bentstraw.ray_diagram(observer=(0.1, 0, 0.1), straw=(0, 0.02),
    ...                                 water_height=0.1, toward=(0, 0.02, 0.05))
    """
    ray = trace(scene, observer=observer, straw=straw, water_height=water_height,
                n_water=n_water, max_events=max_events, wavelength=wavelength,
                direction=direction, toward=toward)
    return ray.plot(ax)


@_keyworded
def explore(
    scene: SceneLike = None,
    *,
    observer: Optional[Vector3] = None,
    straw: Optional[Vector2] = None,
    water_height: Optional[float] = None,
    n_water: Optional[float] = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    wavelength: Optional[float] = None,
    points: int = DEFAULT_POINTS,
    mode: Mode = DEFAULT_MODE,
    backdrop: Backdrop = DEFAULT_BACKDROP,
    lang: Literal["en", "fr"] = "en",
    height: int = 720,
) -> Explorer:
    """The live explorer's page opened on this view: in a notebook cell it shows itself (turn
    the eye, drag the straw, click a ray); elsewhere ``.open()`` opens it in a browser.

    The page and its engine (compiled to WebAssembly) come with the package and are served to
    this machine alone; the browser computes everything, offline, with the same numbers as the
    command line. The keywords are those of :func:`simulate` and :func:`render`, checked the
    same way before the page opens; ``lang`` is the page's language and ``height`` the frame's
    height in pixels in a notebook.

    >>> bentstraw.explore("prism")  # doctest: +SKIP
    """
    loaded = _load(scene, observer, straw, water_height, n_water, max_events, wavelength)
    query: Dict[str, str] = {}
    if isinstance(scene, Scene):
        query["scene-file"] = scene.text
    elif scene is not None:
        path = os.fspath(scene)
        if os.path.exists(path):
            query["scene-file"] = Scene.load(path).text
        else:
            query["scene"] = loaded.name or path

    def numbers(v: Sequence[float]) -> str:
        return ",".join(repr(float(x)) for x in v)

    query["observer"] = numbers(loaded.observer)
    if straw is not None:
        query["straw"] = numbers(_vector(straw, 2, "straw") or ())
    if water_height is not None:
        query["water-height"] = repr(_real(water_height, "water_height"))
    if n_water is not None:
        query["n-water"] = repr(_real(n_water, "n_water"))
    query["max-events"] = str(_count(max_events, "max_events"))
    if wavelength is not None:
        query["wavelength"] = repr(_real(wavelength, "wavelength"))
    query["points"] = str(_count(points, "points"))
    # The picture's choices checked by the engine's own rules: one pixel drawn with them.
    _engine.render(loaded, (1, 1), None, None, mode, DEFAULT_PRUNE, backdrop, 1, False, "mono",
                   "adaptive")
    if lang not in ("en", "fr"):
        raise ValueError(f"lang={lang!r} is not allowed: the page speaks \"en\" or \"fr\"")
    query.update(mode=mode, backdrop=backdrop, lang=lang)
    return Explorer(_explore.address(query), _count(height, "height", 10000))

