"""docs/extending.md runs: its Python blocks, in order, in one namespace (the tutorial's own test included),
and its TOML block loads as a mechanism-file table of the joint it defines."""

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import kinbook  # noqa: E402

from .mechanisms import cam_follower  # noqa: E402

DOC = Path(__file__).resolve().parent.parent / "docs" / "extending.md"


def _blocks(lang):
    return re.findall(rf"```{lang}\n(.*?)```", DOC.read_text(encoding="utf-8"), flags=re.S)


@pytest.fixture(scope="module")
def tutorial():
    namespace = {"__name__": "extending_md"}
    for block in _blocks("python"):
        exec(compile(block, str(DOC), "exec"), namespace)  # our own documentation, not input
    return namespace


def test_the_tutorial_runs_and_its_joint_works_everywhere(tutorial):
    m, cls = tutorial["m"], tutorial["CamFollower"]
    assert kinbook.core.registry.constraint_class("planar", "cam-follower") is cls
    q = m.solve_position(1.0)
    from kinbook.planar import plotting

    ax = plotting.draw(m, q)
    R = m.point_position(q, "follower", "R")
    assert any(np.allclose(getattr(p, "center", (np.nan, np.nan)), R) for p in ax.patches)
    assert "cf" in repr(m.constraint_table())


def test_the_file_block_declares_the_same_joint(tutorial):
    pytest.importorskip("kinbook.core.reader", reason="functions written as text need the safe reader")
    (table,) = _blocks("toml")
    m = kinbook.loads(cam_follower(table))
    assert isinstance(m.constraints[3], tutorial["CamFollower"])
    q = m.solve_position(0.3)
    assert np.isclose(q[7], 2 + np.sin(0.3) / 2)
