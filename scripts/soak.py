#!/usr/bin/python3
"""Long soak of the paper scenes: runs tests/test_soak for longer than ctest does, prints its
measurements (energy, creep of each resting body) and plots them into docs/images/.

Usage: scripts/soak.py [--seconds 60] [--build build] [--out docs/images] [--filter rope_wheel]
Needs a built build/tests/test_soak and Debian's python3-matplotlib (/usr/bin/python3).
Each figure: the scene's kinetic and kinetic + gravitational energy (top), and how far each
resting body's centroid has drifted since the scene settled (bottom), in mm.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

os.environ.setdefault("MPLBACKEND", "Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    with open(path, newline="") as file:
        rows = list(csv.reader(file))
    header, data = rows[0], rows[1:]
    columns = {name: [] for name in header}
    for row in data:
        for name, value in zip(header, row):
            columns[name].append(float(value) if value else float("nan"))
    return columns


def plot(scene, columns, seconds, out):
    time = columns["time"]
    figure, (energy, drift) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    energy.plot(time, columns["total"], label="kinetic + gravitational")
    energy.plot(time, columns["kinetic"], label="kinetic")
    energy.set_ylabel("energy (J)")
    energy.set_title(f"{scene}: {seconds:g} s soak")
    energy.legend(loc="best")
    energy.grid(alpha=0.3)
    for name in columns:
        if name.startswith("drift "):
            drift.plot(time, [1e3 * d for d in columns[name]], label=name[len("drift "):])
    drift.set_ylabel("centroid drift since settled (mm)")
    drift.set_xlabel("time (s)")
    drift.legend(loc="best", fontsize="small")
    drift.grid(alpha=0.3)
    figure.tight_layout()
    path = os.path.join(out, f"soak_{scene}.png")
    figure.savefig(path, dpi=90)
    plt.close(figure)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="simulated seconds per scene")
    parser.add_argument("--build", default="build", help="the build folder")
    parser.add_argument("--out", default="docs/images", help="where the figures go")
    parser.add_argument("--filter", default="*", help="scene name pattern (gtest), e.g. jelly_dish")
    arguments = parser.parse_args()

    binary = os.path.join(arguments.build, "tests", "test_soak")
    if not os.path.exists(binary):
        sys.exit(f"soak: {binary} not found: build the tests first (scripts/setup.sh)")
    os.makedirs(arguments.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as folder:
        environment = dict(os.environ, TANDEM_SOAK_SECONDS=str(arguments.seconds), TANDEM_SOAK_CSV=folder)
        result = subprocess.run([binary, f"--gtest_filter=PaperScenes/Soak.*/{arguments.filter}"],
                                env=environment, text=True, capture_output=True)
        print(result.stdout)
        if result.stderr:
            print(result.stderr, file=sys.stderr)
        for name in sorted(os.listdir(folder)):
            scene = name[:-len(".csv")]
            print("figure:", plot(scene, read_csv(os.path.join(folder, name)), arguments.seconds, arguments.out))
    # The bounds the test asserts are reported above; a soak that breaks them is worth knowing
    # but the figures are still written.
    return result.returncode


if __name__ == "__main__":
    sys.exit(main())
