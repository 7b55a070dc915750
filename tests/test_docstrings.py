"""numpydoc sections and units of the public physics API.

What is checked, for every public function and class (name without a leading underscore,
defined in the module itself, not imported into it) of the physics modules in ``PHYSICS``
(a module that does not exist yet is skipped, so the test holds before and after the
modules are split):

1. The docstring parses with numpydoc's parser (no unknown or repeated section).
2. Parameters: when the callable takes parameters (``self``/``cls`` excluded; a class is
   checked through its constructor's signature), its docstring has a ``Parameters``
   section (a class may use ``Attributes`` instead or as well) that names every one of
   them. A line may name several parameters (``x, y : float``); ``*args`` and ``**kwargs``
   are named with or without their stars. A documented name that is not a parameter is
   reported too.
3. Units: a parameter is *numeric* when its annotation mentions ``float``, ``complex``,
   ``ArrayLike``, ``NDArray`` or ``ndarray`` (an ``NDArray`` of ``int``/``bool`` excepted,
   those are indices and masks), or, without an annotation, when its numpydoc type
   mentions ``float``, ``array_like`` or ``ndarray``. The type or the description of a
   numeric parameter must contain a unit in brackets: a ``[...]`` group on one line whose
   text starts with ``-`` (dimensionless) or with a letter, ``°``, ``µ``, ``Ω`` or ``%``
   followed up to the first blank by letters, digits and ``°µΩ%·*/^.()²³⁻¹-`` (so
   ``[m]``, ``[kg m]``, ``[rad/s]``, ``[N*m]``, ``[-]``, ``[m along the crank axis]``
   pass; ``[0, 1]`` and the citation ``[1]`` do not).
4. Returns: a function whose return annotation is not ``None``/``NoReturn`` (or, without
   an annotation, whose body has a ``return <value>``) has a ``Returns`` section
   (``Yields`` for a generator). Classes need none.

Every entry must pass; there is no list of known failures.
``python tests/test_docstrings.py`` prints the current failures (``module:name`` and what
each lacks).
"""

from __future__ import annotations

import ast
import importlib
import inspect
import re
import textwrap
import warnings
from collections.abc import Callable
from types import ModuleType
from typing import Any

import pytest
from numpy.typing import ArrayLike
from numpydoc.docscrape import NumpyDocString

from .test_architecture import PHYSICS

NUMERIC_ANNOTATION = re.compile(r"\b(float|complex|ArrayLike|NDArray|ndarray)\b")
INTEGER_ARRAY = re.compile(r"^\s*NDArray\[\s*np\.(u?int\w*|bool_?|intp)\s*\]\s*$")
NUMERIC_DOC_TYPE = re.compile(r"\b(float|array_like|ndarray)\b")
UNIT = re.compile(r"\[(-|[A-Za-zΩ°µμ%][A-Za-z0-9°µμΩ%·*/^.()²³⁻¹-]*)(\s[^\[\]\n]*)?\]")
NONE_RETURNS = {"None", "NoReturn", "typing.NoReturn", "Never"}


def _modules() -> list[ModuleType]:
    found = []
    for name in PHYSICS:
        try:
            found.append(importlib.import_module(f"crankbalance.{name}"))
        except ModuleNotFoundError as error:
            if error.name != f"crankbalance.{name}":
                raise  # the module exists but one of its imports is missing
    return found


def public_api() -> dict[str, Callable[..., Any]]:
    """Every public function and class of the physics modules, keyed ``module:name``."""
    api: dict[str, Callable[..., Any]] = {}
    for module in _modules():
        short = module.__name__.rsplit(".", 1)[1]
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
                continue
            if inspect.isfunction(obj) or inspect.isclass(obj):
                api[f"{short}:{name}"] = obj
    return api


def _parameters(obj: Callable[..., Any]) -> list[inspect.Parameter]:
    try:
        signature = inspect.signature(obj)
    except (TypeError, ValueError):  # a class without an inspectable constructor
        return []
    return [p for p in signature.parameters.values() if p.name not in ("self", "cls")]


def _annotation(parameter: inspect.Parameter) -> str:
    if parameter.annotation is inspect.Parameter.empty:
        return ""
    if isinstance(parameter.annotation, str):
        return parameter.annotation
    return inspect.formatannotation(parameter.annotation)


def _is_numeric(parameter: inspect.Parameter, doc_type: str) -> bool:
    annotation = _annotation(parameter)
    if annotation:
        return bool(NUMERIC_ANNOTATION.search(annotation)) and not INTEGER_ARRAY.match(annotation)
    return bool(NUMERIC_DOC_TYPE.search(doc_type))


def _returns_value(function: Callable[..., Any]) -> bool:
    annotation = inspect.signature(function).return_annotation
    if annotation is not inspect.Signature.empty:
        text = annotation if isinstance(annotation, str) else inspect.formatannotation(annotation)
        return text.strip() not in NONE_RETURNS
    try:
        tree = ast.parse(textwrap.dedent(inspect.getsource(function)))
    except (OSError, TypeError, SyntaxError):
        return False
    body = tree.body[0]
    for node in ast.walk(body):
        if isinstance(node, ast.Return) and node.value is not None:
            return True
    return False


def problems(obj: Callable[..., Any]) -> list[str]:
    """What the docstring of ``obj`` lacks under the rules of the module docstring."""
    raw = inspect.getdoc(obj) or ""
    if inspect.isclass(obj) and raw == (inspect.getdoc(object) or ""):
        raw = ""
    if not raw.strip():
        return ["no docstring"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            doc = NumpyDocString(raw)
        except ValueError as error:
            return [f"unparsable docstring ({error})"]
    found = [f"numpydoc: {w.message}" for w in caught]

    params = _parameters(obj)
    sections = ["Parameters", "Other Parameters"]
    if inspect.isclass(obj):
        sections.append("Attributes")
    documented: dict[str, tuple[str, str]] = {}
    for section in sections:
        for entry in doc[section]:
            for name in entry.name.split(","):
                documented[name.strip().lstrip("*")] = (entry.type, " ".join(entry.desc))

    if params and not any(doc[s] for s in sections):
        found.append("no Parameters section")
    else:
        names = {p.name for p in params}
        missing = [p.name for p in params if p.name not in documented]
        if missing:
            found.append(f"Parameters lacks {', '.join(missing)}")
        if params:
            extra = sorted(set(documented) - names)
            if any(name.startswith("..") for name in extra):
                found.append("a directive inside Parameters (move it to Notes)")
            extra = [name for name in extra if not name.startswith("..")]
            if extra and not inspect.isclass(obj):  # a class may document more attributes
                found.append(f"Parameters names non-parameters {', '.join(extra)}")
        no_unit = [
            p.name
            for p in params
            if p.name in documented
            and _is_numeric(p, documented[p.name][0])
            and not UNIT.search(documented[p.name][0] + "\n" + documented[p.name][1])
        ]
        if no_unit:
            found.append(f"no [unit] for {', '.join(no_unit)}")

    if inspect.isfunction(obj) and _returns_value(obj):
        section = "Yields" if inspect.isgeneratorfunction(obj) else "Returns"
        if not doc[section]:
            found.append(f"no {section} section")
    return found


API = public_api()


def test_the_rules_catch_what_they_should() -> None:
    """The checker itself, on small examples."""

    def good(length: float, count: int, factor: ArrayLike) -> float:
        """Do it.

        Parameters
        ----------
        length : float
            Length [m].
        count : int
            How many.
        factor : array_like
            Balance factor [-].

        Returns
        -------
        float
            Result [m].
        """
        return length

    def bad(length: float, speed: float, extra: int) -> float:
        """Do it.

        Parameters
        ----------
        length, speed : float
            Length [0, 1] and speed, see [1].
        """
        return length

    assert problems(good) == []
    assert problems(bad) == [
        "Parameters lacks extra",
        "no [unit] for length, speed",
        "no Returns section",
    ]
    for text in ("[m]", "[kg m]", "[rad/s]", "[-]", "[N*m]", "[kg m^2]", "[°]", "[m along y]"):
        assert UNIT.search(f"Some value {text}."), text
    for text in ("[0, 1]", "[1]", "[ m]", "[]"):
        assert not UNIT.search(f"Some value {text}."), text


def test_public_physics_api_found() -> None:
    assert len(API) > 50, "the discovery of the public physics API found too little"


@pytest.mark.parametrize("key", sorted(API))
def test_docstring(key: str) -> None:
    found = problems(API[key])
    assert not found, f"{key}: {'; '.join(found)} (rules: tests/test_docstrings.py)"


if __name__ == "__main__":
    # print today's failures
    failing = {key: problems(obj) for key, obj in sorted(API.items())}
    for key, found in failing.items():
        if found:
            print(f'    "{key}",  # {"; ".join(found)}')
