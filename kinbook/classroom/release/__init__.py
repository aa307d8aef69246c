"""Students' versions of source notebooks (``kinbook release`` and ``kinbook variant``)."""

from __future__ import annotations

import json
import os
from pathlib import Path

from ...errors import GradingError
from ..files import PUBLIC_DIR, PUBLIC_FILE, atomic_write
from ..notebook import load_source, locked_checksums, student_notebook
from ..variant import check_student_id, references, student_parameters

__all__ = ["release", "write_variant", "write_variants", "write_notebook"]


def write_notebook(nb, path):
    """Write a notebook atomically (:func:`kinbook.classroom.files.atomic_write`), readable by everyone (0644;
    the directories it creates 0755), like nbgrader's releases."""
    import nbformat

    return atomic_write(path, nbformat.writes(nb) + "\n", mode=PUBLIC_FILE, dir_mode=PUBLIC_DIR)


def release(sources, outdir="release"):
    """Write the student version of each source notebook into ``outdir``.

    Solutions become ``# YOUR CODE HERE`` / ``raise NotImplementedError()``, hidden checks are removed,
    locked cells are marked read-only and their checksums recorded in the notebook's metadata and in
    ``outdir/manifest.json`` (the grader recomputes them from the source: the manifest is for the record).
    Parameters keep their defaults; use :func:`write_variant` for per-student versions.

    Returns
    -------
    list of Path
        The notebooks written.
    """

    if isinstance(sources, (str, os.PathLike)):
        sources = [sources]
    outdir = Path(outdir)
    manifest_path = outdir / "manifest.json"
    manifest = json.loads(manifest_path.read_text()) if manifest_path.exists() else {}
    written = []
    for src in sources:
        source = load_source(src)
        parts = references(source)  # fails early on an exercise that cannot be graded
        nb = student_notebook(source)
        if Path(src).resolve() == (outdir / f"{source.exercise}.ipynb").resolve():
            raise GradingError(f"release would overwrite its source {src!r}: choose another -o directory")
        written.append(write_notebook(nb, outdir / f"{source.exercise}.ipynb"))
        manifest[source.exercise] = {
            "locked": locked_checksums(nb),
            "parts": [{"part": p.name, "points": p.points, "answer": p.answer, "check": p.check,
                       "hidden": p.hidden} for p in parts],
        }
    atomic_write(manifest_path, json.dumps(manifest, indent=1, sort_keys=True), mode=PUBLIC_FILE, dir_mode=PUBLIC_DIR)
    return written


def write_variant(source, student, outdir="."):
    """Write ``student``'s own version of ``source`` as ``outdir/<exercise>-<student>.ipynb``; ``student`` must be
    a safe file name (:func:`~kinbook.classroom.variant.check_student_id`)."""
    check_student_id(student)
    source = load_source(source)
    values = student_parameters(source, student)
    return write_notebook(student_notebook(source, values, student), Path(outdir) / f"{source.exercise}-{student}.ipynb")


def write_variants(source, students, outdir="."):
    """Write every student's own version of ``source`` into ``outdir`` (``<exercise>-<student>.ipynb``), in one
    process: the source is read and compiled once (``kinbook variant --roster``; benchmarks/variants.py)."""
    source = load_source(source)
    return [write_variant(source, s, outdir) for s in students]
