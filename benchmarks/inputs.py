"""Issue 13: loading is linear in the number of bodies, and the safe reader refuses in microseconds.

Run: .venv/bin/python benchmarks/inputs.py [N ...]     (default N = 1000 2000 4000 8000 bodies)

Prints, for a chain of N bodies (N revolute joints, N - 1 drivers written as text), the time of
kinbook.files.build on the parsed file (TOML parsing by tomllib is shown apart) and the ratio to the previous N:
2.0 means linear. Then the time to read a typical driver and to refuse hostile expressions.
"""

import sys
import time

import sympy as sp

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10: the same parser as tomli
    import tomli as tomllib

from kinbook.core.reader import ExpressionError, read_expression
from kinbook.files import _no_gc, build


def chain(n):
    lines = ['[mechanism]\nname = "chain"\n', '[[bodies]]\nname = "ground"\npoints = { O = [0, 0] }\n']
    for k in range(1, n):
        lines.append(f'[[bodies]]\nname = "b{k}"\nq0 = [{k - 0.5}, 0, 0]\npoints = {{ L = [-0.5, 0], R = [0.5, 0] }}\n')
    lines.append('[[constraints]]\ntype = "ground"\nbody = "ground"\n')
    lines.append('[[constraints]]\ntype = "revolute"\ni = "ground"\nj = "b1"\npoint_i = "O"\npoint_j = "L"\n')
    for k in range(1, n - 1):
        lines.append(f'[[constraints]]\ntype = "revolute"\ni = "b{k}"\nj = "b{k+1}"\npoint_i = "R"\npoint_j = "L"\n')
    for k in range(1, n):
        lines.append(f'[[constraints]]\ntype = "driver"\nbody = "b{k}"\ncoordinate = "phi"\nf = "0.1*t + {k % 7}/10"\n')
    return "".join(lines)


def loads_toml(text):
    with _no_gc():  # as kinbook.loads parses
        return tomllib.loads(text)


def best(fn, repeat=3):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main(sizes):
    print(f"{'bodies':>8} {'toml (s)':>9} {'build (s)':>10} {'µs/body':>8} {'ratio':>6}")
    prev = None
    for n in sizes:
        text = chain(n)
        t_toml = best(lambda text=text: loads_toml(text), 1)
        data = loads_toml(text)
        t_build = best(lambda data=data: build(data, "chain.toml"), 2)
        ratio = "" if prev is None else f"{t_build / prev:.2f}"
        print(f"{n:>8} {t_toml:9.2f} {t_build:10.2f} {1e6 * t_build / n:8.0f} {ratio:>6}")
        prev = t_build
    t = sp.Symbol("t", real=True)
    print()
    print(f"{'expression':>36} {'µs':>8}  result")
    for text in ("pi/4 + 100*t", "2 + sin(t)", "9**9**9**9", "factorial(10**8)", "(t+1)**100000",
                 "__import__('os').system('x')", "(" * 199 + "t" + ")" * 199, "t" * 1_000_000):
        def read(text=text):
            try:
                return read_expression(text, symbols={"t": t}, where="benchmark")
            except ExpressionError as exc:
                return exc

        r = read()
        us = 1e6 * best(read, 20)
        shown = text if len(text) <= 34 else text[:31] + "..."
        print(f"{shown:>36} {us:8.0f}  {'refused' if isinstance(r, ExpressionError) else r}")


if __name__ == "__main__":
    main([int(a) for a in sys.argv[1:]] or [1000, 2000, 4000, 8000])
