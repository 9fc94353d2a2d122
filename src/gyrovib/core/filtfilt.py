"""A forward-backward second-order-sections filter written a block at a time.

:func:`sosfiltfilt_into` gives the numbers of ``scipy.signal.sosfiltfilt(sos, x)``
(default odd padding of 3·(2·sections + 1) samples, ``sosfilt_zi`` initial
conditions) for a 1-D ``x``, but writes them into a caller's array and holds
no copy of the signal: the padded signal and both passes are taken in blocks,
the filter's state carried from one block to the next (``sosfilt``'s ``zi``
and ``zf``), which is the same recursion sample for sample. A column of a
long recording so costs its output and a few blocks, not three padded copies.

scipy is imported inside the function (a lazy boundary of the package).
"""

from __future__ import annotations

from gyrovib.core._types import FloatArray

#: Samples filtered per call of sosfilt.
BLOCK = 1 << 18


def padding(sos: FloatArray) -> int:
    """sosfiltfilt's default pad length for ``sos``: 3 × its number of taps."""
    ntaps = 2 * sos.shape[0] + 1
    ntaps -= min(int((sos[:, 2] == 0).sum()), int((sos[:, 5] == 0).sum()))
    return int(3 * ntaps)


def sosfiltfilt_into(sos: FloatArray, x: FloatArray, out: FloatArray,
                     block: int = BLOCK) -> FloatArray:
    """``out[:] = sosfiltfilt(sos, x)`` for 1-D float64 ``x`` (any stride), a block at a time.

    ``out`` may be a strided view (a column of a 2-D array) but must not
    overlap ``x``. Raises ValueError as scipy does when ``x`` is not longer
    than the padding.
    """
    # lazy: scipy only where a recording is filtered
    from scipy.signal import sosfilt, sosfilt_zi

    n = x.shape[0]
    edge = padding(sos)
    if n <= edge:
        raise ValueError(f"The length of the input vector x must be greater than padlen, "
                         f"which is {edge}.")
    zi = sosfilt_zi(sos)
    left = 2.0 * x[0] - x[1:edge + 1][::-1]
    right = 2.0 * x[n - 1] - x[n - edge - 1:n - 1][::-1]
    # forward pass over [left, x, right]: the state runs on through the blocks
    head, z = sosfilt(sos, left, zi=zi * left[0])
    for lo in range(0, n, block):
        out[lo:lo + block], z = sosfilt(sos, x[lo:lo + block], zi=z)
    tail, z = sosfilt(sos, right, zi=z)
    # backward pass, from the end of the forward output; the left pad's output is not kept
    tail_back, z = sosfilt(sos, tail[::-1], zi=zi * tail[-1])
    del tail_back
    for hi in range(n, 0, -block):
        lo = max(0, hi - block)
        seg, z = sosfilt(sos, out[lo:hi][::-1], zi=z)
        out[lo:hi] = seg[::-1]
    del head
    return out


__all__ = ["padding", "sosfiltfilt_into"]
