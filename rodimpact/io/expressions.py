"""Restricted arithmetic expressions for model files, evaluated with numpy -- never with Python ``eval``.

Used for area functions of rod segments (thesis eq. 3.24: ``"A1 - 0.3*A0*sin(pi*s/L)"``), force and velocity
histories (variable ``t``) and initial fields (variable ``x``). An expression may contain

* numbers, the named variables of its context and the model's ``[parameters]`` (in SI units),
* the constants ``pi`` and ``e``,
* ``+ - * / ** %``, unary ``-``/``+``, comparisons ``< <= > >= == !=``, ``and``, ``or``, ``not``,
  conditional ``a if cond else b`` (element-wise, like ``where``),
* the functions in :data:`FUNCTIONS` (element-wise numpy functions).

Anything else -- attribute access, subscripts, lambdas, comprehensions, names not listed -- is rejected when the
expression is read, with a message naming the offending piece. The expression is parsed by :mod:`ast` and then
evaluated by walking the checked tree with numpy functions.
"""

from __future__ import annotations

import ast
import math
import operator
from typing import Any, Callable, Mapping

import numpy as np

from .quantities import ModelError

#: Functions allowed in expressions (all element-wise).
FUNCTIONS: dict[str, Callable[..., Any]] = {
    "sin": np.sin, "cos": np.cos, "tan": np.tan, "arcsin": np.arcsin, "arccos": np.arccos, "arctan": np.arctan,
    "asin": np.arcsin, "acos": np.arccos, "atan": np.arctan, "arctan2": np.arctan2, "atan2": np.arctan2,
    "sinh": np.sinh, "cosh": np.cosh, "tanh": np.tanh, "exp": np.exp, "log": np.log, "log10": np.log10,
    "sqrt": np.sqrt, "abs": np.abs, "sign": np.sign, "floor": np.floor, "ceil": np.ceil,
    "min": np.minimum, "max": np.maximum, "minimum": np.minimum, "maximum": np.maximum,
    "where": np.where, "clip": np.clip, "heaviside": lambda x: np.heaviside(x, 1.0),
}
#: Number of arguments of each function (numpy would take a surplus argument as its ``out=`` array).
ARITY: dict[str, int] = {name: 1 for name in FUNCTIONS}
ARITY.update({"arctan2": 2, "atan2": 2, "min": 2, "max": 2, "minimum": 2, "maximum": 2, "where": 3, "clip": 3})
_SIGNATURES = {"where": "where(condition, a, b)", "clip": "clip(x, low, high)", "arctan2": "arctan2(y, x)",
               "atan2": "atan2(y, x)", **{f: f"{f}(a, b)" for f in ("min", "max", "minimum", "maximum")}}
#: Constants available in every expression.
CONSTANTS: dict[str, float] = {"pi": math.pi, "e": math.e}

_BINOPS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
           ast.Pow: operator.pow, ast.Mod: np.mod}
_UNOPS = {ast.USub: operator.neg, ast.UAdd: operator.pos, ast.Not: np.logical_not}
_CMPOPS = {ast.Lt: operator.lt, ast.LtE: operator.le, ast.Gt: operator.gt, ast.GtE: operator.ge,
           ast.Eq: operator.eq, ast.NotEq: operator.ne}
_MAX_LENGTH = 2000
_MAX_NODES = 500


class SafeExpression:
    """A checked expression of the given ``variables`` (e.g. ``("s", "L")``) and ``parameters`` (name -> SI value).

    Calling it with the variables as keyword arguments returns a float array broadcast to their shape. It is
    also a plain callable of one positional argument (the first variable) with the others bound by
    :meth:`bind`, so that it can be handed to :class:`~rodimpact.AreaFunction` or :class:`~rodimpact.History`.
    """

    def __init__(self, source: str, variables: tuple[str, ...], parameters: Mapping[str, float] | None = None,
                 *, path: str = "expression", bound: Mapping[str, float] | None = None) -> None:
        if not isinstance(source, str):
            raise ModelError(f"{path}: an expression must be a string, got {type(source).__name__}")
        self.source = source.strip()
        self.variables = tuple(variables)
        self.parameters = {k: float(v) for k, v in (parameters or {}).items()}
        self.bound = {k: float(v) for k, v in (bound or {}).items()}
        self.path = path
        if not self.source:
            raise ModelError(f"{path}: the expression is empty")
        if len(self.source) > _MAX_LENGTH:
            raise ModelError(f"{path}: the expression is longer than {_MAX_LENGTH} characters")
        try:
            tree = ast.parse(self.source, mode="eval")
        except SyntaxError as exc:
            raise ModelError(f"{path}: cannot read the expression {self.source!r}: {exc.msg} "
                             f"(column {exc.offset})") from None
        if sum(1 for _ in ast.walk(tree)) > _MAX_NODES:
            raise ModelError(f"{path}: the expression is too complex (more than {_MAX_NODES} parts)")
        self._names = set(self.variables) | set(self.parameters) | set(CONSTANTS)
        self._check(tree.body)
        self._tree = tree.body
        self.used_parameters = sorted({n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
                                      & set(self.parameters))

    # ------------------------------------------------------------------ checking
    def _fail(self, node: ast.AST, what: str) -> None:
        piece = ast.get_source_segment(self.source, node) or type(node).__name__
        raise ModelError(f"{self.path}: {what} in the expression {self.source!r}: {piece!r}. Allowed: numbers, "
                         f"the variables {', '.join(self.variables)}, parameters, pi, e, + - * / ** %, "
                         f"comparisons, 'a if c else b' and the functions {', '.join(sorted(FUNCTIONS))}")

    def _check(self, node: ast.AST) -> None:
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                self._fail(node, "only numbers may appear as constants")
        elif isinstance(node, ast.Name):
            if node.id not in self._names:
                known = sorted(set(self.variables) | set(self.parameters))
                raise ModelError(f"{self.path}: unknown name {node.id!r} in the expression {self.source!r}; "
                                 f"known names are {known} plus pi and e "
                                 f"(define constants in [parameters])")
        elif isinstance(node, ast.BinOp):
            if type(node.op) not in _BINOPS:
                self._fail(node, "operator not allowed")
            self._check(node.left)
            self._check(node.right)
        elif isinstance(node, ast.UnaryOp):
            if type(node.op) not in _UNOPS:
                self._fail(node, "operator not allowed")
            self._check(node.operand)
        elif isinstance(node, ast.Compare):
            if any(type(op) not in _CMPOPS for op in node.ops):
                self._fail(node, "comparison not allowed")
            self._check(node.left)
            for c in node.comparators:
                self._check(c)
        elif isinstance(node, ast.BoolOp):
            for v in node.values:
                self._check(v)
        elif isinstance(node, ast.IfExp):
            for part in (node.test, node.body, node.orelse):
                self._check(part)
        elif isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
                self._fail(node, "unknown function")
            if node.keywords:
                self._fail(node, "keyword arguments are not allowed")
            for a in node.args:
                if isinstance(a, ast.Starred):
                    self._fail(a, "starred arguments are not allowed")
                self._check(a)
            name, n = node.func.id, ARITY[node.func.id]
            if len(node.args) != n:
                raise ModelError(f"{self.path}: {name}() takes {n} argument{'s' if n > 1 else ''}: "
                                 f"{_SIGNATURES.get(name, name + '(x)')}, got {len(node.args)} in the expression "
                                 f"{self.source!r}")
        else:
            self._fail(node, f"{type(node).__name__} is not allowed")

    # ------------------------------------------------------------------ evaluation
    def _eval(self, node: ast.AST, env: dict[str, Any]) -> Any:
        if isinstance(node, ast.Constant):
            return np.float64(node.value)     # numpy scalars: overflow gives inf (caught below), not an exception
        if isinstance(node, ast.Name):
            return env[node.id]
        if isinstance(node, ast.BinOp):
            return _BINOPS[type(node.op)](self._eval(node.left, env), self._eval(node.right, env))
        if isinstance(node, ast.UnaryOp):
            return _UNOPS[type(node.op)](self._eval(node.operand, env))
        if isinstance(node, ast.Compare):
            left = self._eval(node.left, env)
            result: Any = True
            for op, comp in zip(node.ops, node.comparators):
                right = self._eval(comp, env)
                result = np.logical_and(result, _CMPOPS[type(op)](left, right))
                left = right
            return result
        if isinstance(node, ast.BoolOp):
            vals = [self._eval(v, env) for v in node.values]
            fn = np.logical_and if isinstance(node.op, ast.And) else np.logical_or
            out = vals[0]
            for v in vals[1:]:
                out = fn(out, v)
            return out
        if isinstance(node, ast.IfExp):
            return np.where(self._eval(node.test, env), self._eval(node.body, env), self._eval(node.orelse, env))
        if isinstance(node, ast.Call):
            return FUNCTIONS[node.func.id](*(self._eval(a, env) for a in node.args))
        raise AssertionError("unchecked node")  # pragma: no cover - _check rejects everything else

    def evaluate(self, **values: Any) -> np.ndarray:
        """Evaluate with the variables given as keyword arguments; returns a float array of their common shape."""
        env: dict[str, Any] = {k: np.float64(v) for k, v in CONSTANTS.items()}
        env.update({k: np.float64(v) for k, v in self.parameters.items()})
        env.update({k: np.float64(v) for k, v in self.bound.items()})
        missing = [v for v in self.variables if v not in values and v not in self.bound]
        if missing:
            raise TypeError(f"{self.path}: values needed for {missing}")
        arrays = {k: np.asarray(v, dtype=float) for k, v in values.items()}
        env.update(arrays)
        shape = np.broadcast_shapes(*(a.shape for a in arrays.values())) if arrays else ()
        with np.errstate(all="ignore"):
            try:
                out = self._eval(self._tree, env)
            except (TypeError, ValueError, ArithmeticError) as exc:
                raise ModelError(f"{self.path}: cannot evaluate {self.source!r}: {exc}") from None
        out = np.broadcast_to(np.asarray(out, dtype=float), shape).astype(float)
        if not np.all(np.isfinite(out)):
            i = int(np.flatnonzero(~np.isfinite(out.ravel()))[0])
            where = ", ".join(f"{k} = {np.broadcast_to(a, shape).ravel()[i]:.6g}" for k, a in arrays.items())
            raise ModelError(f"{self.path}: the expression {self.source!r} gives {out.ravel()[i]} at {where}; "
                             f"it must be finite")
        return out

    def bind(self, **values: float) -> "SafeExpression":
        """A copy with some variables fixed (e.g. the segment length ``L``)."""
        return SafeExpression(self.source, self.variables, self.parameters, path=self.path,
                              bound={**self.bound, **values})

    def __call__(self, x: Any) -> np.ndarray:
        free = [v for v in self.variables if v not in self.bound]
        if len(free) != 1:
            raise TypeError(f"{self.path}: call with keyword arguments for {free}")
        return self.evaluate(**{free[0]: x})

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, SafeExpression) and self.source == other.source
                and self.variables == other.variables and self.bound == other.bound
                and {k: self.parameters[k] for k in self.used_parameters}
                == {k: other.parameters[k] for k in other.used_parameters})

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"SafeExpression({self.source!r})"


def expression_area(source: str, length: float, parameters: Mapping[str, float] | None = None,
                    path: str = "area") -> SafeExpression:
    """An area function A(s) in m^2 of the local position ``s`` (m) with the segment length ``L`` bound."""
    return SafeExpression(source, ("s", "L"), parameters, path=path).bind(L=length)
