"""Frozen records: :func:`dataclasses.dataclass` with ``frozen=True``, made without
compiling code at import.

Every result, model and option set of crankbalance is a frozen record: its fields are
given once, compared by value and never changed afterwards. A frozen dataclass of
Python 3.11 writes the source text of five or six methods per class (``__init__``,
``__repr__``, ``__eq__``, ``__hash__``, ``__setattr__``, ``__delattr__``) and compiles it
while its module is imported: 0.3 to 1.9 ms a class, 8 ms of every ``crankbalance
analyze`` and 17 ms of every ``balance`` on the reference machine, about a tenth of their
cold start (issue 30, docs/performance.md, "Round nine").

:func:`record` keeps the dataclass (``dataclasses.fields``, ``replace``, ``asdict`` and
``is_dataclass`` work as before: the fields are processed by :mod:`dataclasses` itself)
and gives it the same methods as plain functions shared by every record, which read the
fields' order, defaults and flags from the class (``__record__``). What they do is the
dataclass's:

- ``__init__`` takes the fields in order, by position or by name, fills defaults and
  default factories, and calls ``__post_init__`` when the class has one;
- assigning or deleting a field raises :class:`dataclasses.FrozenInstanceError`;
- ``__eq__`` compares the tuples of the fields with ``compare=True`` of two records of
  the same class; ``__hash__`` hashes those with ``hash`` (or ``compare``) true;
- ``__repr__`` shows the fields with ``repr=True``;
- a method the class body defines itself is kept.

A record's constructor fills its fields with one dict update: as fast as the compiled
one when the fields are given by position (1.07 against 1.04 us for ten fields), within
a tenth of a microsecond by name; records are made once per study or per batch, never per
sample.
"""

from __future__ import annotations

import dataclasses
import reprlib
from collections.abc import Callable
from typing import Any, NoReturn, TypeVar, dataclass_transform, overload

_T = TypeVar("_T", bound=type)


class _Spec:
    """What the shared methods read of one record class."""

    __slots__ = (
        *("cls", "fields", "names", "known", "required", "least", "defaults", "unset"),
        "factories",
        *("compared", "hashed", "shown", "post_init"),
    )

    def __init__(self, cls: type) -> None:
        fields = dataclasses.fields(cls)
        missing = dataclasses.MISSING
        self.cls = cls
        self.fields = frozenset(f.name for f in fields)
        #: the arguments of ``__init__``, in order
        self.names = tuple(f.name for f in fields if f.init)
        self.known = frozenset(self.names)
        #: every default (of a field with ``init=False`` too, which ``__init__`` sets; one
        #: with neither default nor factory is left to ``__post_init__``, as a dataclass
        #: leaves it)
        self.defaults = {f.name: f.default for f in fields if f.default is not missing}
        self.factories = {
            f.name: f.default_factory for f in fields if f.default_factory is not missing
        }
        self.required = self.known - self.defaults.keys() - self.factories.keys()
        #: the defaults of the fields ``__init__`` does not take
        self.unset = {k: v for k, v in self.defaults.items() if k not in self.known}
        #: the fewest arguments by position that give every required field
        self.least = max((self.names.index(n) + 1 for n in self.required), default=0)
        self.compared = tuple(f.name for f in fields if f.compare)
        self.hashed = tuple(f.name for f in fields if (f.compare if f.hash is None else f.hash))
        self.shown = tuple(f.name for f in fields if f.repr)
        self.post_init = hasattr(cls, "__post_init__")


def _init(self: Any, *args: Any, **kwargs: Any) -> None:
    spec: _Spec = type(self).__record__
    state = self.__dict__
    count = len(args)
    given: Any
    if count == len(spec.names) and not kwargs:  # every field by position
        state.update(zip(spec.names, args, strict=False))
        if spec.unset:
            state.update(spec.unset)
        given = spec.known
    elif not kwargs and spec.least <= count < len(spec.names):  # the first ones
        state.update(spec.defaults)
        state.update(zip(spec.names, args, strict=False))
        given = spec.names[:count]
    else:
        given = kwargs
        if args:
            given = dict(zip(spec.names, args, strict=False))
            if count > len(spec.names) or not given.keys().isdisjoint(kwargs):
                _refuse(type(self), args, kwargs)
            given.update(kwargs)
        keys = given.keys()
        if not (keys <= spec.known and keys >= spec.required):
            _refuse(type(self), args, kwargs)
        state.update(spec.defaults)
        state.update(given)
    if spec.factories:
        for name, factory in spec.factories.items():
            if name not in given:
                state[name] = factory()
    if spec.post_init:
        self.__post_init__()


def _refuse(cls: type, args: tuple[Any, ...], kwargs: dict[str, Any]) -> NoReturn:
    """The :class:`TypeError` a dataclass's ``__init__`` raises for these arguments."""
    spec: _Spec = getattr(cls, "__record__")  # noqa: B009 (set by record, unknown to mypy)
    title = f"{cls.__qualname__}()"
    if len(args) > len(spec.names):
        raise TypeError(
            f"{title} takes {len(spec.names)} positional arguments but {len(args)} were given"
        )
    for name in spec.names[: len(args)]:
        if name in kwargs:
            raise TypeError(f"{title} got multiple values for argument {name!r}")
    for name in kwargs:
        if name not in spec.known:
            raise TypeError(f"{title} got an unexpected keyword argument {name!r}")
    absent = [n for n in spec.names[len(args) :] if n in spec.required and n not in kwargs]
    raise TypeError(f"{title} missing a required argument: {absent[0]!r}")


def _setattr(self: Any, name: str, value: Any) -> None:
    spec: _Spec = type(self).__record__
    if type(self) is spec.cls or name in spec.fields:
        raise dataclasses.FrozenInstanceError(f"cannot assign to field {name!r}")
    object.__setattr__(self, name, value)


def _delattr(self: Any, name: str) -> None:
    spec: _Spec = type(self).__record__
    if type(self) is spec.cls or name in spec.fields:
        raise dataclasses.FrozenInstanceError(f"cannot delete field {name!r}")
    object.__delattr__(self, name)


def _eq(self: Any, other: Any) -> Any:
    if other.__class__ is not self.__class__:
        return NotImplemented
    names = self.__record__.compared
    return tuple(getattr(self, n) for n in names) == tuple(getattr(other, n) for n in names)


def _hash(self: Any) -> int:
    return hash(tuple(getattr(self, n) for n in self.__record__.hashed))


@reprlib.recursive_repr()
def _repr(self: Any) -> str:
    shown = ", ".join(f"{n}={getattr(self, n)!r}" for n in self.__record__.shown)
    return f"{self.__class__.__qualname__}({shown})"


class _Signature:
    """A record class's signature (:func:`inspect.signature`, ``help``), made when asked:
    building it at import would cost what :func:`record` saves."""

    def __get__(self, instance: Any, owner: type) -> Any:
        import inspect

        spec: _Spec = getattr(owner, "__record__")  # noqa: B009 (set by record, unknown to mypy)
        kind = inspect.Parameter.POSITIONAL_OR_KEYWORD
        parameters = []
        for f in dataclasses.fields(owner):
            if not f.init:
                continue
            default: Any = inspect.Parameter.empty
            if f.name in spec.defaults:
                default = spec.defaults[f.name]
            elif f.name in spec.factories:
                default = _FACTORY
            parameters.append(inspect.Parameter(f.name, kind, default=default, annotation=f.type))
        return inspect.Signature(parameters, return_annotation=None)


class _Factory:
    """The default shown for a field with a default factory, as a dataclass shows it."""

    def __repr__(self) -> str:
        return "<factory>"


_FACTORY = _Factory()
_SIGNATURE = _Signature()


def _make(cls: _T, show: bool, compare: bool) -> _T:
    """Process ``cls``'s fields with :mod:`dataclasses` (no method: nothing compiled), then
    give it the shared methods it does not define itself."""
    body = dict(cls.__dict__)
    dataclasses.dataclass(init=False, repr=False, eq=False)(cls)  # the same class, with fields
    setattr(cls, "__record__", _Spec(cls))  # noqa: B010 (a name mypy does not know)
    methods: dict[str, Any] = {
        "__init__": _init,
        "__setattr__": _setattr,
        "__delattr__": _delattr,
        "__signature__": _SIGNATURE,
    }
    if show:
        methods["__repr__"] = _repr
    if compare:
        methods["__eq__"] = _eq
        methods["__hash__"] = _hash
    for name, method in methods.items():
        # a method of the class body stays; a __hash__ that Python set to None because
        # the body defines __eq__ is not the body's (a dataclass replaces it too)
        if name not in body or (name == "__hash__" and body[name] is None and "__eq__" in body):
            setattr(cls, name, method)
    if body.get("__doc__") is None:
        cls.__doc__ = None  # not the signature dataclasses wrote before the fields' __init__
    return cls


@overload
def record(cls: _T, /) -> _T: ...


@overload
def record(*, repr: bool = True, eq: bool = True) -> Callable[[_T], _T]: ...


@dataclass_transform(frozen_default=True, field_specifiers=(dataclasses.field,))
def record(cls: Any = None, /, *, repr: bool = True, eq: bool = True) -> Any:
    """A frozen dataclass (``@dataclass(frozen=True)``) without compiled methods.

    Parameters
    ----------
    cls : type
        The class, when used bare: ``@record``.
    repr : bool
        Give the class a ``__repr__`` of its fields (``@record(repr=False)``: the class
        keeps ``object``'s or its own).
    eq : bool
        Compare and hash by the fields (``@record(eq=False)``: by identity, as a record
        whose fields hold arrays may rather be).
    """

    def wrap(cls: _T) -> _T:
        return _make(cls, repr, eq)

    return wrap if cls is None else wrap(cls)
