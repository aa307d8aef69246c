"""Students' versions of source notebooks (``kinbook release`` and ``kinbook variant``)."""

from __future__ import annotations

import json
import os
from pathlib import Path

from ...core.atomic import refuse_overwrite, write_all
from ...errors import GradingError
from ..files import PUBLIC_DIR, PUBLIC_FILE, atomic_write
from ..ids import id_key
from ..notebook import load_source, locked_checksums, student_notebook
from ..variant import check_student_id, references, student_parameters

__all__ = ["release", "write_variant", "write_variants", "write_notebook"]


def _text(nb):
    import nbformat  # optional dependency: nbformat (the grading extra)

    return nbformat.writes(nb) + "\n"


def write_notebook(nb, path):
    """Write a notebook atomically (:func:`kinbook.classroom.files.atomic_write`), readable by everyone (0644;
    the directories it creates 0755), like nbgrader's releases."""
    return atomic_write(path, _text(nb), mode=PUBLIC_FILE, dir_mode=PUBLIC_DIR)


def release(sources, outdir="release"):
    """Write the student version of each source notebook into ``outdir``.

    Solutions become ``# YOUR CODE HERE`` / ``raise NotImplementedError()``, hidden checks are removed,
    locked cells are marked read-only and their checksums recorded in the notebook's metadata and in
    ``outdir/manifest.json`` (the grader recomputes them from the source: the manifest is for the record).
    Parameters keep their defaults; use :func:`write_variant` for per-student versions.

    Every source is read and checked (its cells compile, its own code runs, :func:`references`) before anything
    is written, and the notebooks and the manifest are written all or none; a release that would write over one of
    its sources is refused (:class:`~kinbook.errors.OverwriteError`, naming both).

    Returns
    -------
    list of Path
        The notebooks written.
    """

    if isinstance(sources, (str, os.PathLike)):
        sources = [sources]
    outdir = Path(outdir)
    manifest_path = outdir / "manifest.json"
    try:
        manifest = json.loads(manifest_path.read_text(encoding="utf-8")) if manifest_path.exists() else {}
    except (OSError, ValueError) as exc:
        raise GradingError(f"the release's manifest {str(manifest_path)!r} cannot be read ({exc}): move it away and "
                           "release again") from None
    if not isinstance(manifest, dict):
        raise GradingError(f"the release's manifest {str(manifest_path)!r} is not kinbook's: move it away")
    files, inputs = [], []
    for src in sources:
        source = load_source(src)
        parts = references(source)  # fails early on an exercise that cannot be graded
        nb = student_notebook(source)
        inputs.append(("the source", source.path))
        files.append((outdir / f"{source.exercise}.ipynb", _text(nb)))
        manifest[source.exercise] = {
            "locked": locked_checksums(nb),
            "parts": [{"part": p.name, "points": p.points, "answer": p.answer, "check": p.check,
                       "hidden": p.hidden} for p in parts],
        }
    files.append((manifest_path, json.dumps(manifest, indent=1, sort_keys=True)))
    refuse_overwrite([p for p, _ in files], inputs, "release")
    return write_all(files, mode=PUBLIC_FILE, dir_mode=PUBLIC_DIR)[:-1]


def write_variant(source, student, outdir="."):
    """Write ``student``'s own version of ``source`` as ``outdir/<exercise>-<student>.ipynb``; ``student`` must be
    a student id (:func:`~kinbook.classroom.ids.check_id`)."""
    return write_variants(source, [student], outdir)[0]


def write_variants(source, students, outdir="."):
    """Write every student's own version of ``source`` into ``outdir`` (``<exercise>-<student>.ipynb``), in one
    process: the source is read and compiled once (``kinbook variant --roster``; benchmarks/variants.py).

    All or none: every id is checked (the one rule, :mod:`kinbook.classroom.ids`; two ids that are one student under
    its key are refused), every variant is made, and only then are the files written, together
    (:func:`kinbook.core.atomic.write_all`)."""
    source = load_source(source)
    ids, seen = [], {}
    for s in students:
        sid = check_student_id(s)
        if id_key(sid) in seen:
            raise GradingError(f"the students {seen[id_key(sid)]!r} and {sid!r} are one student under the id rule "
                               "(case and Unicode forms): their variants would be one file; nothing was written")
        seen[id_key(sid)] = sid
        ids.append(sid)
    files = [(Path(outdir) / f"{source.exercise}-{sid}.ipynb",
              _text(student_notebook(source, student_parameters(source, sid), sid))) for sid in ids]
    refuse_overwrite([p for p, _ in files], [("the source", source.path)], "variant")
    return write_all(files, mode=PUBLIC_FILE, dir_mode=PUBLIC_DIR)
