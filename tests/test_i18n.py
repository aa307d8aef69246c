"""Translations through gettext (kinbook.i18n): every marked message of the package is in the Spanish catalogue,
translated, not fuzzy, with the same fields; the shipped .mo is the compiled .po; plural forms follow n."""

import gettext
import re
import string
from pathlib import Path

import pytest
import sympy as sp

babel = pytest.importorskip("babel")  # a test/dev dependency (pyproject's test extra): the catalogue's tools

from babel.messages.extract import extract_from_dir  # noqa: E402
from babel.messages.pofile import read_po  # noqa: E402

import kinbook  # noqa: E402
from kinbook import i18n  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
PO = i18n.LOCALE_DIR / "es" / "LC_MESSAGES" / "kinbook.po"
MO = PO.with_suffix(".mo")


def _catalog():
    with PO.open("rb") as f:
        return read_po(f, locale="es", domain="kinbook")


def _marked():
    """(message id, context) of every marked message in kinbook/, read by Babel's extractor as `make translations`
    reads them (pyproject.toml's [tool.babel], the keywords of kinbook.i18n)."""
    out = set()
    for _file, _line, message, _comments, context in extract_from_dir(ROOT / "kinbook", keywords=i18n.KEYWORDS,
                                                                       method_map=[("**.py", "python")]):
        out.add((message if isinstance(message, str) else tuple(message), context))
    return out


def _fields(text):
    return {f for _, f, _, _ in string.Formatter().parse(text) if f}


def test_every_marked_message_is_translated_in_the_spanish_catalogue():
    catalog = _catalog()
    marked = _marked()
    assert len(marked) >= 200
    problems = []
    for message, context in sorted(marked, key=str):
        key = message[0] if isinstance(message, tuple) else message
        entry = catalog.get(key, context=context)
        if entry is None:
            problems.append(("missing", message))
            continue
        strings = entry.string if isinstance(entry.string, tuple) else (entry.string,)
        if entry.fuzzy or not all(strings):
            problems.append(("fuzzy or untranslated", message))
            continue
        ids = message if isinstance(message, tuple) else (message,)
        allowed = set().union(*(_fields(m) for m in ids))
        for s in strings:
            if not _fields(s) <= allowed:  # a translation may leave out {n} (its singular), never invent a field
                problems.append(("fields", message, s))
    assert not problems, problems


def test_the_plural_forms_are_spanish():
    assert _catalog().plural_forms == "nplurals=2; plural=(n != 1);"


def test_the_shipped_mo_is_the_compiled_po():
    """A .po edited without `make translations` leaves a stale .mo: what gettext reads at run time."""
    with MO.open("rb") as f:
        shipped = gettext.GNUTranslations(f)._catalog
    expected = {}
    for m in _catalog():
        if not m.id or not m.string:
            continue
        key = m.id if m.context is None else f"{m.context}\x04{m.id if isinstance(m.id, str) else m.id[0]}"
        if isinstance(m.id, tuple):
            ctx = "" if m.context is None else f"{m.context}\x04"
            for k, s in enumerate(m.string):
                expected[(ctx + m.id[0], k)] = s
        else:
            expected[key] = m.string
    shipped = {k: v for k, v in shipped.items() if k != ""}
    assert shipped == expected


def test_the_catalogue_is_package_data():
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert re.search(r'"kinbook" = \[[^]]*"locale/\*/LC_MESSAGES/\*\.mo"', text)


def test_set_language_switches_every_message_and_plural_forms():
    from kinbook.grading._i18n import Msg, render

    try:
        kinbook.set_language("es")
        assert render(Msg("summary", what="Φ", ok=0, n=1, score=0.0)) == "Φ: 0 de 1 fila correcta (puntuación 0.00)."
        assert render(Msg("summary", what="Φ", ok=2, n=3, score=0.67)) == \
            "Φ: 2 de 3 filas correctas (puntuación 0.67)."
        assert render(Msg("row_ok")) == "correcta" and render(Msg("value_ok")) == "correcto"
    finally:
        kinbook.set_language("en")
    assert render(Msg("summary", what="Φ", ok=0, n=1, score=0.0)) == "Φ: 0 of 1 row correct (score 0.00)."
    with pytest.raises(kinbook.KinbookError, match="`lang` must be one of en, es, got 'fr'"):
        kinbook.set_language("fr")


def test_a_driver_function_is_refused_in_the_language_of_the_moment():
    """A prescribed function of time (kinbook.core.symbolic) is refused through the reader's marked messages: a
    student who types a driver in Spanish mode reads Spanish, the English stays as it was."""
    from kinbook.core.symbolic import time_function

    with pytest.raises(kinbook.ExpressionError) as info:
        time_function("sign(t - 1)", "driver on body 'crank', f")
    err = info.value
    en = ("driver on body 'crank', f: the function of time 'sign(t - 1)' uses sign, which jumps: a prescribed motion "
          "needs two continuous derivatives (for ν and γ); write a smooth function (a blend such as (1 - cos(pi*t))/2), "
          "or drive each phase in its own sweep")
    assert str(err) == en
    try:
        kinbook.set_language("es")
        assert str(err) == ("driver on body 'crank', f: la función del tiempo 'sign(t - 1)' usa sign, que salta: un "
                            "movimiento prescrito necesita dos derivadas continuas (para ν y γ); escribe una función "
                            "suave (un enlace como (1 - cos(pi*t))/2), o analiza cada fase en su propio barrido")
        with pytest.raises(kinbook.ExpressionError, match=r"^f: la función del tiempo 't\*w' usa símbolos desconocidos "
                                                          r"w; se esperaba una expresión de t solo$"):
            time_function(sp.Symbol("w") * sp.Symbol("t"), "f")
    finally:
        kinbook.set_language("en")


def test_any_kinbook_error_may_carry_a_marked_message():
    """KinbookError writes a marked message when shown: a student's mistyped try-it id reads in Spanish, its args
    keep the English (and a pickled copy the marked message)."""
    import pickle

    from kinbook.book import tryits

    with pytest.raises(kinbook.InputError) as info:
        tryits.get("13-1/try-9")
    err = info.value
    en = "no try-it '13-1/try-9'; expected one of 13-1/try-1, 13-1/try-2, 13-1/try-3"
    assert str(err) == en and err.args == (en,)
    try:
        kinbook.set_language("es")
        es = "no existe el ejercicio '13-1/try-9'; se esperaba uno de 13-1/try-1, 13-1/try-2, 13-1/try-3"
        assert str(err) == es and str(pickle.loads(pickle.dumps(err))) == es
        with pytest.raises(kinbook.InputError, match=r"^kb\.another\('13-1/try-1', k\): k debe ser un número entero "
                                                     r"≥ 0 \(0 = los datos del cuaderno\), se recibió -1$"):
            tryits.another("13-1/try-1", -1)
    finally:
        kinbook.set_language("en")
    assert str(kinbook.KinbookError()) == "" and kinbook.KinbookError().args == ()


def _texts_by_language(tree):
    """Every dict display of the module whose keys are language codes besides English: text translated outside the
    catalogue ({"en": …, "es": …}), which test_every_marked_message_is_translated_in_the_spanish_catalogue
    cannot see."""
    import ast

    others = set(i18n.LANGUAGES) - {"en"}
    for node in ast.walk(tree):
        if isinstance(node, ast.Dict) and any(isinstance(k, ast.Constant) and k.value in others for k in node.keys):
            yield node.lineno


def test_no_text_is_translated_outside_the_catalogue():
    """The class of problem stays closed: no {"en": …, "es": …} of user-facing text anywhere in kinbook/ (constraint
    titles, try-it texts, templates: all marked messages, their Spanish in kinbook.po)."""
    import ast

    found = []
    for path in sorted((ROOT / "kinbook").rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        found += [f"{path.relative_to(ROOT)}:{line}" for line in _texts_by_language(tree)]
    assert found == []
    # the scan finds what it looks for
    sample = ast.parse('title = {"en": "gear pair", "es": "engranaje"}\nx = {"en": 1}\n')
    assert list(_texts_by_language(sample)) == [1]


def test_every_constraint_title_of_kinbook_reads_in_spanish():
    """Each constraint type kinbook declares has its title in the catalogue, in the book's vocabulary; the same
    English title is the same Spanish in both chapters."""
    from kinbook.core.registry import constraint_types

    titles = {}
    for chapter in ("planar", "spatial"):
        for name, cls in constraint_types(chapter).items():
            if cls.__module__.startswith("kinbook."):
                titles[f"{chapter} {name}"] = (cls.title, i18n.translate(cls.title, "es"))
    untranslated = [k for k, (en, es) in titles.items() if en == es]
    assert untranslated == [] and len(titles) >= 25
    assert titles["planar gear"] == ("gear pair", "engranaje")
    assert titles["planar revolute"] == titles["spatial revolute"] == ("revolute joint", "par de revolución")
    assert titles["planar driver"] == ("driver", "restricción motriz")
    assert titles["spatial spherical"] == ("spherical joint", "par esférico")
    assert titles["spatial normalization"] == ("Euler-parameter normalization", "normalización de los parámetros de Euler")


def test_an_extension_title_outside_the_catalogue_reads_as_written():
    """docs/extending.md: an extension declares its title as a text, shown as written in Spanish too; a title by
    language is refused where the class is defined."""
    import sympy as sp

    from kinbook import planar
    from kinbook.grading._i18n import constraint_label

    class Hinge(planar.Constraint):
        type_name = "test-i18n-hinge"
        n_eq = 1
        title = "hinge of the test"
        roles = ("i",)
        points = {"P": "i"}

        def phi(self, Q, t=None):
            return [self.point(Q, "P")[0]]

    m = planar.Mechanism("t")
    m.add_body("a", points={"P": (0, 0)})
    m.add(Hinge("a", P="P", name="h"))
    c = m.constraint("h")
    try:
        kinbook.set_language("es")
        assert constraint_label(c) == "hinge of the test h (fila Φ_1)"
    finally:
        kinbook.set_language("en")
    assert constraint_label(c) == "hinge of the test h (row Φ_1)"
    with pytest.raises(kinbook.ModelError, match=r"\('test-i18n-other'\): `title` must be a text, its English "
                                                 r"\(\"cam and follower\"; .*got \{'en': 'x', 'es': 'y'\}"):
        type("Other", (planar.Constraint,), {"type_name": "test-i18n-other", "n_eq": 1, "title": {"en": "x", "es": "y"},
                                             "phi": lambda self, Q, t=None: [sp.S(0)], "__module__": __name__})


def test_the_try_its_read_in_spanish_with_tu():
    """The try-its' texts are marked messages: their Spanish comes from the catalogue and says "tú", as the
    checkers' feedback does."""
    import html as _html

    from kinbook.book import tryits

    item = tryits.get("13-1/try-1")
    try:
        kinbook.set_language("es")
        blank = _html.unescape(repr(tryits.NotAnswered(item)))
        assert blank == ("Pruébalo 1 (13-1) aún no tiene respuesta: sustituye `...` en `my_A = ...` por tu respuesta "
                         "y ejecuta de nuevo la celda. ¿Atascado? `kb.reveal(\"13-1/try-1\")` muestra una solución.")
        assert tryits.reveal("13-1/try-1").why == (
            "la ec. 6 con el ángulo en radianes: np.cos y np.sin toman radianes, así que convierte primero "
            "(np.radians). Las columnas de A son los ejes ξ y η del elemento en componentes globales.")
        assert tryits.get("14-4/try-3").stated() == "P en [1.2, 0, 0] sobre el elemento i (s'_i, s'_j a lo largo de ζ como arriba)"
        assert tryits.get("13-1/try-1").stated() == "φ = 120°"  # notation alone: not a message of the catalogue
        copied = item.check(item.reference_answer(), {"phi_deg": 150})  # a variant asked, the notebook's answered
        assert copied.mistakes == ["wrong_data"]
        assert copied.messages[1] == "esto es la respuesta para los datos del cuaderno, no para los de esta variante"
    finally:
        kinbook.set_language("en")
    assert tryits.reveal("13-1/try-1").why.startswith("eq. 6 with the angle in radians: np.cos and np.sin take radians")
    assert copied.messages[1] == "this is the answer for the notebook's data, not for this variant's"
    assert tryits.get("14-4/try-3").stated() == "P at [1.2, 0, 0] on body i (s'_i, s'_j along ζ as above)"
    po = PO.read_text(encoding="utf-8")
    assert not re.search(r"\b(sustituya|ejecute|Pruébelo|Respóndala|convierta)\b", po)
