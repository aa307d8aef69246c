import subprocess
import sys

from kinbook import examples
from kinbook.cli import main


def test_solve_prints_the_solution(capsys):
    assert main(["solve", "ch13_example2", "-t", "0"]) == 0
    out = capsys.readouterr().out
    q = examples.load("ch13_example2").solve_position(0.0)
    line = next(l for l in out.splitlines() if l.split()[0] == "x4")
    assert abs(float(line.split()[1]) - q[9]) < 1e-5


def test_errors_exit_2_with_a_message(capsys, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[[bodies]]\nname = 'a'\n[[constraints]]\ntype = 'revolute'\ni = 'a'\nj = 'b'\npoint = 'O'\n")
    assert main(["table", str(bad)]) == 2
    assert "bad.toml: constraints[0] (type 'revolute')" in capsys.readouterr().err


def test_console_script_is_installed():
    out = subprocess.run([sys.executable, "-m", "kinbook.cli", "examples"], capture_output=True, text=True, check=True)
    assert "ch13_example1" in out.stdout


def test_a_reader_that_leaves_early_is_not_an_error(tmp_path):
    # `kinbook exercises list | head -n 1`: the pipe closes after the first line; kinbook says nothing on stderr
    # and stops as a command stopped by SIGPIPE does (141), not with "error: [Errno 32] Broken pipe"
    proc = subprocess.Popen([sys.executable, "-c", "import sys; from kinbook.cli import main; "
                             "sys.exit(main(['exercises', 'list']))"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=tmp_path)  # the installed kinbook
    proc.stdout.close()   # the reader is gone before the first line is written
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 141, err
    assert err == ""
