"""ArduPilot DataFlash ``.bin`` recordings (pymavlink, the ``gyrovib[ardupilot]`` extra).

pymavlink's ``DFReader`` indexes the log: the formats it declares (``FMT``) and the
byte offset of every message of each type. The samples are then read straight from
the file with numpy, a block of messages at a time, each stored value promoted to
float64 before any arithmetic (pymavlink's own message objects would cost a Python
object per message). Two sources (``--topic``):

* ``IMU`` (the default): ``GyrX/Y/Z`` in rad/s, ``AccX/Y/Z`` in m/s², ``TimeUS`` in
  µs, one message per sample at the logging rate; the instance is the ``I`` field,
  or in older logs the message's name (``IMU``, ``IMU2``, ``IMU3``: 0, 1, 2).
* ``batch``: the batch sampler's raw samples at the sensor's own rate. An ``ISBH``
  header opens a batch (sequence number ``N``, ``type`` 0 accelerometer or 1 gyro,
  ``instance``, multiplier ``mul``, ``smp_cnt`` samples, the first at ``SampleUS``,
  ``smp_rate`` Hz); ``ISBD`` messages carry it 32 int16 samples per axis at a time
  (``seqno``: which 32). A sample is ``float64(stored) / mul`` (rad/s or m/s²), sample
  j of a batch at ``SampleUS + j / smp_rate``. The sampler records one sensor at a
  time, so a gyro batch and an accelerometer batch never overlap: each gyro batch is
  paired with the accelerometer batch of the same instance nearest in time with the
  same count and rate, sample for sample.

The damage a log records is said (refused under ``strict``): a log that ends inside
a message, bytes that are not part of any message (corrupt, skipped), batches with
samples missing, and the clipped samples that ``VIBE`` counts for the instance.
Everything pymavlink prints is captured (:mod:`gyrovib.api.recordings.quiet`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from gyrovib.api.recordings.quiet import as_notes, captured
from gyrovib.api.recordings.readers import ArrayColumns, ColumnNames, Columns, problem
from gyrovib.errors import literal
from gyrovib.frozen import Frozen

#: The DataFlash sources and the columns they give.
DF_TOPIC, DF_BATCH = "IMU", "batch"
DF_RATE = ("GyrX", "GyrY", "GyrZ")
DF_ACCEL = ("AccX", "AccY", "AccZ")
#: Messages decoded at once.
DF_BLOCK = 1 << 16
#: Bytes at the end of a log that may be a storage block's padding, not damage
#: (pymavlink's own allowance for the garbage at the end of a log).
PADDING = 528
#: The batch sampler's sensor types.
ISB_ACCEL, ISB_GYRO = 0, 1
#: struct codes of pymavlink's formats as numpy types (little-endian, packed).
_NUMPY = {"b": "i1", "B": "u1", "e": "<f2", "h": "<i2", "H": "<u2", "i": "<i4", "I": "<u4",
          "f": "<f4", "d": "<f8", "q": "<i8", "Q": "<u8", "4s": "S4", "16s": "S16",
          "64s": "S64"}


@dataclass(frozen=True, eq=False, repr=False)
class _Type(Frozen):
    """One message type of the log: its numpy record, offsets and name."""

    name: str
    dtype: np.dtype[Any]
    offsets: NDArray[np.int64]
    length: int


class _Log:
    """A DataFlash log's index (pymavlink) and its bytes (a read-only map)."""

    def __init__(self, path: str) -> None:
        try:
            # lazy: pymavlink is optional (gyrovib[ardupilot])
            from pymavlink import DFReader
        except ImportError:
            raise problem(path, "reading an ArduPilot DataFlash log needs pymavlink: "
                                "pip install 'gyrovib[ardupilot]'") from None

        class Index(DFReader.DFReader_binary):  # type: ignore[misc]
            """The index only: the clock (a pass over every message) is not needed."""

            def init_clock(self) -> None:
                self.clock = None

        self.path = path
        self.struct: dict[str, tuple[str, Any, Any]] = DFReader.FORMAT_TO_STRUCT
        self.lines: list[str] = []
        #: Some gyro batch had no accelerometer batch to pair with.
        self.unpaired = False
        try:
            with captured(self.lines):
                index = Index(path, zero_time_base=True)
        except Exception as exc:  # pymavlink raises many kinds on a damaged file
            raise problem(path, f"cannot read as ArduPilot DataFlash: "
                                f"{type(exc).__name__}: {exc}") from None
        try:
            self.size = int(index.data_len)
            self.types = {fmt.name: self._type(fmt, index.offsets[t])
                          for t, fmt in index.formats.items() if index.offsets[t]}
        finally:
            index.close()
        self.raw = np.memmap(path, np.uint8, mode="r") if self.size else np.zeros(0, np.uint8)

    def _type(self, fmt: Any, offsets: Sequence[int]) -> _Type:
        fields: list[tuple[Any, ...]] = []
        for name, code in zip(fmt.columns, fmt.format, strict=False):
            if code == "a":
                fields.append((name, "<i2", (32,)))
            else:
                fields.append((name, _NUMPY[self.struct[code][0]]))
        dtype = np.dtype(fields)
        return _Type(fmt.name, dtype, np.asarray(offsets, dtype=np.int64), int(fmt.len))

    def complete(self, kind: _Type) -> NDArray[np.int64]:
        """The offsets of the messages of a type that end inside the file."""
        return kind.offsets[kind.offsets + kind.length <= self.size]

    def records(self, kind: _Type, fields: Sequence[str]) -> dict[str, NDArray[Any]]:
        """The chosen fields of every complete message of a type, read a block at a time."""
        offsets = self.complete(kind)
        if kind.dtype.itemsize != kind.length - 3:
            raise problem(self.path, f"message {kind.name}: its format declares "
                                     f"{kind.dtype.itemsize} bytes where its length is "
                                     f"{kind.length - 3}")
        out = {f: np.empty((offsets.size, *kind.dtype[f].shape), kind.dtype[f].base)
               for f in fields}
        span = np.arange(3, kind.length)
        for lo in range(0, offsets.size, DF_BLOCK):
            block = offsets[lo:lo + DF_BLOCK]
            rows = self.raw[block[:, None] + span].view(kind.dtype).reshape(-1)
            for f in fields:
                out[f][lo:lo + block.size] = rows[f]
        return out

    def damage(self) -> list[str]:
        """A log that ends inside a message; bytes that belong to no message, inside the
        log or after the last message pymavlink indexed (it stops at a message type
        it does not know); the last :data:`PADDING` bytes of a log may be padding."""
        out = []
        ends = [int(k.offsets[-1]) + k.length for k in self.types.values() if k.offsets.size]
        covered = sum(self.complete(k).size * k.length for k in self.types.values())
        last_end = max([int(self.complete(k)[-1]) + k.length for k in self.types.values()
                        if self.complete(k).size] or [0])
        if ends and max(ends) > self.size:
            out.append(f"the log looks cut short: it ends inside a message after "
                       f"{self.size} bytes, and the flight may have run longer")
        skipped = last_end - covered
        if skipped > 0:
            out.append(f"{skipped} byte(s) inside the log are not part of any message "
                       "(corrupt data, skipped)")
        if self.size - last_end >= PADDING and not (ends and max(ends) > self.size):
            out.append(f"the last {self.size - last_end} byte(s) of the log, after byte "
                       f"{last_end}, were not read: pymavlink found no message it knows "
                       "there (corrupt data); the flight may have run longer")
        return out


def _clipped(log: _Log, instance: int) -> list[str]:
    """The clipped samples VIBE counted for the instance during the log."""
    vibe = log.types.get("VIBE")
    if vibe is None:
        return []
    names = vibe.dtype.names or ()
    if "IMU" in names and "Clip" in names:
        rec = log.records(vibe, ["IMU", "Clip"])
        counts = rec["Clip"][rec["IMU"] == instance]
    elif f"Clip{instance}" in names:
        counts = log.records(vibe, [f"Clip{instance}"])[f"Clip{instance}"]
    else:
        return []
    if counts.size == 0:
        return []
    clipped = int(counts.astype(np.float64).max() - counts.astype(np.float64).min())
    if clipped <= 0:
        return []
    return [f"VIBE counted {clipped} clipped sample(s) on IMU {instance} during the log: "
            "those samples are not the motion"]


# ----------------------------------------------------------------- IMU


def _imu_sources(log: _Log) -> dict[int, tuple[_Type, NDArray[np.bool_] | None]]:
    """instance -> (message type, mask of its messages or None for all)."""
    out: dict[int, tuple[_Type, NDArray[np.bool_] | None]] = {}
    imu = log.types.get("IMU")
    if imu is not None and "I" in (imu.dtype.names or ()):
        which = log.records(imu, ["I"])["I"]
        for i in np.unique(which).tolist():
            out[int(i)] = (imu, which == i)
        return out
    for k, name in enumerate(("IMU", "IMU2", "IMU3")):
        if name in log.types:
            out[k] = (log.types[name], None)
    return out


def _imu(log: _Log, instance: int | None) -> tuple[dict[str, NDArray[Any]], int]:
    sources = _imu_sources(log)
    if not sources:
        raise problem(log.path, "no IMU messages in this log (the batch sampler's are read "
                                "with {topic} batch)", arguments=("topic",))
    listing = {}
    for i, (kind, mask) in sources.items():
        t = log.records(kind, ["TimeUS"])["TimeUS"]
        listing[i] = t if mask is None else t[mask]
    chosen = _choose(log.path, DF_TOPIC, instance, {i: (_rate(t), t.size)
                                                    for i, t in listing.items()})
    kind, mask = sources[chosen]
    rec = log.records(kind, ["TimeUS", *DF_RATE, *DF_ACCEL])
    columns = {k: (v if mask is None else v[mask]) for k, v in rec.items()}
    columns["TimeUS"] = columns["TimeUS"].astype(np.float64)
    return columns, chosen


def _rate(t_us: NDArray[Any]) -> float:
    if t_us.size < 2:
        return float("nan")
    dt = np.diff(np.sort(t_us.astype(np.float64)))
    return float(1e6 / np.median(dt)) if np.median(dt) > 0 else float("nan")


def _choose(path: str, what: str, instance: int | None,
            found: dict[int, tuple[float, int]]) -> int:
    """The instance asked for, or the only one; several without a choice are refused
    with each one's rate and length."""
    shown = ", ".join(f"instance {i} ({rate:.6g} Hz, {n / rate:.6g} s, {n} samples)"
                      for i, (rate, n) in sorted(found.items()))
    if instance is not None:
        if instance not in found:
            raise problem(path, f"{what} has no instance {instance}: {shown}")
        return instance
    if len(found) > 1:
        raise problem(path, f"{literal(what)} is logged by {len(found)} instances: "
                            f"{literal(shown)}; "
                            "choose one with {instance} N", arguments=("instance",))
    return next(iter(found))


# ----------------------------------------------------------------- batch sampler


@dataclass(frozen=True, eq=False, repr=False)
class _Batch(Frozen):
    """One batch: its header's fields and its samples (j -> row of the data)."""

    seq: int
    sensor: int
    instance: int
    mul: float
    count: int
    start: float
    rate: float
    samples: NDArray[np.float64]
    have: NDArray[np.bool_]


def _batches(log: _Log) -> list[_Batch]:
    """Every batch with its samples, each data message under the last header before it
    that has its sequence number."""
    head, data = log.types.get("ISBH"), log.types.get("ISBD")
    if head is None or data is None:
        raise problem(log.path, "no batch sampler messages (ISBH, ISBD) in this log: set "
                                "INS_LOG_BAT_MASK on the vehicle, or read {topic} IMU",
                      arguments=("topic",))
    h = log.records(head, ["N", "type", "instance", "mul", "smp_cnt", "SampleUS",
                           "smp_rate"])
    h_off = log.complete(head)
    batches = [_Batch(int(h["N"][k]), int(h["type"][k]), int(h["instance"][k]),
                      float(h["mul"][k]), int(h["smp_cnt"][k]), float(h["SampleUS"][k]),
                      float(h["smp_rate"][k]), np.zeros((int(h["smp_cnt"][k]), 3)),
                      np.zeros(int(h["smp_cnt"][k]), bool)) for k in range(h_off.size)]
    d = log.records(data, ["N", "seqno", "x", "y", "z"])
    owner = np.searchsorted(h_off, log.complete(data)) - 1
    for m in range(owner.size):
        k = int(owner[m])
        if k < 0 or batches[k].seq != int(d["N"][m]):
            continue
        b = batches[k]
        lo = int(d["seqno"][m]) * 32
        hi = min(lo + 32, b.count)
        if lo >= hi or b.mul == 0:
            continue
        for axis, name in enumerate("xyz"):
            part = d[name][m, :hi - lo].astype(np.float64)
            part /= b.mul
            b.samples[lo:hi, axis] = part
        b.have[lo:hi] = True
    return batches


def _batch(log: _Log, instance: int | None) -> tuple[dict[str, NDArray[Any]], int, list[str]]:
    batches = _batches(log)
    gyro = [b for b in batches if b.sensor == ISB_GYRO]
    found: dict[int, tuple[float, int]] = {}
    for b in gyro:
        rate, n = found.get(b.instance, (b.rate, 0))
        found[b.instance] = (rate, n + int(b.have.sum()))
    if not found:
        raise problem(log.path, "the batch sampler logged no gyro batch in this log")
    chosen = _choose(log.path, "the batch sampler", instance, found)
    mine = [b for b in gyro if b.instance == chosen]
    damage = []
    missing = sum(int((~b.have).sum()) for b in mine)
    if missing:
        damage.append(f"{missing} gyro sample(s) of the batch sampler's instance {chosen} "
                      "were never logged (data messages lost)")
    times = np.concatenate([b.start + np.flatnonzero(b.have) * 1e6 / b.rate for b in mine])
    gyro_samples = np.concatenate([b.samples[b.have] for b in mine])
    columns: dict[str, NDArray[Any]] = {"TimeUS": times}
    columns.update({name: gyro_samples[:, j] for j, name in enumerate(DF_RATE)})
    accel = [b for b in batches if b.sensor == ISB_ACCEL and b.instance == chosen]
    columns.update(_paired_accel(log, mine, accel))
    return columns, chosen, damage


def _paired_accel(log: _Log, gyro: Sequence[_Batch],
                  accel: Sequence[_Batch]) -> dict[str, NDArray[Any]]:
    """The accelerometer columns, each gyro batch's pair sample for sample; none (and a
    note) when some gyro batch has no pair."""
    if not accel:
        return {}
    pairs = [_pair(b, accel) for b in gyro]
    if any(p is None for p in pairs):
        log.unpaired = True
        return {}
    acc = np.concatenate([p.samples[b.have] for b, p in zip(gyro, pairs, strict=True)
                          if p is not None])
    return {name: acc[:, j] for j, name in enumerate(DF_ACCEL)}


def _pair(gyro: _Batch, accel: Sequence[_Batch]) -> _Batch | None:
    """The accelerometer batch nearest in time with the same count and rate, whole."""
    fits = [a for a in accel if a.count == gyro.count and abs(a.rate - gyro.rate)
            <= 0.01 * gyro.rate and a.have.all()]
    return min(fits, key=lambda a: abs(a.start - gyro.start)) if fits else None


# ----------------------------------------------------------------- the reader


def open_dataflash(path: str, topic: str | None = None,
                   instance: int | None = None) -> Columns:
    """An ArduPilot DataFlash log's IMU or batch-sampler samples, with its damage."""
    topic = topic or DF_TOPIC
    if topic not in (DF_TOPIC, DF_BATCH):
        raise problem(path, f"{{topic}} {literal(repr(topic))}: a DataFlash log is read as "
                            f"{DF_TOPIC} (the default) or {DF_BATCH} (the batch sampler's raw "
                            "samples)",
                      arguments=("topic",))
    log = _Log(path)
    if topic == DF_TOPIC:
        columns, chosen = _imu(log, instance)
        lost: list[str] = []
    else:
        columns, chosen, lost = _batch(log, instance)
    out = DataflashColumns(path, list(columns), list(columns.values()), time_scale=1e-6,
                           warnings=tuple(log.damage() + lost + _clipped(log, chosen)))
    out.topic, out.instance = topic, chosen
    out.notes = as_notes("pymavlink", log.lines) + ((
        "not every gyro batch has an accelerometer batch of the same count and rate to "
        "pair with: the accelerations were not read",) if log.unpaired else ())
    return out


class DataflashColumns(ArrayColumns):
    """DataFlash samples: time ``TimeUS`` (µs), rates GyrX/Y/Z, accelerations AccX/Y/Z."""

    def time_index(self) -> int | None:
        return self.names.index("TimeUS")

    def default_columns(self, rate: ColumnNames | None, accel: ColumnNames | None,
                        ) -> tuple[ColumnNames, ColumnNames | None]:
        if rate is None:
            rate = DF_RATE
        if accel is None and all(c in self.names for c in DF_ACCEL):
            accel = DF_ACCEL
        return rate, accel


__all__ = ["DF_ACCEL", "DF_BATCH", "DF_RATE", "DF_TOPIC", "DataflashColumns",
           "open_dataflash"]
