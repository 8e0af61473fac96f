"""matplotlib for worldgen's pictures: the Agg backend (no display), imported quietly where two copies meet.

On a ROS machine worldgen often runs in a venv made with ``--system-site-packages``, beside Debian's or ROS's own
python3-matplotlib (the class runtime). Debian's copy brings its own ``mpl_toolkits`` package, which the venv's
matplotlib then finds first, so its 3D projection fails to load and it warns "Unable to import Axes3D" on every
picture. worldgen draws no 3D plot: that one warning is not shown.
"""

from __future__ import annotations

import warnings


def matplotlib_agg():
    """The ``matplotlib`` module, set to the Agg backend, its projections loaded with that warning filtered."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Unable to import Axes3D", category=UserWarning)
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.projections  # noqa: F401  (where the warning is raised, once per process)
    return matplotlib
