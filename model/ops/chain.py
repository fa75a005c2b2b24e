"""Chains of operations: their text (``mrm bounds "DSS 5, DSS 0.2"``) and their bound (docs/design.md §8).

A chain is a list of :class:`Link`: an operation of the registry, its parameters and, for a several-output
operation, the part the chain follows. Everything about an operation comes from its spec
(:class:`mrm.ops.registry.OperationSpec`): the words that name it, the numbers written after it (its
positional parameters, read by :meth:`~mrm.core.params.ParamSpec.read` as every other path reads them), its
part words, and its place in the bound rule (:attr:`~mrm.ops.registry.OperationSpec.bound`). So a chain's
text, a result's provenance (:mod:`mrm.ops.account`) and the library (:func:`mrm.bound`) give the same bound
with the same labels, and a new operation needs no edit here.

Grammar (case-insensitive; steps separated by ``,`` or ``;``, applied left to right)::

    WORD [number [, number …]] [part] [about x,y]

e.g. ``DSS 1.25 about 3,4``, ``ROT -30 @ (1, 2.5)``, ``SP 1/5``, ``TRANSLATE -1,2.5``, ``EDu``, ``COREFINE 8
first``. A pair may be written ``x,y``, ``x y`` or ``(x, y)``; ``at`` and ``@`` are synonyms of ``about``.
``ROT`` is the discrete-Euclidean rotation dR (a discrete operation); ``SCALE``, ``EROT`` and ``TRANSLATE``
are exact Euclidean maps.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from mrm.core.errors import ParameterError
from mrm.core.limits import check_chain_steps
from mrm.core.models import Model
from mrm.geometry.hausdorff.bounds import N_DIM, BoundResult, BoundStep, bound_of_chain
from mrm.ops.registry import OperationSpec, get_operation, operations

__all__ = ["Link", "chain_bound", "parse_chain"]


@dataclass(frozen=True)
class Link:
    """One step of a chain: an operation, its parameters and the part followed (several-output operations).

    Attributes
    ----------
    spec : OperationSpec
    params : Parameters
        Read and checked (exact numbers).
    part : str
        The output the chain continues with (a co-refinement's part name), or "" for its default.
    """

    spec: OperationSpec
    params: Any
    part: str = ""

    @classmethod
    def of(cls, operation: str | OperationSpec, part: str = "", **params: Any) -> Link:
        """The link of ``operation`` with these parameter values (read exactly, range-checked)."""
        spec = get_operation(operation)
        return cls(spec, spec.params.from_json(params), part)

    @property
    def label(self) -> str:
        """The step as a chain's text writes it (``DSS 5``, ``ROT 30 about 1,2``)."""
        return self.spec.label(self.params, self.part)

    def bound_step(self, n: int = N_DIM) -> BoundStep:
        """The step in the bound rule, on objects of dimension ``n``."""
        return self.spec.bound_step(self.params, self.part, n)


def chain_bound(
    links: Sequence[Link],
    model: Model | str = Model.STANDARD,
    *,
    exact_identities: bool = False,
    n: int = N_DIM,
) -> BoundResult:
    """The error bound of a chain (:func:`mrm.geometry.hausdorff.bounds.bound_of_chain` on its steps).

    A chain beyond the step limit is refused before any step is put into the bound rule (each makes its
    exact map).
    """
    check_chain_steps(len(links))
    return bound_of_chain(
        [link.bound_step(n) for link in links], model, n=n, exact_identities=exact_identities
    )


# ------------------------------------------------------------------------------------------------- parsing
_TOKEN = re.compile(
    r"\s*(?:"
    r"(?P<num>[-+\u2212]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?(?:/\d+)?|[-+]?(?:inf(?:inity)?|nan)\b)"
    r"|(?P<word>[A-Za-z][A-Za-z_\-]*)"
    r"|(?P<punct>[,;()@])"
    r")",
    re.IGNORECASE,
)


def _tokenize(text: str) -> list[tuple[str, str, int]]:
    tokens: list[tuple[str, str, int]] = []
    pos = 0
    while pos < len(text):
        if text[pos:].strip() == "":
            break
        m = _TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            bad = text[pos:].strip()[:12]
            raise ParameterError(f"cannot read {bad!r} at position {pos + 1} of the chain")
        kind = m.lastgroup
        assert kind is not None
        tokens.append((kind, m.group(kind), m.start(kind)))
        pos = m.end()
    return tokens


class _Parser:
    def __init__(self, text: str) -> None:
        self.tokens = _tokenize(text)
        self.i = 0

    def peek(self) -> tuple[str, str, int] | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self) -> tuple[str, str, int]:
        tok = self.peek()
        assert tok is not None
        self.i += 1
        return tok

    def at(self, kind: str, chars: str = "") -> bool:
        tok = self.peek()
        return tok is not None and tok[0] == kind and (not chars or tok[1] in chars)

    def number(self, what: str) -> str:
        tok = self.peek()
        if tok is None or tok[0] != "num":
            got = "the end of the chain" if tok is None else repr(tok[1])
            raise ParameterError(f"{what}: expected a number, got {got}")
        self.i += 1
        return tok[1]

    def pair(self, what: str) -> tuple[str, ...]:
        """A point: two numbers, or three (a centre in space: ``about 1,2,3``)."""
        paren = self.at("punct", "(")
        if paren:
            self.take()
        x = self.number(what)
        if self.at("punct", ","):
            self.take()
        y = self.number(what)
        z: tuple[str, ...] = ()
        if (self.at("punct", ",") and self._number_follows()) or self.at("num"):
            if self.at("punct", ","):
                self.take()
            z = (self.number(what),)
        if paren:
            if not self.at("punct", ")"):
                raise ParameterError(f"{what}: expected ')'")
            self.take()
        return (x, y, *z)

    def link(self) -> Link:
        tok = self.peek()
        if tok is None:
            raise ParameterError("expected an operation at the end of the chain")
        if tok[0] == "punct":
            raise ParameterError(f"empty step at position {tok[2] + 1} of the chain")
        spec = _chain_operation(tok)
        self.take()
        values: dict[str, Any] = {}
        positional = [s for s in spec.params.specs() if s.positional]
        for k, s in enumerate(positional):
            if k > 0 and self.at("punct", ",") and self._number_follows():
                self.take()  # TRANSLATE 1,2: the numbers of one step may be separated by a comma
            if s.optional and not self.at("num"):
                break
            what = f"{spec.symbol or spec.name} {s.label}"
            values[s.name] = self.pair(what) if s.kind == "point" else self.number(what)
        part = ""
        words = {w: p for p, w in spec.part_words.items()}
        if self.at("word") and self.peek()[1].lower() in words:  # type: ignore[index]
            part = words[self.take()[1].lower()]
        tok = self.peek()
        if tok is not None and ((tok[0] == "word" and tok[1].lower() in ("about", "at")) or tok[1] == "@"):
            self.take()
            values["center"] = self.pair(f"{spec.symbol or spec.name} centre")
        return Link(spec, spec.params.from_json(values), part)

    def _number_follows(self) -> bool:
        nxt = self.tokens[self.i + 1] if self.i + 1 < len(self.tokens) else None
        return nxt is not None and nxt[0] == "num"

    def chain(self) -> list[Link]:
        if not self.tokens:
            raise ParameterError("the chain is empty")
        links = [self.link()]
        while self.peek() is not None:
            if not self.at("punct", ",;"):
                tok = self.peek()
                assert tok is not None
                raise ParameterError(
                    f"unexpected {tok[1]!r} at position {tok[2] + 1} after {links[-1].label!r} "
                    "(steps are separated by commas)"
                )
            self.take()
            if self.peek() is None:
                break  # a trailing separator is harmless
            links.append(self.link())
        return links


def _chain_operation(tok: tuple[str, str, int]) -> OperationSpec:
    """The operation a chain's word names: one with a place in the bound rule."""
    if tok[0] == "word":
        try:
            spec = get_operation(tok[1])
        except ParameterError:
            spec = None
        if spec is not None and spec.bound is not None:
            return spec
    names = ", ".join(s.symbol for s in operations() if s.bound is not None and s.symbol)
    raise ParameterError(f"unknown operation {tok[1]!r} at position {tok[2] + 1} (expected one of {names})")


def parse_chain(text: str) -> list[Link]:
    """Read a chain such as ``"DSS 1.25, DSS 5, DSS 0.2, DSS 0.8"`` (applied left to right; module docstring).

    Raises
    ------
    ParameterError
        On an unknown operation, a missing or malformed number, a value its operation refuses (the message
        gives the allowed range).
    """
    if not isinstance(text, str):
        raise ParameterError(f"a chain is a string, got {type(text).__name__}")
    return _Parser(text).chain()
