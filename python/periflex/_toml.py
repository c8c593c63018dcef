"""A scene given as a dict, written as TOML text for the scene reader.

Tables become [tables], lists of dicts become [[arrays of tables]] (body, joint, flex_body, ...),
everything else a TOML value. Only what scenes use: strings, numbers, booleans, lists, dicts.
"""

import math


def value(v, key="value"):
    """One TOML value."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_key(k)} = {value(x, k)}" for k, x in v.items()) + "}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(value(x, key) for x in v) + "]"
    if hasattr(v, "tolist"):  # NumPy scalars and arrays
        return value(v.tolist(), key)
    raise TypeError(f"scene key '{key}': cannot write a {type(v).__name__} as TOML")


def _key(k):
    k = str(k)
    bare = k and all(c.isalnum() or c in "_-" for c in k)
    return k if bare else value(k)


def _is_table_array(v):
    return isinstance(v, (list, tuple)) and len(v) > 0 and all(isinstance(x, dict) for x in v)


def dumps(scene, prefix=""):
    """The TOML text of `scene` (a dict of tables)."""
    lines, tables = [], []
    for k, v in scene.items():
        if isinstance(v, dict) or _is_table_array(v):
            tables.append((k, v))
        else:
            lines.append(f"{_key(k)} = {value(v, prefix + str(k))}")
    for k, v in tables:
        name = prefix + _key(k)
        if isinstance(v, dict):
            lines.append(f"\n[{name}]")
            lines.append(dumps(v, name + "."))
        else:
            for element in v:
                lines.append(f"\n[[{name}]]")
                lines.append(dumps(element, name + "."))
    return "\n".join(line for line in lines if line)
