"""Small mechanism files the tests share, written once: the cam and follower of docs/extending.md (the joint is
each test's own) and a pendulum. Each returns the text of a mechanism file (TOML)."""

CAM_FOLLOWER_BASE = """
[mechanism]
name = "cam"
[[bodies]]
name = "ground"
points = { O = [0, 0], G = [0, 1] }
[[bodies]]
name = "cam"
points = { O = [0, 0] }
[[bodies]]
name = "follower"
points = { R = [0, 0], T = [0, 1] }
q0 = [0, 2.5, 0]
[[constraints]]
type = "ground"
body = "ground"
[[constraints]]
type = "revolute"
i = "ground"
j = "cam"
point = "O"
[[constraints]]
type = "translational"
i = "ground"
j = "follower"
axis = ["O", "G"]
point_j = "R"
"""
"""A cam pinned to the ground at O and a follower (roller centre R) sliding on the ground's line O–G: add the
cam-follower constraint between 'cam' and 'follower' (roller R) and a driver of the cam."""

CAM_DRIVER = """[[constraints]]
type = "driver"
body = "cam"
coordinate = "phi"
f = "t"
"""
"""The cam turning at 1 rad/s."""


def cam_follower(joint):
    """:data:`CAM_FOLLOWER_BASE` with ``joint`` (the TOML table of the cam-follower constraint) and the cam driver."""
    return CAM_FOLLOWER_BASE + joint.strip("\n") + "\n" + CAM_DRIVER


def pendulum(half_length, f):
    """A bar of length 2·``half_length`` pinned at one end O to the ground, centred at x = ``half_length`` at
    q0, its angle driven by ``f``."""
    return f"""
[mechanism]
name = "pendulum"
[[bodies]]
name = "ground"
points = {{ O = [0, 0] }}
[[bodies]]
name = "bar"
q0 = [{half_length}, 0, 0]
points = {{ O = [-{half_length}, 0] }}
[[constraints]]
type = "ground"
body = "ground"
[[constraints]]
type = "revolute"
i = "ground"
j = "bar"
point = "O"
[[constraints]]
type = "driver"
body = "bar"
coordinate = "phi"
f = "{f}"
"""
