"""Figures and tables of ``worldgen drive`` runs: the stop-at-wall step response (distance to the wall against
time, one curve per gain set, with the target line and the tolerance band, as in a PID lecture) or the spin's
drift; and the time series as CSV. Both take the dict :func:`worldgen.sim.exercise.drive_exercise` returns and
give bytes/text, so writing stays all-or-nothing in :mod:`worldgen.core.fsio`."""

from __future__ import annotations

import io

from ..core.mpl import matplotlib_agg


def gains_label(run: dict) -> str:
    return f"kp={run['kp']:g} ki={run['ki']:g} kd={run['kd']:g}"


def plot_png(result: dict) -> bytes:
    """A PNG of the runs in ``result`` (matplotlib's Agg backend, imported here only)."""
    matplotlib_agg()
    import matplotlib.pyplot as plt

    title = f"{result['behaviour']} — {result['world']} ({result['robot']})"
    if result["behaviour"] == "spin":
        fig, ax = plt.subplots(figsize=(8, 4.5))
        for run in result["runs"]:
            ax.plot(run["series"]["t"], [d * 1000 for d in run["series"]["drift"]],
                    label=f"ω={run['omega']:g} rad/s")
        ax.axhline(result["runs"][0]["drift_limit"] * 1000, color="grey", linestyle="--", label="drift limit")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("base_footprint drift from start (mm)")
    else:
        fig, (ax, ax_v) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True, height_ratios=(3, 1))
        first = result["runs"][0]
        target, tol = first["target"], first["tolerance"]
        ax.axhspan(target - tol, target + tol, color="tab:green", alpha=0.12, label=f"target ±{tol:g} m")
        ax.axhline(target, color="black", linestyle="--", linewidth=1, label=f"target {target:g} m")
        for run in result["runs"]:
            series = run["series"]
            line, = ax.plot(series["t"], _nan(series["true"]), label=gains_label(run))
            ax.plot(series["t"], _nan(series["measured"]), linestyle="none", marker=".", markersize=3,
                    color=line.get_color(), alpha=0.5)
            ax_v.step(series["t"], series["v_cmd"], where="post", color=line.get_color())
        ax.set_ylabel("distance to the wall ahead (m)")
        ax.set_ylim(bottom=0)
        ax_v.set_ylabel("v command (m/s)")
        ax_v.set_xlabel("time (s)")
        ax_v.grid(True, alpha=0.3)
        ax.text(0.99, 0.97, "lines: true distance; dots: what the LiDAR reported", transform=ax.transAxes,
                ha="right", va="top", fontsize=8, color="grey")
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper right" if result["behaviour"] == "spin" else "center right")
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def _nan(values: list) -> list[float]:
    return [float("nan") if v is None else v for v in values]


def series_csv(result: dict) -> str:
    """The runs' time series as CSV, one row per sample (fixed 4-decimal floats, empty for no reading)."""
    if result["behaviour"] == "spin":
        rows = ["run,t,x,y,yaw,drift"]
        for n, run in enumerate(result["runs"], 1):
            s = run["series"]
            rows += [f"{n},{_f(t)},{_f(x)},{_f(y)},{_f(yaw)},{_f(d)}"
                     for t, x, y, yaw, d in zip(s["t"], s["x"], s["y"], s["yaw"], s["drift"])]
    else:
        rows = ["run,kp,ki,kd,t,distance,measured,v_cmd,v"]
        for n, run in enumerate(result["runs"], 1):
            s = run["series"]
            rows += [f"{n},{run['kp']:g},{run['ki']:g},{run['kd']:g},{_f(t)},{_f(d)},{_f(m)},{_f(vc)},{_f(v)}"
                     for t, d, m, vc, v in zip(s["t"], s["true"], s["measured"], s["v_cmd"], s["v"])]
    return "\n".join(rows) + "\n"


def _f(value) -> str:
    return "" if value is None else f"{value:.4f}"
