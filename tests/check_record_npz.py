#!/usr/bin/python3
"""`tandem run --record FILE.npz` read back by numpy.load, against the CSV record of the same run.

Usage: check_record_npz.py TANDEM SCENE WORK_DIR

Runs SCENE twice for 25 steps with --record-nodes, once to CSV and once to .npz (and a third time
to a .bin file with --record-format npz), and checks that every number of the .npz equals the
CSV's (written with %.17g: to the last bit), that the shapes, names and node ranges are as
include/tandem/record.h says, and that the archive is a stored zip with good CRCs.
"""
import csv
import os
import subprocess
import sys
import zipfile

import numpy as np

STEPS = 25


def run(tandem, scene, record, *extra):
    subprocess.run([tandem, "run", scene, "--steps", str(STEPS), "--quiet", "--record", record, "--record-nodes", *extra],
                   check=True, stdout=subprocess.DEVNULL)


def main(tandem, scene, work_dir):
    os.makedirs(work_dir, exist_ok=True)
    csv_path = os.path.join(work_dir, "record.csv")
    npz_path = os.path.join(work_dir, "record.npz")
    bin_path = os.path.join(work_dir, "record.bin")
    run(tandem, scene, csv_path)
    run(tandem, scene, npz_path)
    run(tandem, scene, bin_path, "--record-format", "npz")

    with zipfile.ZipFile(npz_path) as archive:
        assert archive.testzip() is None, "a CRC does not match"
        assert all(info.compress_type == zipfile.ZIP_STORED for info in archive.infolist())
    with open(npz_path, "rb") as a, open(bin_path, "rb") as b:
        assert a.read() == b.read(), "--record-format npz wrote another file than the .npz extension"

    record = np.load(npz_path)
    expected = {"step", "time", "rigid_name", "rigid_position", "rigid_orientation", "rigid_linear_velocity",
                "rigid_angular_velocity", "deformable_name", "deformable_node_start", "node_position", "node_velocity"}
    assert set(record.files) == expected, sorted(record.files)

    with open(csv_path, newline="", encoding="utf-8") as file:
        rows = list(csv.DictReader(file))
    rigid = [r for r in rows if r["kind"] == "rigid"]
    nodes = [r for r in rows if r["kind"] == "node"]
    steps = STEPS + 1  # step 0, the start, is recorded too
    names = list(record["rigid_name"])
    bodies = len(names)
    assert bodies > 0 and len(rigid) == steps * bodies, (len(rigid), steps, bodies)
    assert record["step"].dtype == np.int64 and record["step"].tolist() == list(range(steps))
    assert record["time"].dtype == np.float64 and record["time"].shape == (steps,)
    for name, width in (("rigid_position", 3), ("rigid_orientation", 4), ("rigid_linear_velocity", 3),
                        ("rigid_angular_velocity", 3)):
        assert record[name].shape == (steps, bodies, width) and record[name].dtype == np.float64, name

    columns = {"rigid_position": ("x", "y", "z"), "rigid_orientation": ("qw", "qx", "qy", "qz"),
               "rigid_linear_velocity": ("vx", "vy", "vz"), "rigid_angular_velocity": ("wx", "wy", "wz")}
    compared = 0
    for row in rigid:
        s, b = int(row["step"]), int(row["index"])
        assert names[b] == row["name"], (names[b], row["name"])
        assert record["time"][s] == float(row["time"]), (s, record["time"][s], row["time"])
        for name, keys in columns.items():
            got = record[name][s, b].tolist()
            want = [float(row[k]) for k in keys]
            assert got == want, (name, s, names[b], got, want)
            compared += len(keys)

    starts = record["deformable_node_start"].tolist()
    deformables = list(record["deformable_name"])
    assert len(starts) == len(deformables) + 1 and starts[0] == 0
    node_count = starts[-1]
    assert record["node_position"].shape == (steps, node_count, 3)
    assert record["node_velocity"].shape == (steps, node_count, 3)
    assert len(nodes) == steps * node_count, (len(nodes), steps, node_count)
    for row in nodes:
        s, d = int(row["step"]), deformables.index(row["name"])
        n = starts[d] + int(row["index"])
        assert n < starts[d + 1]
        assert record["node_position"][s, n].tolist() == [float(row[k]) for k in ("x", "y", "z")], (s, n)
        assert record["node_velocity"][s, n].tolist() == [float(row[k]) for k in ("vx", "vy", "vz")], (s, n)
        compared += 6

    moved = np.abs(record["node_position"][-1] - record["node_position"][0]).max()
    assert np.isfinite(record["node_position"]).all() and moved > 1e-3, moved  # a run that did something
    size_csv, size_npz = os.path.getsize(csv_path), os.path.getsize(npz_path)
    print(f"check_record_npz: {compared} numbers equal in {steps} steps, {bodies} rigid bodies, {node_count} nodes; "
          f"CSV {size_csv} bytes, npz {size_npz} bytes")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.stderr.write(__doc__)
        sys.exit(2)
    sys.exit(main(*sys.argv[1:]))
