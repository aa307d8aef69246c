"""The constraint family (registration by type name per chapter, declared keys, composites, the compiled
numeric path) and the mechanism that owns its caches (one version counter, one cache)."""

import numpy as np
import pytest
import sympy as sp

import kinbook
from kinbook import ModelError, planar, spatial
from kinbook.core.registry import constraint_class, constraint_types


# --------------------------------------------------------------------------------------------- a new type
class Slot(planar.Constraint):
    """Pin P of body i in a circular slot of radius ρ about centre C of body j."""

    type_name = "test-circular-slot"
    label = "r-c"
    n_eq = 1
    measures = ("length^2",)
    points = {"pin": "i", "centre": "j"}
    numbers = ("radius",)

    def phi(self, Q, t=None):
        d = self.point(Q, "pin") - self.point(Q, "centre")
        return [d.dot(d) - self.radius**2]


def _pendulum():
    m = planar.Mechanism("slot")
    m.add_body("ground", points={"C": (1, 0), "O": (0, 0)})
    m.add_body("bar", points={"O": (0, 0), "P": (2, 0)}, q0=(0, 0, 0.1))
    m.add(planar.Ground("ground"))
    m.add(planar.Revolute("ground", "bar", point="O"))
    return m


def test_a_subclass_registers_itself_in_its_chapter():
    assert constraint_types("planar")["test-circular-slot"] is Slot
    assert planar.CONSTRAINT_TYPES["test-circular-slot"] is Slot  # the live view of the registry
    assert "test-circular-slot" not in constraint_types("spatial")
    assert constraint_class("planar", "test-circular-slot") is Slot
    with pytest.raises(ModelError, match=r"must be one of the spatial constraint types .*got 'test-circular-slot'"):
        constraint_class("spatial", "test-circular-slot")
    assert Slot.title == "test-circular-slot joint"


def test_a_declared_type_gets_its_constructor_and_binds_its_keys():
    c = Slot("bar", "ground", pin="P", centre="C", radius=1)
    assert list(__import__("inspect").signature(Slot).parameters) == ["i", "j", "pin", "centre", "radius", "name"]
    m = _pendulum()
    m.add(c)
    assert c.pin == (2, 0) and c.centre == (1, 0) and c.radius == 1
    (x1, y1, p1), (x2, y2, p2) = m.body_symbols("ground"), m.body_symbols("bar")
    expected = (x2 + 2 * sp.cos(p2) - x1 - sp.cos(p1)) ** 2 + (y2 + 2 * sp.sin(p2) - y1 - sp.sin(p1)) ** 2 - 1
    assert sp.simplify(m.constraint_phi(c)[0] - expected) == 0
    with pytest.raises(ModelError, match="missing a required argument: 'radius'"):
        Slot("bar", "ground", pin="P", centre="C")
    with pytest.raises(ModelError, match=r"`radius` must be a number, got \[1\]"):
        m.add(Slot("bar", "ground", pin="P", centre="C", radius=[1], name="x"))


def test_a_new_type_is_evaluated_through_its_compiled_kernel():
    m = _pendulum()
    m.add(Slot("bar", "ground", pin="P", centre="C", radius=1))
    m.add(Slot("bar", "ground", pin="O", centre="C", radius=0.5, name="second"))  # same kernel, other numbers
    groups = m.compiled[0]
    slot_groups = [g for g in groups if type(g.constraints[0]) is Slot]
    assert len(slot_groups) == 1 and len(slot_groups[0].constraints) == 2
    rng = np.random.default_rng(0)
    q, qd = rng.normal(size=m.n), rng.normal(size=m.n)
    ev = m.evaluate(q, 0.0, qd)
    d = m.symbolic()
    at = {**dict(zip(m.q, q)), **dict(zip(m.qd, qd))}
    for name in ("Phi", "Phi_q", "gamma"):
        np.testing.assert_allclose(ev[name], np.array(getattr(d, name).subs(at), dtype=float).reshape(ev[name].shape),
                                   atol=1e-12, err_msg=name)


def test_a_file_finds_a_new_type_by_its_name():
    text = """
    [[bodies]]
    name = "ground"
    points = { C = [1, 0], O = [0, 0] }
    [[bodies]]
    name = "bar"
    points = { O = [0, 0], P = [2, 0] }
    q0 = [0, 0, 1.4]
    [[constraints]]
    type = "ground"
    body = "ground"
    [[constraints]]
    type = "revolute"
    i = "ground"
    j = "bar"
    point = "O"
    [[constraints]]
    type = "test-circular-slot"
    i = "bar"
    j = "ground"
    pin = "P"
    centre = "C"
    radius = 1.5
    """
    m = kinbook.loads(text)
    assert isinstance(m.constraints[-1], Slot)
    with pytest.raises(kinbook.MechanismFileError, match=r"unknown key 'center' \(accepted keys: i, j, pin, centre"):
        kinbook.loads(text.replace("centre =", "center ="))


def test_declaration_mistakes_are_named_when_the_class_is_written():
    with pytest.raises(ModelError, match=r"'test-no-phi'\): write its Φ in phi"):
        class NoPhi(planar.Constraint):
            type_name = "test-no-phi"
            n_eq = 1

    with pytest.raises(ModelError, match="`measures` needs one of length"):
        class BadMeasure(planar.Constraint):
            type_name = "test-bad-measure"
            n_eq = 1
            measures = ("metres",)

            def phi(self, Q, t=None):
                return [Q[0][0]]

    with pytest.raises(ModelError, match="the planar constraint type 'revolute' is already kinbook.planar"):
        class Hinge(planar.Constraint):
            type_name = "revolute"
            n_eq = 1

            def phi(self, Q, t=None):
                return [Q[0][0]]

    with pytest.raises(ModelError, match="subclass kinbook.planar.Constraint or kinbook.spatial.Constraint"):
        class Loose(kinbook.core.constraint.ConstraintBase):
            type_name = "test-loose"
            n_eq = 1

            def phi(self, Q, t=None):
                return [Q[0][0]]


def test_phi_with_the_wrong_number_of_rows_is_named():
    class Short(planar.Constraint):
        type_name = "test-short"
        n_eq = 2
        points = {"pin": "i"}

        def phi(self, Q, t=None):
            return [self.point(Q, "pin")[0]]

    m = _pendulum()
    m.add(Short("bar", "ground", pin="P"))
    with pytest.raises(ModelError, match=r"test-short joint '2' \(rows 6-7 of Φ\): phi\(\) returns 1 rows, .*n_eq = 2"):
        m.symbolic()
    with pytest.raises(ModelError, match=r"phi\(\) returns 1 rows"):
        m.Phi(m.q0)


def test_composite_rows_wrap_and_measures_follow_from_the_parts():
    rev = spatial.Revolute
    assert rev.parts == ((spatial.Spherical, {}), (spatial.Parallel1, {}))
    assert (rev.n_eq, rev.label, rev.measures) == (5, "s,3 + p1,2", ("length",) * 5)
    assert spatial.RevoluteDriver.wrap == {0: 2 * np.pi}

    class Turn(spatial.Constraint):  # a motorized revolute: a composite of a joint and a wrapped driver row
        type_name = "test-turn"
        parts = (spatial.Revolute, (spatial.RevoluteDriver, {}))

        def __init__(self, i, j, f, name=None):
            super().__init__((i, j), name=name, f=f)

        def _bind_points(self):
            self.P_i = self.P_j = np.zeros(3)
            self.a_i = self.a_j = np.array([0.0, 0.0, 1.0])
            self.h1, self.h2 = np.array([1.0, 0, 0]), np.array([0, 1.0, 0])
            self.f_i, self.g_i, self.f_j = self.h1, self.h2, self.h1

    assert Turn.wrap == {5: 2 * np.pi} and Turn.n_eq == 6
    m = spatial.Mechanism("turn")
    m.add_body("a")
    m.add_body("b")
    m.add(spatial.Ground("a"))
    m.add(Turn("a", "b", f="3*t"))
    assert m.dof == 0
    q = m.simulate(np.linspace(0.0, 1.2, 25)).q[-1]  # θ = 3.6 rad: past π only through the wrap of Turn's row 6
    np.testing.assert_allclose(m.A(q, "b")[:, 0], [np.cos(3.6), np.sin(3.6), 0], atol=1e-10)


def test_a_copy_of_a_composite_reads_its_own_attributes():
    """The checkers build wrong answers by changing a copy's attributes: the copy's parts must see them."""
    import copy

    m = spatial.Mechanism("rev")
    m.add_body("a", points={"O": (0, 0, 0)})
    m.add_body("b", points={"O": (0, 0, 0)})
    m.add(spatial.Revolute("a", "b", point="O", axis_i=(0, 0, 1), axis_j=(0, 0, 1)))
    c = m.constraints[-1]
    m.constraint_phi(c)
    cc = copy.copy(c)
    cc.P_j = np.array([1.0, 0.0, 0.0])
    x2 = m.body_symbols("b")[0]
    assert (m.constraint_phi(c) - m.constraint_phi(cc))[0].diff(x2) == 0  # the shift is a constant
    assert sp.simplify(m.constraint_phi(cc)[0] - m.constraint_phi(c)[0]) != 0


# --------------------------------------------------------------------------------------------- caches
def test_every_change_bumps_the_version_and_empties_the_cache():
    m = _pendulum()
    v = m.version
    calls = []
    assert m.cached(("test", 1), lambda: calls.append(1) or "built") == "built"
    assert m.cached(("test", 1), lambda: calls.append(1) or "again") == "built" and calls == [1]
    for change in (lambda: m.add(planar.Driver("bar", "phi", "t")), lambda: m.remove("driver 1"),
                   lambda: m.add_body("other"), lambda: setattr(m, "kernels", "compiled")):
        m.symbolic()
        change()
        assert m.version == v + 1
        v = m.version
        assert m.cached(("test", 1), lambda: "rebuilt") == "rebuilt"
        m._cache.pop(("test", 1))
    with pytest.raises(kinbook.InputError, match="`kernels` must be one of hand, compiled"):
        m.kernels = "fast"


def test_removing_and_adding_a_constraint_of_the_same_name_leaves_nothing_stale():
    m = _pendulum()
    m.add(planar.Driver("bar", "phi", "t", name="j"))
    q = np.array([0, 0, 0, 0, 0, 0.3])
    assert m.Phi(q, 0.0)[-1] == pytest.approx(0.3)
    m.derivation("j")
    m.remove("j")
    m.add(planar.Driver("bar", "x", "2*t", name="j"))
    assert m.Phi(q, 1.0)[-1] == pytest.approx(-2.0)
    assert m.derivation("j").Phi[0] == m.q[3] - 2 * m.t


def test_grading_after_removing_and_re_adding_a_constraint_named_alike():
    from kinbook.grading import check_phi

    m = planar.Mechanism("two")
    m.add_body("ground", points={"O": (0, 0)})
    m.add_body("bar", points={"O": (-1, 0), "A": (1, 0)}, q0=(1, 0, 0))
    m.add(planar.Ground("ground"))
    m.add(planar.Revolute("ground", "bar", point="O", name="j"))
    (x1, y1, _), (x2, y2, p2) = m.body_symbols("ground"), m.body_symbols("bar")
    assert check_phi([x1 - x2 + sp.cos(p2), y1 - y2 + sp.sin(p2)], m.constraint("j")).passed
    if not any(isinstance(k, tuple) and k[:1] == ("grading",) for k in m._cache):
        pytest.xfail("the checkers keep their targets outside mech.cached (grading/_target.py before h14's switch)")
    m.remove("j")
    m.add(planar.Revolute("ground", "bar", point_i="O", point_j="A", name="j"))
    assert check_phi([x1 - x2 - sp.cos(p2), y1 - y2 - sp.sin(p2)], m.constraint("j")).passed


def test_a_joint_table_says_what_a_negative_count_means():
    """14-5's bench (two free bodies, one constraint of every type) printed "DOF = -22" with no word on it."""
    import kinbook
    from kinbook.book import table14

    bench = table14.bench()
    n_norm = sum(1 for c in bench.constraints if c.kind == "normalization")
    extra = bench.m_geometric - bench.n
    assert extra > 0 and bench.dof == -extra and n_norm == 2
    assert f"{extra} more equations than coordinates" in bench._table_footer()
    assert f"{extra} more equations" in bench.constraint_table()._repr_html_()
    four_bar = kinbook.examples.load("ch13_example1")
    assert four_bar.dof == 1 and "more equations" not in four_bar._table_footer()


# ------------------------------------------------------------------------------------------ declared constants
class Arc(planar.Constraint):
    """Point P of body i at the distance ``length`` from point C of body j, turned by ``phase``: a test type that
    declares its parameters as constants (exact, possibly symbolic, read when the constraint is made)."""

    type_name = "test-arc"
    label = "a"
    n_eq = 1
    measures = ("length^2",)
    points = {"pin": "i", "centre": "j"}
    constants = ("length", "phase")
    defaults = {"phase": None}
    quantities = {"length": "length", "phase": "angle"}

    def _complete(self):
        if self.phase is None:
            self.phase = sp.Integer(0)

    def phi(self, Q, t=None):
        d = self.point(Q, "pin") - self.point(Q, "centre")
        return [d.dot(d) - self.length**2 + self.phase]


def test_declared_constants_are_kept_exact_may_be_symbols_and_are_read_when_made():
    import inspect

    assert list(inspect.signature(Arc).parameters) == ["i", "j", "pin", "centre", "length", "phase", "name"]
    c = Arc("bar", "ground", pin="P", centre="C", length="3*pi/4")
    assert c.length == 3 * sp.pi / 4 and c.phase is None      # exact, before any mechanism
    l = sp.Symbol("l", positive=True)
    assert Arc("bar", "ground", pin="P", centre="C", length=l).length is l
    with pytest.raises(ModelError, match=r"test-arc joint between 'bar' and 'ground', length must be a positive "
                                         r"number, got -2"):
        Arc("bar", "ground", pin="P", centre="C", length=-2)
    with pytest.raises(kinbook.ExpressionError, match="length"):
        Arc("bar", "ground", pin="P", centre="C", length=[1])
    with pytest.raises(kinbook.ExpressionError, match="expected a number, got None"):
        Arc("bar", "ground", pin="P", centre="C", length=None)
    m = _pendulum()
    m.add(c)
    assert c.phase == 0 and c.pin == (2, 0)
    c.bind(m)                                                 # a second binding keeps what was read and filled in
    assert c.length == 3 * sp.pi / 4 and c.phase == 0


OWN_CONSTRUCTOR = {
    ("planar", "simple"): "`body` names its one body (the file key and first positional argument, where a "
                          "declared type names its roles i, j); `coordinate` is one of x, y, phi and sets the row's "
                          "measure",
    ("planar", "driver"): "`body` and `coordinate` as for simple, then the function f",
    ("planar", "ground"): "`body`; `q` is a list of three values bound to `value`, each defaulting to the body's q0",
    ("spatial", "ground"): "`body`; `q` is a list of seven values (x, y, z, e0..e3) bound to r0 and a normalized p0",
    ("planar", "gear"): "three bodies; `phi0` is a list of three initial angles, each defaulting to its body's q0, "
                        "and the messages name a 'gear'",
    ("planar", "rack-pinion"): "`sliding` is a flag and `initial` a table of x_i, phi_i, x_j, each defaulting to "
                               "the bodies' q0",
}
"""The built-in types that write their own constructor, and why the declaration cannot generate it: their
arguments are not declared keys (a single body named `body`, a choice, a flag, a list or table of values with
defaults from the bodies). Strike an entry when its type becomes declared."""


@pytest.mark.parametrize("chapter", ["planar", "spatial"])
def test_the_built_in_types_get_their_constructor_from_their_declaration(chapter):
    own = {name for name, cls in constraint_types(chapter).items()
           if cls.__module__ == f"kinbook.{chapter}.constraints" and not getattr(cls.__init__, "declared", False)}
    assert sorted(own) == sorted(name for ch, name in OWN_CONSTRUCTOR if ch == chapter)


def test_declared_built_ins_keep_their_signatures():
    import inspect

    assert list(inspect.signature(planar.Translational).parameters) == ["i", "j", "axis", "point_j", "phi0", "name"]
    assert list(inspect.signature(planar.RevoluteRevolute).parameters) == ["i", "j", "point_i", "point_j", "length",
                                                                           "name"]
    t = planar.Translational("a", "b", ("P", "Q"), "R", "pi/6")
    assert t.phi0 == sp.pi / 6 and t.axis == ("P", "Q")
    assert planar.RevoluteRevolute("a", "b", "P", "P", 2).length == 2
