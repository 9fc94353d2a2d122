"""Presentation of results in words and frames, above the library that computes them.

======================================  ==========================================
module                                  what it holds
======================================  ==========================================
:mod:`gyrovib.presentation.frames`      ``to_frame``: any result as a tidy pandas
                                        DataFrame (``Result.to_frame()``)
:mod:`gyrovib.presentation.reasons`     why a sensor fails ``select``, in words
======================================  ==========================================
"""
