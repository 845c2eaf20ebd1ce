"""The type stubs (``python/alea/_core.pyi``, with ``py.typed``) describe the built module: every
public class, method and function with its arguments (``tools/stubgen.py --check``)."""
import ast
import subprocess
import sys
from pathlib import Path

import pytest

import alea._core as core

ROOT = Path(__file__).resolve().parent.parent


def test_stubs_are_current_and_cover_every_public_name():
    stub = ROOT / "python" / "alea" / "_core.pyi"
    tree = ast.parse(stub.read_text())
    top = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    top |= {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
    public = {n for n in dir(core) if not n.startswith("_")}
    assert public <= top, public - top
    if not core.SOLVER:
        pytest.skip("toolkit-only build: the stub is written from the full build")
    r = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "stubgen.py"), "--check"],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    assert (stub.parent / "py.typed").exists()
