#!/usr/bin/python3
"""scripts/figures.sh on short runs: every plot is made and holds the runs' data (not its pixels).

Usage: check_figures.py SOURCE_DIR TANDEM WORK_DIR

Runs `scripts/figures.sh WORK_DIR/images --seconds 0.3 --data WORK_DIR/data` and checks, against
the run reports it kept: each PNG exists and is a PNG of a sensible size; figures.json (what was
plotted) has as many points as the runs had steps and iterations, every one finite; the fitted
lines (through the origin) and ns per row-iteration are finite and consistent with the points; the stage shares sum
to one and equal the run reports'; the paper's jelly shares are 43/32/24 %.
"""
import json
import math
import os
import shutil
import struct
import subprocess
import sys

SECONDS = 0.3
PNGS = ["fig1_convergence.png", "fig5_cloth_solve.png", "fig6_jelly_solve.png", "stages.png", "step_time.png"]


def finite(values):
    return all(isinstance(v, (int, float)) and math.isfinite(v) for v in values)


def png_size(path):
    with open(path, "rb") as file:
        head = file.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return struct.unpack(">II", head[16:24])


def main(source_dir, tandem, work_dir):
    shutil.rmtree(work_dir, ignore_errors=True)
    images, data_dir = os.path.join(work_dir, "images"), os.path.join(work_dir, "data")
    subprocess.run(["bash", os.path.join(source_dir, "scripts", "figures.sh"), images, "--seconds", str(SECONDS),
                    "--data", data_dir, "--tandem", tandem], check=True)
    reports = {}
    for scene in ("rope_wheel", "cloth_sphere", "jelly_dish"):
        with open(os.path.join(data_dir, scene + ".json"), encoding="utf-8") as file:
            reports[scene] = json.load(file)
    with open(os.path.join(data_dir, "figures.json"), encoding="utf-8") as file:
        data = json.load(file)

    assert data["png"] == PNGS, data["png"]
    for name in PNGS:
        path = os.path.join(images, name)
        width, height = png_size(path)
        assert width >= 600 and height >= 400 and os.path.getsize(path) > 20000, (name, width, height)

    steps = {scene: round(SECONDS / r["settings"]["time_step"]) for scene, r in reports.items()}
    for scene, report in reports.items():
        assert report["run"]["steps"] == steps[scene], (scene, report["run"]["steps"])

    # Fig. 1: one point per iteration per step, iterations numbered 1..K·n.
    for scene in ("cloth_sphere", "jelly_dish"):
        fig1 = data["fig1"][scene]
        per_step = reports[scene]["settings"]["solver"]["iterations"] * reports[scene]["settings"]["solver"]["substeps"]
        assert len(fig1["rms_delta_lambda"]) == steps[scene] * per_step, (scene, len(fig1["rms_delta_lambda"]))
        assert len(fig1["iteration"]) == len(fig1["rms_delta_lambda"])
        assert sorted(set(fig1["iteration"])) == list(range(1, per_step + 1))
        assert finite(fig1["rms_delta_lambda"]) and min(fig1["rms_delta_lambda"]) >= 0
        assert max(fig1["rms_delta_lambda"]) > 0, f"{scene}: the solver did nothing"
        flat = [v for step in reports[scene]["steps"]["rms_delta_lambda"] for v in step]
        assert fig1["rms_delta_lambda"] == flat

    # Figs. 5 and 6: a point per step, and a fitted line through them.
    for key, scene in (("fig5", "cloth_sphere"), ("fig6", "jelly_dish")):
        fig = data[key]
        assert fig["scene"] == scene
        assert len(fig["rows"]) == len(fig["solve_ms"]) == steps[scene]
        assert fig["rows"] == reports[scene]["steps"]["total_rows"]
        assert fig["solve_ms"] == reports[scene]["steps"]["stage_ms"]["interleaved_solve"]
        assert finite(fig["rows"]) and finite(fig["solve_ms"]) and max(fig["rows"]) > 0
        fit = fig["fit"]
        assert finite([fit["slope_ms_per_row"], fit["ns_per_row_iteration"], fit["median_ns_per_row_iteration"]]), fit
        assert fit["slope_ms_per_row"] > 0 and fit["median_ns_per_row_iteration"] > 0, fit
        assert math.isclose(fit["ns_per_row_iteration"], 1e6 * fit["slope_ms_per_row"] / fit["iterations_per_step"])
        # Least squares through the origin: the residuals are orthogonal to the rows.
        residual = sum(x * (y - fit["slope_ms_per_row"] * x) for x, y in zip(fig["rows"], fig["solve_ms"]))
        assert abs(residual) <= 1e-9 * sum(x * y for x, y in zip(fig["rows"], fig["solve_ms"])), residual

    # Stages: Tandem's shares from the reports, the paper's as its text gives them.
    for scene, shares in data["stages"].items():
        assert math.isclose(sum(shares["tandem"].values()), 1.0, abs_tol=1e-9), (scene, shares["tandem"])
        assert math.isclose(sum(shares["paper"].values()), 1.0, abs_tol=1e-9), (scene, shares["paper"])
        stages = reports[scene]["stages"]
        assert math.isclose(shares["tandem"]["collision detection"], stages["collision_detection"]["share"])
        assert math.isclose(shares["tandem"]["constraint solving"],
                            stages["row_setup"]["share"] + stages["interleaved_solve"]["share"])
    jelly = data["stages"]["jelly_dish"]["paper"]
    assert (jelly["models"], jelly["collision detection"], jelly["constraint solving"]) == (0.43, 0.32, 0.24), jelly
    assert data["stages"]["cloth_sphere"]["paper"]["collision detection"] == 0.45

    # ms per step: a point per step, the real-time line at h.
    for scene in reports:
        series = data["step_time"][scene]
        assert len(series["time"]) == len(series["wall_ms"]) == steps[scene]
        assert finite(series["wall_ms"]) and min(series["wall_ms"]) > 0
        assert series["wall_ms"] == reports[scene]["steps"]["wall_ms"]
    assert data["step_time"]["real_time_ms"] == 1e3 * reports["jelly_dish"]["settings"]["time_step"]
    print(f"check_figures: {len(PNGS)} plots, {sum(steps.values())} steps plotted")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.stderr.write(__doc__)
        sys.exit(2)
    sys.exit(main(*sys.argv[1:]))
