"""The names of eq. (2)'s coefficients and of the terms of Δ_V, each tuple defined once.

Plain tuples, no imports: the format (:mod:`gyrovib.models`), the kernels
(:mod:`gyrovib.core`), the library and the renderers all name coefficients in
these orders, so a column order cannot differ between them.
"""

from __future__ import annotations

#: Column order of a coefficient matrix (eq. 2).
COEFFICIENTS: tuple[str, ...] = ("k0", "k1", "A1", "k2", "k3", "k4", "k5", "m1", "m2", "m31", "m32")
#: The rate polynomial's nonlinear coefficients: what a datasheet envelope bounds
#: (:mod:`gyrovib.core.envelope`), in the order of its x.
POLYNOMIAL: tuple[str, ...] = ("A1", "k2", "k3", "k4", "k5")
#: The coefficients that receive a bound (:mod:`gyrovib.core.synthesis`), in report order;
#: also the columns of a recording's moments (:mod:`gyrovib.core.recording`).
BOUNDED: tuple[str, ...] = (*POLYNOMIAL, "m31", "m32")
#: Names of the additive terms Δ0(1..5): the coefficient each is proportional to.
ADDITIVE_TERMS: tuple[str, ...] = ("A1", "k2", "k4", "m31", "m32")
#: Names of the additive terms of docs/model.md sections 8 and 10: Δ0(6) = ΣG_jk·⟨a_j a_k⟩
#: (``g2``), k3·M3 (``k3``) and k5·M5 (``k5``).
EXTRA_TERMS: tuple[str, ...] = ("g2", "k3", "k5")
#: Every additive term, in the order results show them: ADDITIVE_TERMS, then EXTRA_TERMS.
ALL_TERMS: tuple[str, ...] = (*ADDITIVE_TERMS, *EXTRA_TERMS)
#: The coefficients that may carry an uncertainty, in the order of eq. (2) (k1 = 1 has none).
UNCERTAIN: tuple[str, ...] = tuple(name for name in COEFFICIENTS if name != "k1")
