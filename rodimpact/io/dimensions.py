"""Dimensional check of model-file expressions against the units of their ``[parameters]``.

Numbers inside an expression are SI values of unknown dimension, so the check cannot prove an expression right;
it catches what the parameters and variables *do* determine: an area expression ``"A0"`` whose parameter was
given as ``"1260 mm"`` (a length: the ``^2`` forgotten), a sum of a length and a force, the sine of a length.

Every sub-expression gets a pint dimensionality, or ``None`` ("any") when it involves a bare number or a
parameter given without a unit. Rules: ``+ - %``, comparisons, ``min``/``max``/``where``/``clip`` need equal
dimensions where both are known; ``* /`` combine them (``None`` if either is unknown); ``x ** n`` needs a
dimensionless or numeric exponent; ``sin``, ``exp``, ``log`` and the like need a dimensionless argument and give
a dimensionless result; ``sqrt`` halves the exponents.
"""

from __future__ import annotations

import ast
from typing import Any, Mapping, Optional

from .quantities import DIMENSIONS, ModelError, _registry, pint_quantity

Dim = Optional[Any]     # a pint UnitsContainer, or None for "any dimension"

_DIMENSIONLESS_FUNCTIONS = {"sin", "cos", "tan", "arcsin", "arccos", "arctan", "asin", "acos", "atan", "sinh",
                            "cosh", "tanh", "exp", "log", "log10"}
_SAME_FUNCTIONS = {"abs", "floor", "ceil", "min", "max", "minimum", "maximum", "clip"}


def dimension_of(name: str) -> Any:
    """The pint dimensionality of a :data:`~rodimpact.io.quantities.DIMENSIONS` entry (e.g. ``"area"``)."""
    return _registry().Quantity(1.0, DIMENSIONS[name].pint).dimensionality


class Parameters(dict):
    """``[parameters]`` as name -> SI value, remembering the dimension each was written with (``dimensions``:
    name -> pint dimensionality, ``None`` for a bare number)."""

    def __init__(self, values: Mapping[str, float], raw: Mapping[str, Any]) -> None:
        super().__init__(values)
        self.dimensions: dict[str, Dim] = {
            name: pint_quantity(v, f"parameters.{name}").dimensionality if isinstance(v, str) else None
            for name, v in raw.items()}


class _Checker:
    def __init__(self, source: str, path: str, names: Mapping[str, Dim]) -> None:
        self.source, self.path, self.names = source, path, names
        self.dimensionless = _registry().Quantity(1.0).dimensionality

    def fail(self, node: ast.AST, what: str) -> None:
        piece = ast.get_source_segment(self.source, node) or self.source
        raise ModelError(f"{self.path}: {what} in {piece!r} (expression {self.source!r}); check the units of "
                         f"the [parameters] it uses")

    def same(self, node: ast.AST, dims: list[Dim], what: str) -> Dim:
        known = [d for d in dims if d is not None]
        if any(d != known[0] for d in known[1:]):
            self.fail(node, f"{what} of different dimensions ({', '.join(_show(d) for d in known)})")
        return known[0] if known else None

    def dim(self, node: ast.AST) -> Dim:
        if isinstance(node, ast.Constant):
            return None
        if isinstance(node, ast.Name):
            return self.names.get(node.id)
        if isinstance(node, ast.UnaryOp):
            inner = self.dim(node.operand)
            return self.dimensionless if isinstance(node.op, ast.Not) else inner
        if isinstance(node, ast.BinOp):
            return self.binop(node)
        if isinstance(node, ast.Compare):
            self.same(node, [self.dim(node.left), *(self.dim(c) for c in node.comparators)], "comparison")
            return self.dimensionless
        if isinstance(node, ast.BoolOp):
            for v in node.values:
                self.dim(v)
            return self.dimensionless
        if isinstance(node, ast.IfExp):
            self.dim(node.test)
            return self.same(node, [self.dim(node.body), self.dim(node.orelse)], "the two branches are")
        if isinstance(node, ast.Call):
            return self.call(node)
        raise AssertionError("unchecked node")  # pragma: no cover - SafeExpression rejects everything else

    def binop(self, node: ast.BinOp) -> Dim:
        left, right = self.dim(node.left), self.dim(node.right)
        if isinstance(node.op, (ast.Add, ast.Sub, ast.Mod)):
            return self.same(node, [left, right], "sum or difference")
        if isinstance(node.op, ast.Pow):
            if right is not None and right != self.dimensionless:
                self.fail(node, f"an exponent of dimension {_show(right)}")
            if left is None or left == self.dimensionless:
                return left
            if isinstance(node.right, ast.Constant):
                return left ** float(node.right.value)
            return None
        if left is None or right is None:
            return None
        return left * right if isinstance(node.op, ast.Mult) else left / right

    def call(self, node: ast.Call) -> Dim:
        name = node.func.id  # type: ignore[attr-defined]
        args = [self.dim(a) for a in node.args]
        if name in _DIMENSIONLESS_FUNCTIONS:
            for a, d in zip(node.args, args):
                if d is not None and d != self.dimensionless:
                    self.fail(a, f"{name}() of a quantity of dimension {_show(d)}")
            return self.dimensionless
        if name in ("arctan2", "atan2"):
            self.same(node, args, f"{name}() of arguments")
            return self.dimensionless
        if name in ("sign", "heaviside"):
            return self.dimensionless
        if name == "sqrt":
            return None if not args or args[0] is None else args[0] ** 0.5
        if name == "where":
            return self.same(node, args[1:], "where() of values")
        if name in _SAME_FUNCTIONS:
            return self.same(node, args, f"{name}() of arguments")
        return None


def _show(dim: Any) -> str:
    text = str(dim)
    return text if text and text != "dimensionless" else "1 (dimensionless)"


def check_dimension(expr: Any, expected: str, variables: Mapping[str, str], parameters: Mapping[str, float]) -> None:
    """Raise :class:`ModelError` (with the expression's key path) if ``expr`` (a
    :class:`~rodimpact.io.expressions.SafeExpression`) is dimensionally inconsistent or, where its dimension is
    determined, differs from ``expected`` (a :data:`DIMENSIONS` name). ``variables`` names the dimension of each
    variable (``{"s": "length"}``); ``parameters`` is checked only if it is a :class:`Parameters`."""
    parameter_dims: Mapping[str, Dim] = getattr(parameters, "dimensions", {})
    names: dict[str, Dim] = {k: dimension_of(v) for k, v in variables.items()}
    names.update({k: dimension_of("dimensionless") for k in ("pi", "e")})
    names.update({k: d for k, d in parameter_dims.items() if k in expr.parameters})
    checker = _Checker(expr.source, expr.path, names)
    got = checker.dim(ast.parse(expr.source, mode="eval").body)
    want = dimension_of(expected)
    if got is not None and got != want:
        used = ", ".join(f"{k} in {_show(parameter_dims[k])}" for k in expr.used_parameters
                         if parameter_dims.get(k) is not None)
        article = "an" if expected[0] in "aeiou" else "a"
        raise ModelError(f"{expr.path}: the expression {expr.source!r} has dimension {_show(got)}, but {article} "
                         f"{expected} ({DIMENSIONS[expected].si}) is expected" + (f" ({used})" if used else "")
                         + "; check the units of the [parameters] it uses")
