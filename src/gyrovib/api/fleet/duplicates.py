"""Several recordings joined are distinct recordings (docs/recordings.md).

One log given twice — the same path, another path to the same file, or a copy
under another name — would count its time twice in the joined mission (θ_V, the
noise budget) and its spectra twice in the envelope. It is refused, naming
both: the paths before anything is read (:func:`refuse_same_paths`), the
contents by their SHA-256 once each recording is read (:func:`refuse_same_contents`).
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence

from gyrovib.api.recordings.readers import RecordingError
from gyrovib.errors import Problem


def refuse_same_paths(paths: Sequence[str]) -> None:
    """A file named twice (the same path, or two paths to one file) is refused."""
    seen: dict[str, str] = {}
    for path in paths:
        key = os.path.normcase(os.path.realpath(path))
        if key in seen:
            first = seen[key]
            how = "given twice" if first == path else f"the same file as {first}"
            raise RecordingError(Problem(
                f"this recording is {how}: each recording is joined once (twice, its time "
                "would count twice in the joined mission); drop the repeat", path))
        seen[key] = path


def refuse_same_contents(files: Iterable[tuple[str, str]]) -> None:
    """Two recordings with one SHA-256 (``(path, sha256)`` pairs) are refused."""
    seen: dict[str, str] = {}
    for path, digest in files:
        if digest in seen:
            raise RecordingError(Problem(
                f"this recording has the same contents (SHA-256 {digest[:12]}…) as "
                f"{seen[digest]}: each recording is joined once (twice, its time would count "
                "twice in the joined mission); drop the copy", path))
        seen[digest] = path
