"""What the examples' plots share: matplotlib without a display, and a figure saved with each legend
beside its axes (no corner of these plots is free of data), checked, so a legend never hides a curve."""
import os

import matplotlib

matplotlib.use("Agg")  # files only, no window needed
import matplotlib.pyplot as plt  # noqa: E402,F401  (the examples take pyplot from here)


def save(fig, axes, path):
    """Puts the legend of each of `axes` beside it, checks it covers none of them, and saves the figure
    to `path` (its folder made if missing)."""
    for ax in axes:
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    fig.canvas.draw()
    for ax in axes:
        assert not ax.get_legend().get_window_extent().overlaps(ax.get_window_extent()), "a legend covers the data"
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=110)
    print(f"plot: {path}")
