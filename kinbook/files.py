"""Mechanism files (TOML): bodies, points, constraints and drivers. The format is documented in
docs/mechanism-files.md.

A file names its kind (``kind = "planar"`` by default, or ``"spatial"``); each ``[[constraints]]`` table has a
``type`` (a constraint type registered in the kind's chapter, :func:`kinbook.core.registry.constraint_types`) and the keyword arguments of that constraint's class.
"""

from __future__ import annotations

import contextlib
import functools
import gc
import importlib
import inspect
import os
import stat
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

from .core.mechanism import MAX_BODIES
from .core.registry import constraint_class
from .errors import KinbookError, MechanismFileError

__all__ = ["load", "loads"]

_KINDS = {"planar": "kinbook.planar", "spatial": "kinbook.spatial"}


MAX_FILE_BYTES = 16 * 2**20
"""Largest mechanism file :func:`load` reads (16 MiB: some 60,000 bodies)."""


_META = {"name", "title", "source", "kind"}
_BODY_NAMES = {"i", "j", "k", "body"}  # keys of a constraint that name a body


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
        The file is missing, unreadable, larger than :data:`MAX_FILE_BYTES`, not UTF-8, not valid TOML, or
        describes something kinbook cannot build; the message names the file and the key.
    """
    try:
        path = Path(os.fspath(path))
    except TypeError:
        raise MechanismFileError(f"expected the path of a mechanism file, got {type(path).__name__}") from None
    try:
        # opened without blocking and checked before reading: a FIFO would wait for a writer forever, a device
        # (/dev/zero) never end
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0))
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            os.close(fd)
            kind = ("a directory" if stat.S_ISDIR(mode) else "a FIFO (named pipe)" if stat.S_ISFIFO(mode)
                    else "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else "a socket"
                    if stat.S_ISSOCK(mode) else "something else")
            raise MechanismFileError(f"{path}: cannot read the mechanism file: it is {kind}, not a regular file")
        with os.fdopen(fd, "rb") as fh:
            raw = fh.read(MAX_FILE_BYTES + 1)
    except MechanismFileError:
        raise
    except OSError as exc:
        raise MechanismFileError(f"{path}: cannot read the mechanism file ({exc.strerror or exc})") from None
    except ValueError as exc:  # a path with a NUL byte
        raise MechanismFileError(f"{path!r}: not a usable file name ({exc})") from None
    if len(raw) > MAX_FILE_BYTES:
        raise MechanismFileError(f"{path}: the mechanism file is larger than {MAX_FILE_BYTES // 2**20} MiB")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise MechanismFileError(f"{path}: not UTF-8 text (byte {exc.start} is 0x{raw[exc.start]:02x}); "
                                 "save the file as UTF-8") from None
    return loads(text, source=str(path))


def loads(text, source="<string>"):
    """Build a mechanism from the text of a mechanism file (see :func:`load`)."""
    source = str(source)
    if not isinstance(text, str):
        raise MechanismFileError(f"{source}: expected the text of a mechanism file, got {type(text).__name__}")
    if len(text) > MAX_FILE_BYTES:
        raise MechanismFileError(f"{source}: the mechanism file is larger than {MAX_FILE_BYTES // 2**20} MiB")
    try:
        with _no_gc():
            data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise MechanismFileError(f"{source}: not valid TOML: {exc}") from None
    except RecursionError:  # arrays nested thousands deep
        raise MechanismFileError(f"{source}: not valid TOML: nested too deeply") from None
    return build(data, source)


def _table(value, where, source):
    if not isinstance(value, dict):
        raise MechanismFileError(f"{source}: `{where}` must be a table, got {type(value).__name__}")
    return value


def _text(value, where, source, default=None):
    if value is None:
        return default
    if not isinstance(value, str):
        raise MechanismFileError(f"{source}: `{where}` must be a string, got {type(value).__name__} {value!r:.60}")
    return value


def _array_of_tables(value, where, source, required):
    if value is None or (isinstance(value, list) and not value):
        if required:
            raise MechanismFileError(f"{source}: needs at least one [[{where}]] table")
        return []
    if not isinstance(value, list):
        raise MechanismFileError(f"{source}: `{where}` must be an array of tables ([[{where}]]), got "
                                 f"{type(value).__name__}")
    most = MAX_BODIES if where == "bodies" else 4 * MAX_BODIES
    if len(value) > most:
        raise MechanismFileError(f"{source}: {len(value)} [[{where}]] tables, more than the {most} kinbook reads")
    return value


@contextlib.contextmanager
def _no_gc():
    """Python's cyclic garbage collector rescans every live object at each full collection: parsing and building
    tens of thousands of bodies then costs time growing with their square. Nothing made here is garbage."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def build(data, source="<data>"):
    """Build a mechanism from the parsed contents of a mechanism file (a dict)."""
    with _no_gc():
        return _build(data, source)


def _build(data, source):
    source = str(source)
    data = _table(data, "the file", source)
    meta = _table(data.get("mechanism", {}), "mechanism", source)
    unknown = set(data) - {"mechanism", "bodies", "constraints"}
    if unknown:
        raise MechanismFileError(f"{source}: unknown top-level key(s) {', '.join(sorted(unknown))} "
                                 "(expected: mechanism, bodies, constraints)")
    unknown = sorted(set(meta) - _META)
    if unknown:
        raise MechanismFileError(f"{source}: unknown key 'mechanism.{unknown[0]}' (accepted keys: "
                                 f"{', '.join(sorted(_META))})")
    kind = _text(meta.get("kind"), "mechanism.kind", source, "planar")
    if kind not in _KINDS:
        raise MechanismFileError(f"{source}: `mechanism.kind` must be one of {', '.join(_KINDS)}, got {kind!r}")
    try:
        module = importlib.import_module(_KINDS[kind])
    except ModuleNotFoundError:
        raise MechanismFileError(f"{source}: {kind} mechanisms are not available in this version") from None
    default_name = Path(source).stem if source.endswith(".toml") else "mechanism"
    name = _text(meta.get("name"), "mechanism.name", source, default_name)
    mech = module.Mechanism(name, title=_text(meta.get("title"), "mechanism.title", source))
    mech.source = _text(meta.get("source"), "mechanism.source", source)

    bodies = _array_of_tables(data.get("bodies"), "bodies", source, required=True)
    add_body = _parameters(type(mech).add_body)
    for k, body in enumerate(bodies):
        label = body.get("name") if isinstance(body, dict) else None
        where = f"bodies[{k}]" + (f" ('{label}')" if isinstance(label, str) else "")
        body = _table(body, where, source)
        _check_keys(body, add_body, where, source, skip=("self",))
        if not isinstance(body["name"], str):
            raise MechanismFileError(f"{source}: {where}: `name` must be a string, got "
                                     f"{type(body['name']).__name__} {body['name']!r:.60}")
        try:
            mech.add_body(**body)
        except KinbookError as exc:
            raise MechanismFileError(f"{source}: {where}: {exc}") from None

    for k, spec in enumerate(_array_of_tables(data.get("constraints"), "constraints", source, required=False)):
        where = f"constraints[{k}]"
        spec = dict(_table(spec, where, source))
        ctype = spec.pop("type", None)
        if not isinstance(ctype, str):
            raise MechanismFileError(f"{source}: {where}: `type` must be the name of a constraint type, got "
                                     f"{type(ctype).__name__} {ctype!r}")
        try:
            cls = constraint_class(kind, ctype, files=True)
        except KinbookError as exc:
            raise MechanismFileError(f"{source}: {where}: {exc}") from None
        where += f" (type '{ctype}')"
        _check_keys(spec, _parameters(cls.__init__), where, source, skip=("self",))
        for key in sorted(_BODY_NAMES.intersection(spec)) + (["name"] if "name" in spec else []):
            if not isinstance(spec[key], str):
                what = "a body name" if key in _BODY_NAMES else "a name"
                raise MechanismFileError(f"{source}: {where}: `{key}` must be a string ({what}), got "
                                         f"{type(spec[key]).__name__} {spec[key]!r:.60}")
        try:
            mech.add(cls(**spec))
        except KinbookError as exc:
            raise MechanismFileError(f"{source}: {where}: {exc}") from None
    try:
        mech.validate()
    except KinbookError as exc:
        raise MechanismFileError(f"{source}: {exc}") from None
    return mech


@functools.lru_cache(maxsize=None)
def _parameters(function):
    return inspect.signature(function).parameters


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
