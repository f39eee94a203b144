#!/usr/bin/python3
"""The paper's figures from Tandem's run reports (`tandem run --report-json`).

Usage: plot_figures.py REPORT_DIR OUT_DIR [DATA_JSON]

REPORT_DIR holds rope_wheel.json, cloth_sphere.json and jelly_dish.json, the run reports of the
paper's three scenes (scripts/figures.sh makes them). Writes to OUT_DIR:

  fig1_convergence.png   RMS of delta-lambda per iteration, every step of the cloth and jelly runs (paper Fig. 1)
  fig5_cloth_solve.png   interleaved-solve time against row count, every step, fitted line (paper Fig. 5)
  fig6_jelly_solve.png   the same for the jelly scene (paper Fig. 6)
  stages.png             each scene's share of a step per stage, beside the paper's numbers
  step_time.png          ms per step over each run, with the real-time line

and DATA_JSON (default OUT_DIR/figures.json): every number plotted, for tests and for reuse.
Needs numpy and matplotlib (Debian's python3-numpy, python3-matplotlib); runs with no display.
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.patches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

SCENES = ["rope_wheel", "cloth_sphere", "jelly_dish"]
LABELS = {"rope_wheel": "rope over a wheel (Fig. 4)", "cloth_sphere": "cloth on a sphere (Fig. 3)",
          "jelly_dish": "jellies under a bar (Fig. 2)"}
SHORT = {"rope_wheel": "rope", "cloth_sphere": "cloth", "jelly_dish": "jelly"}
COLOURS = {"rope_wheel": "#4c72b0", "cloth_sphere": "#dd8452", "jelly_dish": "#55a868"}

# The paper's stage shares (§5): the jelly scene's caption of Fig. 6 gives 43 % force and position
# dynamics, 32 % collision detection, 24 % constraint solving, "time integration and rigid-body
# simulation negligible"; the cloth's caption of Fig. 3 gives collision detection "about 45 %" and
# nothing else; the rope scene has no breakdown.
CATEGORIES = ["models", "collision detection", "constraint solving", "integration, rigid bodies", "not given"]
CATEGORY_COLOURS = ["#8172b3", "#c44e52", "#4c72b0", "#937860", "#dddddd"]
PAPER_SHARES = {
    "rope_wheel": {"not given": 1.0},
    "cloth_sphere": {"collision detection": 0.45, "not given": 0.55},
    "jelly_dish": {"models": 0.43, "collision detection": 0.32, "constraint solving": 0.24,
                   "integration, rigid bodies": 0.01},
}
# Tandem's stages, gathered into the paper's categories.
STAGE_CATEGORY = {"models": "models", "collision_detection": "collision detection", "row_setup": "constraint solving",
                  "interleaved_solve": "constraint solving", "rigid_prediction": "integration, rigid bodies",
                  "integrate": "integration, rigid bodies"}
PAPER_JELLY_MS = (6.0, 14.0)  # mean and worst ms per 20 ms step (Fig. 2's caption), 3.4 GHz Core i7


def load_reports(report_dir):
    reports = {}
    for scene in SCENES:
        with open(os.path.join(report_dir, scene + ".json"), encoding="utf-8") as file:
            reports[scene] = json.load(file)
    return reports


def iterations_per_step(report):
    solver = report["settings"]["solver"]
    return solver["iterations"] * solver["substeps"]


def convergence_figure(reports, out_dir, data):
    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=110)
    rng = np.random.default_rng(1)
    data["fig1"] = {}
    for scene, marker, size in (("cloth_sphere", "o", 9), ("jelly_dish", "x", 16)):
        per_step = reports[scene]["steps"]["rms_delta_lambda"]
        iteration = np.array([k + 1 for step in per_step for k in range(len(step))], dtype=float)
        rms = np.array([value for step in per_step for value in step], dtype=float)
        shown = rms > 0  # a step with no rows has nothing to plot on a log scale
        jitter = rng.uniform(-0.18, 0.18, size=iteration.size)
        offset = -0.1 if scene == "cloth_sphere" else 0.1
        ax.scatter(iteration[shown] + offset + jitter[shown] * 0.5, rms[shown], marker=marker, s=size, linewidths=0.8,
                   alpha=0.35, color=COLOURS[scene], label=f"{SHORT[scene]}: every step")
        k_count = iterations_per_step(reports[scene])
        medians = [float(np.median(rms[(iteration == k) & shown])) if np.any((iteration == k) & shown) else math.nan
                   for k in range(1, k_count + 1)]
        ax.plot(np.arange(1, k_count + 1) + offset, medians, color=COLOURS[scene], linewidth=2,
                label=f"{SHORT[scene]}: median")
        data["fig1"][scene] = {"iteration": iteration.tolist(), "rms_delta_lambda": rms.tolist(),
                               "median": medians, "steps": len(per_step)}
    # A step with hardly any rows gives an RMS many decades below the rest: clip the axis to six
    # decades under the smallest median and say how many points lie below.
    all_rms = np.concatenate([np.array(v["rms_delta_lambda"]) for v in data["fig1"].values()])
    all_medians = [m for v in data["fig1"].values() for m in v["median"] if m > 0]
    if all_medians and np.any(all_rms > 0):
        bottom = min(all_medians) * 1e-6
        below = int(np.sum((all_rms > 0) & (all_rms < bottom)))
        ax.set_ylim(bottom=bottom, top=all_rms.max() * 5)
        if below:
            ax.text(0.01, 0.01, f"{below} points below the axis", transform=ax.transAxes, fontsize=7, color="gray")
    ax.set_yscale("log")
    ax.set_xlabel("iteration of the interleaved solve")
    ax.set_ylabel("RMS of Δλ over Tandem's rows (N·s)")
    ax.set_xticks(range(1, max(iterations_per_step(reports[s]) for s in ("cloth_sphere", "jelly_dish")) + 1))
    ax.set_title("Convergence per iteration (paper Fig. 1: dots cloth, crosses jelly)", fontsize=10)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8, loc="lower left", bbox_to_anchor=(0.0, 0.04))
    fig.tight_layout()
    path = os.path.join(out_dir, "fig1_convergence.png")
    fig.savefig(path)
    plt.close(fig)
    return path


def solve_figure(report, scene, figure_name, paper_figure, out_dir, data):
    steps = report["steps"]
    rows = np.array(steps["total_rows"], dtype=float)
    solve_ms = np.array(steps["stage_ms"]["interleaved_solve"], dtype=float)
    time = np.array(steps["time"], dtype=float)
    k_count = iterations_per_step(report)
    # The paper's claim is a cost linear in the rows: time = c · rows, fitted through the origin
    # by least squares (c = Σ rows·time / Σ rows²). Tandem's row count varies little within a run,
    # so a line with an intercept would be fitted to the spread of a nearly vertical cloud.
    slope = float(np.dot(rows, solve_ms) / np.dot(rows, rows)) if np.dot(rows, rows) > 0 else 0.0
    ns_per_row_iteration = 1e6 * slope / k_count
    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=110)
    points = ax.scatter(rows, solve_ms, s=10, alpha=0.6, c=time, cmap="viridis", label="one step")
    fig.colorbar(points, ax=ax, pad=0.01).set_label("simulated time of the step (s)", fontsize=8)
    line_x = np.array([0.0, rows.max() * 1.05 if rows.size else 1.0])
    ax.plot(line_x, slope * line_x, color="black", linewidth=1.5,
            label=f"fit through 0: {1e3 * slope:.3g} µs per row\n= {ns_per_row_iteration:.3g} ns per row-iteration "
                  f"(K·n = {k_count})")
    ax.set_xlabel("rows in the step (Tandem's scalar constraint rows)")
    ax.set_ylabel("interleaved solve (ms per step)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.set_title(f"{LABELS[scene]}: solve time against rows (paper {paper_figure})", fontsize=10)
    ax.grid(True, alpha=0.25)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    path = os.path.join(out_dir, figure_name)
    fig.savefig(path)
    plt.close(fig)
    data[figure_name.split("_")[0]] = {"scene": scene, "rows": rows.tolist(), "solve_ms": solve_ms.tolist(),
                                       "time": time.tolist(),
                                       "fit": {"slope_ms_per_row": slope, "iterations_per_step": k_count,
                                               "ns_per_row_iteration": float(ns_per_row_iteration),
                                               "median_ns_per_row_iteration":
                                                   float(np.median(1e6 * solve_ms[rows > 0] / rows[rows > 0] / k_count))
                                                   if np.any(rows > 0) else 0.0}}
    return path


def tandem_shares(report):
    shares = {category: 0.0 for category in CATEGORIES}
    for stage, values in report["stages"].items():
        shares[STAGE_CATEGORY[stage]] += values["share"]
    return shares


def stages_figure(reports, out_dir, data):
    fig, ax = plt.subplots(figsize=(8.4, 4.2), dpi=110)
    labels, y = [], 0
    data["stages"] = {}
    for scene in SCENES:
        tandem = tandem_shares(reports[scene])
        paper = {category: PAPER_SHARES[scene].get(category, 0.0) for category in CATEGORIES}
        mean_ms = reports[scene]["step_ms"]["mean"]
        data["stages"][scene] = {"tandem": tandem, "paper": paper, "tandem_mean_ms": mean_ms,
                                 "tandem_stage_ms": {s: v["mean_ms"] for s, v in reports[scene]["stages"].items()}}
        for who, shares in (("paper", paper), ("Tandem", tandem)):
            left = 0.0
            for category, colour in zip(CATEGORIES, CATEGORY_COLOURS):
                width = shares[category]
                if width <= 0:
                    continue
                ax.barh(y, width, left=left, color=colour, edgecolor="white", height=0.8,
                        hatch="//" if category == "not given" else None)
                if width >= 0.06:
                    text = f"not given ({100 * width:.0f} %)" if category == "not given" else f"{100 * width:.0f} %"
                    ax.text(left + width / 2, y, text, ha="center", va="center", fontsize=8,
                            color="black" if category == "not given" else "white")
                left += width
            labels.append(f"{SHORT[scene]}, {who}" + (f" ({mean_ms:.2g} ms/step)" if who == "Tandem" else ""))
            y += 1
        y += 0.5
    ticks = [i + 0.5 * (i // 2) for i in range(len(labels))]
    ax.set_yticks(ticks, labels, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlim(0, 1)
    ax.xaxis.set_major_formatter(matplotlib.ticker.PercentFormatter(1.0))
    ax.set_xlabel("share of a step's time")
    ax.set_title("Where a step's time goes: Tandem (mean over the run) beside the paper", fontsize=10)
    handles = [matplotlib.patches.Patch(facecolor=c, hatch="//" if n == "not given" else None, label=n)
               for n, c in zip(CATEGORIES, CATEGORY_COLOURS)]
    ax.legend(handles=handles, fontsize=7.5, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=5, frameon=False)
    fig.text(0.01, 0.01, "Tandem's constraint solving = row setup + interleaved solve; its integration includes the "
             "position passes (strain limiting, impact zones).", fontsize=7, color="dimgray")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    path = os.path.join(out_dir, "stages.png")
    fig.savefig(path)
    plt.close(fig)
    return path


def step_time_figure(reports, out_dir, data):
    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=110)
    data["step_time"] = {}
    h_ms = 1e3 * reports["jelly_dish"]["settings"]["time_step"]
    for scene in SCENES:
        steps = reports[scene]["steps"]
        time = np.array(steps["time"], dtype=float)
        wall_ms = np.array(steps["wall_ms"], dtype=float)
        mean = reports[scene]["step_ms"]["mean"]
        ax.plot(time, wall_ms, linewidth=0.9, color=COLOURS[scene], label=f"{LABELS[scene]}: mean {mean:.3g} ms")
        data["step_time"][scene] = {"time": time.tolist(), "wall_ms": wall_ms.tolist(), "mean_ms": mean,
                                    "time_step_ms": 1e3 * reports[scene]["settings"]["time_step"]}
    ax.axhline(h_ms, color="black", linestyle="--", linewidth=1.2, label=f"real time: h = {h_ms:g} ms per step")
    ax.axhline(PAPER_JELLY_MS[0], color=COLOURS["jelly_dish"], linestyle=":", linewidth=1.2,
               label=f"paper, jelly: mean {PAPER_JELLY_MS[0]:g} ms (worst {PAPER_JELLY_MS[1]:g}), 3.4 GHz i7")
    ax.set_yscale("log")
    ax.set_xlabel("simulated time (s)")
    ax.set_ylabel("wall-clock ms per step")
    ax.set_title("Cost of each step over a run (below the dashed line: faster than real time)", fontsize=10)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=7.5, loc="upper right")
    fig.tight_layout()
    path = os.path.join(out_dir, "step_time.png")
    fig.savefig(path)
    plt.close(fig)
    data["step_time"]["real_time_ms"] = h_ms
    return path


def main(argv):
    if len(argv) not in (3, 4):
        sys.stderr.write(__doc__)
        return 2
    report_dir, out_dir = argv[1], argv[2]
    data_path = argv[3] if len(argv) == 4 else os.path.join(out_dir, "figures.json")
    try:
        reports = load_reports(report_dir)
    except (OSError, ValueError, KeyError) as error:
        sys.stderr.write(f"plot_figures: cannot read the run reports in '{report_dir}': {error}\n")
        return 1
    os.makedirs(out_dir, exist_ok=True)
    data = {"scenes": {s: {"steps": r["run"]["steps"], "time_step": r["settings"]["time_step"],
                           "iterations_per_step": iterations_per_step(r)} for s, r in reports.items()}}
    made = [convergence_figure(reports, out_dir, data),
            solve_figure(reports["cloth_sphere"], "cloth_sphere", "fig5_cloth_solve.png", "Fig. 5", out_dir, data),
            solve_figure(reports["jelly_dish"], "jelly_dish", "fig6_jelly_solve.png", "Fig. 6", out_dir, data),
            stages_figure(reports, out_dir, data),
            step_time_figure(reports, out_dir, data)]
    data["png"] = [os.path.basename(path) for path in made]
    with open(data_path, "w", encoding="utf-8") as file:
        json.dump(data, file)
    for path in made:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
