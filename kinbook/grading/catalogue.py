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

from ..i18n import N_, Np_, translate
from ._i18n import add_texts

__all__ = ["Mistake", "MISTAKES", "explain", "codes", "CONTEXTS"]

CONTEXTS = ("planar", "spatial", "gear", "rack", "driver", "speed", "accel", "rotation", "parameters", "vector",
            "position", "omega", "angles", "value")
"""Contexts a hint can be written for (the first that the mistake has is used)."""


@dataclass(frozen=True)
class Mistake:
    """One entry of the catalogue.

    Attributes
    ----------
    code : str
        Stable identifier, e.g. ``"swapped_bodies"``.
    title, hint : str
        In English, marked for translation (the Spanish is in the gettext catalogue, :mod:`kinbook.i18n`).
    hints : dict
        Context-specific hints: ``{context: hint}`` (contexts of :data:`CONTEXTS`).
    """

    code: str
    title: str
    hint: str
    hints: dict = field(default_factory=dict)

    def text(self, lang=None, context=None):
        """``(title, hint)`` in ``lang`` (default: the current language), the hint of the first of the
        ``context`` names the entry has."""
        hint = self.hint
        for ctx in ([context] if isinstance(context, str) else list(context or ())):
            if ctx in self.hints:
                hint = self.hints[ctx]
                break
        return translate(self.title, lang), translate(hint, lang)


def _m(code, title, hint, **contexts):
    return Mistake(code, title, hint, dict(contexts))


_ENTRIES = [
    _m("malformed",
       N_("malformed answer"),
       N_("the answer could not be read or evaluated; the message says what was expected")),
    _m("unknown_symbol",
       N_("unknown symbol"),
       N_("write the answer in the mechanism's coordinates x1, y1, phi1, x2 … (φ1 and phi_1 work too), velocities "
           "dx1, dy1, dphi1 … and time t"),
       spatial=N_("write the answer in the coordinates x1, y1, z1, e01, e11, e21, e31, x2 …, velocities dx1, de01 … "
                  "and time t")),
    _m("not_finite",
       N_("not a finite real number"),
       N_("the answer evaluates to NaN, inf or a complex number; look for a division by zero, a square root of a "
           "negative number or an undefined operation")),
    _m("wrong_shape",
       N_("wrong shape"),
       N_("Φ has one row per constraint equation (m rows); Φ_q is m × n, one column per coordinate")),
    _m("transposed",
       N_("transposed matrix"),
       N_("rows and columns exchanged: row k of Φ_q holds ∂Φ_k/∂q, one column per coordinate"),
       rotation=N_("rows and columns exchanged: A maps local to global components (s = A s'), its columns are the "
                   "body axes in global components; Aᵀ maps global to local")),
    _m("missing_row",
       N_("missing row"),
       N_("every constraint contributes its rows, drivers included (the book appends Φ^(d) below Φ)")),
    _m("extra_row",
       N_("extra row"),
       N_("a row that is none of the constraint equations graded here (one too many)")),
    _m("dependent_row",
       N_("dependent row"),
       N_("a row that repeats others (twice the same row, a multiple of one, their square or product, a constant "
           "combination) adds no equation: the set of rows must keep the rank of the constraints — write each "
           "independent equation once")),
    _m("masked_row",
       N_("true only because of another constraint"),
       N_("each constraint's rows must hold for every position of its own bodies: a row that is true only because "
          "another constraint holds too (the ground's φ1 = 0, a driver's angle) is not that constraint's equation — "
          "write each joint's rows without using the other constraints")),
    _m("vanishing_factor",
       N_("a factor that vanishes"),
       N_("a row multiplied by a function of q (cos φ2, e0, x1 …) vanishes wherever that factor does, even where the "
          "joint is broken: its zero set is larger than the constraint's. Multiply a row by a nonzero constant only")),
    _m("only_at_samples",
       N_("right only where it was sampled"),
       N_("the row equals the constraint's at the configurations the checker samples, not at others: each row must be "
          "the constraint's equation at every configuration (the checker compares again at configurations drawn from "
          "the answer itself)")),
    _m("whole_turn",
       N_("a whole turn added to a row that is no angle"),
       N_("2πk (whole turns) may be added to a row that measures an angle — a driver's φ_i − f(t), a slot's φ_i − φ_j "
          "− φ⁰: a body turned by 2π is placed as before. A row that measures a length (a point's x or y, a "
          "distance) changes with it: the joint no longer holds there")),
    _m("row_order",
       N_("rows not in the book's order"),
       N_("the exercise asks for the book's order: constraints in the order of the joint table, drivers last")),
    _m("swapped_entries",
       N_("entries exchanged"),
       N_("the right numbers in the wrong places: check which coordinate, row or column each entry belongs to (q = "
           "[x1, y1, φ1, x2 …]; a point's [x, y]; row k of a matrix is its k-th equation)")),
    _m("zero_row",
       N_("a row that is zero"),
       N_("a row of Φ that is 0 states no equation: each row of a constraint is an expression that vanishes where "
          "the joint holds (and only there)")),
    _m("wrong_value",
       N_("wrong value"),
       N_("the value differs from the reference and matches none of the catalogued mistakes; recheck the derivation "
           "step by step")),
    _m("sign_flip",
       N_("sign error"),
       N_("one term (or a whole row or entry) has the opposite sign; check each term against r_i + A_i s'_i − r_j − "
           "A_j s'_j and its derivatives"),
       gear=N_("a pitch-radius term has the opposite sign: [(φ_i − φ_i⁰) − (φ_k − φ_k⁰)] ρ_i + [(φ_j − φ_j⁰) − (φ_k "
               "− φ_k⁰)] ρ_j = 0 (eq. 38), with ρ < 0 for an internal gear"),
       rack=N_("the rack term has the opposite sign: (φ_i − φ_i⁰) ρ_i − (x_j − x_j⁰) = 0 (eq. 40; eq. 42 adds x_i − "
               "x_i⁰ for a sliding pinion)"),
       driver=N_("the prescribed motion enters as q − f(t) = 0: check the sign of f(t) and of its derivatives (ν = "
                 "f'(t), γ = f''(t) for the driver's row)"),
       spatial=N_("one term has the opposite sign; check each term against r_i + A_i s'_i − r_j − A_j s'_j, d = r_j "
                  "+ A_j s'_j − r_i − A_i s'_i and their derivatives B_k = 2(E_k s̄'_k + s'_k p_kᵀ)"),
       speed=N_("a velocity term has the opposite sign: ṙ^P = ṙ + B s' φ̇ (eq. 10), B = dA/dφ"),
       accel=N_("an acceleration term has the opposite sign: r̈^P = r̈ + B s' φ̈ − A s' φ̇² (eq. 13)"),
       rotation=N_("an entry of the matrix has the opposite sign: rebuild it from the formula the question names "
                   "and check the sign of each product; each column of A is a body axis in global components"),
       parameters=N_("p and −p describe the same orientation, but the question asks for e0 ≥ 0: when e0 comes out "
                     "negative, take −p")),
    _m("missing_term",
       N_("missing term"),
       N_("one term of the reference is absent from the answer"),
       gear=N_("a term of eq. 38 is missing: with a moving carrier k, both wheels turn relative to it, (φ_i − φ_i⁰) "
               "− (φ_k − φ_k⁰)"),
       accel=N_("a term is missing: r̈^P = r̈ + B s' φ̈ − A s' φ̇² has a tangential and a centripetal part"),
       normalization=N_("a body's normalization row pᵀp − 1 = 0 has Φ_q = 2pᵀ, ν = 0 and γ = −2ṗᵀṗ: its γ is not "
                        "zero")),
    _m("swapped_bodies",
       N_("bodies i and j swapped"),
       N_("the joint's roles are not symmetric here: keep body i (the one carrying the axis or the first radius) as "
           "the book's table assigns it"),
       gear=N_("the pitch radii belong to their wheels: ρ_i multiplies the turn of wheel i, ρ_j that of wheel j")),
    _m("swapped_points",
       N_("local points swapped between the bodies"),
       N_("s'_i^P holds the coordinates of P in body i's frame and s'_j^P those in body j's frame; they were swapped")),
    _m("A_transposed",
       N_("Aᵀ used for A"),
       N_("A(φ) = [[cos φ, −sin φ], [sin φ, cos φ]] maps local to global: r^P = r + A s'"),
       spatial=N_("A(p) = 2[(e0² − ½)I + eeᵀ + e0ẽ] maps local to global components: r^P = r + A s'; Aᵀ maps global "
                  "to local")),
    _m("local_vector",
       N_("local instead of global vector"),
       N_("s' has local components (ξ, η); in Φ the vector must be in global components, A s'"),
       spatial=N_("s' has local components (ξ, η, ζ); in Φ every vector must be in global components, A s'")),
    _m("degrees",
       N_("degrees instead of radians"),
       N_("angles, angular velocities and φ⁰ constants are in radians (135° = 3π/4)"),
       rotation=N_("sin and cos take radians: convert the angles first (np.radians), then build the matrix"),
       parameters=N_("the rotation angle χ goes into e0 = cos(χ/2), e = u sin(χ/2) in radians")),
    _m("missing_square",
       N_("a squared term missing its square"),
       N_("check every power: l² in the revolute-revolute joint, φ̇² in γ")),
    _m("book_misprint",
       N_("the book's misprinted formula"),
       N_("the answer follows a formula the book prints wrongly; the erratum shows the correct one and the evidence "
           "(kinbook.book.errata)")),
    _m("missing_chain_rule",
       N_("missing chain-rule term"),
       N_("A depends on φ: ∂(A s')/∂φ = B s' (and its time derivative brings φ̇); it was treated as constant"),
       spatial=N_("A depends on p: ∂(A s')/∂p = 2(E s̄' + s' pᵀ) (Table 14.1's B_k, C_k); it was treated as constant")),
    _m("A_for_B",
       N_("A used where B belongs"),
       N_("the derivative of A(φ) is B(φ) = [[−sin φ, −cos φ], [cos φ, −sin φ]], not A itself")),
    _m("B_for_A",
       N_("B used where A belongs"),
       N_("A(φ) = [[cos φ, −sin φ], [sin φ, cos φ]] itself turns local components into global ones (r^P = r + A s', "
          "eq. 5); B(φ) = dA/dφ appears only where A is differentiated (velocities, eq. 10)")),
    _m("eg_jacobian",
       N_("2Eā without 2apᵀ"),
       N_("∂(A a)/∂p = 2(E ā + a pᵀ) for kinbook's (and Table 14.1's) A = 2[(e0² − ½)I + eeᵀ + e0ẽ]; 2Eā alone is "
           "the derivative of E Gᵀ a, which equals A a only on the unit sphere — its rows differ by multiples of the "
           "normalization row 2pᵀ, and γ must then change too")),
    _m("nu_sign",
       N_("ν with the wrong sign"),
       N_("the velocity equations are Φ_q q̇ = ν with ν = −Φ_t; if your Φ row is the negative of the book's, pass "
           "your Φ as phi=... so that its sign is taken into account")),
    _m("nu_missing",
       N_("ν missing −Φ_t"),
       N_("a driver that depends on time has ν = −Φ_t ≠ 0 (for φ − f(t) it is f'(t))")),
    _m("gamma_sign",
       N_("γ with the wrong sign"),
       N_("γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt; mind the minus sign (the book drops it in one place, erratum "
           "13.8-gamma-sign); if your Φ row is the negative of the book's, pass it as phi=..."),
       spatial=N_("γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt (§14.5), for Table 14.1's rows too: mind the minus sign; if "
                  "your Φ row is the negative of the reference's, pass it as phi=...")),
    _m("missing_qt_term",
       N_("missing 2Φ_qt q̇"),
       N_("when Φ_q depends on t, γ has the term −2Φ_qt q̇")),
    _m("missing_tt_term",
       N_("missing Φ_tt"),
       N_("a driver φ − f(t) contributes −Φ_tt = f''(t) to γ")),
    _m("scaled",
       N_("off by a constant factor"),
       N_("the answer is the expected one times a simple factor; look for a forgotten factor (2, ½, a length) or a "
           "unit conversion applied twice")),
    _m("not_rounded",
       N_("a constant that is not the exercise's, rounded"),
       N_("a decimal that stands for an exact constant (3π/4, √3/2, a length) must be that constant correctly "
          "rounded to at least 3 significant digits — or write it exactly: 3*pi/4, sqrt(3)/2")),
    _m("not_orthogonal",
       N_("not an orthogonal matrix"),
       N_("a rotation matrix satisfies AᵀA = I: its columns are unit vectors, perpendicular to each other")),
    _m("left_handed",
       N_("a left-handed frame (det A = −1)"),
       N_("the columns are orthonormal but form a left-handed frame: the third axis must be ζ = ξ × η (det A = +1)")),
    _m("factor_2_missing",
       N_("factor 2 missing"),
       N_("A(p) = 2[(e0² − ½)I + eeᵀ + e0ẽ]: the book prints the matrix without its factor 2 (erratum 14.3-A-of-p)"),
       vector=N_("ω = 2Eṗ and ω' = 2Gṗ: the factor 2 comes from differentiating A(p), which is quadratic in p")),
    _m("missing_normalization",
       N_("Euler-parameter normalization forgotten"),
       N_("every body in space adds the row pᵀp − 1 = 0 to Φ (its Jacobian row is 2pᵀ, its γ is −2ṗᵀṗ)")),
    _m("not_normalized",
       N_("Euler parameters not normalized"),
       N_("Euler parameters satisfy the normalization constraint pᵀp = e0² + e1² + e2² + e3² = 1")),
    _m("full_angle",
       N_("χ where χ/2 belongs"),
       N_("Euler parameters use half the rotation angle: e0 = cos(χ/2), e = u sin(χ/2)")),
    _m("G_for_E",
       N_("E and G exchanged"),
       N_("ω = 2Eṗ gives the angular velocity in global components, ω' = 2Gṗ in the body's")),
    _m("wrong_frame",
       N_("components in the wrong frame"),
       N_("ω (global components) and ω' (body components) are the same vector in two frames: ω = A ω'")),
    _m("scalar_last",
       N_("e0 written last"),
       N_("kinbook and the book write p = [e0, e1, e2, e3], the scalar part first (scipy's as_quat() gives [e1, e2, "
           "e3, e0])")),
    _m("extrinsic_order",
       N_("turns in the reverse (extrinsic) order"),
       N_("the book's z-x-z angles turn about the moving axes: A = A_z(ψ) A_x(θ) A_z(φ), first ψ; multiplying in the "
           "reverse order turns about the fixed axes")),
    _m("A_for_AT",
       N_("A used where Aᵀ belongs"),
       N_("A maps local to global components (s = A s'); the local components of a global vector are s' = Aᵀ s")),
]

# ------------------------------------------------------------- numeric answers (try-its, exercise parts)
_ENTRIES += [
    _m("wrong_data",
       N_("computed for other data"),
       N_("the answer fits other data than the question's: the values printed earlier in the notebook, or the "
          "notebook's own case instead of this variant's; reread the data of the question")),
    _m("relative_speed",
       N_("speed relative to the carrier"),
       N_("eq. 38 relates the turns relative to the carrier k, (φ_j − φ_j⁰) − (φ_k − φ_k⁰); the absolute speed adds "
          "the carrier's own φ̇_k back")),
    _m("rate_exchanged",
       N_("φ̈ and φ̇² exchanged"),
       N_("in r̈^P = r̈ + B s' φ̈ − A s' φ̇² (eq. 13) the tangential part B s' carries the angular acceleration φ̈ "
          "and the centripetal part −A s' the square of the angular velocity")),
    _m("angle_rates",
       N_("angle rates for ω"),
       N_("[ψ̇, θ̇, φ̇] are not the components of ω or ω': the three rates turn about three different axes (z, the "
          "line of nodes, ζ), and ω' = [ψ̇ sin θ sin φ + θ̇ cos φ, ψ̇ sin θ cos φ − θ̇ sin φ, ψ̇ cos θ + φ̇] (§14.2)")),
    _m("assembly_mode",
       N_("the other assembly mode"),
       N_("Φ(q) = 0 has another solution here — the same driver angle with the loop closed the other way; "
          "Newton–Raphson finds the one nearest its starting guess, so start from the guess the question gives")),
    _m("not_converged",
       N_("iteration not converged"),
       N_("stop Newton–Raphson only when the residual |Φ(q)| and the step |Δq| are both tiny (1e-10, say): an earlier "
          "iterate is not yet a solution")),
    _m("lever_arm",
       N_("lever arm from the wrong point"),
       N_("∂(A s')/∂φ = B s': the lever arm s' runs from the body's own origin (a rocker's O_3, its midpoint in the "
          "book's examples) to the point, not from the pivot it turns about")),
    _m("own_arm",
       N_("each body's own arm in s_iᵀs_j"),
       N_("∂(s_iᵀ s_j)/∂p_i = s_jᵀ C_i: the derivative of body i's arm times the other body's arm s_j (Table 14.1's "
          "n1 row), not s_iᵀ C_i")),
    _m("newton_step",
       N_("not a Newton–Raphson step"),
       N_("each step solves Φ_q(q_k) Δq = −Φ(q_k) at the current iterate, then q_{k+1} = q_k + Δq: mind the minus "
          "sign, evaluate Φ_q and Φ at the current q_k (and at the question's t)")),
]

# ------------------------------------------------------------- what mutation testing found unnamed (issue 29)
_ENTRIES += [
    _m("sin_cos",
       N_("sin and cos exchanged"),
       N_("in A(φ) = [[cos φ, −sin φ], [sin φ, cos φ]] the cosine sits on the diagonal: ξ goes with cos φ in x and "
          "with sin φ in y (eq. 5); write each product from A's row, not from memory"),
       rotation=N_("each elementary turn has its cosines on the diagonal and ±sin off it: write A_z and A_x from "
                   "their definitions (§14.2), not from memory"),
       angles=N_("θ = arccos a33, not arcsin: the third row of A is [sin θ sin φ, sin θ cos φ, cos θ] (§14.2)"),
       omega=N_("write ω' = [ψ̇ sin θ sin φ + θ̇ cos φ, ψ̇ sin θ cos φ − θ̇ sin φ, ψ̇ cos θ + φ̇] term by term: each "
                "sine and cosine belongs to one angle's projection (§14.2)"),
       parameters=N_("e0 = cos(χ/2) and e = u sin(χ/2): the cosine goes with e0, the sine with the axis")),
    _m("other_body",
       N_("the other body's coordinate"),
       N_("each point turns with its own body: A_i s'_i takes body i's angle φ_i (and its rate φ̇_i), A_j s'_j body "
          "j's; check which body each point, angle and rate belongs to")),
    _m("radians_twice",
       N_("an angle converted to radians twice"),
       N_("the angle is already in radians (the coordinates φ_i, the result of arctan2 or arccos): convert only a "
          "value given in degrees, once")),
    _m("arctan_quadrant",
       N_("arctan where arctan2 belongs"),
       N_("arctan(y/x) returns an angle in (−90°, 90°) and loses the quadrant when x < 0: read the angle with "
          "arctan2(y, x), which keeps the signs of both")),
    _m("factor_2_extra",
       N_("a term counted twice"),
       N_("a term is twice what it should be: the 2 of 2Φ_qt q̇ belongs to the cross terms only; the squared rates "
          "φ̇² come once (eq. 13)")),
]

MISTAKES = {m.code: m for m in _ENTRIES}
"""Catalogue entries by code."""


def _hints_for(code, **contexts):
    """More context hints for an entry (the hint follows the quantity asked: a number, a point's position …)."""
    MISTAKES[code].hints.update(contexts)


_hints_for(
    "sign_flip",
    position=N_("a term has the opposite sign: x^P = x + ξ cos φ − η sin φ, y^P = y + ξ sin φ + η cos φ (eq. 5)"),
    omega=N_("a sign is wrong: ω = 2Eṗ with E = [−e, ẽ + e0 I], ω' = 2Gṗ with G = [−e, −ẽ + e0 I] (§14.3)"),
    angles=N_("a sign is wrong: read θ = arccos a33, ψ = atan2(a13, −a23), φ = atan2(a31, a32) from the z-x-z A "
              "(§14.2)"),
    value=N_("the sign of your number is wrong: write the formula term by term and check each term's sign against the "
             "book's equation"))
_hints_for(
    "local_vector",
    position=N_("s' has local components (ξ, η); turn it into global ones with A before adding it to r: r^P = r + A "
                "s' (eq. 5)"))
_hints_for(
    "A_for_B",
    position=N_("a position uses A: r^P = r + A s' (eq. 5); B = dA/dφ belongs to velocities (eq. 10)"),
    speed=N_("differentiate A s' in time: d(A s')/dt = B s' φ̇ with B = dA/dφ (eq. 10), not A s' φ̇"),
    accel=N_("in r̈^P = r̈ + B s' φ̈ − A s' φ̇² (eq. 13) B goes with φ̈ and A with φ̇²"))
_hints_for(
    "swapped_entries",
    accel=N_("the right numbers in the wrong places: x comes before y, and each row of γ belongs to the row of Φ it "
             "comes from (a revolute joint's x row, then its y row)"),
    speed=N_("the right numbers in the wrong places: x comes before y, and each row of ν belongs to the row of Φ it "
             "comes from"),
    angles=N_("the z-x-z angles come in the order of the turns: ψ (about z), θ (about the line of nodes), φ (about ζ)"),
    vector=N_("the right numbers in the wrong places: a vector's components come in the order x, y(, z)"),
    value=N_("the right numbers in the wrong places: check which entry each number belongs to"))
_hints_for(
    "wrong_frame",
    vector=N_("s (global components) and s' (body components) are one arrow in two frames: s = A s', s' = Aᵀ s (eq. "
              "9)"),
    position=N_("r^P = r + A s': r is already in global components, only s' is turned"),
    omega=N_("ω (global components) and ω' (body components) are the same vector in two frames: ω = A ω'"))
_hints_for(
    "transposed",
    angles=N_("these are the angles of Aᵀ (the passive reading): the book's A maps body to global components, its "
              "third row is [sin θ sin φ, sin θ cos φ, cos θ]"))
_hints_for(
    "extrinsic_order",
    angles=N_("ψ and φ exchanged: ψ is read from the third column (a13, −a23), φ from the third row (a31, a32)"))
_hints_for(
    "degrees",
    value=N_("angles and angular velocities are in radians (np.radians(90) = π/2): convert before you multiply or "
             "take a sine"),
    angles=N_("give the angles in radians (np.radians converts; atan2 and arccos already return radians)"))
_hints_for(
    "missing_term",
    position=N_("r^P = r + A s' (eq. 5 in the plane, §14.1 in space): the body's origin plus the turned local vector"))


def codes():
    """All mistake codes, in catalogue order."""
    return list(MISTAKES)


def explain(code, lang=None, context=None):
    """Title and hint of a mistake code in the current (or given) language and context: ``(title, hint)``."""
    return MISTAKES[code].text(lang, context)


# Details: what exactly was found (named in a row's message after the title)
add_texts({
    "d.sign_of": N_("the sign of {what}"),
    "d.sign_of_term": N_("the sign of the term {term}"),
    "d.missing_term": N_("the term {term} is missing"),
    "d.coordinate": N_("{name} of body {body}"),
    "d.local": N_("{coord} of {point} on body {body}"),
    "d.point": N_("{point} on body {body} (A s')"),
    "d.radius": N_("the pitch radius of wheel {body}"),
    "d.length_not_squared": N_("l instead of l²"),
    "d.constant_degrees": N_("the constant {name} in degrees"),
    "d.function_degrees": N_("f(t) in degrees"),
    "d.book_row": N_("see erratum {id}"),
    "d.factor": N_("factor {c}"),
    "d.factor_length": N_("the length {a}–{b} of body {body}"),
    "d.factor_radius": N_("the distance of {point} from the origin of body {body}"),
    "d.factor_local": N_("the length |{a}| of body {body}"),
    "d.factor_local_pair": N_("the length |{a} − {b}| of body {body}"),
    "d.factor_joint_length": N_("the joint's length {name}"),
    "d.multiplied_by": N_("multiplied by {c}, {what}"),
    "d.row_of": N_("this is the row that belongs to {other}; the row of {row} goes here (each row is derived from its "
                   "own row of Φ)"),
    "d.zero_like": N_("your row is 0 — it is also what the mistake '{code}' gives for {ref}"),
    "d.or_sign_of_term": N_("the same expression as the sign of the term {term} slipped: check both"),
    "d.jacobian_of": N_("the Jacobian of {c}·{ref}: the derivative of {ref} keeps all its factors (the 2 of ∂(dᵀd)/∂q = "
                        "2dᵀ∂d/∂q, of A(p) = 2[…]); pass your own Φ as phi= if you scaled it"),
    "d.degrees_value": N_("{got} is {expected} rad in degrees"),
    "d.not_rounded": N_("a constant differs from the exercise's: {value} is not {exact} rounded ({digits} significant "
                        "digits); round it correctly to at least 3 digits, or write {exact}"),
    "d.on_body": N_("{what} on body {body} only"),
    "d.other_angle": N_("A of body {body} built with the orientation of body {other}"),
    "d.length_dropped": N_("the length term −l² is missing"),
    "d.rotation_columns": N_("the derivative of A s' written in the other body's rotation columns: each body's "
                             "B s' (∂/∂φ, ∂/∂p) goes under its own coordinates"),
    "d.angles_exchanged": N_("the two bodies' orientations exchanged: each A built with the other body's angle"),
    "d.motion_degrees": N_("the motion f(t) − f(0) (its amplitude or its rate) in degrees"),
    "d.cross_terms": N_("the cross terms (products of one body's velocities with the other's)"),
    "d.dC_missing": N_("dᵀC_i, the derivative of s_i, is missing: s_i = A_i s'_i depends on p_i too"),
    "d.vanishing": N_("the factor {factor} vanishes at {where}, where your row is zero although {ref} = {value} is "
                      "not"),
    "d.vanishing_jacobian": N_("your row is f(q) × {ref}'s row, and f goes from {lo} to {hi} over the "
                               "configurations compared: it vanishes in between"),
    "d.only_at_samples": N_("equal to {ref} at the sampled configurations, but not at {where}"),
    "d.whole_turn": N_("your row is {row}, and {ref} does not measure an angle: a whole turn leaves only an angle as it "
                       "was"),
    "d.vanishing_at": N_("your row vanishes at {where}, where {ref} = {value} does not"),
    # the same details, the term described and not written (a try-it: the term written out is the answer)
    "d.sign_of_kind": N_("the term with the wrong sign is {kind}"),
    "d.missing_kind": N_("the one missing is {kind}"),
    "d.or_sign_of_kind": N_("the same expression as a term's sign slipped ({kind}): check both"),
    "k.constant": N_("a constant"),
    "k.time": N_("a term of t alone (from the driver's function of time)"),
    "k.velocity_squared": N_("a term quadratic in the velocities"),
    "k.velocity": N_("a term linear in the velocities"),
    "k.rotation": N_("a term of a body's rotation (its angle or Euler parameters)"),
    "k.origin": N_("a term of a body's origin (x, y, z)"),
    "k.of_bodies": Np_("{what}, of body {bodies}", "{what}, of bodies {bodies}"),
})
