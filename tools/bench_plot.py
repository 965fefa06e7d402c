#!/usr/bin/env python3
"""Plots of a `pt bench` run: relMSE against render time (log-log, one line per
configuration) and a labelled contact sheet of the images at each time budget.

pt bench writes this script into its output folder and runs it there; run it again by hand
(python3 plot.py DIR) after editing. Needs matplotlib (Debian: python3-matplotlib)."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(folder):
    with open(os.path.join(folder, "bench.csv"), newline="") as f:
        return list(csv.DictReader(f))


def read_info(folder):
    info = {}
    path = os.path.join(folder, "bench_info.txt")
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                key, _, value = line.partition(":")
                info[key.strip()] = value.strip()
    return info


def plot_error_against_time(rows, info, folder):
    fig, ax = plt.subplots(figsize=(8, 6))
    configs = list(dict.fromkeys(r["config"] for r in rows))
    for config in configs:
        points = [(float(r["seconds"]), float(r["relmse"])) for r in rows if r["config"] == config]
        points.sort()
        ax.loglog([p[0] for p in points], [p[1] for p in points], marker="o", label=config)
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("relMSE against the reference")
    ax.set_title("%s\n%s" % (info.get("scene", ""), info.get("device", "")), fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "relmse_vs_time.png"), dpi=100)
    plt.close(fig)


def contact_sheet(rows, budget, folder):
    chosen = [r for r in rows if r["budget_s"] == budget]
    columns = min(5, len(chosen))
    lines = (len(chosen) + columns - 1) // columns
    fig, axes = plt.subplots(lines, columns, figsize=(3 * columns, 3.3 * lines), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for ax, r in zip(axes.flat, chosen):
        ax.imshow(plt.imread(os.path.join(folder, r["image"])))
        ax.set_title("%s\n%s spp, relMSE %.3g" % (r["config"], r["spp"], float(r["relmse"])), fontsize=8)
    fig.suptitle("equal time: %s s" % budget, fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "contact_%ss.png" % budget), dpi=100)
    plt.close(fig)


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    rows = read_rows(folder)
    if not rows:
        sys.exit("bench_plot: %s/bench.csv has no rows" % folder)
    plot_error_against_time(rows, read_info(folder), folder)
    for budget in dict.fromkeys(r["budget_s"] for r in rows):
        contact_sheet(rows, budget, folder)


if __name__ == "__main__":
    main()
