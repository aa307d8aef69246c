"""The mistake catalogue: every mistake a checker can name, with a stable code, a title and a hint.

Codes are stable: exercises, tests and grade books refer to them. docs/mistakes.md documents each one with an
example; :func:`explain` gives the title and hint in the current language (see :func:`kinbook.set_language`).

Mistakes are detected by *generating* the wrong answer from kinbook's reference (re-deriving Φ with bodies
i and j swapped, with Aᵀ for A, γ with the opposite sign …) and testing the student's answer for numeric
equivalence with it, so a code is only reported when the answer really is that mistake.
"""

from __future__ import annotations

from dataclasses import dataclass

from ._i18n import get_language

__all__ = ["Mistake", "MISTAKES", "explain", "codes"]


@dataclass(frozen=True)
class Mistake:
    """One entry of the catalogue.

    Attributes
    ----------
    code : str
        Stable identifier, e.g. ``"swapped_bodies"``.
    title, hint : dict
        ``{"en": ..., "es": ...}``.
    """

    code: str
    title: dict
    hint: dict

    def text(self, lang=None):
        lang = lang or get_language()
        return self.title.get(lang, self.title["en"]), self.hint.get(lang, self.hint["en"])


def _m(code, title_en, title_es, hint_en, hint_es):
    return Mistake(code, {"en": title_en, "es": title_es}, {"en": hint_en, "es": hint_es})


_ENTRIES = [
    # ------------------------------------------------------------- form of the answer
    _m("malformed", "malformed answer", "respuesta mal formada",
       "the answer could not be read or evaluated; see the message for what was expected",
       "la respuesta no se pudo leer o evaluar; el mensaje indica qué se esperaba"),
    _m("unknown_symbol", "unknown symbol", "símbolo desconocido",
       "write Φ in the mechanism's coordinates x1, y1, phi1, x2 …, velocities dx1, dy1, dphi1 … and time t",
       "escribe Φ en las coordenadas del mecanismo x1, y1, phi1, x2 …, velocidades dx1, dy1, dphi1 … y el "
       "tiempo t"),
    _m("not_finite", "NaN or infinite value", "valor NaN o infinito",
       "the answer evaluates to NaN or inf; look for a division by zero or an undefined operation",
       "la respuesta da NaN o inf; busca una división por cero o una operación no definida"),
    _m("wrong_shape", "wrong shape", "forma incorrecta",
       "Φ has one row per constraint equation (m rows); Φ_q is m × n, one column per coordinate",
       "Φ tiene una fila por ecuación de restricción (m filas); Φ_q es m × n, una columna por coordenada"),
    _m("transposed", "transposed matrix", "matriz traspuesta",
       "rows and columns exchanged: row k of Φ_q holds ∂Φ_k/∂q (one column per coordinate); A maps local "
       "to global components, Aᵀ global to local",
       "filas y columnas intercambiadas: la fila k de Φ_q contiene ∂Φ_k/∂q (una columna por coordenada); A "
       "pasa de componentes locales a globales, Aᵀ de globales a locales"),
    _m("missing_row", "missing row", "falta una fila",
       "every constraint contributes its rows, drivers included (the book appends Φ^(d) below Φ)",
       "cada restricción aporta sus filas, también las motrices (el libro añade Φ^(d) debajo de Φ)"),
    _m("extra_row", "extra row", "fila sobrante",
       "a row that is not one of the mechanism's constraint equations (a repeated row, or one too many)",
       "una fila que no es ninguna ecuación de restricción del mecanismo (repetida, o una de más)"),
    _m("row_order", "rows not in the book's order", "filas fuera del orden del libro",
       "the exercise asks for the book's order: constraints in the order of the joint table, drivers last",
       "el ejercicio pide el orden del libro: restricciones en el orden de la tabla de pares, las motrices "
       "al final"),
    _m("wrong_value", "wrong value", "valor incorrecto",
       "the value differs from the reference and matches none of the catalogued mistakes; recheck the "
       "derivation step by step",
       "el valor difiere de la referencia y no coincide con ningún error catalogado; revisa la deducción "
       "paso a paso"),
    # ------------------------------------------------------------- building Φ
    _m("sign_flip", "sign error", "error de signo",
       "one term (or a whole row or entry) has the opposite sign; check each term against r_i + A_i s'_i − "
       "r_j − A_j s'_j and its derivatives",
       "un término (o una fila o elemento entero) tiene el signo cambiado; compara cada término con "
       "r_i + A_i s'_i − r_j − A_j s'_j y sus derivadas"),
    _m("missing_term", "missing term", "falta un término",
       "one term of the reference is absent from the answer",
       "un término de la referencia no aparece en la respuesta"),
    _m("swapped_bodies", "bodies i and j swapped", "elementos i y j intercambiados",
       "the joint's roles are not symmetric here: keep body i (the one carrying the axis or the first "
       "radius) as the book's table assigns it",
       "los papeles del par no son simétricos aquí: mantén el elemento i (el que lleva el eje o el primer "
       "radio) como asigna la tabla del libro"),
    _m("swapped_points", "local points swapped between the bodies", "puntos locales intercambiados",
       "s'_i^P holds the (ξ, η) of P in body i's frame and s'_j^P those in body j's frame; they were swapped",
       "s'_i^P contiene las (ξ, η) de P en el sistema del elemento i y s'_j^P las del elemento j; están "
       "intercambiadas"),
    _m("A_transposed", "Aᵀ used for A", "Aᵀ en lugar de A",
       "A(φ) = [[cos φ, −sin φ], [sin φ, cos φ]] maps local to global: r^P = r + A s'",
       "A(φ) = [[cos φ, −sen φ], [sen φ, cos φ]] pasa de locales a globales: r^P = r + A s'"),
    _m("local_vector", "local instead of global vector", "vector local en lugar de global",
       "s' has local components (ξ, η); in Φ the vector must be in global components, A s'",
       "s' tiene componentes locales (ξ, η); en Φ el vector debe ir en componentes globales, A s'"),
    _m("degrees", "degrees instead of radians", "grados en lugar de radianes",
       "angles, angular velocities and φ⁰ constants are in radians (135° = 3π/4)",
       "los ángulos, velocidades angulares y constantes φ⁰ van en radianes (135° = 3π/4)"),
    _m("missing_square", "a squared term missing its square", "falta el cuadrado de un término",
       "check every power: l² in the revolute-revolute joint, φ̇² in γ",
       "revisa cada potencia: l² en el par revolución-revolución, φ̇² en γ"),
    # ------------------------------------------------------------- deriving Φ_q, ν, γ
    _m("missing_chain_rule", "missing chain-rule term", "falta un término de la regla de la cadena",
       "A depends on φ: ∂(A s')/∂φ = B s' (and its time derivative brings φ̇); it was treated as constant",
       "A depende de φ: ∂(A s')/∂φ = B s' (y su derivada temporal aporta φ̇); se trató como constante"),
    _m("A_for_B", "A used where B belongs", "A en lugar de B",
       "the derivative of A(φ) is B(φ) = [[−sin φ, −cos φ], [cos φ, −sin φ]], not A itself",
       "la derivada de A(φ) es B(φ) = [[−sen φ, −cos φ], [cos φ, −sen φ]], no la propia A"),
    _m("nu_sign", "ν with the wrong sign", "ν con el signo cambiado",
       "the velocity equations are Φ_q q̇ = ν with ν = −Φ_t (minus the partial derivative in time)",
       "las ecuaciones de velocidad son Φ_q q̇ = ν con ν = −Φ_t (menos la derivada parcial respecto al "
       "tiempo)"),
    _m("nu_missing", "ν missing −Φ_t", "falta −Φ_t en ν",
       "a driver that depends on time has ν = −Φ_t ≠ 0 (for φ − f(t) it is f'(t))",
       "una restricción motriz que depende del tiempo tiene ν = −Φ_t ≠ 0 (para φ − f(t) es f'(t))"),
    _m("gamma_sign", "γ with the wrong sign", "γ con el signo cambiado",
       "γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt; mind the minus sign (the book prints it without the minus "
       "in one place)",
       "γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt; cuidado con el signo menos (el libro lo omite en un lugar)"),
    _m("missing_qt_term", "missing 2Φ_qt q̇", "falta 2Φ_qt q̇",
       "when Φ_q depends on t, γ has the term −2Φ_qt q̇",
       "cuando Φ_q depende de t, γ tiene el término −2Φ_qt q̇"),
    _m("missing_tt_term", "missing Φ_tt", "falta Φ_tt",
       "a driver φ − f(t) contributes −Φ_tt = f''(t) to γ",
       "una restricción motriz φ − f(t) aporta −Φ_tt = f''(t) a γ"),
    # ------------------------------------------------------------- spatial (numbers)
    _m("not_orthogonal", "not an orthogonal matrix", "matriz no ortogonal",
       "a rotation matrix satisfies AᵀA = I and det A = +1",
       "una matriz de rotación cumple AᵀA = I y det A = +1"),
    _m("missing_normalization", "Euler-parameter normalization forgotten",
       "falta la normalización de los parámetros de Euler",
       "every body in space adds the row pᵀp − 1 = 0 to Φ (its Jacobian row is 2pᵀ, its γ is −2ṗᵀṗ)",
       "cada elemento en el espacio añade la fila pᵀp − 1 = 0 a Φ (su fila del jacobiano es 2pᵀ, su γ es "
       "−2ṗᵀṗ)"),
    _m("not_normalized", "Euler parameters not normalized", "parámetros de Euler sin normalizar",
       "Euler parameters satisfy the normalization constraint pᵀp = e0² + e1² + e2² + e3² = 1",
       "los parámetros de Euler cumplen la restricción de normalización pᵀp = e0² + e1² + e2² + e3² = 1"),
    _m("scaled", "off by a constant factor", "difiere en un factor constante",
       "the answer is proportional to the expected one; look for a forgotten factor (2, ½, l …)",
       "la respuesta es proporcional a la esperada; busca un factor olvidado (2, ½, l …)"),
]

MISTAKES = {m.code: m for m in _ENTRIES}
"""Catalogue entries by code."""


def codes():
    """All mistake codes, in catalogue order."""
    return list(MISTAKES)


def explain(code, lang=None):
    """Title and hint of a mistake code in the current (or given) language: ``(title, hint)``."""
    return MISTAKES[code].text(lang)
