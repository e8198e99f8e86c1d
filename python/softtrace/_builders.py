"""Builder functions: one per kind of the kinds table (softtrace.nodes()): soft_blend([...]),
soft_object(distance, potential), lp_metric(radii, n), ...; and one per object of the scene's own
(softtrace._native.scene_keys()): the shapes sphere(center, radius), box(corner1, corner2), ...,
material(color, ...), the lights point_light(position, ...), ... and area_light(axis1, ...). Each
returns the dict the scene format writes ({"type": kind, ...} for nodes, shapes and lights),
checked when a Field or a scene is made from it."""
import inspect
from typing import Any, Callable, Dict, List, Optional, Tuple

# Keys any node may carry besides its kind's parameters (docs/scene-format.md, "Placement").
PLACEMENT = ("translate", "rotate", "scale", "matrix")


def _kind_doc(kind: Dict[str, Any]) -> str:
    lines = ["%s (%s): %s" % (kind["name"], kind["group"], kind["summary"]), ""]
    for p in kind["params"]:
        text = "    %s: %s" % (p["name"], p["type"])
        if p["range"]:
            text += ", " + p["range"]
        lines.append(text + " (default: %s)" % p["default"])
    if kind["group"] == "node":
        lines.append("    translate, rotate, scale, matrix: where the node is placed")
    lines += ["", "Returns the node as a dict, e.g. %s(...)[\"type\"] == %r." % (kind["name"],
                                                                             kind["name"])]
    return "\n".join(lines)


def _make(name: str, kind: Optional[str], params: List[str], keywords: List[str],
          doc: str) -> Callable[..., Dict[str, Any]]:
    """A builder `name(*params, *, keywords)` of {"type": kind, key: value, ...} (no "type" when
    `kind` is None) holding only the keys given."""
    params, accepted = list(params), list(params) + list(keywords)

    def build(*args: Any, **kwargs: Any) -> Dict[str, Any]:
        if len(args) > len(params):
            raise TypeError("%s() takes at most %d positional arguments (%s), %d given" %
                            (name, len(params), ", ".join(params), len(args)))
        node: Dict[str, Any] = {} if kind is None else {"type": kind}
        node.update(zip(params, args))
        for key, value in kwargs.items():
            if key not in accepted:
                raise TypeError("%s() has no parameter '%s' (expected %s)" %
                                (name, key, ", ".join(accepted) or "none"))
            if key in node:
                raise TypeError("%s() got '%s' twice" % (name, key))
            node[key] = value
        return node

    # Parameters with no default in the table are still optional here: some are required only
    # with others ("r1 ... with base conic"), and the loader says which one is missing.
    positional = [inspect.Parameter(p, inspect.Parameter.POSITIONAL_OR_KEYWORD, default=None)
                  for p in params]
    keyword_only = [inspect.Parameter(p, inspect.Parameter.KEYWORD_ONLY, default=None)
                    for p in keywords]
    build.__name__ = build.__qualname__ = name
    build.__doc__ = doc
    build.__signature__ = inspect.Signature(positional + keyword_only)  # type: ignore[attr-defined]
    return build


def _kind_builder(kind: Dict[str, Any]) -> Callable[..., Dict[str, Any]]:
    params = [p["name"] for p in kind["params"]]
    placement = [k for k in PLACEMENT if k not in params] if kind["group"] == "node" else []
    return _make(kind["name"], kind["name"], params, placement, _kind_doc(kind))


def _scene_builder(list_name: str, keys: List[str]) -> Optional[Tuple[str, Callable[..., Any]]]:
    """The builder of the scene object whose keys docs/scene-format.md lists under `list_name`
    (None for those written by hand: top level, camera, image, object, animation)."""
    where = 'docs/scene-format.md, "%s"' % list_name
    group, _, kind = list_name.partition(": ")
    own = [k for k in keys if k != "type"]
    if group == "shape":  # the value of an object's "shape"
        params = [k for k in own if k not in PLACEMENT]
        placement = [k for k in own if k in PLACEMENT]
        doc = ("%s: an object's \"shape\", {\"type\": %r, ...} (%s): %s; placed by %s.\n\n"
               ">>> sphere([0, 0, 0], 2, translate=[0, 0, 1])\n"
               "{'type': 'sphere', 'center': [0, 0, 0], 'radius': 2, 'translate': [0, 0, 1]}"
               % (kind, kind, where, ", ".join(params), ", ".join(placement)))
        return kind, _make(kind, kind, params, placement, doc)
    if group == "light":  # an entry of the scene's "lights"
        name = kind + "_light"
        doc = ("%s: an entry of the scene's \"lights\", {\"type\": %r, ...} (%s): %s.\n\n"
               ">>> point_light([0, -50, 80], intensity=0.8)\n"
               "{'type': 'point', 'position': [0, -50, 80], 'intensity': 0.8}"
               % (name, kind, where, ", ".join(own)))
        return name, _make(name, kind, own, [], doc)
    if list_name == "material":  # an object's "material"
        doc = ("material: an object's \"material\" (%s): %s.\n\n"
               ">>> material([0.8, 0.1, 0.1], phong=0.6)\n"
               "{'color': [0.8, 0.1, 0.1], 'phong': 0.6}" % (where, ", ".join(own)))
        return "material", _make("material", None, own, [], doc)
    if list_name == "area light":  # a point or spot light's "area"
        doc = ("area_light: a point or spot light's \"area\" (%s): %s.\n\n"
               ">>> area_light([4, 0, 0], [0, 4, 0], 3, 3)\n"
               "{'axis1': [4, 0, 0], 'axis2': [0, 4, 0], 'size1': 3, 'size2': 3}"
               % (where, ", ".join(own)))
        return "area_light", _make("area_light", None, own, [], doc)
    return None


def builders(kinds: List[Dict[str, Any]],
             scene_keys: List[Tuple[str, List[str]]]) -> Dict[str, Callable[..., Dict[str, Any]]]:
    """Every kind's builder, by the kind's name, and the scene objects' (shapes, lights, material,
    area_light). A name both would take is a ValueError: one would hide the other."""
    out = {k["name"]: _kind_builder(k) for k in kinds}
    for list_name, keys in scene_keys:
        made = _scene_builder(list_name, list(keys))
        if made is None:
            continue
        if made[0] in out:
            raise ValueError("builder '%s' named twice (a kind and %s)" % (made[0], list_name))
        out[made[0]] = made[1]
    return out
