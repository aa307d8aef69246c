"""Numeric answers — read, tolerances, compare entry by entry, name the slip: the primitives under the numeric
checkers (:func:`~kinbook.grading.values.check_value`, :func:`~kinbook.grading.rotation_values.check_rotation`,
:func:`~kinbook.grading.rotation_values.check_euler_parameters`, :func:`~kinbook.grading.newton.check_iterates`).

* the checkers' options: :func:`real_option`, :func:`tolerances`, :func:`periodic_mask`, :func:`name_option`,
  :func:`angles_option`, :func:`reveal_option`;
* the answer and the reference: :func:`read_numbers` (real numbers only, texts through kinbook's reader),
  :func:`expected_of` (an :class:`~kinbook.grading.expected.Expected`, copied);
* the verdict: :func:`close`, :func:`compare` (the whole comparison and diagnosis: the Expected's named mistakes
  first, then degrees for radians, a transposed matrix, the sign, a plausible factor, exchanged entries …) and
  :func:`failed`.

``reveal=False`` (the notebooks' try-its) keeps the reference value out of the feedback: a wrong answer is told
which entries are off and how — the sign, too large or too small, the length or the direction of a vector — and
the mistake's name, never the number it should have been.
"""

from __future__ import annotations

import numbers

import numpy as np

from ..core.reader import read_number
from ..errors import ExpressionError, InputError
from ..i18n import N_, Message, Np_
from ._i18n import Msg, add_texts
from .expected import DEG, Expected
from .read import Refused, numbers_of
from .report import PRINTED, CheckResult, RowResult, fmt, hints

__all__ = ["PLAUSIBLE_FACTORS", "real_option", "tolerances", "periodic_mask", "name_option", "angles_option", "reveal_option",
           "read_numbers", "expected_of", "close", "compare", "failed"]

PLAUSIBLE_FACTORS = (2.0, 0.5, -2.0, -0.5, np.pi, 1 / np.pi, 2 * np.pi, 1 / (2 * np.pi), np.pi / 180, 3.0, 1 / 3, 1000.0,
              1e-3)
"""Factors a slip can put on a whole answer (a forgotten 2, π, a unit); "multiplied by c" only for these."""
_MAX_RTOL = 0.1

add_texts({
    "v.off_head": Np_("wrong: {n} of {total} entries is off — {entries}",
                      "wrong: {n} of {total} entries are off — {entries}"),
    "v.off_scalar": N_("wrong: your value {how}"),
    "v.off_count": N_("wrong: {k} of {n} entries are off (the table says how)"),
    "v.entry_how": N_("{where} {how}"),
    "v.more": N_("and {k} more"),
    "v.too_large": N_("is too large"),
    "v.too_small": N_("is too small"),
    "v.far_too_large": N_("is far too large (more than 10 times)"),
    "v.far_too_small": N_("is far too small (less than a tenth)"),
    "v.too_large_abs": N_("is too large in magnitude"),
    "v.is_zero": N_("is zero and should not be"),
    "v.wrong_sign": N_("has the wrong sign (its size is right)"),
    "v.wrong_sign_size": N_("has the wrong sign, and its size is off too"),
    "v.angle_high": N_("is too large (compared modulo 360°)"),
    "v.angle_low": N_("is too small (compared modulo 360°)"),
    "v.length_right": N_("the length of your vector is right; its direction is not"),
    "v.direction_right": N_("your vector points the right way; its length is not right"),
    "v.got_type": N_("{what}: expected real numbers (a number, a list or an array), got {type}"),
    "v.scaled_units": N_("your answer is the expected one multiplied by {c} (a unit conversion: m and mm?)"),
    "v.scaled_step": N_("your answer is off by one constant factor throughout: {step}"),
    "v.step_units": N_("check the units of each length (m and mm?)"),
    "v.step_angle": N_("check the step where an angle is put in radians (from degrees, turns or a fraction of a turn)"),
    "v.step_factor": N_("check each constant factor of the formula you used (a number in it, a diameter for a radius)"),
    "v.of_type": N_("an object of type {type}"),
    "v.container_of": N_("a {type} of {inner}"),
    "v.empty_container": N_("an empty {type}"),
})


# ================================================================================================ options
def real_option(value, arg, *, low=None, high=None, positive=False):
    """A finite real option as a float, or InputError naming the argument."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.floating, np.integer)):
        raise InputError(f"`{arg}` must be a real number, got {value!r}")
    x = float(value)
    if not np.isfinite(x):
        raise InputError(f"`{arg}` must be finite, got {value!r}")
    if (low is not None and x < low) or (high is not None and x > high) or (positive and x <= 0):
        bound = f"in [{low:g}, {high:g}]" if high is not None else ("> 0" if positive else f"≥ {low:g}")
        raise InputError(f"`{arg}` must be {bound}, got {value!r}")
    return x


def tolerances(rtol, atol, e):
    """Validated (rtol, atol). A tolerance that would pass a wrong answer (rtol > 0.1, atol as large as a
    tenth of the reference) or fail a right one (negative) is refused."""
    rtol = real_option(rtol, "rtol", low=0.0, high=_MAX_RTOL)
    atol = real_option(atol, "atol", low=0.0)
    scale = float(np.max(np.abs(e), initial=0.0))
    if scale > 0 and atol >= 0.1 * scale:
        raise InputError(f"`atol` = {atol:g} would accept wrong answers: the reference's largest entry is "
                         f"{scale:.6g}; use at most a tenth of it (or rtol)")
    if scale == 0 and atol > 1e-3:
        raise InputError(f"`atol` = {atol:g} would accept wrong answers: the reference is zero; use at most 1e-3")
    return rtol, atol


def periodic_mask(periodic, shape):
    """`periodic` (flat 0-based indices of angles, or a boolean mask of the value's shape) as a mask."""
    size = int(np.prod(shape)) if shape else 1
    if periodic is None:
        return np.zeros(shape, bool)
    if isinstance(periodic, (bool, np.bool_)):
        return np.full(shape, bool(periodic))
    if isinstance(periodic, (numbers.Integral, np.integer)):
        periodic = (periodic,)
    try:
        arr = np.asarray(periodic)
    except (TypeError, ValueError):
        raise InputError(f"`periodic` must be flat indices of the angles or a boolean mask, got {periodic!r}") \
            from None
    if arr.dtype.kind == "b":
        if arr.size != size:
            raise InputError(f"`periodic` as a mask must have {size} entries (the value's), got {arr.size}")
        return arr.reshape(shape)
    if arr.size == 0:
        return np.zeros(shape, bool)
    if arr.dtype.kind not in "iu" or arr.ndim != 1:
        raise InputError(f"`periodic` must be a list of flat indices (integers) or a boolean mask, got "
                         f"{periodic!r}")
    if arr.min() < 0 or arr.max() >= size:
        raise InputError(f"`periodic` index out of range for a value with {size} entries: {arr.tolist()}")
    mask = np.zeros(size, bool)
    mask[arr] = True
    return mask.reshape(shape)


def name_option(name, default):
    if name is None:
        return default
    if isinstance(name, str) or (isinstance(name, dict) and "en" in name and all(isinstance(v, str) for v in
                                                                                   name.values())):
        return name
    raise InputError(f"`name` must be a text (or {{'en': …, 'es': …}}), got {name!r}")


def angles_option(angles):
    if angles is not None and not isinstance(angles, (bool, np.bool_)):
        raise InputError(f"`angles` must be True, False or None, got {angles!r}")
    return angles is not False


def reveal_option(reveal):
    if not isinstance(reveal, (bool, np.bool_)):
        raise InputError(f"`reveal` must be True or False, got {reveal!r}")
    return bool(reveal)


# ================================================================================================ reading
def _fmt_array(a):
    """Numbers as they are shown: 6 significant digits, no round-off noise, nested brackets."""
    a = np.asarray(a, float)
    if a.ndim == 0 or a.size == 1:
        return fmt(a.ravel()[0])
    if a.ndim == 1:
        return "[" + ", ".join(fmt(x) for x in a) + "]"
    return "[" + ", ".join(_fmt_array(r) for r in a) + "]"


def close(a, b, rtol, atol, periodic=None):
    d = a - b
    if periodic is not None and periodic.any():
        d = np.where(periodic, (d + np.pi) % (2 * np.pi) - np.pi, d)
    return bool(np.all(np.abs(d) <= atol + rtol * np.max(np.abs(b), initial=0.0)))


def _texts(answer):
    """A text or a (nested) list of texts read as numbers through kinbook's reader ("pi/4", "-0.5"); None
    when the answer holds no text."""
    def walk(x, where):
        if isinstance(x, str):
            return read_number(x, where=Msg("answer_at", index=where))
        if isinstance(x, (list, tuple)):
            return [walk(v, f"{where}[{k + 1}]") for k, v in enumerate(x)]
        return x

    def has_text(x):
        return isinstance(x, str) or (isinstance(x, (list, tuple)) and any(has_text(v) for v in x))

    if isinstance(answer, np.ndarray) and answer.dtype.kind in "US":
        answer = answer.tolist()
    if not has_text(answer):
        return None
    return walk(answer, "")


def read_numbers(answer, name):
    """The answer as a float array of its own shape (refuses bools, complex values, objects; texts of numbers
    are read by kinbook's reader)."""
    try:
        parsed = _texts(answer)
    except ExpressionError as exc:
        return None, Refused("malformed", "reader", message=exc.message)
    except RecursionError:
        return None, Refused("malformed", "nested_deeper")
    if parsed is not None:
        answer = parsed
    try:
        arr = numbers_of(answer, Msg("answer"))
    except Refused as exc:
        if exc.key == "not_numbers":
            return None, Refused("malformed", "v.got_type", what=Msg("answer"), type=_got_type(answer))
        return None, exc
    try:
        raw = np.asarray(answer, dtype=float)
    except (TypeError, ValueError):  # a sympy matrix of numbers: as read
        raw = arr
    return (raw if raw.size == arr.size and raw.ndim <= 2 else arr), None


def _got_type(x):
    """What was received, for the student: "a list of dict, str" (written when shown)."""
    if isinstance(x, (list, tuple)):
        inner = sorted({type(v).__name__ for v in x})[:3]
        if not inner:
            return Msg("v.empty_container", type=type(x).__name__)
        return Msg("v.container_of", type=type(x).__name__, inner=", ".join(inner))
    return Msg("v.of_type", type=type(x).__name__)


def failed(name, msg, code):
    return CheckResult(False, 0.0, [msg], [code], (), name)


def expected_of(expected):
    """The expected value as an :class:`Expected` (a copy: checking never changes the caller's object); an
    :class:`InputError` naming the argument when it is not real finite numbers."""
    value = None
    if isinstance(expected, Expected):
        value = np.asarray(expected.value, dtype=float)
    elif not isinstance(expected, (bool, np.bool_)):
        try:
            value = np.asarray(expected, dtype=float)
        except (TypeError, ValueError):
            pass
    if value is None or value.size == 0 or not np.all(np.isfinite(value)):
        raise InputError(f"`expected` must be real finite numbers (computed with kinbook) or an "
                         f"kinbook.grading.expected.Expected, got {_got_type(expected).render('en')}")
    return expected.copy() if isinstance(expected, Expected) else Expected(value)


def _shape(a, e, name):
    """``a`` reshaped to ``e``'s shape when only singleton axes differ; (a, None) or (None, failed result)."""
    if a.shape == e.shape:
        return a, None
    if a.size == e.size and a.squeeze().shape == e.squeeze().shape:
        return a.reshape(e.shape), None
    if a.ndim == 2 and a.T.shape == e.shape:
        return a, "transposed"
    return None, failed(name, Msg("wrong_shape", expected=e.shape, got=a.shape), "wrong_shape")


def _indexed(name, idx):
    """"A[1, 2]" — in every language when the name is translated."""
    suffix = "[" + ", ".join(str(int(i) + 1) for i in idx) + "]" if len(idx) else ""
    if isinstance(name, Message):
        return Message(N_("{name}{index}"), name=name, index=suffix) if suffix else name
    if isinstance(name, dict):
        return {lang: text + suffix for lang, text in name.items()}
    return name + suffix


def compare(answer, exp, rtol, atol, name, degrees=True, per=None, extra=None, reveal=True):
    e = np.asarray(exp.value, dtype=float)
    per = np.zeros(e.shape, bool) if per is None else per
    a, refused = read_numbers(answer, name)
    if refused is not None:
        return failed(name, Msg(refused.key, **refused.fields), refused.code)
    a, problem = _shape(a, e, name)
    if isinstance(problem, CheckResult):
        return problem
    if not np.all(np.isfinite(a)):
        return failed(name, Msg("not_finite", where=name), "not_finite")
    contexts = tuple(exp.context) or (exp.kind,)
    if problem == "transposed":
        ok = close(a.T, e, rtol, atol)
        msg = Msg("transposed", expected=e.shape, got=a.shape)
        notes = [msg] + ([Msg("transposed_right")] if ok else [])
        return CheckResult(False, 0.5 if ok else 0.0, notes + hints(["transposed"], {"transposed": contexts}),
                           ["transposed"], (), name)
    if close(a, e, rtol, atol, per):
        return CheckResult(True, 1.0, [Msg("value_ok")], [], _rows(a, e, rtol, atol, per, name, None, True), name)
    for value, why in exp.equivalents:
        if close(a, np.asarray(value, float).reshape(e.shape), rtol, atol, per):
            return CheckResult(True, 1.0, [why], [], (), name)
    code, detail, erratum, note = _diagnose(a, e, exp, rtol, atol, per, degrees, extra, name)
    if not reveal and isinstance(detail, Msg) and "step" in detail.fields:  # the factor itself would be the answer
        detail = Msg("v.scaled_step", step=detail.fields["step"])
    notes = _head(a, e, rtol, atol, per, name, reveal)
    if note is not None:
        notes.append(note)
    if erratum:
        notes.append(Msg("book_misprint", id=erratum) if code in PRINTED else Msg("d.book_row", id=erratum))
    if detail is not None:
        notes.append(detail)
    rows = _rows(a, e, rtol, atol, per, name, code, reveal)
    # a mistake of some entries (an entry's sign, two entries exchanged) keeps the credit of the right ones
    global_codes = code not in ("wrong_value", "sign_flip", "swapped_entries")
    good = sum(1 for r in rows if r.status == "ok")
    score = 0.0 if global_codes or not rows else good / len(rows)
    codes = [code]
    return CheckResult(False, round(score, 6), notes + hints(codes, {c: contexts for c in codes}), codes,
                       tuple(rows), name)


def _head(a, e, rtol, atol, per, name, reveal):
    """The first line of a wrong answer's feedback: the expected value (reveal) or which entries are off."""
    err = np.abs(_diff(a, e, per))
    if reveal:
        where = np.unravel_index(int(np.argmax(err)), err.shape) if err.ndim else ()
        return [Msg("value_wrong", expected=_fmt_array(e), got=_fmt_array(a), err=fmt(err.max()),
                    where=_indexed(name, where))]
    scale = np.max(np.abs(e), initial=0.0)
    if e.size == 1:
        return [Msg("v.off_scalar", how=_how(a.ravel()[0], e.ravel()[0], per.ravel()[0], rtol, atol, scale))]
    wrong = [idx for idx in np.ndindex(e.shape) if err[idx] > atol + rtol * scale]
    if len(wrong) > 3 and e.size <= 64:  # the table below says how each one is off
        head = Msg("v.off_count", k=len(wrong), n=e.size)
    else:
        shown = [Msg("v.entry_how", where=_indexed(name, idx), how=_how(a[idx], e[idx], per[idx], rtol, atol, scale))
                 for idx in wrong[:6]]
        if len(wrong) > 6:
            shown.append(Msg("v.more", k=len(wrong) - 6))
        head = Msg("v.off_head", n=len(wrong), total=e.size, entries=shown)
    if e.ndim == 1 and e.size in (2, 3) and not per.any():
        na, ne = np.linalg.norm(a), np.linalg.norm(e)
        if ne > 0 and na > 0:
            if abs(na - ne) <= atol + rtol * ne:
                return [head, Msg("v.length_right")]
            if float(a @ e) / (na * ne) > 1 - 1e-9:
                return [head, Msg("v.direction_right")]
    return [head]


def _diff(a, e, per):
    d = a - e
    if per.any():
        d = np.where(per, (d + np.pi) % (2 * np.pi) - np.pi, d)
    return d


def _how(x, y, periodic, rtol, atol, scale):
    """How one entry is off, without its reference value: sign, too large or small (or by how much)."""
    tol = atol + rtol * scale
    if periodic:
        d = (x - y + np.pi) % (2 * np.pi) - np.pi
        return Msg("v.angle_high" if d > 0 else "v.angle_low")
    if abs(y) <= tol:
        return Msg("v.too_large_abs")
    if abs(x) <= tol:
        return Msg("v.is_zero")
    if np.sign(x) != np.sign(y):
        return Msg("v.wrong_sign" if abs(abs(x) - abs(y)) <= tol else "v.wrong_sign_size")
    r = abs(x) / abs(y)
    if r > 10:
        return Msg("v.far_too_large")
    if r < 0.1:
        return Msg("v.far_too_small")
    return Msg("v.too_large" if r > 1 else "v.too_small")


def _rows(a, e, rtol, atol, per, name, code, reveal):
    if a.size > 64:
        return []
    scale = np.max(np.abs(e), initial=0.0)
    rows = []
    for idx in np.ndindex(e.shape):
        x, y = a[idx], e[idx]
        d = x - y
        if per[idx]:
            d = (d + np.pi) % (2 * np.pi) - np.pi
        good = abs(d) <= atol + rtol * scale
        label = _indexed(name, idx)
        if good:
            text = ""
        elif reveal:
            text = Msg("value_entry", got=fmt(x), expected=fmt(y))
        else:
            text = _how(x, y, per[idx], rtol, atol, scale)
        rows.append(RowResult(label, "ok" if good else "wrong", text, None if good else (code or "wrong_value"),
                              (), 1.0 if good else 0.0))
    return rows


def _diagnose(a, e, exp, rtol, atol, per, degrees, extra, name="value"):
    """(code, detail, erratum, note) of a wrong answer."""
    for code, value, detail, erratum in exp.variants:
        v = np.asarray(value, float)
        if v.shape != e.shape and v.size == e.size:
            v = v.reshape(e.shape)
        if v.shape == e.shape and not close(v, e, rtol, atol, per) and close(a, v, rtol, atol, per):
            return code, detail, erratum, None
    if extra is not None:
        found = extra(a, e)
        if found is not None:
            return found
    if a.ndim == 2 and a.shape[0] == a.shape[1] and close(a.T, e, rtol, atol):
        return "transposed", None, None, Msg("transposed_right")
    nz = np.abs(e) > max(atol, 1e-12)
    if degrees and nz.any():
        # the answer in degrees where it differs (angles among other entries: q = [x, y, φ])
        wrong = ~np.isclose(a, e, rtol=rtol, atol=atol)
        deg = np.isclose(a, e * DEG, rtol=rtol, atol=atol * DEG)
        if per.any():
            deg |= per & np.isclose(np.mod(a, 360.0), np.mod(e * DEG, 360.0), rtol=rtol, atol=1e-3)
        if wrong.any() and np.all(deg[wrong]) and np.all(nz[wrong]):
            return "degrees", None, None, None
    if nz.any() and close(a, -e, rtol, atol):
        return "sign_flip", None, None, None
    found = _entry_signs(a, e, rtol, atol, per, name) or _exchanged(a, e, rtol, atol, name)
    if found is not None:
        return found
    return _scaled(a, e, rtol, atol)


def _scaled(a, e, rtol, atol):
    """"scaled" only for a plausible factor (2, ½, π, 1000 …) of a nonzero reference by a nonzero answer: a
    coincidence (a midpoint, a zero) is not a diagnosis."""
    flat_a, flat_e = a.ravel(), e.ravel()
    ee = float(flat_e @ flat_e)
    scale = np.max(np.abs(flat_e), initial=0.0)
    if ee == 0 or np.max(np.abs(flat_a), initial=0.0) <= atol + rtol * scale:
        return "wrong_value", None, None, None
    c = float(flat_a @ flat_e) / ee
    if not np.isfinite(c) or not close(a, c * e, rtol, atol):
        return "wrong_value", None, None, None
    for p in PLAUSIBLE_FACTORS:
        if abs(c - p) <= 1e-3 * abs(p):
            key = "v.scaled_units" if p in (1000.0, 1e-3) else "value_scaled"
            return "scaled", Msg(key, c=fmt(p), step=Msg(_scaled_step(p))), None, None
    return "wrong_value", None, None, None


def _scaled_step(p):
    """The step a plausible factor points at, named without the factor (which would give the answer away)."""
    if p in (1000.0, 1e-3):
        return "v.step_units"
    if any(abs(p - a) <= 1e-9 * abs(a) for a in (np.pi, 1 / np.pi, 2 * np.pi, 1 / (2 * np.pi), np.pi / 180)):
        return "v.step_angle"
    return "v.step_factor"


def _wrong_entries(a, e, rtol, atol, per):
    scale = np.max(np.abs(e), initial=0.0)
    d = _diff(a, e, per)
    return np.abs(d) > atol + rtol * scale, scale


def _entry_signs(a, e, rtol, atol, per, name):
    """Some entries (not all) with the opposite sign, the others right: "sign_flip", naming them."""
    wrong, scale = _wrong_entries(a, e, rtol, atol, per)
    if not wrong.any() or wrong.all():
        return None
    flipped = np.abs(a + e) <= atol + rtol * scale
    if not np.all(flipped[wrong]) or not np.all(np.abs(e[wrong]) > max(atol, 1e-12)):
        return None
    where = [_indexed(name, idx) for idx in zip(*np.nonzero(wrong))] if a.ndim else [name]
    return "sign_flip", Msg("value_signs", where=where), None, None


def _exchanged(a, e, rtol, atol, name):
    """Two entries of a vector, or two rows or two columns of a matrix, exchanged (and nothing else wrong):
    "swapped_entries", naming them."""
    per = np.zeros(e.shape, bool)
    if a.ndim == 1 or (a.ndim == 2 and 1 in a.shape):
        flat_a, flat_e = a.ravel(), e.ravel()
        wrong, _ = _wrong_entries(flat_a, flat_e, rtol, atol, per.ravel())
        idx = np.nonzero(wrong)[0]
        if len(idx) == 2:
            i, j = idx
            swapped = flat_e.copy()
            swapped[[i, j]] = swapped[[j, i]]
            if close(flat_a, swapped, rtol, atol):
                return "swapped_entries", Msg("value_exchanged", a=_indexed(name, (i,)), b=_indexed(name, (j,))), \
                    None, None
        return None
    if a.ndim != 2:
        return None
    for axis, key in ((0, "value_rows_exchanged"), (1, "value_cols_exchanged")):
        A, E = (a, e) if axis == 0 else (a.T, e.T)
        wrong = [k for k in range(E.shape[0]) if not close(A[k], E[k], rtol, atol)]
        if len(wrong) == 2:
            i, j = wrong
            if close(A[i], E[j], rtol, atol) and close(A[j], E[i], rtol, atol):
                return "swapped_entries", Msg(key, a=i + 1, b=j + 1), None, None
    return None
