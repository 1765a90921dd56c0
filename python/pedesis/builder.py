"""Initial configurations, as the ABP tutorial's pymd.builder."""
from . import _pedesis


def random_init(phi, L, rcut=0.0, outfile="init.json", seed=1, dim=2, Ly=None, Lz=None,
                radius=1.0):
    """Writes N = round(phi V) particles at uniform random positions, centres at least
    rcut apart (minimum image), each with a uniform random director, in a periodic box
    L x Ly (x Lz) centred at the origin, to `outfile` in the tutorial's JSON layout.
    The same file as `pedesis init random --phi .. --L .. --rcut .. --seed ..`.
    Returns the path. Raises InputError for impossible parameters (phi too high for
    rcut, non-positive lengths)."""
    _pedesis._random_init(float(phi), float(L), float(rcut), outfile, int(seed), int(dim),
                          None if Ly is None else float(Ly), None if Lz is None else float(Lz),
                          float(radius))
    return outfile
