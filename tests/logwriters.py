"""Small writers of synthetic flight logs for the reader tests: ArduPilot DataFlash
(``.bin``), PX4 ULog (``.ulg``) and Betaflight's blackbox_decode CSV.

Every log written here says in its own header that its data are synthetic (a
DataFlash ``MSG``, a ULog ``sys_name`` info message, a CSV's first column name is
the decoder's). The byte layouts follow the formats' public descriptions:
DataFlash messages are ``A3 95 type`` then the packed fields that the type's
``FMT`` message declares (pymavlink's ``FORMAT_TO_STRUCT``); ULog is a 16-byte
header then ``uint16 size, uint8 type`` framed messages (``B`` flags, ``I`` info,
``F`` formats, ``A`` subscriptions, ``D`` data).
"""

from __future__ import annotations

import struct
from collections.abc import Sequence
from pathlib import Path

import numpy as np

SYNTHETIC = "synthetic data written by gyrovib's tests"

# ----------------------------------------------------------------- DataFlash

_STRUCT = {"a": "64s", "b": "b", "B": "B", "h": "h", "H": "H", "i": "i", "I": "I",
           "f": "f", "d": "d", "n": "4s", "N": "16s", "Z": "64s", "Q": "Q", "q": "q"}


class DataflashWriter:
    """FMT messages on first use of a type, then its packed messages."""

    def __init__(self) -> None:
        self.out = bytearray()
        self.types: dict[str, tuple[int, str]] = {}
        self.declare("MSG", "QZ", "TimeUS,Message")
        self.write("MSG", 0, SYNTHETIC.encode())

    def declare(self, name: str, fmt: str, columns: str) -> None:
        kind = 0x81 + len(self.types)
        packed = "<" + "".join(_STRUCT[c] for c in fmt)
        self.types[name] = (kind, packed)
        length = 3 + struct.calcsize(packed)
        self.out += bytes([0xA3, 0x95, 0x80]) + struct.pack(
            "<BB4s16s64s", kind, length, name.encode(), fmt.encode(), columns.encode())

    def write(self, name: str, *values: object) -> None:
        kind, packed = self.types[name]
        self.out += bytes([0xA3, 0x95, kind]) + struct.pack(packed, *values)

    def save(self, path: Path, tail: bytes = b"") -> Path:
        path.write_bytes(bytes(self.out) + tail)
        return path


def dataflash_imu(path: Path, t_us: np.ndarray, gyro: Sequence[np.ndarray],
                  accel: Sequence[np.ndarray], clips: Sequence[int] = (0, 0)) -> Path:
    """IMU messages of one or more instances (``I``), interleaved in time, rad/s and m/s²
    stored as float32; a VIBE message per instance at the start and the end with the
    clip counts ``0`` then ``clips[i]``."""
    w = DataflashWriter()
    w.declare("IMU", "QBffffffIIfBBHH",
              "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz")
    w.declare("VIBE", "QBfffI", "TimeUS,IMU,VibeX,VibeY,VibeZ,Clip")
    for i in range(len(gyro)):
        w.write("VIBE", int(t_us[0]), i, 0.1, 0.1, 0.1, 0)
    for n in range(t_us.size):
        for i, (g, a) in enumerate(zip(gyro, accel, strict=True)):
            w.write("IMU", int(t_us[n]), i, *g[n].tolist(), *a[n].tolist(), 0, 0, 40.0,
                    1, 1, 400, 400)
    for i in range(len(gyro)):
        w.write("VIBE", int(t_us[-1]), i, 0.1, 0.1, 0.1, int(clips[i]))
    return w.save(path)


def dataflash_batches(path: Path, batches: Sequence[tuple[int, int, float, float, float,
                                                           np.ndarray]]) -> Path:
    """The batch sampler's messages: per batch ``(sensor type, instance, multiplier,
    rate Hz, first sample µs, int16 samples (n, 3))``, an ISBH then ISBD of 32
    samples each."""
    w = DataflashWriter()
    w.declare("ISBH", "QHBBHHQf", "TimeUS,N,type,instance,mul,smp_cnt,SampleUS,smp_rate")
    w.declare("ISBD", "QHHaaa", "TimeUS,N,seqno,x,y,z")
    for seq, (kind, instance, mul, rate, start, raw) in enumerate(batches):
        now = int(start + raw.shape[0] * 1e6 / rate)
        w.write("ISBH", now, seq, kind, instance, int(mul), raw.shape[0], int(start), rate)
        for s in range(raw.shape[0] // 32):
            block = raw[32 * s:32 * s + 32].astype("<i2")
            w.write("ISBD", now, seq, s, *(block[:, j].tobytes() for j in range(3)))
    return w.save(path)


# ----------------------------------------------------------------- ULog

_ULOG_TYPES = {"uint8_t": "B", "int16_t": "h", "uint32_t": "I", "uint64_t": "Q",
               "float": "f", "int8_t": "b", "uint16_t": "H", "int32_t": "i", "double": "d"}


class UlogWriter:
    """A ULog file: header, flags, an info message saying the data are synthetic,
    formats, subscriptions and data messages."""

    def __init__(self, version: int = 1) -> None:
        self.out = bytearray(b"ULog\x01\x12\x35" + bytes([version]) + struct.pack("<Q", 0))
        self.message("B", bytes(40))
        key = b"char[%d] sys_name" % len(SYNTHETIC)
        self.message("I", bytes([len(key)]) + key + SYNTHETIC.encode())
        self.formats: dict[str, list[tuple[str, int, str]]] = {}
        self.subscribed: dict[tuple[str, int], int] = {}

    def message(self, kind: str, payload: bytes) -> None:
        self.out += struct.pack("<HB", len(payload), ord(kind)) + payload

    def format(self, name: str, fields: Sequence[tuple[str, int, str]]) -> None:
        """fields: (type, array length or 0, name)."""
        self.formats[name] = list(fields)
        text = name + ":" + "".join(f"{t}{f'[{n}]' if n else ''} {f};" for t, n, f in fields)
        self.message("F", text.encode())

    def subscribe(self, name: str, multi_id: int = 0) -> int:
        msg_id = len(self.subscribed)
        self.subscribed[(name, multi_id)] = msg_id
        self.message("A", struct.pack("<BH", multi_id, msg_id) + name.encode())
        return msg_id

    def data(self, name: str, multi_id: int, values: dict[str, object]) -> None:
        msg_id = self.subscribed[(name, multi_id)]
        body = b""
        for t, n, f in self.formats[name]:
            code = _ULOG_TYPES[t]
            body += (struct.pack(f"<{n}{code}", *values[f]) if n      # type: ignore[misc]
                     else struct.pack(f"<{code}", values[f]))
        self.message("D", struct.pack("<H", msg_id) + body)

    def save(self, path: Path) -> Path:
        path.write_bytes(bytes(self.out))
        return path


FIFO_FIELDS = [("uint64_t", 0, "timestamp"), ("uint64_t", 0, "timestamp_sample"),
               ("uint32_t", 0, "device_id"), ("float", 0, "dt"), ("float", 0, "scale"),
               ("uint8_t", 0, "samples"), ("int16_t", 32, "x"), ("int16_t", 32, "y"),
               ("int16_t", 32, "z")]
STATUS_FIELDS = [("uint64_t", 0, "timestamp"), ("uint32_t", 0, "accel_device_id"),
                 ("uint32_t", 0, "gyro_device_id"), ("uint32_t", 3, "accel_clipping"),
                 ("uint32_t", 3, "gyro_clipping")]


def ulog_fifo(path: Path, dt_us: float, per_message: int,
              gyro: Sequence[np.ndarray], accel: Sequence[np.ndarray | None],
              gyro_scale: float, accel_scale: float, clips: Sequence[int] = (0, 0),
              version: int = 1) -> Path:
    """sensor_gyro_fifo (and sensor_accel_fifo where given) of one or more instances:
    int16 samples (n, 3), ``per_message`` of them a message; the newest sample of a
    message at ``timestamp_sample``; vehicle_imu_status at the start and the end with
    gyro clip counts 0 then ``clips[i]`` on X."""
    w = UlogWriter(version)
    w.format("sensor_gyro_fifo", FIFO_FIELDS)
    w.format("sensor_accel_fifo", FIFO_FIELDS)
    w.format("vehicle_imu_status", STATUS_FIELDS)
    for i in range(len(gyro)):
        w.subscribe("sensor_gyro_fifo", i)
        if accel[i] is not None:
            w.subscribe("sensor_accel_fifo", i)
        w.subscribe("vehicle_imu_status", i)
    n = gyro[0].shape[0]
    for i in range(len(gyro)):
        _status(w, i, 1000, [0, 0, 0])
    for m in range(n // per_message):
        lo, hi = m * per_message, (m + 1) * per_message
        stamp = round(1000 + (hi - 1) * dt_us)
        for i in range(len(gyro)):
            for topic, raw, scale, device in (("sensor_gyro_fifo", gyro[i], gyro_scale, 10 + i),
                                              ("sensor_accel_fifo", accel[i], accel_scale,
                                               20 + i)):
                if raw is None:
                    continue
                block = np.zeros((32, 3), np.int16)
                block[:per_message] = raw[lo:hi]
                w.data(topic, i, {"timestamp": stamp + 50, "timestamp_sample": stamp,
                                  "device_id": device, "dt": dt_us, "scale": scale,
                                  "samples": per_message, "x": block[:, 0].tolist(),
                                  "y": block[:, 1].tolist(), "z": block[:, 2].tolist()})
    for i in range(len(gyro)):
        _status(w, i, int(1000 + n * dt_us), [int(clips[i]), 0, 0])
    return w.save(path)


def _status(w: UlogWriter, i: int, stamp: int, gyro_clip: list[int]) -> None:
    w.data("vehicle_imu_status", i, {"timestamp": stamp, "accel_device_id": 20 + i,
                                     "gyro_device_id": 10 + i, "accel_clipping": [0, 0, 0],
                                     "gyro_clipping": gyro_clip})


# ----------------------------------------------------------------- Betaflight


def betaflight_csv(path: Path, t_us: np.ndarray, gyro_degs: np.ndarray,
                   acc: np.ndarray | None) -> Path:
    """The columns blackbox_decode writes (a few of them), ", "-separated as it does."""
    names = ["loopIteration", "time (us)", "axisP[0]", "gyroADC[0]", "gyroADC[1]",
             "gyroADC[2]"] + (["accSmooth[0]", "accSmooth[1]", "accSmooth[2]"]
                              if acc is not None else [])
    lines = [", ".join(names)]
    for n in range(t_us.size):
        row = [str(n), str(int(t_us[n])), "0", *(repr(float(v)) for v in gyro_degs[n])]
        if acc is not None:
            row += [repr(float(v)) for v in acc[n]]
        lines.append(", ".join(row))
    path.write_text("\n".join(lines) + "\n")
    return path
