"""Betaflight blackbox logs, as the CSV that ``blackbox_decode`` writes (``--preset betaflight``).

``blackbox_decode`` (Betaflight's blackbox-tools) turns a ``.bbl`` into one CSV per
flight whose header names each field, separated by ``", "``: the frame time
``time (us)`` in µs, the filtered gyro ``gyroADC[0..2]`` and the accelerometer
``accSmooth[0..2]`` (``accADC[0..2]`` in newer firmware). Units: Betaflight logs
the gyro already scaled to deg/s, and ``blackbox_decode`` writes it so by default
(``--unit-rotation raw``) as by ``--unit-rotation deg/s``: the rate unit is deg/s
(rad/s after ``--unit-rotation rad/s``: say ``--rate-unit rad/s``). The
accelerometer is written in the sensor's counts unless decoded with
``--unit-acceleration g`` (or ``m/s2``); counts have a scale (``acc_1G`` in the log's
header) that the CSV does not carry, so the accelerations are read only when
``--accel-unit`` says which unit the file holds.
"""

from __future__ import annotations

from gyrovib.api.recordings.readers import ColumnNames, Columns, CsvColumns, open_csv, problem
from gyrovib.errors import Note

PRESETS = ("betaflight",)
#: The columns blackbox_decode writes.
BF_TIME = "time (us)"
BF_RATE = ("gyroADC[0]", "gyroADC[1]", "gyroADC[2]")
BF_ACCEL = (("accSmooth[0]", "accSmooth[1]", "accSmooth[2]"),
            ("accADC[0]", "accADC[1]", "accADC[2]"))


class BetaflightColumns(CsvColumns):
    """blackbox_decode's CSV: time in µs, the gyro in deg/s, the accelerometer in the unit
    ``--accel-unit`` names (not read without it)."""

    time_scale = 1e-6
    accel_unit_given = False

    def time_index(self) -> int | None:
        return self.names.index(BF_TIME) if BF_TIME in self.names else None

    def default_columns(self, rate: ColumnNames | None, accel: ColumnNames | None,
                        ) -> tuple[ColumnNames, ColumnNames | None]:
        if rate is None:
            missing = [c for c in BF_RATE if c not in self.names]
            if missing:
                raise problem(self.path, f"{{preset}} betaflight: no column {missing[0]!r} "
                                         "(blackbox_decode's CSV names the gyro gyroADC[0..2])",
                              1, 1, arguments=("preset",))
            rate = BF_RATE
        if accel is None:
            found = next((names for names in BF_ACCEL
                          if all(c in self.names for c in names)), None)
            if found is not None and self.accel_unit_given:
                accel = found
            elif found is not None:
                self.notes = (Note(f"{found[0][:-3]}[0..2] not read: blackbox_decode writes "
                                   "the accelerometer in the sensor's counts unless told "
                                   "--unit-acceleration g; give {accel_unit} (or m/s^2) for "
                                   "a file decoded so", ("accel_unit", "g")),)
        return rate, accel


def open_betaflight(path: str, accel_unit_given: bool) -> Columns:
    """A CSV of blackbox_decode, read with the Betaflight preset."""
    plain = open_csv(path)
    assert isinstance(plain, CsvColumns)
    if BF_TIME not in plain.names:
        raise problem(path, f"{{preset}} betaflight: no column {BF_TIME!r} (the first row of "
                            "blackbox_decode's CSV names it)", 1, 1, arguments=("preset",))
    out = BetaflightColumns(path, plain.names, plain.count)
    out.accel_unit_given = accel_unit_given
    return out


__all__ = ["BF_ACCEL", "BF_RATE", "BF_TIME", "PRESETS", "BetaflightColumns", "open_betaflight"]
