"""Writes ``python/alea/_core.pyi``, the type stubs of the extension module, from the built
module itself (names, signatures and docstrings from ``inspect``) and a table of argument and
return types by name. Run after ``maturin develop``:

    python tools/stubgen.py            # writes the stub
    python tools/stubgen.py --check    # exits 1 if the committed stub is out of date

``tests/test_stubs.py`` runs the check, so a new function or argument cannot ship without its
stub. The stub describes the full build (feature ``solver``): on a toolkit-only build
(``_core.SOLVER`` false) the script refuses to run.
"""
import inspect
import sys
from pathlib import Path

import alea._core as core

STUB = Path(__file__).resolve().parent.parent / "python" / "alea" / "_core.pyi"

ARG_TYPES = {
    "law": "LawLike",
    "marginals": "Sequence[Law]",
    "correlation": "ArrayLike",
    "n": "int",
    "seed": "int",
    "scramble_seed": "int",
    "degree": "int",
    "order": "int",
    "level": "int",
    "maximin": "int",
    "modes": "int",
    "threads": "int",
    "counts": "Sequence[int]",
    "cells": "ArrayLike",
    "nodes": "ArrayLike",
    "points": "ArrayLike",
    "values": "ArrayLike",
    "data": "ArrayLike",
    "x": "ArrayLike",
    "p": "ArrayLike",
    "xi": "ArrayLike",
    "lo": "ArrayLike",
    "hi": "ArrayLike",
    "path": "Union[str, os.PathLike[str]]",
    "directory": "Union[str, os.PathLike[str]]",
    "study": "Union[str, os.PathLike[str]]",
    "restart": "bool",
    "nested": "bool",
    "progress": "Callable[..., Any]",
    "kernel": "str",
    "transform": "str",
    "integration": "str",
    "families": "Sequence[str]",
    "bandwidth": "float",
    "variables": "Sequence[int]",
    "bounds": "Tuple[float, float]",
    "model": 'Union[Callable[[Matrix], ArrayLike], "PolynomialChaos", "PiecewiseLinear"]',
    "threshold": "float",
    "starts": "ArrayLike",
    "max_iter": "int",
    "max_draws": "int",
    "samples_per_level": "int",
    "max_levels": "int",
    "second_order": "bool",
}
# Arguments whose type depends on the function (`level`: a sparse-grid level elsewhere, a
# confidence level in the reliability methods).
FUNCTION_ARG_TYPES = {
    ("importance_sampling", "level"): "float",
    ("subset_simulation", "level"): "float",
}
FLOAT_ARGS = {
    "mean", "std", "alpha", "beta", "mu", "sigma", "shape", "scale", "loc", "mode",
    "variance", "variance_fraction", "q", "max_terms_fraction", "stop_factor",
    "length", "tol", "step", "target_cov", "p0", "rho",
}
RETURNS = {
    "monte_carlo": "Matrix", "lhs": "Matrix", "sobol": "Matrix", "grid": "Matrix",
    "pc_collocation": "Matrix", "quadrature": "Tuple[Matrix, Vector]", "fit": "Any",
    "read_store": "Dict[str, Any]", "rebuild_outputs": "Dict[str, Any]",
    "run_study_file": "Dict[str, Any]",
    "form": "ReliabilityResult",
    "importance_sampling": "ReliabilityResult", "subset_simulation": "ReliabilityResult",
}
# Property types by class (others are `Any`).
PROPERTY_TYPES = {
    "ReliabilityResult": {
        "method": "str", "pf": "float", "interval": "Optional[Tuple[float, float]]",
        "level": "Optional[float]", "cov": "Optional[float]", "beta": "Optional[float]",
        "generalised_beta": "float", "design_point": "Optional[Vector]",
        "design_point_u": "Optional[Vector]", "importance_factors": "Optional[Vector]",
        "design_points": "Matrix", "design_point_betas": "Vector",
        "curvatures": "Optional[Vector]", "pf_breitung": "Optional[float]",
        "pf_tvedt": "Optional[float]", "calls": "int", "warnings": "List[str]",
    },
}
# The stub's preamble, composed from what it declares: the typing names it imports, the array
# aliases and the module attributes.
TYPING_NAMES = ["Any", "Callable", "Dict", "List", "Optional", "Sequence", "Tuple", "Union"]
ALIASES = [
    ("Matrix", "npt.NDArray[np.float64]"),
    ("Vector", "npt.NDArray[np.float64]"),
    ("LawLike", 'Union["Joint", "Law", Sequence["Law"]]'),
]
ATTRIBUTES = [("__version__", "str"), ("SOLVER", "bool")]
HEADER = "\n".join(
    [
        '"""Type stubs of ``alea._core`` (written by ``tools/stubgen.py`` from the built module: '
        "do not\nedit by hand).\"\"\"",
        "import os",
        "from typing import " + ", ".join(TYPING_NAMES),
        "",
        "import numpy as np",
        "import numpy.typing as npt",
        "from numpy.typing import ArrayLike",
        "",
    ]
    + [f"{name} = {value}" for name, value in ALIASES]
    + [""]
    + [f"{name}: {kind}" for name, kind in ATTRIBUTES]
) + "\n"


def arg_type(name, function=None):
    if (function, name) in FUNCTION_ARG_TYPES:
        return FUNCTION_ARG_TYPES[(function, name)]
    if name in ARG_TYPES:
        return ARG_TYPES[name]
    if name in FLOAT_ARGS:
        return "float"
    return "Any"


def params(sig, method, function=None):
    out = ["self"] if method else []
    star = False
    for p in sig.parameters.values():
        if p.name == "self":
            continue
        if p.kind == p.KEYWORD_ONLY and not star:
            out.append("*")
            star = True
        t = arg_type(p.name, function)
        if p.default is p.empty:
            out.append(f"{p.name}: {t}")
        elif p.default is None:
            out.append(f"{p.name}: Optional[{t}] = None")
        else:
            out.append(f"{p.name}: {t} = {p.default!r}")
    return ", ".join(out)


def doc(obj, indent):
    d = inspect.getdoc(obj)
    if not d:
        return ""
    d = d.replace('"""', "'''").replace("\\", "\\\\")
    pad = " " * indent
    body = "\n".join(pad + line if line else "" for line in d.splitlines())
    return f'{pad}"""\n{body}\n{pad}"""\n'


def signature(obj):
    try:
        return inspect.signature(obj)
    except (TypeError, ValueError):
        return None


def function(name, f, indent=0, method=False, decorator=None):
    sig = signature(f)
    pad = " " * indent
    ps = params(sig, method, name) if sig else ("self, *args: Any, **kwargs: Any" if method else "*args: Any, **kwargs: Any")
    ret = RETURNS.get(name, "Any")
    head = f"{pad}@{decorator}\n" if decorator else ""
    d = doc(f, indent + 4)
    return f"{head}{pad}def {name}({ps}) -> {ret}:\n{d}{pad}    ...\n"


def klass(name, cls):
    base = ""
    mro = [b for b in cls.__mro__[1:] if getattr(core, b.__name__, None) is b]
    if mro:
        base = f"({mro[0].__name__})"
    out = f"class {name}{base}:\n{doc(cls, 4)}"
    init = signature(cls)
    if init is not None:
        out += f"    def __init__({params(init, True)}) -> None: ...\n"
    for attr, raw in sorted(cls.__dict__.items()):
        if attr.startswith("_"):
            continue
        if isinstance(raw, staticmethod) or type(raw).__name__ == "builtin_function_or_method":
            out += function(attr, getattr(cls, attr), 4, False, "staticmethod")
        elif isinstance(raw, classmethod) or type(raw).__name__ == "classmethod_descriptor":
            out += function(attr, getattr(cls, attr), 4, False, "staticmethod")
        elif type(raw).__name__ == "getset_descriptor" or isinstance(raw, property):
            kind = PROPERTY_TYPES.get(name, {}).get(attr, "Any")
            out += f"    @property\n    def {attr}(self) -> {kind}: ...\n"
        elif callable(raw):
            out += function(attr, raw, 4, True)
    return out


def render():
    parts = [HEADER]
    names = sorted(n for n in dir(core) if not n.startswith("_"))
    classes = [n for n in names if isinstance(getattr(core, n), type)]
    # Base classes first.
    classes.sort(key=lambda n: (len(getattr(core, n).__mro__), n))
    for n in classes:
        parts.append("\n" + klass(n, getattr(core, n)))
    for n in names:
        if n not in classes and callable(getattr(core, n)):
            parts.append("\n" + function(n, getattr(core, n)))
    return "".join(parts)


def main():
    if not core.SOLVER:
        print("alea._core was built without the feature `solver`: the stub is written from the "
              "full build (maturin develop --release)", file=sys.stderr)
        sys.exit(2)
    text = render()
    if "--check" in sys.argv:
        if not STUB.exists() or STUB.read_text() != text:
            print(f"{STUB} is out of date: run python tools/stubgen.py", file=sys.stderr)
            sys.exit(1)
        return
    STUB.write_text(text)
    (STUB.parent / "py.typed").write_text("")
    print(f"wrote {STUB}")


if __name__ == "__main__":
    main()
