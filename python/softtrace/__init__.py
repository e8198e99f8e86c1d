"""softtrace: implicit soft objects, their blends and a ray-marching renderer (docs/python.md).

>>> import softtrace
>>> scene = softtrace.load_dict({
...     "camera": {"eye": [0, -60, 20], "target": [0, 0, 0]},
...     "image": {"width": 32, "height": 24},
...     "objects": [{"field": softtrace.soft_blend([
...         softtrace.soft_object(softtrace.lp_metric([10, 10, 10], 2), translate=[-6, 0, 0]),
...         softtrace.soft_object(softtrace.lp_metric([10, 10, 10], 2), translate=[6, 0, 0])])}]})
>>> softtrace.render(scene)["rgba"].shape
(24, 32, 4)
>>> round(float(softtrace.Field(scene).eval([0, 0, 0])), 6)
0.635039
"""
import builtins
import os
from typing import Any, Callable, Dict, Iterable, Mapping, Optional, Union

import numpy as np

from . import _builders, _display, _json, _native
from ._native import SceneError, __version__

SceneError.__module__ = __name__

PathLike = Union[str, "os.PathLike[str]"]
_MAX_SCENE_BYTES = 256 << 20  # renderer/scene/scene.h kMaxSceneBytes
Node = Dict[str, Any]  # what a builder returns: the node as a scene file holds it

__all__ = ["Scene", "Field", "SceneError", "load_scene", "parse_scene", "load_dict", "render",
           "write_exr", "read_exr", "exr_attributes", "mesh", "write_mesh", "nodes", "__version__"]


class Scene(_native.Scene):
    """A scene: camera, image settings, background, lights and objects (docs/scene-format.md).

    Settings read as plain values, with every key of the file format (camera: projection, eye,
    target, up, fov, aperture, focal_distance, blur_samples, and aspect when given; image: width, height, spp,
    max_trace_level, and antialias and ambient_occlusion when on; a light: the keys its entry gave, as given, and its defaults), and change by
    assignment, checked as in a file (a refused value raises SceneError and leaves the scene as
    it was)::

        scene.camera = dict(scene.camera, fov=40)
        scene.width, scene.height = 320, 240
        scene.lights = [{"type": "point", "position": [0, 0, 50]}]
        scene.lights = None          # back to the default lights, which follow the camera

    An assignment replaces the scene this object holds and never changes one a render is using:
    renders running in other threads keep the scene they started with. Scenes pickle as their
    JSON text; in Jupyter a scene shows as a small render.
    """

    def __init__(self, text: Union[str, bytes], name: str = "<scene>") -> None:
        """The scene of JSON `text` (comments allowed); errors name `name`."""
        super().__init__(text, name)

    @property
    def text(self) -> str:
        """The JSON text the scene was parsed from (after an assignment: the text it made)."""
        return self._bytes.decode("utf-8", "replace")

    def to_dict(self) -> Dict[str, Any]:
        """The scene as a dict (what load_dict takes)."""
        import json
        return json.loads(self.text)

    def __reduce__(self) -> Any:
        return (Scene, (self._bytes, self.path))

    def __repr__(self) -> str:
        return "<softtrace.Scene %r %dx%d, %d spp, objects %s>" % (
            self.path, self.width, self.height, self.spp, ", ".join(self.objects))

    def _repr_png_(self) -> bytes:
        """A render of at most 320 pixels a side, over the background (Jupyter's picture)."""
        width, height = _display.preview_size(self.width, self.height)
        rgba = render(self, width=width, height=height, spp=1, flatten=True)["rgba"]
        return _display.png_bytes(rgba[..., :3])


class Field(_native.Field):
    """A compiled field: an object's field of a scene, or a node from JSON text or a dict.

    >>> f = Field(soft_object(lp_metric([2, 2, 2], 2)))    # radius 2, Blanc's potential
    >>> f.eval([[0, 0, 1], [1, 0, 0], [0, 0, 2]]).tolist()
    [0.5, 0.5, 0.0]

    Fields pickle as their node's JSON text and convention.
    """

    def __init__(self, source: Union[_native.Scene, str, Mapping[str, Any]],
                 object: Optional[str] = None, *, convention: str = "soft",
                 name: str = "<field>") -> None:
        """The field of `source`: a Scene's object named `object` (default: the first), or a
        node given as JSON text or a dict (a builder's), checked for an object of `convention`
        (soft, zero or constructive); errors name `name`."""
        if isinstance(source, _native.Scene):
            if convention != "soft" or name != "<field>":
                raise TypeError("convention and name are a node's, not a scene object's")
            super().__init__(source, object or "")
        else:
            if object is not None:
                raise TypeError("object names a scene's object; this field is a node")
            text = source if isinstance(source, str) else _json.dumps(source)
            super().__init__(text, convention, name)

    def eval(self, points: Any) -> np.ndarray:
        """Values at `points`, an array of shape (..., 3): an array of shape (...).

        >>> Field(soft_object(lp_metric([2, 2, 2], 2))).eval(np.zeros((4, 5, 3))).shape
        (4, 5)
        """
        return self._eval(points)

    def gradient(self, points: Any) -> "tuple[np.ndarray, np.ndarray]":
        """(values of shape (...), gradients of shape (..., 3)) at `points` of shape (..., 3).

        >>> values, gradients = Field(soft_object(lp_metric([2, 2, 2], 2))).gradient([0, 0, 1])
        >>> float(values), gradients.shape, float(gradients[2])
        (0.5, (3,), -1.0)
        """
        return self._gradient(points)

    def __reduce__(self) -> Any:
        return (_field_of_json, (self.json, self.convention, self.name))

    def __repr__(self) -> str:
        return "<softtrace.Field %s (%s)>" % (self.name, self.convention)


def _field_of_json(text: str, convention: str, name: str) -> Field:
    return Field(text, convention=convention, name=name)


def load_scene(path: PathLike) -> Scene:
    """The scene file at `path`, checked.

    A missing or unreadable file raises the OSError open() raises (FileNotFoundError, ...), a
    path with a NUL byte ValueError, a bad scene SceneError with the located line the command
    line prints (`scene.json:3:7: ...` or `scene.json: /objects/0/field/n: ...`).
    """
    # Read as the command line reads (renderer/scene/scene.cpp): in blocks, stopping at the first
    # block with a NUL byte (the parser then names its line and column) or past the size limit,
    # so that an endless input (/dev/zero, a pipe) is bounded.
    chunks, size = [], 0
    with open(path, "rb") as f:  # refuses "x.json\0junk" (ValueError: embedded null byte)
        while True:
            block = f.read(1 << 16)
            chunks.append(block)
            size += len(block)
            if not block or b"\0" in block:
                break
            if size > _MAX_SCENE_BYTES:
                raise SceneError(f"{os.fsdecode(path)}: larger than {_MAX_SCENE_BYTES >> 20} MiB; "
                                 "a scene file may be at most that")
    return Scene(b"".join(chunks), os.fsdecode(path))  # the bytes, as the command line reads them


def parse_scene(text: Union[str, bytes], name: str = "<scene>") -> Scene:
    """The scene of JSON `text`; errors name `name`.

    >>> parse_scene('{"camera": {"eye": [0, -9, 0], "target": [0, 0, 0]}, "objects": []}')
    Traceback (most recent call last):
    ...
    softtrace.SceneError: <scene>: /objects: expected at least one object
    """
    return Scene(text, name)


def load_dict(scene: Mapping[str, Any], name: str = "<dict>") -> Scene:
    """The scene of a dict as the scene format writes it (numpy arrays allowed for vectors);
    errors name `name` and the JSON pointer of the value."""
    return Scene(_json.dumps(scene), name)


def render(scene: Scene, *, width: int = 0, height: int = 0, spp: int = 0,
           frame: Optional[int] = None, aovs: Iterable[str] = (), threads: int = 0,
           progress: Optional[Callable[[int, int], Any]] = None, flatten: bool = False,
           outputs: Iterable[PathLike] = ()) -> Dict[str, np.ndarray]:
    """Renders the scene's camera view to a dict of float32 arrays.

    "rgba" (height, width, 4) is premultiplied linear RGBA as the EXR output holds it (with
    `flatten`, RGB over the background and A = 1); `aovs` adds any of "depth" (height, width:
    distance along the pixel-centre ray, inf for the background), "normal" (height, width, 3)
    "steps" (height, width: field evaluations of that ray) and "albedo" (height, width, 3: the
    hit material's colour, 0 for the background). width, height and spp of 0 keep
    the scene's, and one of width and height alone keeps the scene's aspect; frames above 2^26
    pixels are refused as the command line refuses them. `frame` renders that frame of the
    scene's animation (scene.frames of them), as `softtrace render --frame` does.

    `threads` caps the cores used (0: all); the picture is the same bits for any number.
    `progress(done, total)` is called with pixels done, about 50 times a second, on the calling
    thread; an exception it raises, or Ctrl-C (KeyboardInterrupt), stops the render within a
    sample's time. `outputs` (.exr, .png) are written as `softtrace render -o` writes them: all
    or nothing, checked before the work.

    >>> scene = load_scene(os.path.join(os.path.dirname(__file__), "..", "..", "scenes",
    ...                                  "fig000_12b_soft_blend.json"))  # doctest: +SKIP
    >>> image = render(scene, width=64, aovs=["depth"])  # doctest: +SKIP
    >>> sorted(image)  # doctest: +SKIP
    ['depth', 'rgba']
    """
    if isinstance(aovs, str):
        raise TypeError("aovs is a list of names, e.g. ['depth', 'normal']")
    if frame is not None and frame < 0:
        raise ValueError("frame must be >= 0 (frames are numbered from 0)")
    return _native.render(scene, width, height, spp, -1 if frame is None else frame, list(aovs),
                          threads, progress, flatten,
                          [os.fspath(o) for o in outputs])


def write_exr(path: PathLike, arrays: Mapping[str, Any],
              attributes: Optional[Mapping[str, str]] = None) -> None:
    """Writes float arrays as the channels of an EXR file, all or nothing.

    A (height, width) array is the channel its key names; a (height, width, C) array is C
    channels, named by its key's comma-separated names ("R,G,B") or, for render()'s keys, as the
    command line names them: rgba -> R,G,B,A, depth -> Z, normal -> N.X,N.Y,N.Z, steps -> steps.
    So write_exr("out.exr", render(scene, aovs=["depth"])) writes R, G, B, A and Z.
    `attributes` are string attributes for the header.
    """
    _native.write_exr(os.fspath(path), dict(arrays), dict(attributes or {}))


def read_exr(path: PathLike) -> Dict[str, np.ndarray]:
    """The channels of an EXR file (its first part's data window), by name, as float32
    (height, width) arrays, in the order `softtrace diff` lists them (R, G, B, A, Z, ...).
    exr_attributes(path) gives the header's string attributes."""
    with open(path, "rb"):  # FileNotFoundError and friends, as open() raises them
        pass
    return _native.read_exr(os.fspath(path))


def exr_attributes(path: PathLike) -> Dict[str, str]:
    """The string attributes of an EXR file's header (softtrace/sceneHash, software, ...)."""
    with open(path, "rb"):
        pass
    return _native.exr_attributes(os.fspath(path))


def mesh(scene: Union[Scene, PathLike], object: Optional[str] = None, *, voxel: float = 0.0,
         cells: int = 128, bounds: Optional[Iterable[float]] = None, threads: int = 0):
    """A closed, manifold, outward-oriented triangle mesh of an object's surface (docs/mesh.md).

    Returns (vertices (V, 3) float64, faces (F, 3) int64, unit normals (V, 3), linear RGB colours
    (V, 3)). `voxel` > 0 sets the cell size, else `cells` cells span the region's longest side;
    `bounds` [x0, x1, y0, y1, z0, z1] replaces the object's bounds (the mesh is capped where it
    cuts the solid). The same bits for any `threads`.
    """
    target = scene if isinstance(scene, _native.Scene) else os.fspath(scene)
    return _native.mesh(target, object, voxel, cells, None if bounds is None else list(bounds),
                        threads)


def write_mesh(path: PathLike, vertices: Any, faces: Any, normals: Any = None,
               colors: Any = None) -> None:
    """Writes a mesh as .obj, .ply, .stl or .glb (as `softtrace mesh -o`), all or nothing."""
    _native.write_mesh(os.fspath(path), vertices, faces, normals, colors)


def nodes() -> list:
    """Every kind a scene may name: dicts of name, group (node, potential, radius transform),
    summary (the formula and where the papers give it) and params (name, type, range,
    default), as `softtrace nodes` lists them. Each kind also has a builder here:

    >>> soft_object(lp_metric([3, 3, 3], 2), wyvill())
    {'type': 'soft_object', 'distance': {'type': 'lp_metric', 'radii': [3, 3, 3], 'n': 2}, \
'potential': {'type': 'wyvill'}}
    """
    return _native.nodes()


_BUILDERS = _builders.builders(nodes(), _native.scene_keys())
globals().update(_BUILDERS)
# `from softtrace import *` brings every builder but those named as Python's builtins (min, max),
# which it would hide; softtrace.min and softtrace.max are there all the same.
__all__ += [name for name in _BUILDERS if name not in dir(builtins)]
