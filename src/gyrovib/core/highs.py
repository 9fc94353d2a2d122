"""Linear programmes solved by HiGHS through its own Python bindings, ``highspy``.

The datasheet worst case (docs/model.md section 11) is a semi-infinite LP solved on
refined grids; each grid LP goes to HiGHS. ``highspy`` is the HiGHS team's own
binding of the same solver scipy vendors for ``linprog(method="highs")``; it
is used directly because importing it takes ~15 ms where importing
``scipy.optimize`` takes ~350 ms, which would dominate a first
``gyrovib analyze``. It is imported on the first solve, so runs without
datasheet sensors never load it.

Matrices are passed column-wise (CSC: ``start``, ``index``, ``value``) so no
sparse-matrix library is needed to build them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gyrovib.core._types import FloatArray
from gyrovib.frozen import Frozen

#: Tolerances of the envelope's grid LPs (HiGHS defaults are 1e-7).
TIGHT: dict[str, float | str] = {"primal_feasibility_tolerance": 1e-10,
                                 "dual_feasibility_tolerance": 1e-10,
                                 "presolve": "off"}


@dataclass(frozen=True, eq=False, repr=False)
class Solution(Frozen):
    """A solve: ``ok`` (optimal), the primal ``x``, the row duals, HiGHS's status text.

    ``row_dual`` is the sensitivity of the (minimised) objective to each row's
    bound, the same sign convention as scipy's ``res.eqlin.marginals``.
    """

    ok: bool
    x: FloatArray
    row_dual: FloatArray
    status: str


class Model:
    """One LP kept in HiGHS so that it can grow and be re-solved from its last basis.

    min costᵀx s.t. row_lower ≤ A·x ≤ row_upper, col_lower ≤ x ≤ col_upper;
    A (m × n) is given column-wise: the entries of column j are
    ``value[start[j]:start[j+1]]`` in rows ``index[start[j]:start[j+1]]``.
    Infinite bounds are ±inf. ``options`` are HiGHS option names and values.
    Columns added by :meth:`add_columns` enter non-basic at their bound, so the
    last optimal basis stays primal feasible and the next :meth:`run` starts
    from it (the envelope's exchange adds grid points as such columns).
    """

    def __init__(self, cost: np.ndarray, start: np.ndarray, index: np.ndarray,
                 value: np.ndarray, row_lower: np.ndarray, row_upper: np.ndarray,
                 col_lower: np.ndarray, col_upper: np.ndarray,
                 options: dict[str, float | str] | None = None) -> None:
        # lazy: highspy only where a datasheet envelope needs the LP
        import highspy

        cost = np.ascontiguousarray(cost, dtype=float)
        n = cost.size
        m = np.asarray(row_lower).size
        lp = highspy.HighsLp()
        lp.num_col_ = n
        lp.num_row_ = m
        lp.col_cost_ = cost
        lp.col_lower_ = np.ascontiguousarray(col_lower, dtype=float)
        lp.col_upper_ = np.ascontiguousarray(col_upper, dtype=float)
        lp.row_lower_ = np.ascontiguousarray(row_lower, dtype=float)
        lp.row_upper_ = np.ascontiguousarray(row_upper, dtype=float)
        lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
        lp.a_matrix_.num_col_ = n
        lp.a_matrix_.num_row_ = m
        lp.a_matrix_.start_ = np.ascontiguousarray(start, dtype=np.int32)
        lp.a_matrix_.index_ = np.ascontiguousarray(index, dtype=np.int32)
        lp.a_matrix_.value_ = np.ascontiguousarray(value, dtype=float)
        # The base class: highspy.Highs's constructor registers Python callbacks
        # and prints HiGHS's banner to the C stdout before any option can silence
        # it, which would corrupt a JSON document written to stdout.
        self._optimal = highspy.HighsModelStatus.kOptimal
        self._h = highspy._Highs()  # type: ignore[attr-defined]
        self._h.setOptionValue("output_flag", False)
        self._h.setOptionValue("threads", 1)
        for key, val in (options or {}).items():
            self._h.setOptionValue(key, val)
        self._h.passModel(lp)

    def add_columns(self, cost: np.ndarray, start: np.ndarray, index: np.ndarray,
                    value: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> None:
        """Append columns (``start`` has one entry per new column plus the end)."""
        cost = np.ascontiguousarray(cost, dtype=float)
        st = np.ascontiguousarray(start, dtype=np.int32)
        self._h.addCols(cost.size, cost, np.ascontiguousarray(lower, dtype=float),
                        np.ascontiguousarray(upper, dtype=float), int(st[-1]), st[:-1],
                        np.ascontiguousarray(index, dtype=np.int32),
                        np.ascontiguousarray(value, dtype=float))

    def run(self) -> Solution:
        """Solve (from the last basis, if any) and return the solution."""
        self._h.run()
        status = self._h.getModelStatus()
        sol = self._h.getSolution()
        return Solution(ok=status == self._optimal,
                        x=np.asarray(sol.col_value, dtype=float),
                        row_dual=np.asarray(sol.row_dual, dtype=float),
                        status=self._h.modelStatusToString(status))


def solve(cost: np.ndarray, start: np.ndarray, index: np.ndarray, value: np.ndarray,
          row_lower: np.ndarray, row_upper: np.ndarray, col_lower: np.ndarray,
          col_upper: np.ndarray, options: dict[str, float | str] | None = None) -> Solution:
    """min costᵀx s.t. row_lower ≤ A·x ≤ row_upper and the column bounds (see :class:`Model`)."""
    return Model(cost, start, index, value, row_lower, row_upper, col_lower, col_upper,
                 options).run()
