"""Order: the hexatic bond order psi6 (2D) and clusters by a distance criterion."""
import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from .box import Box


def psi6(positions, box, neighbours=6):
    """The hexatic bond order of a 2D frame: per particle psi6_j = (1/n) sum over its n
    nearest neighbours k of exp(6 i theta_jk), theta_jk the angle of r_k - r_j; and the
    global |< psi6_j >|. 1 on a perfect triangular lattice, ~1/sqrt(N) for a gas.
    Returns (global, local) with local the complex psi6_j."""
    box = box if isinstance(box, Box) else Box(box)
    if box.dimension != 2:
        raise ValueError("psi6 is for 2D frames")
    x = box.wrap(np.asarray(positions, dtype=float))
    tree = cKDTree(x, boxsize=box.tree_size())
    _, idx = tree.query(x, k=neighbours + 1)
    dr = box.minimum_image(x[idx[:, 1:]] - x[:, None, :])
    local = np.exp(6j * np.arctan2(dr[..., 1], dr[..., 0])).mean(axis=1)
    return float(np.abs(local.mean())), local


def clusters(positions, box, cutoff):
    """Clusters: particles closer than ``cutoff`` belong to one cluster (the connected
    components of the contact graph). Returns (labels, sizes): each particle's cluster
    index, and the size of each cluster, largest first (labels are renumbered to match)."""
    box = box if isinstance(box, Box) else Box(box)
    x = box.wrap(np.asarray(positions, dtype=float))
    tree = cKDTree(x, boxsize=box.tree_size())
    pairs = tree.query_pairs(cutoff, output_type="ndarray")
    n = len(x)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    count, labels = connected_components(graph, directed=False)
    sizes = np.bincount(labels, minlength=count)
    order = np.argsort(-sizes, kind="stable")
    rank = np.empty(count, dtype=int)
    rank[order] = np.arange(count)
    return rank[labels], sizes[order]
