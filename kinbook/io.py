"""Mechanism files (TOML): bodies, points, constraints and drivers. The format is documented in
docs/mechanism-files.md.

A file names its kind (``kind = "planar"`` by default, or ``"spatial"``); each ``[[constraints]]`` table has a
``type`` (a constraint type registered in the kind's chapter, :func:`kinbook.model.constraint_types`) and the keyword arguments of that constraint's class.
"""

from __future__ import annotations

import importlib
import inspect
import os
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

from .errors import KinbookError, MechanismFileError
from .model import constraint_class

__all__ = ["load", "loads"]

_KINDS = {"planar": "kinbook.planar", "spatial": "kinbook.spatial"}


def load(path):
    """Read a mechanism file.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    Mechanism
        A :class:`kinbook.planar.Mechanism` (or spatial mechanism when the file says ``kind = "spatial"``).

    Raises
    ------
    MechanismFileError
        The file is missing, is not valid TOML, or describes something kinbook cannot build; the message names
        the file and the key.
    """
    path = Path(os.fspath(path))
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise MechanismFileError(f"{path}: cannot read the mechanism file ({exc.strerror})") from None
    return loads(text, source=str(path))


def loads(text, source="<string>"):
    """Build a mechanism from the text of a mechanism file (see :func:`load`)."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise MechanismFileError(f"{source}: not valid TOML: {exc}") from None
    return build(data, source)


def _table(value, where, source):
    if not isinstance(value, dict):
        raise MechanismFileError(f"{source}: `{where}` must be a table, got {type(value).__name__}")
    return value


def build(data, source="<data>"):
    """Build a mechanism from the parsed contents of a mechanism file (a dict)."""
    meta = _table(data.get("mechanism", {}), "mechanism", source)
    unknown = set(data) - {"mechanism", "bodies", "constraints"}
    if unknown:
        raise MechanismFileError(f"{source}: unknown top-level key(s) {', '.join(sorted(unknown))} "
                                 "(expected: mechanism, bodies, constraints)")
    kind = meta.get("kind", "planar")
    if kind not in _KINDS:
        raise MechanismFileError(f"{source}: `mechanism.kind` must be one of {', '.join(_KINDS)}, got {kind!r}")
    try:
        module = importlib.import_module(_KINDS[kind])
    except ModuleNotFoundError:
        raise MechanismFileError(f"{source}: {kind} mechanisms are not available in this version") from None
    name = meta.get("name", Path(source).stem if source.endswith(".toml") else "mechanism")
    mech = module.Mechanism(name, title=meta.get("title"))
    mech.source = meta.get("source")

    bodies = data.get("bodies")
    if not isinstance(bodies, list) or not bodies:
        raise MechanismFileError(f"{source}: needs at least one [[bodies]] table")
    add_body = inspect.signature(mech.add_body).parameters
    for k, body in enumerate(bodies):
        where = f"bodies[{k}]" + (f" ('{body.get('name')}')" if isinstance(body, dict) and "name" in body else "")
        body = _table(body, where, source)
        _check_keys(body, add_body, where, source, skip=())
        try:
            mech.add_body(**body)
        except KinbookError as exc:
            raise MechanismFileError(f"{source}: {where}: {exc}") from None

    for k, spec in enumerate(data.get("constraints", [])):
        where = f"constraints[{k}]"
        spec = dict(_table(spec, where, source))
        ctype = spec.pop("type", None)
        try:
            cls = constraint_class(kind, ctype, files=True)
        except KinbookError as exc:
            raise MechanismFileError(f"{source}: {where}: {exc}") from None
        where += f" (type '{ctype}')"
        _check_keys(spec, inspect.signature(cls.__init__).parameters, where, source, skip=("self",))
        try:
            mech.add(cls(**spec))
        except KinbookError as exc:
            raise MechanismFileError(f"{source}: {where}: {exc}") from None
    return mech


def _check_keys(table, params, where, source, skip):
    accepted = [p for p in params if p not in skip]
    unknown = [k for k in table if k not in params or k in skip]
    if unknown:
        raise MechanismFileError(
            f"{source}: {where}: unknown key '{unknown[0]}' (accepted keys: {', '.join(accepted)})"
        )
    missing = [p for p, v in params.items()
               if p not in skip and v.default is inspect.Parameter.empty and p not in table]
    if missing:
        raise MechanismFileError(f"{source}: {where}: missing key '{missing[0]}'")
