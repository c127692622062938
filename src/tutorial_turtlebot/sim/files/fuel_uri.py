"""Fuel URLs (``https://fuel.ignitionrobotics.org/1.0/OWNER/models/NAME/VERSION/files/PATH``)
found as Gazebo 11 finds them: in the Fuel cache on disk, never downloaded. No ROS and no
pybullet here; asset_uri.resolve_uri hands every ``http://`` and ``https://`` URI to
``fuel_file`` (and raises its errors).

Gazebo 11 reads such a URI through ignition-fuel-tools 4 (FuelModelDatabase::CachedFilePath,
FuelClient::CachedModelFile, LocalCache::MatchingModel):

- The URL is ``SCHEME://HOST[/API VERSION]/OWNER/models/NAME/VERSION/files/PATH`` (a model
  file), or the same without ``/files/PATH`` and with VERSION optional (a model, as an
  ``<include>`` names it). VERSION is a number or ``tip``.
- The cache is ``$IGN_FUEL_CACHE_PATH`` where that is a folder, else ``~/.ignition/fuel``;
  ``$GZ_FUEL_CACHE_PATH`` (newer gz-fuel-tools' name, which Gazebo 11 does not read) is looked
  in after it. A model is cached at ``CACHE/HOST/OWNER/models/NAME/N/`` with a model.config in
  that folder; ``tip`` (or no version) is the highest N there. Owner and name are matched
  whatever their letter case (fuel-tools stores them lowercase since 4.x, as written before),
  ``%20`` is a space; fuel.ignitionrobotics.org and fuel.gazebosim.org are the same server,
  each cache folder looked in for the other's URLs.
- Not in the cache: Gazebo 11 logs an error ("Unable to download model") and loads the world
  without that file. Here a model folder of the same NAME on the model path
  (``model://NAME/PATH``, asset_uri.ModelPath) is taken next; else asset_uri raises
  ``FuelNotCached``, which world_sdf makes one warning a file (one line for them all when there
  are many).
"""
import os
import re
from typing import Callable, List, Optional, Tuple
from urllib.parse import unquote

FUEL_SERVERS = ("fuel.ignitionrobotics.org", "fuel.gazebosim.org")   # one server, two names
_HEAD = r"^(?:https?)://([^/\s]+)/+(?:[0-9]+\.[0-9]+/+)?([^/\s]+)/+models/+([^/]+)"
_FILE_URL = re.compile(_HEAD + r"/+([0-9]*|tip)/+files/+(.*)$")
_MODEL_URL = re.compile(_HEAD + r"/*(?:/([0-9]*|tip))?/*$")


def is_web_uri(uri: str) -> bool:
    """Whether ``uri`` is an ``http://`` or ``https://`` URI (Gazebo 11 reads those from the
    Fuel cache only)."""
    return uri[:8].lower().startswith(("http://", "https://"))


def parse_fuel(uri: str) -> Optional[Tuple[str, str, str, str, Optional[str]]]:
    """(host, owner, name, version ("" for the tip), file path or None for a model URL) of a
    Fuel URL, owner, name and path with their %XX decoded; None if ``uri`` is no Fuel URL."""
    match = _FILE_URL.match(uri)
    if match:
        host, owner, name, version, path = match.groups()
        return host.lower(), unquote(owner), unquote(name), _version(version), unquote(path)
    match = _MODEL_URL.match(uri)
    if match:
        host, owner, name, version = match.groups()
        return host.lower(), unquote(owner), unquote(name), _version(version or ""), None
    return None


def _version(text: str) -> str:
    """"" for the tip (``tip`` or none), else the version number as the cache names it."""
    return "" if text in ("", "tip") else str(int(text))


def cache_roots(environ=os.environ) -> List[str]:
    """The Fuel cache folders, in search order: IGN_FUEL_CACHE_PATH if it is a folder (else
    ~/.ignition/fuel, as fuel-tools falls back), then GZ_FUEL_CACHE_PATH if set."""
    roots = []
    ign = environ.get("IGN_FUEL_CACHE_PATH", "")
    if ign and os.path.isdir(ign):
        roots.append(ign)
    elif environ.get("HOME"):
        roots.append(os.path.join(environ["HOME"], ".ignition", "fuel"))
    gz = environ.get("GZ_FUEL_CACHE_PATH", "")
    if gz and gz not in roots:
        roots.append(gz)
    return roots


def _child(folder: str, name: str) -> Optional[str]:
    """``folder``/``name`` if it is a folder, else the first (sorted) folder whose name differs
    from ``name`` only in letter case; None if there is none."""
    exact = os.path.join(folder, name)
    if os.path.isdir(exact):
        return exact
    try:
        names = sorted(n for n in os.listdir(folder) if n.lower() == name.lower())
    except OSError:
        return None
    return next((os.path.join(folder, n) for n in names
                 if os.path.isdir(os.path.join(folder, n))), None)


def cached_model(root: str, host: str, owner: str, name: str, version: str) -> Optional[str]:
    """The cached model folder ``root/HOST/OWNER/models/NAME/VERSION`` (the highest version
    for ``version`` ""), one holding a model.config; None if there is none."""
    hosts = [host] + ([h for h in FUEL_SERVERS if h != host] if host in FUEL_SERVERS else [])
    for each in hosts:
        owner_dir = _child(os.path.join(root, each), owner)
        models = _child(owner_dir, "models") if owner_dir else None
        model = _child(models, name) if models else None
        if model is None:
            continue
        try:
            versions = [v for v in os.listdir(model) if v.isdigit()
                        and os.path.isfile(os.path.join(model, v, "model.config"))]
        except OSError:
            continue
        if version:
            versions = [v for v in versions if int(v) == int(version)]
        if versions:
            return os.path.join(model, max(versions, key=int))
    return None


def fuel_file(uri: str, environ, find: Callable[[str], Optional[str]]
              ) -> Tuple[Optional[str], str]:
    """(the absolute path of the cached file, or model folder, the Fuel URL ``uri`` names,
    else of ``find("NAME/PATH")`` (a model folder on the model path); "") if either is there;
    (None, why) for an http(s) URI that is no Fuel URL or whose path leaves its model; (None,
    "") if it is in neither place. ``environ`` gives the cache folders. Nothing is
    downloaded."""
    parsed = parse_fuel(uri.strip())
    if parsed is None:
        return None, ("not a Fuel model or model file URL (Gazebo 11 reads http and https "
                      "URIs from its Fuel cache alone)")
    host, owner, name, version, path = parsed
    inner = os.path.normpath(path or ".")
    if inner.startswith(os.pardir) or os.path.isabs(inner):
        return None, "its file path leaves the model's folder"
    for root in cache_roots(environ):
        model = cached_model(root, host, owner, name, version)
        if model is not None and os.path.lexists(os.path.join(model, inner)):
            return os.path.normpath(os.path.join(model, inner)), ""
    return find(os.path.normpath(os.path.join(name, inner))), ""


def searched_line(environ, model_path: str) -> str:
    """Where Fuel URLs were searched, one line (``model_path``: the model path described)."""
    return ("Fuel URLs searched the Fuel cache (%s), then model://NAME on %s; nothing is "
            "downloaded (ign fuel download -u URL fills the cache)"
            % (":".join(cache_roots(environ)) or "no HOME", model_path))
