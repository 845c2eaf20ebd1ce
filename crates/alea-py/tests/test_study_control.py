"""Watching and stopping a study from Python: the progress line, Ctrl-C, a locked study
directory and messages in the terms of ``alea.run``'s arguments.

The Ctrl-C test starts a child interpreter on a long Monte Carlo study of the plate
(``data/plate.toml`` on a 200 x 40 mesh with 50 000 Monte Carlo runs), sends it SIGINT once runs are being
committed, and checks that it stops within a few seconds with ``KeyboardInterrupt``, that the
runs it finished are in the store, and that a new ``alea.run`` on the directory resumes from
them.
"""

import fcntl
import io
import os
import re
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

import alea
from alea._study import _ProgressLine

DATA = Path(__file__).parent / "data"
PLATE = DATA / "plate.toml"
solver = pytest.mark.skipif(not alea.SOLVER, reason="toolkit-only build (no solver)")


def long_study(tmp_path: Path) -> Path:
    path = tmp_path / "long.toml"
    text = PLATE.read_text()
    assert "runs = 200\n" in text
    # A finer mesh: about 700 runs a second on 2 cores, a study of over a minute.
    assert "cells = [10, 2]\n" in text
    text = text.replace("cells = [10, 2]\n", "cells = [200, 40]\n")
    path.write_text(text.replace("runs = 200\n", "runs = 50000\n"))
    return path


class Enough(Exception):
    """Raised by a progress callback to stop a study."""


def test_progress_line_counts_runs_and_time_left():
    out = io.StringIO()
    line = _ProgressLine(out, every=0.0)
    assert line.line(0, 200, 0.0) == "alea: 0/200 runs (0 %), 0 s   "
    line(50, 200)  # 50 runs resumed from the store: not counted in the rate
    assert line.line(100, 200, 10.0) == "alea: 100/200 runs (50 %), 10 s, about 20 s left   "
    line(200, 200)
    line.close()
    text = out.getvalue()
    assert text.startswith("\ralea: 50/200 runs (25 %)") and "\ralea: 200/200 runs (100 %)" in text
    assert text.endswith("\n") and text.count("\n") == 1


def test_progress_line_shows_at_most_five_times_a_second():
    out = io.StringIO()
    line = _ProgressLine(out)
    for done in range(100):
        line(done, 100)
    line(100, 100)  # the last one is always shown
    assert out.getvalue().count("\r") == 2
    assert out.getvalue().endswith("alea: 100/100 runs (100 %), 0 s   ")


def test_progress_line_is_silent_when_never_called():
    out = io.StringIO()
    _ProgressLine(out).close()
    assert out.getvalue() == ""


@solver
def test_progress_argument(tmp_path, capsys):
    directory = tmp_path / "plate"
    alea.run(PLATE, directory=directory, progress=False)
    assert capsys.readouterr().err == ""  # finished: the next calls solve nothing
    alea.run(PLATE, directory=directory, progress=True)
    assert re.fullmatch(r"\ralea: 237/237 runs \(100 %\), \d+ s   \n", capsys.readouterr().err)
    alea.run(PLATE, directory=directory)  # default: stderr is not a terminal under pytest
    assert capsys.readouterr().err == ""
    with pytest.raises(TypeError, match="progress must be"):
        alea.run(PLATE, directory=directory, progress="yes")


CHILD = textwrap.dedent(
    """
    import signal, sys, alea
    # A background shell job (CI) starts its children with SIGINT ignored, and Python then
    # installs no KeyboardInterrupt handler: install it, as an interactive session has it.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    started = False
    def progress(done, total):
        global started
        if done > 0 and not started:
            started = True
            print("started", total, flush=True)
    alea.run(sys.argv[1], directory=sys.argv[2], progress=progress, threads=2)
    print("finished", flush=True)
    """
)


@solver
def test_ctrl_c_stops_the_study_and_the_next_run_resumes(tmp_path):
    study, directory = long_study(tmp_path), tmp_path / "long"
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD, str(study), str(directory)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        first = child.stdout.readline()
        assert first == "started 50037\n", child.stderr.read() if not first else first
        # While the child runs, the directory is locked: StudyLocked names the child.
        with pytest.raises(alea.StudyLocked, match="in use by") as locked:
            alea.run(study, directory=directory, progress=False)
        assert isinstance(locked.value, ValueError)
        assert f"pid {child.pid} " in locked.value.holder
        assert locked.value.directory == directory
        assert "directory=" in str(locked.value) and "--dir" not in str(locked.value)
        time.sleep(0.3)
        stopped_at = time.monotonic()
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=20)
        elapsed = time.monotonic() - stopped_at
    finally:
        child.kill()
        child.wait()
    # Python ends on an uncaught KeyboardInterrupt by dying of SIGINT.
    assert child.returncode == -signal.SIGINT, err
    assert "KeyboardInterrupt" in err and "finished" not in out
    assert elapsed < 3.0, f"the study took {elapsed:.1f} s to stop"
    stored = len(alea.open_store(directory).runs)
    assert 0 < stored < 50037
    # A new run resumes: it starts from the stored runs (then is stopped by its callback, which
    # also stops the study at once).
    calls = []

    def progress(done, total):
        calls.append((done, total))
        raise Enough()

    started = time.monotonic()
    with pytest.raises(Enough):
        alea.run(study, directory=directory, progress=progress)
    assert time.monotonic() - started < 10.0
    assert calls == [(stored, 50037)]
    assert len(alea.open_store(directory).runs) == stored


@solver
def test_locked_directory_raises_study_locked(tmp_path):
    directory = tmp_path / "held"
    directory.mkdir()
    (directory / "lock").write_text("pid 4242 on host elsewhere, started 2026-01-01 (a test)")
    fd = os.open(directory, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)  # as another process holding it
        for call in (
            lambda: alea.run(PLATE, directory=directory, progress=False),
            lambda: alea.report(directory),
        ):
            with pytest.raises(alea.StudyLocked) as e:
                call()
            assert e.value.holder == "pid 4242 on host elsewhere, started 2026-01-01 (a test)"
            assert e.value.directory == directory
            assert "is in use by pid 4242" in str(e.value)
    finally:
        os.close(fd)
    # Released: the study runs.
    assert len(alea.run(PLATE, directory=directory, progress=False).runs) == 237


def test_study_locked_is_a_value_error():
    assert issubclass(alea.StudyLocked, ValueError)
    e = alea.StudyLocked("d is in use by p", "d", "p")
    assert str(e) == "d is in use by p" and e.holder == "p" and e.directory == Path("d")


@solver
def test_messages_speak_of_python_arguments(tmp_path):
    directory = tmp_path / "plate"
    alea.run(PLATE, directory=directory, progress=False)
    changed = tmp_path / "plate.toml"
    text = PLATE.read_text()
    assert "traction = [200.0, 0.0]" in text
    changed.write_text(text.replace("traction = [200.0, 0.0]", "traction = [210.0, 0.0]"))
    with pytest.raises(ValueError, match="different study or version") as e:
        alea.run(changed, directory=directory, progress=False)
    message = str(e.value)
    assert "Run again with restart=True to discard them, or pass another directory=" in message
    assert "--restart" not in message and "--dir" not in message
    # restart=True is indeed the way out.
    res = alea.run(changed, directory=directory, restart=True, progress=False)
    assert res.computed == 237
    # A file where a directory belongs.
    a_file = tmp_path / "a_file"
    a_file.write_text("")
    with pytest.raises(ValueError, match="give directory= a directory"):
        alea.run(PLATE, directory=a_file, progress=False)


@solver
def test_a_raising_callback_stops_the_study_and_report_notes_speak_python(tmp_path):
    directory = tmp_path / "plate"

    def progress(done, total):
        if done >= 60:
            raise Enough()

    with pytest.raises(Enough):
        alea.run(PLATE, directory=directory, progress=progress)
    # Stopped after the groups of runs under way (8 runs each, one per thread).
    stored = len(alea.open_store(directory).runs)
    assert 60 <= stored < 60 + 8 * os.cpu_count() + 8
    notes = alea.report(directory).notes
    missing = f"{237 - stored} of 237 runs are missing"
    note = next(n for n in notes if n.startswith(missing))
    assert note.endswith(f"compute them with `alea.run({str(PLATE)!r}, directory={str(directory)!r})`".replace("'", '"'))
    assert not any("--dir" in n or "`alea run`" in n for n in notes)


@solver
def test_samples_of_is_an_array(tmp_path):
    res = alea.run(PLATE, directory=tmp_path / "plate", progress=False)
    for method in res.methods:
        x = res.samples_of(method.label)
        assert isinstance(x, np.ndarray) and x.ndim == 2
        assert x.shape[1] == len(res.sample_columns_of(method.label))
