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
G0 = 9.80665
D2R = np.pi / 180.0


def motion(n: int, fs: float, seed: int, tone: float, amp: float,
           sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """Rates (n, 3) deg/s: slow manoeuvres (< 0.3 Hz), a tone of amplitude ``amp`` at
    ``tone`` Hz on every axis and white noise of standard deviation ``sigma``; and
    specific force (n, 3) in g: gravity, a slow sway and a smaller noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / fs
    slow = np.column_stack([20 * np.sin(2 * np.pi * 0.3 * t), 10 * np.cos(2 * np.pi * 0.2 * t),
                            30 + 15 * np.sin(2 * np.pi * 0.25 * t)])
    rate = slow + amp * np.sin(2 * np.pi * tone * t)[:, None] + rng.normal(0, sigma, (n, 3))
    force = np.column_stack([0.1 * np.sin(2 * np.pi * 0.2 * t), np.zeros(n), -np.ones(n)])
    force = force + rng.normal(0, 0.05, (n, 3))
    return rate, force

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


# ----------------------------------------------------------------- the docs' examples

#: The FIFO's int16 scales (float32, as PX4 logs them): ±2000 deg/s and ±16 g full scale.
GYRO_SCALE = float(np.float32(np.radians(2000.0) / 32767))
ACCEL_SCALE = float(np.float32(16 * G0 / 32767))


def fifo_example(path: Path, seconds: float = 20.0, **kw: object
                 ) -> tuple[Path, list[np.ndarray], list[np.ndarray]]:
    """sensor_gyro_fifo and sensor_accel_fifo at 4 kHz, 16 samples a message, two
    instances: 0 with a 210 Hz tone of 3 deg/s and 1 deg/s of noise, 1 with 345 Hz,
    8 deg/s and 2.5 deg/s."""
    fs, n = 4000.0, int(seconds * 4000)
    gyro, accel = [], []
    for i, (tone, amp, sigma) in enumerate(((210.0, 3.0, 1.0), (345.0, 8.0, 2.5))):
        w, g = motion(n, fs, 20 + i, tone, amp, sigma)
        gyro.append(np.round(w * D2R / GYRO_SCALE).astype(np.int16))
        accel.append(np.round(g * G0 / ACCEL_SCALE).astype(np.int16))
    out = ulog_fifo(path, 250.0, 16, gyro, accel, GYRO_SCALE, ACCEL_SCALE,
                    **kw)  # type: ignore[arg-type]
    return out, gyro, accel


def batch_example(path: Path, count: int = 2048, batches: int = 12) -> Path:
    """The batch sampler at 2 kHz as ArduPilot logs it: an accelerometer batch, then
    the gyro batch of the same instance 1.2 s later, every 3 s; a 310 Hz tone of 5 deg/s
    and 1.5 deg/s of noise."""
    fs, mul_g, mul_a = 2000.0, 16384 / 35.0, 32767 / (16 * G0)
    out: list[tuple[int, int, float, float, float, np.ndarray]] = []
    start = 1e6
    for b in range(batches):
        w, g = motion(count, fs, 10 + b, 310.0, 5.0, 1.5)
        out.append((0, 0, mul_a, fs, start, np.round(g * G0 * mul_a).astype(np.int16)))
        out.append((1, 0, mul_g, fs, start + 1.2e6,
                    np.round(w * D2R * mul_g).astype(np.int16)))
        start += 3e6
    return dataflash_batches(path, out)


def betaflight_example(path: Path) -> Path:
    """20 s at 2 kHz: a 260 Hz tone of 4 deg/s and 1.2 deg/s of noise, gyroADC rounded
    to whole deg/s as the firmware logs it, accSmooth decoded in g."""
    fs, n = 2000.0, 40000
    w, g = motion(n, fs, 5, 260.0, 4.0, 1.2)
    return betaflight_csv(path, np.round(np.arange(n) * 1e6 / fs), np.round(w), g)


def main(directory: str) -> None:
    """Write the docs' synthetic logs (docs/recordings.md) into ``directory``, each
    written beside and then moved into place whole."""
    import os

    where = Path(directory)
    where.mkdir(parents=True, exist_ok=True)
    part = f".part{os.getpid()}"
    for name, write in (("fifo.ulg", fifo_example), ("batch.bin", batch_example),
                        ("betaflight.csv", betaflight_example)):
        write(where / (name + part))  # type: ignore[operator]
        os.replace(where / (name + part), where / name)


if __name__ == "__main__":
    import sys

    main(sys.argv[1] if len(sys.argv) > 1 else "/tmp/gyrovib-logs")
