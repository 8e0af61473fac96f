"""Connected components of a graph given as pairs of node indices, in vectorised numpy (no scipy needed)."""

from __future__ import annotations


def connected_labels(n: int, a, b):
    """A label per node (0 … n−1) such that nodes joined by the pairs ``a[i]``–``b[i]`` (index arrays), directly
    or through others, share a label: the smallest index of their component."""
    import numpy as np

    label = np.arange(n)
    a, b = np.asarray(a, dtype=np.int64), np.asarray(b, dtype=np.int64)
    while True:   # union-find: hook each pair's larger root onto the smaller (any one write wins), then jump
        la, lb = label[a], label[b]
        differ = la != lb
        if not differ.any():
            return label
        label[np.maximum(la[differ], lb[differ])] = np.minimum(la[differ], lb[differ])
        while True:
            jumped = label[label]
            if (jumped == label).all():
                break
            label = jumped
