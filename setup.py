"""kinbook's package layout for setuptools; everything else (metadata, dependencies, package data) is in
pyproject.toml.

The packages are every package under ``kinbook/`` plus ``kinbook.exercises``, which is the checkout's
``exercises/`` folder: the shipped exercise notebooks stay where instructors, the tests and the other
notebooks find them, and install as package data of ``kinbook.exercises`` (an editable install maps the
package onto the folder). pyproject.toml alone cannot add a mapped package to the ones it finds.
"""

from setuptools import find_packages, setup

setup(
    packages=[*find_packages(include=["kinbook", "kinbook.*"]), "kinbook.exercises"],
    package_dir={"kinbook.exercises": "exercises"},
)
