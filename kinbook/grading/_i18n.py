"""Language of the feedback: English (default) or Spanish, switched with :func:`kinbook.set_language`.

Every sentence a checker writes is a template here, in both languages, keyed by a short id. Checkers do not
write sentences: they keep :class:`Msg` objects (a key and its fields), and a result renders them in the
current language when it is shown — translation is the last step, so a result made in English reads in
Spanish after ``set_language("es")``. Templates use the book's notation (Φ, Φ_q, ν, γ, ξ, η, φ).
"""

from __future__ import annotations

__all__ = ["set_language", "get_language", "tr", "Msg", "render", "both", "constraint_label", "row_name",
           "rows_name", "LANGUAGES"]

LANGUAGES = ("en", "es")
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

    if lang not in LANGUAGES:
        raise InputError(f"`lang` must be one of {', '.join(LANGUAGES)}, got {lang!r}")
    _state["lang"] = lang


def get_language():
    """The current feedback language, "en" or "es"."""
    return _state["lang"]


class Msg:
    """A sentence to be written later: a template key and its fields (which may be Msg objects, or dicts
    by language, themselves rendered when the sentence is)."""

    __slots__ = ("key", "fields")

    def __init__(self, key, **fields):
        if key not in _TEXT:
            raise KeyError(f"no feedback template {key!r}")
        self.key, self.fields = key, fields

    def __repr__(self):
        return f"Msg({self.key!r})"

    def __str__(self):
        return render(self)

    def __eq__(self, other):
        return isinstance(other, Msg) and (self.key, self.fields) == (other.key, other.fields)

    __hash__ = None


def render(x, lang=None):
    """A Msg, a {"en": …, "es": …} dict, a list of those, or a plain value, as text in ``lang`` (default:
    the current language)."""
    lang = lang or _state["lang"]
    if isinstance(x, Msg):
        table = _TEXT[x.key]
        text = table.get(lang) or table["en"]
        return text.format(**{k: _field(v, lang) for k, v in x.fields.items()})
    if isinstance(x, dict) and "en" in x:
        return x.get(lang) or x["en"]
    return x if isinstance(x, str) else str(x)


def _field(v, lang):
    if isinstance(v, (Msg, dict)):
        return render(v, lang)
    if isinstance(v, (list, tuple)) and v and all(isinstance(e, (Msg, dict, str)) for e in v):
        sep = "; "
        return sep.join(render(e, lang) for e in v)
    return v


def tr(key, **fields):
    """The template ``key`` in the current language, filled with ``fields`` (rendered now)."""
    return render(Msg(key, **fields))


def both(fn):
    """{"en": fn("en"), "es": fn("es")}: a text computed once per language, chosen when shown."""
    return {lang: fn(lang) for lang in LANGUAGES}


def row_name(k):
    """Book name of the 0-based row ``k`` of Φ: "Φ_4"."""
    return f"Φ_{k + 1}"


def rows_name(rows):
    """"Φ_4–Φ_5" (or "Φ_12") for 0-based rows."""
    rows = list(rows)
    if len(rows) == 1:
        return row_name(rows[0])
    return f"{row_name(rows[0])}–{row_name(rows[-1])}"


def _title(c, lang):
    """The class's title (``title = {"en": …, "es": …}``, every registered constraint class has one)."""
    title = getattr(c, "title", None)
    if isinstance(title, dict) and title.get("en"):
        return title.get(lang) or title["en"]
    return str(getattr(c, "type_name", None) or type(c).__name__)


def constraint_label(c, lang=None):
    """"revolute joint 1 (rows Φ_4–Φ_5)" / "par de revolución 1 (filas Φ_4–Φ_5)"."""
    lang = lang or _state["lang"]
    kind = _title(c, lang)
    name = str(c.name)
    if c.kind == "driver" and name.startswith("driver"):
        name = name[len("driver"):].strip()
    if getattr(c, "per_body", False) or c.kind == "normalization" or len(c.bodies) == 1 and c.kind == "simple" \
            and name in ("ground",):
        what = f"{kind} '{c.bodies[0].name}'"
    else:
        what = f"{kind} {name}"
    rows = list(range(c.rows.start, c.rows.stop))
    word = ("fila" if len(rows) == 1 else "filas") if lang == "es" else ("row" if len(rows) == 1 else "rows")
    return f"{what} ({word} {rows_name(rows)})"


def constraint_labels(c):
    """constraint_label in every language (a dict rendered when shown)."""
    return both(lambda lang: constraint_label(c, lang))


_TEXT = {
    # ------------------------------------------------------------------ headers of the result table
    "h.row": {"en": "row", "es": "fila"},
    "h.verdict": {"en": "verdict", "es": "veredicto"},
    "h.score": {"en": "score", "es": "puntuación"},
    "h.mistakes": {"en": "mistakes", "es": "errores"},
    "h.passed": {"en": "passed", "es": "correcto"},
    "h.failed": {"en": "failed", "es": "incorrecto"},
    # ------------------------------------------------------------------ verdicts (headlines)
    "all_correct": {
        "en": "{what} is correct: all {n} rows match kinbook's reference.",
        "es": "{what} es correcto: las {n} filas coinciden con la referencia de kinbook.",
    },
    "all_correct_equivalent": {
        "en": "{what} is correct: your {n} rows define the same constraints as the reference's {m} (same zero set "
              "and rank where the mechanism is assembled).",
        "es": "{what} es correcto: tus {n} filas definen las mismas restricciones que las {m} de la referencia "
              "(mismo conjunto de ceros y mismo rango donde el mecanismo está montado).",
    },
    "all_consistent": {
        "en": "{what} is consistent with your Φ: all {n} rows follow from it (full credit); {k} of them differ "
              "from the reference because your Φ does.",
        "es": "{what} es coherente con tu Φ: las {n} filas se deducen de él (puntuación completa); {k} de "
              "ellas difieren de la referencia porque tu Φ difiere.",
    },
    "summary": {
        "en": "{what}: {ok} of {n} rows correct (score {score:.2f}).",
        "es": "{what}: {ok} de {n} filas correctas (puntuación {score:.2f}).",
    },
    "summary_entries": {
        "en": "{what}: {ok} of {n} rows fully correct, {eok} of {en} nonzero entries right (score {score:.2f}).",
        "es": "{what}: {ok} de {n} filas totalmente correctas, {eok} de {en} elementos no nulos bien "
              "(puntuación {score:.2f}).",
    },
    "summary_half": {
        "en": "{what}: {ok} of {n} rows correct, {half} more right but out of place (half credit each; score "
              "{score:.2f}).",
        "es": "{what}: {ok} de {n} filas correctas y {half} más correctas pero fuera de sitio (media puntuación "
              "cada una; puntuación {score:.2f}).",
    },
    "summary_transposed": {
        "en": "{what}: 0 of {n} rows correct as given; the matrix is right once transposed (half credit: score "
              "{score:.2f}).",
        "es": "{what}: 0 de {n} filas correctas tal como están; la matriz es correcta una vez traspuesta (media "
              "puntuación: {score:.2f}).",
    },
    # ------------------------------------------------------------------ one row
    "row_ok": {"en": "correct", "es": "correcta"},
    "row_ok_scaled": {
        "en": "correct: the reference row multiplied by {c}, which defines the same constraint",
        "es": "correcta: la fila de referencia multiplicada por {c}, que define la misma restricción",
    },
    "row_ok_jacobian_scaled": {
        "en": "correct: the reference row multiplied by {c} (the Jacobian of {c}·{ref})",
        "es": "correcta: la fila de referencia multiplicada por {c} (el jacobiano de {c}·{ref})",
    },
    "row_equivalent": {
        "en": "correct: not the reference's form, but it vanishes exactly where {refs} do(es) and adds the same "
              "independent equation",
        "es": "correcta: no es la forma de la referencia, pero se anula exactamente donde lo hace(n) {refs} y "
              "aporta la misma ecuación independiente",
    },
    "row_equivalent_jacobian": {
        "en": "correct: not the reference's row, but at every configuration a combination of {refs} — the "
              "Jacobian of an equivalent formulation of the constraint",
        "es": "correcta: no es la fila de la referencia, pero en cada configuración es una combinación de {refs} "
              "— el jacobiano de una formulación equivalente de la restricción",
    },
    "row_moved": {
        "en": "right, but it is {ref}: the exercise asks for the book's order (half credit)",
        "es": "correcta, pero es {ref}: el ejercicio pide el orden del libro (media puntuación)",
    },
    "row_depends_repeat": {
        "en": "row {k} depends on row {j}: it repeats it{times}, so it adds no equation",
        "es": "la fila {k} depende de la fila {j}: la repite{times}, así que no aporta ninguna ecuación",
    },
    "times": {"en": " multiplied by {c}", "es": " multiplicada por {c}"},
    "row_depends_function": {
        "en": "row {k} depends on {rows}: it vanishes together with its gradient where the mechanism is assembled "
              "(a power or product of those rows), so it adds no independent equation",
        "es": "la fila {k} depende de {rows}: se anula junto con su gradiente donde el mecanismo está montado "
              "(una potencia o un producto de esas filas), así que no aporta ninguna ecuación independiente",
    },
    "row_depends_combination": {
        "en": "row {k} depends on rows {rows}: it is a constant combination of them, so it adds no equation",
        "es": "la fila {k} depende de las filas {rows}: es una combinación constante de ellas, así que no aporta "
              "ninguna ecuación",
    },
    "row_depends_free": {
        "en": "row {k} adds nothing to this constraint: it is {what}, which holds anyway (a row of the body, not "
              "of this joint)",
        "es": "la fila {k} no añade nada a esta restricción: es {what}, que se cumple de todos modos (una fila "
              "del elemento, no de este par)",
    },
    "row_wrong": {
        "en": "wrong: it is not {ref} ({owner}), nor a multiple of any other row",
        "es": "incorrecta: no es {ref} ({owner}) ni un múltiplo de ninguna otra fila",
    },
    "row_extra": {
        "en": "extra row: it matches no row of the reference",
        "es": "fila sobrante: no coincide con ninguna fila de la referencia",
    },
    "row_missing": {
        "en": "missing: no row of your answer is {ref} ({owner})",
        "es": "falta: ninguna fila de tu respuesta es {ref} ({owner})",
    },
    "row_missing_own": {
        "en": "missing: your Φ has a row {k} and this answer has no row for it",
        "es": "falta: tu Φ tiene una fila {k} y esta respuesta no tiene ninguna para ella",
    },
    "row_mistake": {"en": "wrong — {title}", "es": "incorrecta — {title}"},
    "row_mistake_detail": {"en": "wrong — {title}: {detail}", "es": "incorrecta — {title}: {detail}"},
    "book_misprint": {
        "en": "this is the book's printed formula, which is wrong: see erratum {id}",
        "es": "esta es la fórmula impresa en el libro, que es incorrecta: ver la errata {id}",
    },
    "your_row": {"en": "your row {k}", "es": "tu fila {k}"},
    "row_line": {"en": "{label} — {owner}: {text}", "es": "{label} — {owner}: {text}"},
    "row_line_short": {"en": "{label}: {text}", "es": "{label}: {text}"},
    "row_extra_at": {
        "en": "your row {k}: extra row, it matches no row of the reference",
        "es": "tu fila {k}: fila sobrante, no coincide con ninguna fila de la referencia",
    },
    "row_with_entries": {"en": "{text}; wrong entries: {entries}", "es": "{text}; elementos incorrectos: {entries}"},
    "entries_wrong": {"en": "wrong entries: {entries}", "es": "elementos incorrectos: {entries}"},
    "consistent_correct": {"en": "consistent with your Φ, and correct", "es": "coherente con tu Φ, y correcta"},
    "consistent_not_correct": {
        "en": "consistent with your Φ (full credit here); the row of Φ it comes from differs from the reference "
              "and was graded in the Φ part",
        "es": "coherente con tu Φ (puntuación completa aquí); la fila de Φ de la que procede difiere de la "
              "referencia y se calificó en el apartado de Φ",
    },
    "correct_not_consistent": {
        "en": "correct, although it does not follow from your Φ",
        "es": "correcta, aunque no se deduce de tu Φ",
    },
    "hint": {"en": "Hint ({title}): {hint}", "es": "Pista ({title}): {hint}"},
    "symbolic_confirmed": {
        "en": "sympy confirmed the equivalence symbolically",
        "es": "sympy confirmó la equivalencia simbólicamente",
    },
    "symbolic_unconfirmed": {
        "en": "sympy did not confirm {n} of the matched entries symbolically (expressions this size are only "
              "compared numerically); the verdict rests on the numeric comparison at {N} configurations",
        "es": "sympy no confirmó simbólicamente {n} de las coincidencias (expresiones de este tamaño solo se "
              "comparan numéricamente); el veredicto se basa en la comparación numérica en {N} configuraciones",
    },
    # ------------------------------------------------------------------ malformed answers
    "bad_type": {
        "en": "expected {expected}; got an object of type {type}",
        "es": "se esperaba {expected}; se recibió un objeto de tipo {type}",
    },
    "expect_answer": {
        "en": "no answer: give a sympy Matrix, a list of expressions or strings in the mechanism's coordinates, a "
              "function {signature}, or numbers with at=",
        "es": "no hay respuesta: da una Matrix de sympy, una lista de expresiones o cadenas en las coordenadas "
              "del mecanismo, una función {signature}, o números con at=",
    },
    "expect_Phi": {"en": "Φ as expressions, strings or a function f(q, t)",
                   "es": "Φ como expresiones, cadenas o una función f(q, t)"},
    "expect_Phi_q": {"en": "Φ_q as a matrix of expressions or strings, or a function f(q, t)",
                     "es": "Φ_q como matriz de expresiones o cadenas, o una función f(q, t)"},
    "expect_nu": {"en": "ν as expressions, strings or a function f(q, t)",
                  "es": "ν como expresiones, cadenas o una función f(q, t)"},
    "expect_gamma": {"en": "γ as expressions in q, q̇ and t, strings or a function f(q, qd, t)",
                     "es": "γ como expresiones en q, q̇ y t, cadenas o una función f(q, qd, t)"},
    "bool_answer": {
        "en": "True and False are not numbers: give the value itself",
        "es": "True y False no son números: da el valor mismo",
    },
    "complex_answer": {
        "en": "the answer has complex numbers: kinematic quantities are real",
        "es": "la respuesta tiene números complejos: las magnitudes cinemáticas son reales",
    },
    "not_numbers": {
        "en": "{what}: expected real numbers, got something else",
        "es": "{what}: se esperaban números reales, se recibió otra cosa",
    },
    "callable_result": {"en": "your function's result", "es": "el resultado de tu función"},
    "answer": {"en": "the answer", "es": "la respuesta"},
    "too_many_numbers": {
        "en": "your function returned {size} numbers (at most {limit} are read)",
        "es": "tu función devolvió {size} números (se leen como mucho {limit})",
    },
    "too_many_axes": {
        "en": "wrong shape: a vector or a matrix was expected, got an array of shape {shape}",
        "es": "forma incorrecta: se esperaba un vector o una matriz, se recibió un array de forma {shape}",
    },
    "returns_symbols": {
        "en": "a function must return numbers, not symbolic expressions",
        "es": "una función debe devolver números, no expresiones simbólicas",
    },
    "ragged": {"en": "wrong shape: rows of different lengths", "es": "forma incorrecta: filas de distinta longitud"},
    "nested_deeper": {"en": "wrong shape: lists nested too deeply", "es": "forma incorrecta: listas anidadas de más"},
    "empty_answer": {"en": "the answer is empty", "es": "la respuesta está vacía"},
    "empty_text": {"en": "{where} is empty", "es": "{where} está vacía"},
    "bad_entry": {
        "en": "{where}: expected an expression, a string or a number, got {type}",
        "es": "{where}: se esperaba una expresión, una cadena o un número, se recibió {type}",
    },
    "not_an_expression": {
        "en": "{where}: {type} is not an expression of a number (a relation or a set?)",
        "es": "{where}: {type} no es una expresión de un número (¿una relación o un conjunto?)",
    },
    "reader": {"en": "{message}", "es": "{message}"},
    "unsupported": {
        "en": "the answer cannot be evaluated: {what}",
        "es": "la respuesta no se puede evaluar: {what}",
    },
    "unknown_symbols": {
        "en": "{where}: unknown symbol(s) {names}: write the answer in the coordinates x1, y1, phi1 … (or φ1, "
              "phi_1), velocities dx1, dphi1 … and t",
        "es": "{where}: símbolo(s) desconocido(s) {names}: escribe la respuesta en las coordenadas x1, y1, phi1 … "
              "(o φ1, phi_1), velocidades dx1, dphi1 … y t",
    },
    "callable_failed": {
        "en": "your function raised {error} when called as {signature}",
        "es": "tu función lanzó {error} al llamarla como {signature}",
    },
    "needs_expression": {
        "en": "numbers cannot be differentiated: give Φ as expressions or a function",
        "es": "los números no se pueden derivar: da Φ como expresiones o como función",
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
    "transposed_right": {"en": "once transposed it would be correct", "es": "una vez traspuesta sería correcta"},
    "needs_configuration": {
        "en": "numbers are the values at one configuration: give the configuration, at={{'q': ..., 'qd': ..., "
              "'t': ...}} (or give the formula instead)",
        "es": "los números son los valores en una configuración: da la configuración, at={{'q': ..., 'qd': ..., "
              "'t': ...}} (o da la fórmula)",
    },
    "bad_configuration": {
        "en": "cannot use at={at}: {error}",
        "es": "no se puede usar at={at}: {error}",
    },
    "phi_unusable": {
        "en": "your Φ could not be used for error carried forward ({reason}); graded against the reference",
        "es": "tu Φ no se pudo usar para arrastrar el error ({reason}); se calificó frente a la referencia",
    },
    "bad_order": {
        "en": "`order` must be 'any' or 'book', got {order!r}",
        "es": "`order` debe ser 'any' o 'book', se recibió {order!r}",
    },
    "not_a_target": {"en": "{message}", "es": "{message}"},
    # ------------------------------------------------------------------ values
    "value_ok": {"en": "correct", "es": "correcto"},
    "value_ok_equivalent": {"en": "correct: {why}", "es": "correcto: {why}"},
    "value_wrong": {
        "en": "wrong: expected {expected}, got {got} (largest difference {err} in {where})",
        "es": "incorrecto: se esperaba {expected}, se recibió {got} (mayor diferencia {err} en {where})",
    },
    "value_entry": {"en": "{got} ≠ {expected}", "es": "{got} ≠ {expected}"},
    "value_scaled": {
        "en": "your answer is the expected one multiplied by {c}",
        "es": "tu respuesta es la esperada multiplicada por {c}",
    },
    "value_signs": {"en": "the sign of {where}", "es": "el signo de {where}"},
    "value_exchanged": {"en": "{a} and {b} are exchanged", "es": "{a} y {b} están intercambiados"},
    "value_rows_exchanged": {"en": "rows {a} and {b} are exchanged", "es": "las filas {a} y {b} están intercambiadas"},
    "value_cols_exchanged": {"en": "columns {a} and {b} are exchanged",
                             "es": "las columnas {a} y {b} están intercambiadas"},
    "p_negated": {
        "en": "correct: −p describes the same orientation as p (both are valid Euler parameters)",
        "es": "correcto: −p describe la misma orientación que p (ambos son parámetros de Euler válidos)",
    },
    "angles_alternative": {
        "en": "correct: the other triple of z-x-z angles that gives the same A (ψ ± π, −θ, φ ± π)",
        "es": "correcto: la otra terna de ángulos z-x-z que da la misma A (ψ ± π, −θ, φ ± π)",
    },
    "orthogonal_fail": {
        "en": "A is not orthogonal: the largest entry of AᵀA − I is {err}",
        "es": "A no es ortogonal: el mayor elemento de AᵀA − I es {err}",
    },
    "det_fail": {
        "en": "det A = {det}: a rotation matrix has det A = +1",
        "es": "det A = {det}: una matriz de rotación tiene det A = +1",
    },
    "norm_fail": {
        "en": "pᵀp = {norm}: Euler parameters satisfy pᵀp = 1",
        "es": "pᵀp = {norm}: los parámetros de Euler cumplen pᵀp = 1",
    },
    "entry": {"en": "entry {where}", "es": "el elemento {where}"},
    "the_value": {"en": "the value", "es": "el valor"},
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


def add_texts(table):
    """Register more templates (used by the catalogue's details)."""
    for key, value in table.items():
        if key in _TEXT:
            raise KeyError(f"feedback template {key!r} defined twice")
        _TEXT[key] = value
