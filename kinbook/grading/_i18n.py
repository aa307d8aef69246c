"""Language of the feedback: English (default) or Spanish, switched with :func:`kinbook.set_language`.

Every sentence a checker writes is a template here, in both languages, keyed by a short id. Templates use the
book's notation (Φ, Φ_q, ν, γ, ξ, η, φ) and ``str.format`` fields.
"""

from __future__ import annotations

__all__ = ["set_language", "get_language", "tr", "constraint_label", "row_name", "rows_name"]

_LANGUAGES = ("en", "es")
_state = {"lang": "en"}


def set_language(lang):
    """Choose the language of grading feedback.

    Parameters
    ----------
    lang : {"en", "es"}
        English or Spanish.

    Examples
    --------
    >>> set_language("es"); get_language()
    'es'
    >>> set_language("en")
    """
    from ..errors import InputError

    if lang not in _LANGUAGES:
        raise InputError(f"`lang` must be one of {', '.join(_LANGUAGES)}, got {lang!r}")
    _state["lang"] = lang


def get_language():
    """The current feedback language, "en" or "es"."""
    return _state["lang"]


def tr(key, **fields):
    """The template ``key`` in the current language, filled with ``fields``."""
    table = _TEXT[key]
    text = table.get(_state["lang"]) or table["en"]
    return text.format(**fields)


_TYPE_NAMES = {
    "revolute": ("revolute joint", "par de revolución"),
    "translational": ("translational joint", "par de traslación"),
    "revolute-revolute": ("revolute-revolute joint", "par revolución-revolución"),
    "revolute-translational": ("revolute-translational joint", "par revolución-traslación"),
    "gear": ("gear pair", "engranaje"),
    "rack-pinion": ("rack-and-pinion", "piñón-cremallera"),
    "driver": ("driver", "restricción motriz"),
    "relative-driver": ("relative-angle driver", "restricción motriz de ángulo relativo"),
    "distance-driver": ("distance driver", "restricción motriz de distancia"),
    "ground": ("simple constraints of the fixed body", "restricciones simples del elemento fijo"),
    "simple": ("simple constraint", "restricción simple"),
    # spatial (chapter 14)
    "normalization": ("Euler-parameter normalization", "normalización de los parámetros de Euler"),
    "spherical": ("spherical joint", "par esférico"),
    "universal": ("universal joint", "junta universal"),
    "cylindrical": ("cylindrical joint", "par cilíndrico"),
    "spherical-spherical": ("spherical-spherical joint", "par esférico-esférico"),
    "normal-1": ("normal-1 constraint", "restricción normal-1"),
    "normal-2": ("normal-2 constraint", "restricción normal-2"),
    "parallel-1": ("parallel-1 constraint", "restricción paralela-1"),
    "parallel-2": ("parallel-2 constraint", "restricción paralela-2"),
    "revolute-driver": ("revolute driver", "restricción motriz de rotación"),
}


def row_name(k):
    """Book name of the 0-based row ``k`` of Φ: "Φ_4"."""
    return f"Φ_{k + 1}"


def rows_name(rows):
    """"Φ_4–Φ_5" (or "Φ_12") for 0-based rows."""
    rows = list(rows)
    if len(rows) == 1:
        return row_name(rows[0])
    return f"{row_name(rows[0])}–{row_name(rows[-1])}"


def constraint_label(c):
    """"revolute joint 1 (rows Φ_4–Φ_5)" / "par de revolución 1 (filas Φ_4–Φ_5)"."""
    en, es = _TYPE_NAMES.get(c.type_name, (c.type_name, c.type_name))
    kind = es if _state["lang"] == "es" else en
    name = str(c.name)
    if c.kind == "driver" and name.startswith("driver"):
        name = name[len("driver"):].strip()
    if c.type_name in ("ground", "normalization"):
        what = f"{kind} '{c.bodies[0].name}'"
    elif c.kind == "simple":
        what = f"{kind} {name}"
    else:
        what = f"{kind} {name}"
    rows = list(range(c.rows.start, c.rows.stop))
    if _state["lang"] == "es":
        where = f"fila {rows_name(rows)}" if len(rows) == 1 else f"filas {rows_name(rows)}"
    else:
        where = f"row {rows_name(rows)}" if len(rows) == 1 else f"rows {rows_name(rows)}"
    return f"{what} ({where})"


_TEXT = {
    # ------------------------------------------------------------------ quantities
    "q.Phi": {"en": "Φ", "es": "Φ"},
    "q.Phi_q": {"en": "Φ_q", "es": "Φ_q"},
    "q.nu": {"en": "ν", "es": "ν"},
    "q.gamma": {"en": "γ", "es": "γ"},
    "q.value": {"en": "value", "es": "valor"},
    # ------------------------------------------------------------------ verdicts
    "all_correct": {
        "en": "{what} is correct: all {n} rows match kinbook's reference.",
        "es": "{what} es correcto: las {n} filas coinciden con la referencia de kinbook.",
    },
    "summary": {
        "en": "{what}: {ok} of {n} rows correct (score {score:.2f}).",
        "es": "{what}: {ok} de {n} filas correctas (puntuación {score:.2f}).",
    },
    "row_ok": {"en": "correct", "es": "correcta"},
    "your_row": {"en": "your row {k}", "es": "tu fila {k}"},
    "all_consistent": {
        "en": "{what} is consistent with your Φ: all {n} rows follow from it (full credit); {k} of them differ "
              "from the book because your Φ does.",
        "es": "{what} es coherente con tu Φ: las {n} filas se deducen de él (puntuación completa); {k} de "
              "ellas difieren del libro porque tu Φ difiere.",
    },
    "row_ok_scaled": {
        "en": "correct (the reference row multiplied by {c:g}, which defines the same constraint)",
        "es": "correcta (la fila de referencia multiplicada por {c:g}, que define la misma restricción)",
    },
    "row_ok_as": {
        "en": "correct: it is {ref} of the reference, multiplied by {c:g}",
        "es": "correcta: es la {ref} de la referencia, multiplicada por {c:g}",
    },
    "row_ok_moved": {
        "en": "correct, but it is the book's {ref}: the exercise asks for the book's order",
        "es": "correcta, pero es la {ref} del libro: el ejercicio pide el orden del libro",
    },
    "row_equivalent": {
        "en": "accepted: not the book's form, but it vanishes exactly where {ref} does and defines the same "
              "constraint",
        "es": "aceptada: no es la forma del libro, pero se anula exactamente donde lo hace {ref} y define la "
              "misma restricción",
    },
    "row_wrong": {
        "en": "wrong: it does not match {ref} ({owner}) nor any other row",
        "es": "incorrecta: no coincide con {ref} ({owner}) ni con ninguna otra fila",
    },
    "row_extra": {
        "en": "extra row: it matches no row of the reference",
        "es": "fila sobrante: no coincide con ninguna fila de la referencia",
    },
    "row_missing": {
        "en": "missing: no row of your answer is {ref} ({owner})",
        "es": "falta: ninguna fila de tu respuesta es {ref} ({owner})",
    },
    "row_mistake": {
        "en": "wrong — {title}: {hint}",
        "es": "incorrecta — {title}: {hint}",
    },
    "row_mistake_short": {"en": "wrong — {title}", "es": "incorrecta — {title}"},
    "hint": {"en": "Hint ({title}): {hint}", "es": "Pista ({title}): {hint}"},
    "entries_wrong": {
        "en": "wrong entries: {entries}",
        "es": "elementos incorrectos: {entries}",
    },
    "consistent_correct": {
        "en": "consistent with your Φ, and correct",
        "es": "coherente con tu Φ, y correcta",
    },
    "consistent_not_correct": {
        "en": "consistent with your Φ (full credit here); the row of Φ it comes from is wrong and was graded "
              "in the Φ part",
        "es": "coherente con tu Φ (puntuación completa aquí); la fila de Φ de la que procede es incorrecta y "
              "se calificó en el apartado de Φ",
    },
    "correct_not_consistent": {
        "en": "correct, although it does not follow from your Φ",
        "es": "correcta, aunque no se deduce de tu Φ",
    },
    "not_zero_on_manifold": {
        "en": "it is not zero at configurations where the mechanism is assembled, so it is not a constraint of "
              "this mechanism",
        "es": "no se anula en configuraciones en las que el mecanismo está montado, así que no es una "
              "restricción de este mecanismo",
    },
    "scaled_rows_note": {
        "en": "rows may be reordered or multiplied by a nonzero constant",
        "es": "las filas pueden reordenarse o multiplicarse por una constante no nula",
    },
    "symbolic_confirmed": {
        "en": "sympy confirmed the equivalence symbolically",
        "es": "sympy confirmó la equivalencia simbólicamente",
    },
    "symbolic_unconfirmed": {
        "en": "sympy could not confirm the {n} matched entries symbolically within the time limit; the verdict "
              "rests on the numeric comparison",
        "es": "sympy no pudo confirmar simbólicamente las {n} coincidencias dentro del límite de tiempo; el "
              "veredicto se basa en la comparación numérica",
    },
    # ------------------------------------------------------------------ malformed answers
    "bad_type": {
        "en": "expected {expected}; got an object of type {type}",
        "es": "se esperaba {expected}; se recibió un objeto de tipo {type}",
    },
    "expect_symbolic": {
        "en": "a sympy Matrix, a list of expressions or strings in {symbols}, a function {signature}, or numbers",
        "es": "una Matrix de sympy, una lista de expresiones o cadenas en {symbols}, una función {signature}, "
              "o números",
    },
    "unparsable": {
        "en": "cannot read {text!r} as a formula: {error}",
        "es": "no se puede leer {text!r} como fórmula: {error}",
    },
    "unknown_symbols": {
        "en": "unknown symbol(s) {names}: write the answer in {allowed}",
        "es": "símbolo(s) desconocido(s) {names}: escribe la respuesta en {allowed}",
    },
    "too_large": {
        "en": "the expression is too large to grade ({size} nodes, the limit is {limit})",
        "es": "la expresión es demasiado grande para calificarla ({size} nodos, el límite es {limit})",
    },
    "timeout": {
        "en": "the answer took longer than {seconds:g} s to read or evaluate",
        "es": "la respuesta tardó más de {seconds:g} s en leerse o evaluarse",
    },
    "callable_failed": {
        "en": "your function raised {error} when called as {signature}",
        "es": "tu función lanzó {error} al llamarla como {signature}",
    },
    "evaluation_failed": {
        "en": "cannot evaluate the answer numerically: {error}",
        "es": "no se puede evaluar la respuesta numéricamente: {error}",
    },
    "not_finite": {
        "en": "the answer is not a finite real number (NaN, inf or complex) in {where}",
        "es": "la respuesta no es un número real finito (NaN, inf o complejo) en {where}",
    },
    "wrong_shape": {
        "en": "wrong shape: expected {expected}, got {got}",
        "es": "forma incorrecta: se esperaba {expected}, se recibió {got}",
    },
    "transposed": {
        "en": "the matrix is transposed: expected {expected} (one row per constraint equation, one column per "
              "coordinate), got {got}",
        "es": "la matriz está traspuesta: se esperaba {expected} (una fila por ecuación de restricción, una "
              "columna por coordenada), se recibió {got}",
    },
    "transposed_right": {
        "en": "once transposed it would be correct",
        "es": "una vez traspuesta sería correcta",
    },
    "needs_configuration": {
        "en": "numbers are graded at a configuration: pass at={{'q': ..., 'qd': ..., 't': ...}}",
        "es": "los números se califican en una configuración: pasa at={{'q': ..., 'qd': ..., 't': ...}}",
    },
    "phi_unusable": {
        "en": "your Φ could not be used for error carried forward ({reason}); graded against the book",
        "es": "tu Φ no se pudo usar para arrastrar el error ({reason}); se calificó frente al libro",
    },
    # ------------------------------------------------------------------ values
    "value_ok": {"en": "correct", "es": "correcto"},
    "value_wrong": {
        "en": "wrong: expected {expected}, got {got} (largest error {err:.3g} at {where})",
        "es": "incorrecto: se esperaba {expected}, se recibió {got} (mayor error {err:.3g} en {where})",
    },
    "value_scaled": {
        "en": "your answer is the expected one multiplied by {c:.4g}",
        "es": "tu respuesta es la esperada multiplicada por {c:.4g}",
    },
    "p_negated": {
        "en": "correct: −p describes the same orientation as p (both are valid Euler parameters)",
        "es": "correcto: −p describe la misma orientación que p (ambos son parámetros de Euler válidos)",
    },
    "orthogonal_fail": {
        "en": "A is not orthogonal: ‖AᵀA − I‖ = {err:.3g}",
        "es": "A no es ortogonal: ‖AᵀA − I‖ = {err:.3g}",
    },
    "det_fail": {
        "en": "det A = {det:.4g}: a rotation matrix has det A = +1",
        "es": "det A = {det:.4g}: una matriz de rotación tiene det A = +1",
    },
    "norm_fail": {
        "en": "pᵀp = {norm:.6g}: Euler parameters satisfy pᵀp = 1",
        "es": "pᵀp = {norm:.6g}: los parámetros de Euler cumplen pᵀp = 1",
    },
    "row_order_hint": {
        "en": "every row is right for some order of Φ (or some constant factor), but not in the book's order: "
              "pass your own Φ as phi=... so that the rows are matched to it, or use order='any'",
        "es": "cada fila es correcta para algún orden de Φ (o algún factor constante), pero no en el orden del "
              "libro: pasa tu propio Φ como phi=... para emparejar las filas con él, o usa order='any'",
    },
    "row_order_msg": {
        "en": "the rows are right but not in the book's order",
        "es": "las filas son correctas pero no están en el orden del libro",
    },
}
