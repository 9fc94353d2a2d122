"""PX4 ULog recordings (pyulog, the ``gyrovib[ulog]`` extra): a topic's instance as columns.

Topics (docs/recordings.md): ``sensor_combined`` (the default; ``gyro_rad[0..2]``
in rad/s, ``accelerometer_m_s2[0..2]`` in m/s²), ``sensor_gyro`` (``x``, ``y``,
``z``), any other topic whose columns ``--rate-columns`` names, and
``sensor_gyro_fifo``: the raw high-rate FIFO, kHz. A FIFO message holds up to 32
int16 samples per axis, ``samples`` of them valid, the newest taken at
``timestamp_sample`` and each earlier one ``dt`` µs before it; a sample is
``float64(x[k]) · float64(scale)`` rad/s (m/s² for ``sensor_accel_fifo``, which is
paired with the gyro FIFO of the same instance: its samples are interpolated
linearly onto the gyro's times).

A topic logged by several instances (``multi_id``) needs ``--instance N``; without
it, one instance is taken, several are refused with a list of each one's rate and
length. The damage a log records is said, never analysed silently: a log that ends
inside a message (cut short), data pyulog skipped as corrupt, and clipped samples
counted by ``vehicle_imu_status``. Before pyulog reads a byte of data, the formats the
log declares are flattened here as pyulog will flatten them
(:func:`check_format_cost`): nested types multiply, and a tiny edit of a log can make
one message cost millions of fields; such a log is refused at the format's place.
Everything pyulog prints is captured (:mod:`gyrovib.api.recordings.quiet`).
"""

from __future__ import annotations

import io
import os
import struct
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from gyrovib.api.recordings.quiet import as_notes, captured
from gyrovib.api.recordings.readers import ArrayColumns, ColumnNames, Columns, problem
from gyrovib.core._types import FloatArray
from gyrovib.errors import literal

#: ULog's default topic and its fields (rad/s, m/s², timestamps in µs).
ULOG_TOPIC = "sensor_combined"
ULOG_RATE = ("gyro_rad[0]", "gyro_rad[1]", "gyro_rad[2]")
ULOG_ACCEL = ("accelerometer_m_s2[0]", "accelerometer_m_s2[1]", "accelerometer_m_s2[2]")
#: The raw FIFO topics, and the columns their samples are given as.
FIFO_GYRO, FIFO_ACCEL = "sensor_gyro_fifo", "sensor_accel_fifo"
FIFO_RATE = ("x", "y", "z")
FIFO_ACCEL_COLUMNS = ("accel_x", "accel_y", "accel_z")
#: The topic whose clip counters say which samples were clipped.
IMU_STATUS = "vehicle_imu_status"

#: The most fields one message may flatten to (nested types and arrays multiplied
#: out, as pyulog does): PX4's own topics stay below a thousand.
MAX_FIELDS = 16_384
_BASIC = {"int8_t": 1, "uint8_t": 1, "int16_t": 2, "uint16_t": 2, "int32_t": 4,
          "uint32_t": 4, "int64_t": 8, "uint64_t": 8, "float": 4, "double": 8,
          "bool": 1, "char": 1}
_DEFINITIONS = {ord(c) for c in "BFIMPQ"}


# ----------------------------------------------------------------- format cost


def _formats(path: str) -> dict[str, tuple[int, list[tuple[str, int]]]]:
    """The ``F`` messages of the definitions section: name -> (byte offset, [(type,
    count)]), count 0 for a scalar field."""
    out: dict[str, tuple[int, list[tuple[str, int]]]] = {}
    with open(path, "rb") as fh:
        if len(fh.read(16)) < 16:
            return out
        while len(head := fh.read(3)) == 3:
            size, kind = struct.unpack("<HB", head)
            if kind not in _DEFINITIONS:
                break
            where = fh.tell() - 3
            body = fh.read(size)
            if kind != ord("F"):
                continue
            text = body.decode("ascii", errors="replace")
            name, _, fields = text.partition(":")
            parsed = []
            for field in fields.split(";"):
                kind_name = field.strip().split(" ")[0]
                if not kind_name:
                    continue
                base, _, count = kind_name.partition("[")
                parsed.append((base, int(count.rstrip("]")) if count.rstrip("]").isdigit()
                               else 0))
            out[name] = (where, parsed)
    return out


def check_format_cost(path: str) -> None:
    """Refuse a log one of whose formats flattens to more than :data:`MAX_FIELDS`
    fields, or refers to itself: what pyulog would spend on each of its messages,
    estimated from the definitions before any data is read."""
    formats = _formats(path)
    memo: dict[str, int] = {}

    def leaves(name: str, seen: tuple[str, ...]) -> int:
        if name in memo:
            return memo[name]
        if name in seen:
            raise problem(path, f"format {seen[0]!r} (byte {formats[seen[0]][0]}) contains "
                                f"itself through {name!r}: refused before reading")
        total = 0
        for base, count in formats[name][1]:
            one = 1 if base in _BASIC or base not in formats else leaves(base, (*seen, name))
            total += one * max(count, 1)
            if total > MAX_FIELDS:
                break
        memo[name] = total
        return total

    for name, (where, _) in formats.items():
        if leaves(name, ()) > MAX_FIELDS:
            raise problem(path, f"format {name!r} (byte {where}) flattens to more than "
                                f"{MAX_FIELDS} fields per message (its nested types and "
                                "arrays multiplied out): refused before reading, as a log "
                                "edited or damaged to cost more than it holds")


# ----------------------------------------------------------------- reading


class _Watched(io.BufferedReader):
    """A file that remembers a read that found fewer bytes than asked at the end of the
    file, inside a message (``(asked, got, size)``), until a later read finds all it
    asked: the log is cut short when pyulog's reading ended so, not when a search for
    sync in the middle of the log reached the end and the reading went on."""

    short: tuple[int, int, int] | None = None

    def read(self, size: int | None = -1, /) -> bytes:
        data = super().read(size)
        if size is not None and size > 0:
            if 0 < len(data) == size:
                self.short = None
            elif len(data) < size and (len(data) > 0 or size != 3) \
                    and self.tell() >= os.fstat(self.fileno()).st_size:
                self.short = (size, len(data), self.tell())
        return data


def _topics(topic: str) -> list[str]:
    if topic == FIFO_GYRO:
        return [FIFO_GYRO, FIFO_ACCEL, IMU_STATUS]
    return [topic, IMU_STATUS]


def open_ulog(path: str, topic: str | None = None, instance: int | None = None) -> Columns:
    """A PX4 ULog's topic and instance (pyulog), with its damage as warnings."""
    try:
        # lazy: pyulog is optional (gyrovib[ulog])
        from pyulog import ULog
    except ImportError:
        raise problem(path, "reading PX4 ULog needs pyulog: pip install 'gyrovib[ulog]'") \
            from None
    topic = topic or ULOG_TOPIC
    check_format_cost(path)
    lines: list[str] = []
    fh = _Watched(io.FileIO(path, "rb"))
    try:
        with captured(lines):
            log = ULog(fh, _topics(topic))
    except Exception as exc:  # pyulog raises many kinds on a damaged file
        raise problem(path, f"cannot read as PX4 ULog: {type(exc).__name__}: {exc}") \
            from None
    finally:
        fh.close()
    data, multi_id = _instance(path, log, topic, instance)
    if topic == FIFO_GYRO:
        columns = _fifo_columns(path, log, data, multi_id)
    else:
        names = ["timestamp", *[k for k in data if k != "timestamp"]]
        columns = {k: data[k] for k in names}
    stamps = columns["timestamp"]
    warnings = (_damage(path, topic, fh.short, bool(log.file_corruption), stamps)
                + _clipping(log, data, multi_id))
    out = UlogColumns(path, list(columns), list(columns.values()), time_scale=1e-6,
                      warnings=warnings)
    out.topic, out.instance = topic, multi_id
    out.notes = as_notes("pyulog", lines)
    return out


def _instance(path: str, log: Any, topic: str,
              instance: int | None) -> tuple[dict[str, NDArray[np.generic]], int]:
    """The data of the topic's chosen instance, and its multi_id."""
    found = sorted((d for d in log.data_list if d.name == topic), key=lambda d: d.multi_id)
    if not found:
        raise problem(path, f"no topic {literal(repr(topic))} in this log (choose one with "
                            "{topic})",
                      arguments=("topic",))
    if instance is not None:
        chosen = [d for d in found if d.multi_id == instance]
        if not chosen:
            raise problem(path, f"{topic} has no instance {instance}: "
                                f"{_listing(topic, found)}")
        return chosen[0].data, instance
    if len(found) > 1:
        raise problem(path, f"{literal(topic)} is logged by {len(found)} instances: "
                            f"{literal(_listing(topic, found))}; choose one with "
                            "{instance} N",
                      arguments=("instance",))
    return found[0].data, int(found[0].multi_id)


def _listing(topic: str, found: Sequence[Any]) -> str:
    """Each instance with its rate and length."""
    parts = []
    for d in found:
        t = d.data["timestamp"].astype(np.float64) * 1e-6
        per = d.data["samples"].astype(np.float64) if topic in (FIFO_GYRO, FIFO_ACCEL) \
            else np.ones(t.size)
        seconds = float(t[-1] - t[0]) if t.size > 1 else 0.0
        rate = float(per[1:].sum() / seconds) if seconds > 0 else float("nan")
        parts.append(f"instance {d.multi_id} ({rate:.6g} Hz, {seconds:.6g} s, "
                     f"{int(per.sum())} samples)")
    return ", ".join(parts)


def fifo_samples(data: dict[str, NDArray[np.generic]]) -> tuple[FloatArray, FloatArray]:
    """A FIFO topic's samples in the order logged: times in µs (n,) and the three axes
    (n, 3) in its unit, each ``float64(raw) · float64(scale)``. The raw arrays are taken
    out of ``data`` as they are used, so that they go as soon as they are converted."""
    stamp = data["timestamp_sample" if "timestamp_sample" in data else "timestamp"]
    count = data["samples"].astype(np.intp)
    width = sum(1 for k in data if k.startswith("x["))
    k = np.arange(width)
    valid = k[None, :] < count[:, None]
    times = (stamp.astype(np.float64)[:, None]
             - (count[:, None] - 1 - k[None, :]) * data["dt"].astype(np.float64)[:, None])[valid]
    scale = data["scale"].astype(np.float64)[:, None]
    out = np.empty((times.size, 3))
    for axis, name in enumerate("xyz"):
        values = np.column_stack([data.pop(f"{name}[{j}]") for j in range(width)]
                                 ).astype(np.float64)
        values *= scale
        out[:, axis] = values[valid]
        del values
    return times, out


def _fifo_columns(path: str, log: Any, data: dict[str, NDArray[np.generic]],
                  multi_id: int) -> dict[str, NDArray[np.generic]]:
    """The gyro FIFO's samples (rad/s) and, where the same instance logged one, the
    accelerometer FIFO's (m/s²) interpolated onto the gyro's times (taken as they are
    where both have the same times)."""
    times, rate = _in_order(*fifo_samples(data))
    columns: dict[str, NDArray[np.generic]] = {"timestamp": times}
    columns.update({name: rate[:, j] for j, name in enumerate(FIFO_RATE)})
    accel = [d for d in log.data_list if d.name == FIFO_ACCEL and d.multi_id == multi_id]
    if accel:
        a_times, a = _in_order(*fifo_samples(accel[0].data))
        same = a_times.shape == times.shape and bool(np.array_equal(a_times, times))
        for j, name in enumerate(FIFO_ACCEL_COLUMNS):
            columns[name] = a[:, j] if same else np.interp(times, a_times, a[:, j])
    return columns


def _in_order(times: FloatArray, values: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Samples sorted by time (a copy only when they are not already)."""
    if times.size < 2 or bool(np.all(times[1:] >= times[:-1])):
        return times, values
    order = np.argsort(times, kind="stable")
    return times[order], values[order]


def _damage(path: str, topic: str, short: tuple[int, int, int] | None, corrupt: bool,
            stamps: NDArray[np.generic]) -> tuple[str, ...]:
    """The warnings of a cut (the last message incomplete) or corrupt log."""
    seconds = (float(stamps[-1]) - float(stamps[0])) * 1e-6 if len(stamps) > 1 else 0.0
    read = f"{len(stamps)} samples = {seconds:.6g} s of {topic} read"
    out = []
    if short is not None:
        out.append(f"the log looks cut short: it ends inside a message after "
                   f"{os.path.getsize(path)} bytes; {read}, and the flight may have run longer")
    if corrupt:
        out.append(f"pyulog found corrupt data inside the log and skipped it; {read}")
    return tuple(out)


def _clipping(log: Any, data: dict[str, NDArray[np.generic]], multi_id: int) -> tuple[str, ...]:
    """Clipped samples that ``vehicle_imu_status`` counted for this sensor (matched by
    device id where both give it, else by instance), per axis."""
    device = data.get("device_id")
    out = []
    for d in (d for d in log.data_list if d.name == IMU_STATUS):
        for kind in ("gyro", "accel"):
            if not _same_sensor(d, kind, device, multi_id):
                continue
            clipped = [_counted(d.data.get(f"{kind}_clipping[{j}]")) for j in range(3)]
            if any(clipped):
                out.append(f"{IMU_STATUS} instance {d.multi_id} counted clipped {kind} "
                           f"samples during the log (X {clipped[0]}, Y {clipped[1]}, "
                           f"Z {clipped[2]}): those samples are not the motion")
    return tuple(out)


def _same_sensor(status: Any, kind: str, device: NDArray[np.generic] | None,
                 multi_id: int) -> bool:
    """Whether a ``vehicle_imu_status`` instance speaks of the sensor read."""
    ids = status.data.get(f"{kind}_device_id")
    if device is None:
        return bool(status.multi_id == multi_id)
    return (ids is not None and len(ids) > 0 and len(device) > 0
            and int(ids[-1]) == int(device[-1]))


def _counted(counter: NDArray[np.generic] | None) -> int:
    """What a cumulative counter counted during the log."""
    if counter is None or len(counter) == 0:
        return 0
    values = counter.astype(np.float64)
    return int(values.max() - values.min())


class UlogColumns(ArrayColumns):
    """A ULog topic: its default columns are sensor_combined's, the FIFO's x, y, z
    (and its accelerometer's), or x, y, z of a sensor_gyro."""

    def default_columns(self, rate: ColumnNames | None, accel: ColumnNames | None,
                        ) -> tuple[ColumnNames, ColumnNames | None]:
        if rate is None:
            rate = (FIFO_RATE if all(c in self.names for c in FIFO_RATE)
                    and ULOG_RATE[0] not in self.names else ULOG_RATE)
        if accel is None:
            for names in (ULOG_ACCEL, FIFO_ACCEL_COLUMNS):
                if all(c in self.names for c in names):
                    accel = names
        return rate, accel


__all__ = ["FIFO_ACCEL", "FIFO_GYRO", "MAX_FIELDS", "ULOG_ACCEL", "ULOG_RATE", "ULOG_TOPIC",
           "UlogColumns", "check_format_cost", "fifo_samples", "open_ulog"]
