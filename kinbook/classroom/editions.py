"""The editions of an exercise: which source a submission was released from, and grading it under the current one.

An instructor edits a source after releasing it — a part's points, a check, a typo in a locked cell. The students'
notebooks still hold the locked cells of the release they got. Checked against the *current* release, every one of
them would be ``tampered``. Instead, a submission is checked against the release its student got: the current
source's first, then each earlier source the gradebook graded with (``Gradebook.sources``) or the instructor named
(``--released-from``). The first whose locked code cells the submission holds, unchanged and in order, is the
student's edition (:func:`edition_of`). Its locked cells are then replaced by the current release's
(:func:`carry_over`), as nbgrader's autograde overwrites them from the source: the student's answer cells and
cells of their own stay where they were, and every part — its points, its checks — is graded under the current
source.

A submission that matches no edition is ``tampered``, and its message quotes the edition closest to it, never a
cell of an edit the student cannot have seen. When most of a class matches none (:func:`class_would_be_tampered`),
the source changed since the release and nothing is graded: the message names the source's cells that changed
(:func:`edited_cells`), in the source, not in the students' notebooks.

Whose release a notebook is comes first (:func:`released_for`): a notebook released for another student is
``wrong-release`` (a copying signal for the instructor), never matched against editions.
"""

from __future__ import annotations

import difflib

from .notebook import checksum, find_parameters, load_source, missing_locked, parse_submission, student_notebook
from .release_kind import released_for  # whose release a notebook is: one rule (kinbook.classroom.release_kind)
from .results import Refused
from .sanitize import clean

__all__ = ["Edition", "editions", "edition_of", "carry_over", "edited_cells", "class_would_be_tampered",
           "earlier_sources", "released_for"]


class Edition:
    """The notebook one student got from one source: its cells and its locked cells.

    Attributes
    ----------
    source : Source
    nb : nbformat.NotebookNode
        The release (``student_notebook``).
    current : bool
        Made from the source being graded with.
    """

    def __init__(self, source, values, student, current):
        self.source, self.current = source, current
        self.nb = student_notebook(source, values, student if values is not None else None)
        self.locked = [c for c in self.nb.cells if c.get("metadata", {}).get("kinbook", {}).get("locked")]
        self.code_locked = [c for c in self.locked if c.cell_type == "code"]

    def missing_code(self, cells):
        """Ids of this edition's locked code cells that ``cells`` do not hold unchanged and in order."""
        return missing_locked([(c["id"], checksum(c)) for c in self.code_locked], cells)

    def missing_text(self, cells):
        return missing_locked([(c["id"], checksum(c)) for c in self.locked if c.cell_type != "code"], cells)

    def position(self, cell_id):
        """The position (from 1) of a cell in this release, as the student saw it."""
        return next(i for i, c in enumerate(self.nb.cells, 1) if c["id"] == cell_id)

    def cell_name(self, cell):
        """A cell of this release as the student saw it: "cell 6 “part("revolute_OA", …”"."""
        first = next((line.strip() for line in cell.source.splitlines() if line.strip()), "")
        return f"cell {self.position(cell['id'])}" + (f" “{clean(first, 60)}”" if first else "")


def editions(source, earlier, values, student):
    """The editions a submission may come from: the current source's, then each of ``earlier`` (other sources of
    the same exercise, most recent first)."""
    out = [Edition(source, values, student, True)]
    out += [Edition(s, values, student, False) for s in earlier if s.sha256 != source.sha256]
    return out


def edition_of(cells, candidates):
    """``(edition, missing)``: the first edition whose locked code cells ``cells`` hold (``missing`` empty), else the
    one with the fewest missing (to name what is missing in the release the student most likely got)."""
    best = None
    for e in candidates:
        missing = e.missing_code(cells)
        if not missing:
            return e, []
        if best is None or len(missing) < len(best[1]):
            best = (e, missing)
    return best


def _matched(cells, locked):
    """{index in ``cells``: index in ``locked``} of the locked cells found in ``cells``, in order (by checksum)."""
    sums = [checksum(c) for c in cells]
    out, at = {}, 0
    for k, c in enumerate(locked):
        try:
            i = sums.index(checksum(c), at)
        except ValueError:
            continue
        out[i], at = k, i + 1
    return out


def carry_over(cells, old, new):
    """The submission's ``cells`` with the locked cells of edition ``old`` replaced by edition ``new``'s.

    The two releases are aligned cell by cell (by checksum, :class:`difflib.SequenceMatcher`; a cell edited in
    place pairs with its new text); each of the student's own cells — answer cells, cells they added, locked text
    they edited — stays after the locked cell it followed. A locked cell the new source removed goes; one it added
    comes in its place in the new release's order.

    Returns
    -------
    list of dict
        Cells as :func:`~kinbook.classroom.notebook.parse_submission` gives them.
    """
    if old is new:
        return cells
    a = [checksum(c) for c in old.nb.cells]
    b = [checksum(c) for c in new.nb.cells]
    pair = {}  # index of a locked cell in old.nb → index in new.nb
    for tag, i1, i2, j1, j2 in difflib.SequenceMatcher(None, a, b, autojunk=False).get_opcodes():
        if tag == "equal" or (tag == "replace" and i2 - i1 == j2 - j1):
            pair.update(zip(range(i1, i2), range(j1, j2)))
    old_locked = [i for i, c in enumerate(old.nb.cells) if c in old.locked]
    found = {i: old_locked[k] for i, k in _matched(cells, old.locked).items()}  # cell → old.nb index
    anchored = {}  # new.nb index (or -1: the top) → the student's cells that follow it
    anchor = -1
    for i, c in enumerate(cells):
        if i in found:
            j = pair.get(found[i])
            if j is not None and new.nb.cells[j] in new.locked:
                anchor = j
            continue
        anchored.setdefault(anchor, []).append(c)
    out = list(anchored.get(-1, []))
    for j, c in enumerate(new.nb.cells):
        if c in new.locked:
            out.append({"cell_type": c.cell_type, "source": c.source, "id": c["id"]})
        out += anchored.get(j, [])
    return out


def edited_cells(current, missing_ids):
    """The cells of ``current``'s source (an :class:`Edition`) whose released text is not in the students'
    notebooks (``missing_ids``: release cell ids, most common first), as "cell 12 (“part("whole_phi", 5, …”)" —
    numbered as in the source notebook, the instructor's file."""
    out = []
    by_id = {c["id"]: i for i, c in enumerate(current.source.nb.cells, 1)}
    for cid in missing_ids:
        c = next(c for c in current.nb.cells if c["id"] == cid)
        first = next((line.strip() for line in c.source.splitlines() if line.strip()), "")
        out.append(f"cell {by_id.get(cid, '?')} (“{clean(first, 60)}”)")
    return out


def class_would_be_tampered(source, submissions, earlier, per_student):
    """The sentence that stops a run when most ``submissions`` ((student, bytes), at least 2) hold the locked cells of
    no edition of ``source`` (``earlier``: the other sources), else None. The students' own parameters cells are
    left out (drawing them costs the instructor's code per student); notebooks that are not readable or are another
    student's release are the grader's to report."""
    checks = []
    for student, data in submissions:
        try:
            cells, meta = parse_submission(data, metadata=True)
        except Refused:
            continue
        if released_for(meta, cells, student, per_student)[0]:
            continue
        candidates = editions(source, earlier, None, student)
        params = {e.source.nb.cells[find_parameters(e.source.nb)[0]]["id"] for e in candidates} if per_student else ()
        misses = [[m for m in e.missing_code(cells) if m not in params] for e in candidates]
        checks.append(misses[0] if all(misses) else [])
    tampered = [m for m in checks if m]
    if len(tampered) < 2 or 2 * len(tampered) <= len(checks):
        return None
    counts = {}
    for missing in tampered:
        for cid in missing:
            counts[cid] = counts.get(cid, 0) + 1
    common = sorted(counts, key=lambda c: -counts[c])
    named = [c for c in common if counts[c] * 2 > len(tampered)] or common[:1]
    cells = edited_cells(Edition(source, None, None, True), named[:3])
    return (f"{len(tampered)} of {len(checks)} submissions do not hold the locked cells of {source.path} as it is "
            f"now — its {', '.join(cells)} {'differs' if len(cells) == 1 else 'differ'} from the notebook the "
            "students were given: the source was edited after its release. Nothing was graded. Give the source the "
            "notebooks were released from with --released-from FILE (kinbook then grades every submission under the "
            "edited source, each checked against the release its student got), or undo the edit.")

def earlier_sources(book, source, released_from=()):
    """The other sources a submission of ``source``'s exercise may have been released from: the files
    ``released_from`` (``--released-from``, under any name), then every source the gradebook ``book`` kept, most
    recent first; all of them kept in the gradebook from now on."""
    earlier = []
    for path in released_from or ():
        old = load_source(path)
        old.exercise = source.exercise  # a copy of the earlier source, under any name
        earlier.append(old)
    seen = {source.sha256} | {e.sha256 for e in earlier}
    earlier += [e for e in book.sources(source.exercise) if e.sha256 not in seen]
    for old in earlier:
        book.keep_source(old)
    return earlier
