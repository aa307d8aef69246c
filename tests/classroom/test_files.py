"""Reading collected/ as untrusted input (kinbook.classroom.files) and the one atomic writer."""

import errno
import os
import unicodedata

import pytest

from kinbook.classroom.files import atomic_write, collect, read_entry, student_id
from kinbook.classroom.results import Refused
from kinbook.errors import DiskFullError


def test_links_fifos_and_devices_are_refused_and_never_opened(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("private")
    c = tmp_path / "collected"
    (c / "alice").mkdir(parents=True)
    (c / "alice" / "ex01.ipynb").write_text("{}")
    (c / "bob").mkdir()
    os.symlink(secret, c / "bob" / "ex01.ipynb")
    os.symlink(c / "alice", c / "carol")          # a directory link: its content is not read either
    os.mkfifo(c / "ex01-dave.ipynb")               # would block a plain open() forever
    found = {e.student: e for e in collect([c], "ex01", max_bytes=1000)}
    assert found["alice"].status is None and read_entry(found["alice"], 1000) == b"{}"
    assert (found["bob"].status, found["carol"].status, found["dave"].status) == ("refused",) * 3
    assert "symbolic link" in found["bob"].message and "FIFO" in found["dave"].message


def test_a_file_replaced_after_listing_is_refused(tmp_path):
    (tmp_path / "ex01-eve.ipynb").write_text("{}")
    (entry,) = collect([tmp_path], "ex01", max_bytes=1000)
    (tmp_path / "other").write_text("{ }")                    # another file (another inode) put in its place
    os.replace(tmp_path / "other", tmp_path / "ex01-eve.ipynb")
    with pytest.raises(Refused, match="replaced"):
        read_entry(entry, 1000)
    os.remove(tmp_path / "ex01-eve.ipynb")
    os.symlink("/etc/hostname", tmp_path / "ex01-eve.ipynb")  # swapped for a link between listing and reading
    with pytest.raises(Refused, match="cannot be opened as a regular file"):
        read_entry(entry, 1000)


def test_oversized_files_are_refused_unread(tmp_path):
    (tmp_path / "big.ipynb").write_bytes(b" " * 2000)
    (entry,) = collect([tmp_path], "ex01", max_bytes=1000)
    assert entry.status == "too-large" and "2,000 bytes" in entry.message


def test_ids_are_normalized_and_clashes_reported_per_entry(tmp_path):
    for name in (unicodedata.normalize("NFC", "José"), unicodedata.normalize("NFD", "José"), "Josè", "ANA", "ana",
                 "x" * 100, "alice", "ａｌｉｃｅ"):
        (tmp_path / f"{name}.ipynb").write_text("{}")
    found = collect([tmp_path], "ex01", max_bytes=1000)
    status = {}
    for e in found:
        status.setdefault(e.student, []).append(e.status)
    # one id in NFC and NFD: two notebooks of José, of one standing (neither is a later attempt): both graded, the
    # best counts (kinbook.classroom.choice)
    assert status["José"] == [None, None]
    assert status["Josè"] == [None]                            # another name: graded
    assert status["ANA"] == ["duplicate-id"] and status["ana"] == ["duplicate-id"]  # one file on a Mac: who is real?
    assert status["alice"] == [None] and status["ａｌｉｃｅ"] == ["duplicate-id"]  # a look-alike never zeroes alice
    (fake,) = [e for e in found if e.student == "ａｌｉｃｅ"]
    assert fake.signals == [("look-alike", "the id 'ａｌｉｃｅ' looks like 'alice'")] and "tmp" not in fake.message
    (long,) = [e for e in found if e.student.startswith("xxx")]
    assert long.status == "bad-id" and len(long.student) <= 64


def test_student_id():
    assert student_id("alice") == ("alice", None)
    assert student_id("../etc") == ("_etc", None)
    sid, problem = student_id("a" * 65)
    assert len(sid) <= 64 and "65 characters" in problem
    assert student_id(".hidden")[0] == "hidden"


def test_atomic_write_leaves_the_old_file_or_the_new_one(tmp_path, monkeypatch):
    path = tmp_path / "grades.csv"
    atomic_write(path, "old")

    def broken(fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(os, "fsync", broken)
    with pytest.raises(DiskFullError, match="grades.csv.*no space left"):
        atomic_write(path, "new")
    assert path.read_text() == "old" and os.listdir(tmp_path) == ["grades.csv"]
