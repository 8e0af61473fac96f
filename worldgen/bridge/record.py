"""A run's records: ``--plot`` (the path from above, over the walls, with start, end and contact marks),
``--csv`` (the time series). ``--bag`` is written by the simulator node itself, with Debian's rosbag, from the
very messages it publishes and receives."""

from __future__ import annotations

import io
import math

from ..core.mpl import matplotlib_agg
from ..geometry.markings import floor_markings, footprint
from ..geometry.slices import footprints_between


def plot_png(world, trace: dict, result, person: dict | None = None) -> bytes:
    """A PNG of the robot's path over the world's walls (matplotlib's Agg backend, imported here only)."""
    matplotlib_agg()
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 7))
    for footprint in footprints_between(world.scene, 0.05, 0.3):
        for polygon in getattr(footprint.geometry, "geoms", [footprint.geometry]):
            if hasattr(polygon, "exterior"):
                xs, ys = polygon.exterior.xy
                ax.fill(xs, ys, color="0.55", linewidth=0)
    _draw_markings(ax, world.scene)
    odom = trace.get("odom", [])
    xs, ys = [r[1] for r in odom], [r[2] for r in odom]
    if person and trace.get("person"):
        ax.plot([p[1] for p in trace["person"]], [p[2] for p in trace["person"]], color="tab:orange",
                linestyle="--", linewidth=1, label="person")
    ax.plot(xs, ys, color="tab:blue", linewidth=1.5, label="path (base_footprint)")
    if odom:
        ax.plot(xs[:1], ys[:1], marker="o", color="tab:green", linestyle="none", markersize=8, label="start")
        ax.plot(xs[-1:], ys[-1:], marker="s", color="tab:red", linestyle="none", markersize=8, label="end")
        end = odom[-1]
        ax.annotate("", xy=(end[1] + 0.25 * math.cos(end[3]), end[2] + 0.25 * math.sin(end[3])),
                    xytext=(end[1], end[2]), arrowprops={"arrowstyle": "->", "color": "tab:red"})
    for contact in trace.get("contacts", []):
        row = min(odom, key=lambda r: abs(r[0] - contact["time"])) if odom else None
        if row is not None:
            ax.plot([row[1]], [row[2]], marker="x", color="black", markersize=10, mew=2, linestyle="none")
    if trace.get("contacts"):
        ax.plot([], [], marker="x", color="black", linestyle="none", mew=2, label="contact")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    verdict = "pass" if result.ok else "fail"
    ax.set_title(f"{result.path} — {verdict}", fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def _draw_markings(ax, scene) -> None:
    """The floor markings (tape, patches) in their own colours, under the path."""
    drawn = False
    for marking in floor_markings(scene):
        for shape in marking.shapes:
            outline = footprint(shape)
            for polygon in getattr(outline, "geoms", [outline]):
                if hasattr(polygon, "exterior"):
                    xs, ys = polygon.exterior.xy
                    color = shape.color or (0.7, 0.7, 0.7, 1.0)
                    ax.fill(xs, ys, color=tuple(color[:3]), linewidth=0, zorder=0.5)
                    drawn = True
    if drawn:
        ax.fill([], [], color="gold", label="floor marking (tape)")


def _f(value) -> str:
    return "" if value is None else f"{value:.4f}"


def trace_csv(trace: dict) -> str:
    """One row per drive update (30 Hz): pose, speeds, the command in force, and the last scan's distances."""
    scans = trace.get("scans", [])
    rows = ["t,x,y,yaw,v,omega,cmd_v,cmd_omega,front_m,nearest_m,clearance_m"]
    i = -1
    for row in trace.get("odom", []):
        while i + 1 < len(scans) and scans[i + 1][0] <= row[0] + 1e-9:
            i += 1
        scan = scans[i] if i >= 0 else [None] * 5
        rows.append(",".join(_f(v) for v in (*row[:8], scan[1], scan[3], scan[4])))
    return "\n".join(rows) + "\n"
