"""The mistake catalogue: every mistake a checker can name, with a stable code, a title and a hint.

Codes are stable: exercises, tests and grade books refer to them. docs/mistakes.md documents each one with an
example; :func:`explain` gives the title and hint in the current language (see :func:`kinbook.set_language`),
in the notation of the context the mistake was found in: a spatial joint's hint shows spatial formulas, a
gear row's the gear equation, a speed (ν) or an acceleration (γ) their own.

Mistakes are detected by *generating* the wrong answer from kinbook's reference (:mod:`kinbook.grading.mistakes`)
and testing the student's answer for equality with it, so a code is only reported when the answer really is
that mistake.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ._i18n import add_texts, get_language

__all__ = ["Mistake", "MISTAKES", "explain", "codes", "CONTEXTS"]

CONTEXTS = ("planar", "spatial", "gear", "rack", "driver", "speed", "accel", "rotation", "parameters", "vector")
"""Contexts a hint can be written for (the first that the mistake has is used)."""


@dataclass(frozen=True)
class Mistake:
    """One entry of the catalogue.

    Attributes
    ----------
    code : str
        Stable identifier, e.g. ``"swapped_bodies"``.
    title, hint : dict
        ``{"en": ..., "es": ...}``.
    hints : dict
        Context-specific hints: ``{context: {"en": ..., "es": ...}}`` (contexts of :data:`CONTEXTS`).
    """

    code: str
    title: dict
    hint: dict
    hints: dict = field(default_factory=dict)

    def text(self, lang=None, context=None):
        lang = lang or get_language()
        hint = self.hint
        for ctx in ([context] if isinstance(context, str) else list(context or ())):
            if ctx in self.hints:
                hint = self.hints[ctx]
                break
        return self.title.get(lang, self.title["en"]), hint.get(lang, hint["en"])


def _m(code, title_en, title_es, hint_en, hint_es, **contexts):
    hints = {k: {"en": v[0], "es": v[1]} for k, v in contexts.items()}
    return Mistake(code, {"en": title_en, "es": title_es}, {"en": hint_en, "es": hint_es}, hints)


_ENTRIES = [
    # ------------------------------------------------------------- form of the answer
    _m("malformed", "malformed answer", "respuesta mal formada",
       "the answer could not be read or evaluated; the message says what was expected",
       "la respuesta no se pudo leer o evaluar; el mensaje indica qué se esperaba"),
    _m("unknown_symbol", "unknown symbol", "símbolo desconocido",
       "write the answer in the mechanism's coordinates x1, y1, phi1, x2 … (φ1 and phi_1 work too), velocities "
       "dx1, dy1, dphi1 … and time t",
       "escribe la respuesta en las coordenadas del mecanismo x1, y1, phi1, x2 … (también φ1 y phi_1), "
       "velocidades dx1, dy1, dphi1 … y el tiempo t",
       spatial=("write the answer in the coordinates x1, y1, z1, e01, e11, e21, e31, x2 …, velocities dx1, de01 "
                "… and time t",
                "escribe la respuesta en las coordenadas x1, y1, z1, e01, e11, e21, e31, x2 …, velocidades dx1, "
                "de01 … y el tiempo t")),
    _m("not_finite", "not a finite real number", "no es un número real finito",
       "the answer evaluates to NaN, inf or a complex number; look for a division by zero, a square root of a "
       "negative number or an undefined operation",
       "la respuesta da NaN, inf o un número complejo; busca una división por cero, la raíz de un número "
       "negativo o una operación no definida"),
    _m("wrong_shape", "wrong shape", "forma incorrecta",
       "Φ has one row per constraint equation (m rows); Φ_q is m × n, one column per coordinate",
       "Φ tiene una fila por ecuación de restricción (m filas); Φ_q es m × n, una columna por coordenada"),
    _m("transposed", "transposed matrix", "matriz traspuesta",
       "rows and columns exchanged: row k of Φ_q holds ∂Φ_k/∂q, one column per coordinate",
       "filas y columnas intercambiadas: la fila k de Φ_q contiene ∂Φ_k/∂q, una columna por coordenada",
       rotation=("rows and columns exchanged: A maps local to global components (s = A s'), its columns are "
                 "the body axes in global components; Aᵀ maps global to local",
                 "filas y columnas intercambiadas: A pasa de componentes locales a globales (s = A s'), sus "
                 "columnas son los ejes del elemento en componentes globales; Aᵀ pasa de globales a locales")),
    _m("missing_row", "missing row", "falta una fila",
       "every constraint contributes its rows, drivers included (the book appends Φ^(d) below Φ)",
       "cada restricción aporta sus filas, también las motrices (el libro añade Φ^(d) debajo de Φ)"),
    _m("extra_row", "extra row", "fila sobrante",
       "a row that is none of the constraint equations graded here (one too many)",
       "una fila que no es ninguna de las ecuaciones de restricción que se califican aquí (una de más)"),
    _m("dependent_row", "dependent row", "fila dependiente",
       "a row that repeats others (twice the same row, a multiple of one, their square or product, a constant "
       "combination) adds no equation: the set of rows must keep the rank of the constraints — write each "
       "independent equation once",
       "una fila que repite otras (la misma fila dos veces, un múltiplo de una, su cuadrado o su producto, una "
       "combinación constante) no aporta ninguna ecuación: el conjunto de filas debe mantener el rango de las "
       "restricciones — escribe cada ecuación independiente una vez"),
    _m("row_order", "rows not in the book's order", "filas fuera del orden del libro",
       "the exercise asks for the book's order: constraints in the order of the joint table, drivers last",
       "el ejercicio pide el orden del libro: restricciones en el orden de la tabla de pares, las motrices "
       "al final"),
    _m("swapped_entries", "entries exchanged", "elementos intercambiados",
       "the right numbers in the wrong places: check which coordinate, row or column each entry belongs to "
       "(q = [x1, y1, φ1, x2 …]; a point's [x, y]; row k of a matrix is its k-th equation)",
       "los números correctos en posiciones equivocadas: comprueba a qué coordenada, fila o columna corresponde "
       "cada elemento (q = [x1, y1, φ1, x2 …]; [x, y] de un punto; la fila k de una matriz es su ecuación k)"),
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
       "r_i + A_i s'_i − r_j − A_j s'_j y sus derivadas",
       gear=("a pitch-radius term has the opposite sign: [(φ_i − φ_i⁰) − (φ_k − φ_k⁰)] ρ_i + "
             "[(φ_j − φ_j⁰) − (φ_k − φ_k⁰)] ρ_j = 0 (eq. 38), with ρ < 0 for an internal gear",
             "un término de radio primitivo tiene el signo cambiado: [(φ_i − φ_i⁰) − (φ_k − φ_k⁰)] ρ_i + "
             "[(φ_j − φ_j⁰) − (φ_k − φ_k⁰)] ρ_j = 0 (ec. 38), con ρ < 0 para un engranaje interior"),
       rack=("the rack term has the opposite sign: (φ_i − φ_i⁰) ρ_i − (x_j − x_j⁰) = 0 (eq. 40; eq. 42 adds "
             "x_i − x_i⁰ for a sliding pinion)",
             "el término de la cremallera tiene el signo cambiado: (φ_i − φ_i⁰) ρ_i − (x_j − x_j⁰) = 0 (ec. 40; "
             "la ec. 42 añade x_i − x_i⁰ si el piñón se desplaza)"),
       driver=("the prescribed motion enters as q − f(t) = 0: check the sign of f(t) and of its derivatives "
               "(ν = f'(t), γ = f''(t) for the driver's row)",
               "el movimiento prescrito entra como q − f(t) = 0: revisa el signo de f(t) y de sus derivadas "
               "(ν = f'(t), γ = f''(t) en la fila de la restricción motriz)"),
       spatial=("one term has the opposite sign; check each term against r_i + A_i s'_i − r_j − A_j s'_j, "
                "d = r_j + A_j s'_j − r_i − A_i s'_i and their derivatives B_k = 2(E_k s̄'_k + s'_k p_kᵀ)",
                "un término tiene el signo cambiado; compara cada término con r_i + A_i s'_i − r_j − A_j s'_j, "
                "d = r_j + A_j s'_j − r_i − A_i s'_i y sus derivadas B_k = 2(E_k s̄'_k + s'_k p_kᵀ)"),
       speed=("a velocity term has the opposite sign: ṙ^P = ṙ + B s' φ̇ (eq. 10), B = dA/dφ",
              "un término de velocidad tiene el signo cambiado: ṙ^P = ṙ + B s' φ̇ (ec. 10), B = dA/dφ"),
       accel=("an acceleration term has the opposite sign: r̈^P = r̈ + B s' φ̈ − A s' φ̇² (eq. 13)",
              "un término de aceleración tiene el signo cambiado: r̈^P = r̈ + B s' φ̈ − A s' φ̇² (ec. 13)")),
    _m("missing_term", "missing term", "falta un término",
       "one term of the reference is absent from the answer",
       "un término de la referencia no aparece en la respuesta",
       gear=("a term of eq. 38 is missing: with a moving carrier k, both wheels turn relative to it, "
             "(φ_i − φ_i⁰) − (φ_k − φ_k⁰)",
             "falta un término de la ec. 38: con un portasatélites k móvil, ambas ruedas giran respecto a él, "
             "(φ_i − φ_i⁰) − (φ_k − φ_k⁰)"),
       accel=("a term is missing: r̈^P = r̈ + B s' φ̈ − A s' φ̇² has a tangential and a centripetal part",
              "falta un término: r̈^P = r̈ + B s' φ̈ − A s' φ̇² tiene una parte tangencial y una centrípeta")),
    _m("swapped_bodies", "bodies i and j swapped", "elementos i y j intercambiados",
       "the joint's roles are not symmetric here: keep body i (the one carrying the axis or the first "
       "radius) as the book's table assigns it",
       "los papeles del par no son simétricos aquí: mantén el elemento i (el que lleva el eje o el primer "
       "radio) como asigna la tabla del libro",
       gear=("the pitch radii belong to their wheels: ρ_i multiplies the turn of wheel i, ρ_j that of wheel j",
             "los radios primitivos pertenecen a sus ruedas: ρ_i multiplica el giro de la rueda i, ρ_j el de la "
             "rueda j")),
    _m("swapped_points", "local points swapped between the bodies", "puntos locales intercambiados",
       "s'_i^P holds the coordinates of P in body i's frame and s'_j^P those in body j's frame; they were "
       "swapped",
       "s'_i^P contiene las coordenadas de P en el sistema del elemento i y s'_j^P las del elemento j; están "
       "intercambiadas"),
    _m("A_transposed", "Aᵀ used for A", "Aᵀ en lugar de A",
       "A(φ) = [[cos φ, −sin φ], [sin φ, cos φ]] maps local to global: r^P = r + A s'",
       "A(φ) = [[cos φ, −sen φ], [sen φ, cos φ]] pasa de locales a globales: r^P = r + A s'",
       spatial=("A(p) = 2[(e0² − ½)I + eeᵀ + e0ẽ] maps local to global components: r^P = r + A s'; Aᵀ maps "
                "global to local",
                "A(p) = 2[(e0² − ½)I + eeᵀ + e0ẽ] pasa de componentes locales a globales: r^P = r + A s'; Aᵀ "
                "pasa de globales a locales")),
    _m("local_vector", "local instead of global vector", "vector local en lugar de global",
       "s' has local components (ξ, η); in Φ the vector must be in global components, A s'",
       "s' tiene componentes locales (ξ, η); en Φ el vector debe ir en componentes globales, A s'",
       spatial=("s' has local components (ξ, η, ζ); in Φ every vector must be in global components, A s'",
                "s' tiene componentes locales (ξ, η, ζ); en Φ todo vector debe ir en componentes globales, A s'")),
    _m("degrees", "degrees instead of radians", "grados en lugar de radianes",
       "angles, angular velocities and φ⁰ constants are in radians (135° = 3π/4)",
       "los ángulos, velocidades angulares y constantes φ⁰ van en radianes (135° = 3π/4)",
       rotation=("sin and cos take radians: convert the angles first (np.radians), then build the matrix",
                 "sen y cos toman radianes: convierte primero los ángulos (np.radians) y luego construye la "
                 "matriz"),
       parameters=("the rotation angle χ goes into e0 = cos(χ/2), e = u sin(χ/2) in radians",
                   "el ángulo de giro χ entra en e0 = cos(χ/2), e = u sen(χ/2) en radianes")),
    _m("missing_square", "a squared term missing its square", "falta el cuadrado de un término",
       "check every power: l² in the revolute-revolute joint, φ̇² in γ",
       "revisa cada potencia: l² en el par revolución-revolución, φ̇² en γ"),
    _m("book_misprint", "the book's misprinted formula", "la fórmula errónea del libro",
       "the answer follows a formula the book prints wrongly; the erratum shows the correct one and the "
       "evidence (kinbook.book.errata)",
       "la respuesta sigue una fórmula que el libro imprime mal; la errata muestra la correcta y la "
       "evidencia (kinbook.book.errata)"),
    # ------------------------------------------------------------- deriving Φ_q, ν, γ
    _m("missing_chain_rule", "missing chain-rule term", "falta un término de la regla de la cadena",
       "A depends on φ: ∂(A s')/∂φ = B s' (and its time derivative brings φ̇); it was treated as constant",
       "A depende de φ: ∂(A s')/∂φ = B s' (y su derivada temporal aporta φ̇); se trató como constante",
       spatial=("A depends on p: ∂(A s')/∂p = 2(E s̄' + s' pᵀ) (Table 14.1's B_k, C_k); it was treated as "
                "constant",
                "A depende de p: ∂(A s')/∂p = 2(E s̄' + s' pᵀ) (B_k, C_k de la Tabla 14.1); se trató como "
                "constante")),
    _m("A_for_B", "A used where B belongs", "A en lugar de B",
       "the derivative of A(φ) is B(φ) = [[−sin φ, −cos φ], [cos φ, −sin φ]], not A itself",
       "la derivada de A(φ) es B(φ) = [[−sen φ, −cos φ], [cos φ, −sen φ]], no la propia A"),
    _m("eg_jacobian", "2Eā without 2apᵀ", "2Eā sin 2apᵀ",
       "∂(A a)/∂p = 2(E ā + a pᵀ) for kinbook's (and Table 14.1's) A = 2[(e0² − ½)I + eeᵀ + e0ẽ]; 2Eā alone is "
       "the derivative of E Gᵀ a, which equals A a only on the unit sphere — its rows differ by multiples of "
       "the normalization row 2pᵀ, and γ must then change too",
       "∂(A a)/∂p = 2(E ā + a pᵀ) para la A = 2[(e0² − ½)I + eeᵀ + e0ẽ] de kinbook (y de la Tabla 14.1); 2Eā "
       "sola es la derivada de E Gᵀ a, que solo coincide con A a sobre la esfera unidad — sus filas difieren en "
       "múltiplos de la fila de normalización 2pᵀ, y entonces γ también cambia"),
    _m("nu_sign", "ν with the wrong sign", "ν con el signo cambiado",
       "the velocity equations are Φ_q q̇ = ν with ν = −Φ_t; if your Φ row is the negative of the book's, pass "
       "your Φ as phi=... so that its sign is taken into account",
       "las ecuaciones de velocidad son Φ_q q̇ = ν con ν = −Φ_t; si tu fila de Φ es la opuesta de la del libro, "
       "pasa tu Φ como phi=... para que se tenga en cuenta su signo"),
    _m("nu_missing", "ν missing −Φ_t", "falta −Φ_t en ν",
       "a driver that depends on time has ν = −Φ_t ≠ 0 (for φ − f(t) it is f'(t))",
       "una restricción motriz que depende del tiempo tiene ν = −Φ_t ≠ 0 (para φ − f(t) es f'(t))"),
    _m("gamma_sign", "γ with the wrong sign", "γ con el signo cambiado",
       "γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt; mind the minus sign (the book drops it in one place, erratum "
       "13.8-gamma-sign); if your Φ row is the negative of the book's, pass it as phi=...",
       "γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt; cuidado con el signo menos (el libro lo omite en un lugar, errata "
       "13.8-gamma-sign); si tu fila de Φ es la opuesta de la del libro, pásala como phi=..."),
    _m("missing_qt_term", "missing 2Φ_qt q̇", "falta 2Φ_qt q̇",
       "when Φ_q depends on t, γ has the term −2Φ_qt q̇",
       "cuando Φ_q depende de t, γ tiene el término −2Φ_qt q̇"),
    _m("missing_tt_term", "missing Φ_tt", "falta Φ_tt",
       "a driver φ − f(t) contributes −Φ_tt = f''(t) to γ",
       "una restricción motriz φ − f(t) aporta −Φ_tt = f''(t) a γ"),
    # ------------------------------------------------------------- numbers, rotations, Euler parameters
    _m("scaled", "off by a constant factor", "difiere en un factor constante",
       "the answer is the expected one times a simple factor; look for a forgotten factor (2, ½, a length) or a "
       "unit conversion applied twice",
       "la respuesta es la esperada multiplicada por un factor sencillo; busca un factor olvidado (2, ½, una "
       "longitud) o una conversión de unidades aplicada dos veces"),
    _m("not_orthogonal", "not an orthogonal matrix", "matriz no ortogonal",
       "a rotation matrix satisfies AᵀA = I: its columns are unit vectors, perpendicular to each other",
       "una matriz de rotación cumple AᵀA = I: sus columnas son vectores unitarios, perpendiculares entre sí"),
    _m("left_handed", "a left-handed frame (det A = −1)", "un sistema a izquierdas (det A = −1)",
       "the columns are orthonormal but form a left-handed frame: the third axis must be ζ = ξ × η (det A = +1)",
       "las columnas son ortonormales pero forman un sistema a izquierdas: el tercer eje debe ser ζ = ξ × η "
       "(det A = +1)"),
    _m("factor_2_missing", "factor 2 missing", "falta el factor 2",
       "A(p) = 2[(e0² − ½)I + eeᵀ + e0ẽ]: the book prints the matrix without its factor 2 (erratum 14.3-A-of-p)",
       "A(p) = 2[(e0² − ½)I + eeᵀ + e0ẽ]: el libro imprime la matriz sin su factor 2 (errata 14.3-A-of-p)",
       vector=("ω = 2Eṗ and ω' = 2Gṗ: the factor 2 comes from differentiating A(p), which is quadratic in p",
               "ω = 2Eṗ y ω' = 2Gṗ: el factor 2 viene de derivar A(p), que es cuadrática en p")),
    _m("missing_normalization", "Euler-parameter normalization forgotten",
       "falta la normalización de los parámetros de Euler",
       "every body in space adds the row pᵀp − 1 = 0 to Φ (its Jacobian row is 2pᵀ, its γ is −2ṗᵀṗ)",
       "cada elemento en el espacio añade la fila pᵀp − 1 = 0 a Φ (su fila del jacobiano es 2pᵀ, su γ es "
       "−2ṗᵀṗ)"),
    _m("not_normalized", "Euler parameters not normalized", "parámetros de Euler sin normalizar",
       "Euler parameters satisfy the normalization constraint pᵀp = e0² + e1² + e2² + e3² = 1",
       "los parámetros de Euler cumplen la restricción de normalización pᵀp = e0² + e1² + e2² + e3² = 1"),
    _m("full_angle", "χ where χ/2 belongs", "χ en lugar de χ/2",
       "Euler parameters use half the rotation angle: e0 = cos(χ/2), e = u sin(χ/2)",
       "los parámetros de Euler usan la mitad del ángulo de giro: e0 = cos(χ/2), e = u sen(χ/2)"),
    _m("G_for_E", "E and G exchanged", "E y G intercambiadas",
       "ω = 2Eṗ gives the angular velocity in global components, ω' = 2Gṗ in the body's",
       "ω = 2Eṗ da la velocidad angular en componentes globales, ω' = 2Gṗ en las del elemento"),
    _m("wrong_frame", "components in the wrong frame", "componentes en el sistema equivocado",
       "ω (global components) and ω' (body components) are the same vector in two frames: ω = A ω'",
       "ω (componentes globales) y ω' (componentes del elemento) son el mismo vector en dos sistemas: ω = A ω'"),
    _m("scalar_last", "e0 written last", "e0 escrito al final",
       "kinbook and the book write p = [e0, e1, e2, e3], the scalar part first (scipy's as_quat() gives "
       "[e1, e2, e3, e0])",
       "kinbook y el libro escriben p = [e0, e1, e2, e3], con la parte escalar primero (as_quat() de scipy da "
       "[e1, e2, e3, e0])"),
    _m("extrinsic_order", "turns in the reverse (extrinsic) order", "giros en el orden inverso (extrínseco)",
       "the book's z-x-z angles turn about the moving axes: A = A_z(ψ) A_x(θ) A_z(φ), first ψ; multiplying in "
       "the reverse order turns about the fixed axes",
       "los ángulos z-x-z del libro giran alrededor de los ejes móviles: A = A_z(ψ) A_x(θ) A_z(φ), primero ψ; "
       "multiplicar en el orden inverso gira alrededor de los ejes fijos"),
    _m("A_for_AT", "A used where Aᵀ belongs", "A en lugar de Aᵀ",
       "A maps local to global components (s = A s'); the local components of a global vector are s' = Aᵀ s",
       "A pasa de componentes locales a globales (s = A s'); las componentes locales de un vector global son "
       "s' = Aᵀ s"),
]

MISTAKES = {m.code: m for m in _ENTRIES}
"""Catalogue entries by code."""


def codes():
    """All mistake codes, in catalogue order."""
    return list(MISTAKES)


def explain(code, lang=None, context=None):
    """Title and hint of a mistake code in the current (or given) language and context: ``(title, hint)``."""
    return MISTAKES[code].text(lang, context)


# Details: what exactly was found (named in a row's message after the title)
add_texts({
    "d.sign_of": {"en": "the sign of {what}", "es": "el signo de {what}"},
    "d.sign_of_term": {"en": "the sign of the term {term}", "es": "el signo del término {term}"},
    "d.missing_term": {"en": "the term {term} is missing", "es": "falta el término {term}"},
    "d.coordinate": {"en": "{name} of body {body}", "es": "{name} del elemento {body}"},
    "d.local": {"en": "{coord} of {point} on body {body}", "es": "{coord} de {point} en el elemento {body}"},
    "d.point": {"en": "{point} on body {body} (A s')", "es": "{point} en el elemento {body} (A s')"},
    "d.radius": {"en": "the pitch radius of wheel {body}", "es": "el radio primitivo de la rueda {body}"},
    "d.length_not_squared": {"en": "l instead of l²", "es": "l en lugar de l²"},
    "d.constant_degrees": {"en": "the constant {name} in degrees", "es": "la constante {name} en grados"},
    "d.function_degrees": {"en": "f(t) in degrees", "es": "f(t) en grados"},
    "d.book_row": {"en": "see erratum {id}", "es": "ver la errata {id}"},
    "d.factor": {"en": "factor {c}", "es": "factor {c}"},
    "d.factor_length": {"en": "the length {a}–{b} of body {body}", "es": "la longitud {a}–{b} del elemento {body}"},
    "d.factor_radius": {"en": "the distance of {point} from the origin of body {body}",
                        "es": "la distancia de {point} al origen del elemento {body}"},
    "d.factor_local": {"en": "the length |{a}| of body {body}", "es": "la longitud |{a}| del elemento {body}"},
    "d.factor_local_pair": {"en": "the length |{a} − {b}| of body {body}",
                            "es": "la longitud |{a} − {b}| del elemento {body}"},
    "d.factor_joint_length": {"en": "the joint's length {name}", "es": "la longitud {name} del par"},
    "d.multiplied_by": {"en": "multiplied by {c}, {what}", "es": "multiplicada por {c}, {what}"},
    "d.degrees_value": {"en": "{got} is {expected} rad in degrees", "es": "{got} es {expected} rad en grados"},
})
