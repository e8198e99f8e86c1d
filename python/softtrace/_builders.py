"""One builder function per kind of the kinds table (softtrace.nodes()): soft_blend([...]),
soft_object(distance, potential), lp_metric(radii, n), ... Each returns the node as the dict the
scene format writes, {"type": kind, ...}, checked when a Field or a scene is made from it."""
import inspect
from typing import Any, Callable, Dict, List

# Keys any node may carry besides its kind's parameters (docs/scene-format.md, "Placement").
PLACEMENT = ("translate", "rotate", "scale", "matrix")


def _doc(kind: Dict[str, Any]) -> str:
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


def _builder(kind: Dict[str, Any]) -> Callable[..., Dict[str, Any]]:
    name = kind["name"]
    params = [p["name"] for p in kind["params"]]
    keywords = params + ([k for k in PLACEMENT if k not in params] if kind["group"] == "node"
                         else [])

    def build(*args: Any, **kwargs: Any) -> Dict[str, Any]:
        if len(args) > len(params):
            raise TypeError("%s() takes at most %d positional arguments (%s), %d given" %
                            (name, len(params), ", ".join(params), len(args)))
        node: Dict[str, Any] = {"type": name}
        node.update(zip(params, args))
        for key, value in kwargs.items():
            if key not in keywords:
                raise TypeError("%s() has no parameter '%s' (expected %s)" %
                                (name, key, ", ".join(keywords) or "none"))
            if key in node:
                raise TypeError("%s() got '%s' twice" % (name, key))
            node[key] = value
        return node

    # Parameters with no default in the table are still optional here: some are required only
    # with others ("r1 ... with base conic"), and the loader says which one is missing.
    positional = [inspect.Parameter(p, inspect.Parameter.POSITIONAL_OR_KEYWORD, default=None)
                  for p in params]
    placement = [inspect.Parameter(p, inspect.Parameter.KEYWORD_ONLY, default=None)
                 for p in keywords[len(params):]]
    build.__name__ = build.__qualname__ = name
    build.__doc__ = _doc(kind)
    build.__signature__ = inspect.Signature(positional + placement)  # type: ignore[attr-defined]
    return build


def builders(kinds: List[Dict[str, Any]]) -> Dict[str, Callable[..., Dict[str, Any]]]:
    """Every kind's builder, by the kind's name."""
    return {k["name"]: _builder(k) for k in kinds}
