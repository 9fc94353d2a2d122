"""The array type aliases of the package, defined once: float, integer, complex, boolean,
a breakpoint table."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

#: An array of float64 (any shape).
FloatArray = NDArray[np.float64]
#: An array of int64 (any shape).
IntArray = NDArray[np.int64]
#: An array of complex128 (any shape).
ComplexArray = NDArray[np.complex128]
#: An array of booleans (any shape).
BoolArray = NDArray[np.bool_]
#: A breakpoint table on log-log axes: frequencies in Hz and values
#: (:mod:`gyrovib.core.transmissibility`).
Table = tuple[FloatArray, FloatArray]
