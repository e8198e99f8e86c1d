"""Python values to the JSON text the scene loader parses."""
import json
from typing import Any


def _plain(value: Any) -> Any:
    """numpy arrays and scalars (anything with tolist()) as lists and numbers."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError("%s is not a scene value (expected dicts, lists, numbers, strings, "
                    "booleans or numpy arrays)" % type(value).__name__)


def dumps(value: Any) -> str:
    """JSON text of `value`; NaN and infinity are refused, as the scene format has none."""
    try:
        return json.dumps(value, default=_plain, allow_nan=False)
    except ValueError as e:
        raise ValueError("%s: the scene format has no NaN or infinity" % e) from None
