"""One module per command: ``analyze``, ``sweep``, ``bounds``, ``select``.

Each runs the shared pipeline of :mod:`gyrovib.api.study.prepare`, evaluates the
model on what it prepared and returns a result of :mod:`gyrovib.api.evaluation.results`.
"""
