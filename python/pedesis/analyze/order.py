"""Order: the hexatic bond order psi6 (2D) and clusters by a distance criterion."""
import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from .box import Box


def psi6(positions, box, neighbours=6, weighting="nearest"):
    """The hexatic bond order of a 2D frame: per particle psi6_j = sum_k w_jk exp(6 i
    theta_jk) / sum_k w_jk, theta_jk the angle of r_k - r_j; and the global |< psi6_j >|.
    1 on a perfect triangular lattice, ~1/sqrt(N) for a gas.

    ``weighting="nearest"``: the ``neighbours`` nearest particles, w = 1.
    ``weighting="voronoi"``: the Voronoi neighbours, w = the length of the shared cell
    edge (Mickel et al., J. Chem. Phys. 138, 044501 (2013)): no neighbour count to
    choose, and continuous as a neighbour appears or leaves (a square lattice gives 0,
    where 6 nearest neighbours are a tie). Returns (global, local), local the complex
    psi6_j."""
    box = box if isinstance(box, Box) else Box(box)
    if box.dimension != 2:
        raise ValueError("psi6 is for 2D frames")
    x = box.wrap(np.asarray(positions, dtype=float))
    if weighting == "voronoi":
        i, dr, weight = _voronoi_bonds(x, box)
        bond = weight * np.exp(6j * np.arctan2(dr[:, 1], dr[:, 0]))
        total = np.bincount(i, weights=bond.real, minlength=len(x)) + \
            1j * np.bincount(i, weights=bond.imag, minlength=len(x))
        local = total / np.maximum(np.bincount(i, weights=weight, minlength=len(x)), 1e-300)
    elif weighting == "nearest":
        tree = cKDTree(x, boxsize=box.tree_size())
        _, idx = tree.query(x, k=neighbours + 1)
        dr = box.minimum_image(x[idx[:, 1:]] - x[:, None, :])
        local = np.exp(6j * np.arctan2(dr[..., 1], dr[..., 0])).mean(axis=1)
    else:
        raise ValueError(f"psi6: weighting must be 'nearest' or 'voronoi', not {weighting!r}")
    return float(np.abs(local.mean())), local


def _voronoi_bonds(x, box):
    """The Voronoi bonds of 2D points in a box: (i, r_j - r_i, edge length) for every
    ordered pair of neighbours, i an original point. Periodic axes are handled by copies
    of the points within a margin of the far edges (qhull's tessellation has no periodic
    mode); walled axes by none (the outermost cells are open and keep their finite
    edges)."""
    from scipy.spatial import Voronoi

    n = len(x)
    spacing = np.sqrt(box.volume / max(n, 1))
    margin = [min(L, 4.0 * spacing) if p else 0.0 for L, p in zip(box.lengths, box.periodic)]
    copies = [x]
    for sx in (-1, 0, 1):
        for sy in (-1, 0, 1):
            if (sx, sy) == (0, 0) or (sx and not margin[0]) or (sy and not margin[1]):
                continue
            shifted = x + np.array([sx * box.lengths[0], sy * box.lengths[1]])
            near = np.ones(n, dtype=bool)
            for a, s in enumerate((sx, sy)):
                if s:
                    near &= (shifted[:, a] > -margin[a]) & (shifted[:, a] < box.lengths[a] + margin[a])
            copies.append(shifted[near])
    points = np.concatenate(copies)
    vor = Voronoi(points)
    ridges = vor.ridge_points
    vertices = np.array([v if -1 not in v else [-1, -1] for v in vor.ridge_vertices])
    finite = vertices[:, 0] >= 0
    ridges, vertices = ridges[finite], vertices[finite]
    length = np.linalg.norm(vor.vertices[vertices[:, 0]] - vor.vertices[vertices[:, 1]], axis=1)
    out_i, out_dr, out_w = [], [], []
    for a, b in ((0, 1), (1, 0)):
        # bonds of original points only; an image keeps its shifted position, so the bond
        # vector needs no minimum image
        mine = ridges[:, a] < n
        out_i.append(ridges[mine, a])
        out_dr.append(points[ridges[mine, b]] - points[ridges[mine, a]])
        out_w.append(length[mine])
    return np.concatenate(out_i), np.concatenate(out_dr), np.concatenate(out_w)


def clusters(positions, box, cutoff, min_neighbours=0, types=None):
    """Clusters: particles closer than ``cutoff`` belong to one cluster (the connected
    components of the contact graph). With ``min_neighbours`` only the particles with at
    least that many within ``cutoff`` take part (the dense phase of motility-induced
    phase separation: 5 of a close-packed disk's 6); the others get label -1.
    ``cutoff`` may be an (S, S) array, one distance per pair of species, with ``types``
    (N,) the species index of each particle.
    Returns (labels, sizes): each particle's cluster index, and the size of each cluster,
    largest first (labels are renumbered to match)."""
    box = box if isinstance(box, Box) else Box(box)
    x = box.wrap(np.asarray(positions, dtype=float))
    tree = cKDTree(x, boxsize=box.tree_size())
    per_pair = np.ndim(cutoff) == 2
    if per_pair and types is None:
        raise ValueError("clusters: a cutoff per pair of species needs types")
    pairs = tree.query_pairs(np.max(cutoff) if per_pair else cutoff, output_type="ndarray")
    if per_pair and len(pairs):
        t = np.asarray(types)
        r = np.linalg.norm(box.minimum_image(x[pairs[:, 0]] - x[pairs[:, 1]]), axis=1)
        pairs = pairs[r <= np.asarray(cutoff)[t[pairs[:, 0]], t[pairs[:, 1]]]]
    n = len(x)
    member = np.ones(n, dtype=bool)
    if min_neighbours > 0:
        member = np.bincount(pairs.ravel(), minlength=n) >= min_neighbours
        pairs = pairs[member[pairs[:, 0]] & member[pairs[:, 1]]]
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    # the components of left-out particles are singletons of their own; drop them
    kept = np.unique(labels[member])
    if len(kept) == 0:  # no particle has min_neighbours: no dense phase
        return np.full(n, -1), np.zeros(0, dtype=int)
    relabel = np.full(labels.max() + 1 if n else 0, -1)
    relabel[kept] = np.arange(len(kept))
    labels = np.where(member, relabel[labels], -1)
    sizes = np.bincount(labels[member], minlength=len(kept))
    order = np.argsort(-sizes, kind="stable")
    rank = np.empty(len(kept), dtype=int)
    rank[order] = np.arange(len(kept))
    return np.where(member, rank[np.maximum(labels, 0)], -1), sizes[order]


