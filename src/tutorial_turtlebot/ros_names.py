"""ROS graph resource names as rosgraph.names checks them, without ROS (sim/ may not import it).

A name: "" (the namespace itself), or a letter, "/" or "~" first, then letters, digits, _ and /,
never "//". A namespace: names of a letter then letters, digits and _, joined by "/", with an
optional leading and trailing "/"; "" and "/" are the root.
"""
import re

_NAME = re.compile(r"^([~/A-Za-z][A-Za-z0-9_/]*)?$")
_NAMESPACE = re.compile(r"^/?([A-Za-z][A-Za-z0-9_]*/)*([A-Za-z][A-Za-z0-9_]*)?/?$")


def is_legal_name(name) -> bool:
    """Whether ``name`` is a legal ROS graph resource name (topic, service, node, param)."""
    return isinstance(name, str) and bool(_NAME.match(name)) and "//" not in name


def is_legal_namespace(namespace) -> bool:
    """Whether ``namespace`` is a legal ROS namespace ("tb3_0", "/tb3_0/", "/a/b", "", "/")."""
    return (isinstance(namespace, str) and bool(_NAMESPACE.match(namespace))
            and "//" not in namespace)
