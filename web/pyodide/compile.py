"""Compile the Python sources of wheels (and of the standard library's zip) to bytecode; run inside Pyodide by
compile.mjs, so that the bytecode is exactly what Pyodide's Python 3.12 reads. See web/pyodide_site.py."""

import base64
import hashlib
import json
import os
import py_compile
import sys
import zipfile

HOST = "/host"
TMP = "/tmp/compile"
CACHE_TAG = sys.implementation.cache_tag


def bytecode(source, filename):
    """The unchecked-hash .pyc of ``source`` (bytes), or None when it does not compile (a template, Python 2)."""
    with open(TMP + ".py", "wb") as f:
        f.write(source)
    try:
        py_compile.compile(TMP + ".py", cfile=TMP + ".pyc", dfile=filename, doraise=True,
                           invalidation_mode=py_compile.PycInvalidationMode.UNCHECKED_HASH)
    except py_compile.PyCompileError:
        return None
    with open(TMP + ".pyc", "rb") as f:
        return f.read()


def record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def compile_zip(src, dst, mode, prefix):
    """Write ``dst``: ``src`` with each .py compiled — in its place (``replace``) or in __pycache__ (``beside``)."""
    entries, record = [], None
    with zipfile.ZipFile(src) as z:
        for info in z.infolist():
            data = z.read(info)
            if info.filename.endswith(".dist-info/RECORD"):
                record = info
                continue
            pyc = bytecode(data, prefix + info.filename) if info.filename.endswith(".py") else None
            if pyc is None or mode == "beside":
                entries.append((info, data))
            if pyc is not None:
                folder, base = os.path.split(info.filename[:-3])
                name = (info.filename[:-3] + ".pyc" if mode == "replace" else
                        (folder + "/" if folder else "") + f"__pycache__/{base}.{CACHE_TAG}.pyc")
                entries.append((zipfile.ZipInfo(name, info.date_time), pyc))
    if record is not None:  # the wheel's list of files, for the files it now holds
        lines = [record_line(i.filename, d) for i, d in entries] + [f"{record.filename},,"]
        entries.append((record, ("\n".join(lines) + "\n").encode()))
    with zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as z:
        for info, data in entries:
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, data)


def main(jobs):
    with open(jobs) as f:
        jobs = json.load(f)
    for job in jobs:
        compile_zip(HOST + job["src"], HOST + job["dst"], job["mode"], job["prefix"])
