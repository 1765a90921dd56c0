"""Every engine writes every frame format, and each file is read by the reader people
use: python3-gsd for GSD, VTK's vtkXMLPolyDataReader for VTP, ASE for extended XYZ,
json for the tutorial layout and numpy for the table. The particle count, box and
species names come from the config (known inputs); positions must agree between the
five files of one frame (exactly for the text formats, which write round-trip
decimals; to float32 rounding for GSD) and lie inside the box."""
import json
import math

# Test dependencies (scripts/install-deps.sh): a missing one fails the test, it is
# never skipped.
import gsd.hoomd as gsd_hoomd
import numpy as np
import pytest
import vtk
from ase.io.extxyz import key_val_str_to_dict, read_xyz
from vtk.util.numpy_support import vtk_to_numpy

FORMATS = 'formats = ["gsd", "vtp", "xyz", "json", "table"]'

HARD_SPECIES = """
[[species]]
name = "small"
count = 24
radius = 0.5
[[species]]
name = "big"
count = 8
radius = 0.8
mass = 2.5
"""

HARD_RUN = HARD_SPECIES + """
[run]
time = 1.0
[output]
log_interval = 0.5
snapshot_interval = 0.5
progress = false
""" + FORMATS

CONFIGS = {
    "event_2d": ("""dimension = 2
seed = 3
[box]
lengths = [12.0, 10.0]
boundary = ["wall", "periodic"]
""" + HARD_RUN, 2, [12.0, 10.0], ["small", "big"], 3),
    "stepped_3d": ("""dimension = 3
dynamics = "stepped"
seed = 4
[box]
length = 9.0
[stepped]
dt = 0.01
""" + HARD_RUN, 3, [9.0, 9.0, 9.0], ["small", "big"], 3),
    "brownian_2d": ("""dimension = 2
dynamics = "brownian"
seed = 5
[box]
lengths = [14.0, 12.0]
[[species]]
name = "A"
count = 30
radius = 1.0
[initial]
positions = "random"
[[force]]
name = "harmonic"
k = 10.0
[[force]]
name = "self_propulsion"
alpha = 1.0
[[integrator]]
name = "brownian"
T = 0.1
gamma = 1.0
[[integrator]]
name = "brownian_rotation"
T = 0.1
gamma = 1.0
[run]
steps = 20
dt = 0.01
[output]
snapshot_every = 10
progress = false
""" + FORMATS, 2, [14.0, 12.0], ["A"], 3),
}


def by_tag(ids, values):
    order = np.argsort(np.asarray(ids))
    return np.asarray(values)[order]


def read_json(path, dim):
    doc = json.loads(path.read_text())["system"]
    ps = doc["particles"]
    return (np.array([p["id"] for p in ps]), np.array([p["type"] for p in ps]),
            np.array([p["r"] for p in ps], dtype=float).reshape(-1, dim), doc["box"])


def pedesis_comment_line(line):
    """ASE takes a "species" column for chemical symbols and refuses other names
    ("A", "small"); read pedesis's species names as a plain string column instead
    (docs/formats.md shows this for users)."""
    info = key_val_str_to_dict(line)
    info["Properties"] = info["Properties"].replace("species:S:1", "type_name:S:1")
    return info


def read_xyz_with_ase(path):
    with open(path) as f:
        return list(read_xyz(f, index=slice(None), properties_parser=pedesis_comment_line))


def read_vtp(path):
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(str(path))
    reader.Update()
    poly = reader.GetOutput()
    points = vtk_to_numpy(poly.GetPoints().GetData())
    ids = vtk_to_numpy(poly.GetPointData().GetArray("id"))
    return ids, points


@pytest.mark.parametrize("name", sorted(CONFIGS))
def test_every_format_reads_back(tmp_path, run_cli, name):
    text, dim, lengths, species, frames = CONFIGS[name]
    (tmp_path / "run.toml").write_text(text)
    run_cli("run", "run.toml", "--out", "out", cwd=tmp_path)
    out = tmp_path / "out"
    n = 32 if species != ["A"] else 30

    traj = gsd_hoomd.open(str(out / "trajectory.gsd"), "rb")
    xyz = read_xyz_with_ase(out / "trajectory.xyz")
    assert len(traj) == frames and len(xyz) == frames
    for k in range(frames):
        ids, types, r, box = read_json(out / "snapshots" / f"frame_{k:06d}.json", dim)
        assert len(ids) == n and sorted(ids) == list(range(n))
        assert [box[key] for key in ("Lx", "Ly", "Lz")[:dim]] == lengths
        r = by_tag(ids, r)
        types = by_tag(ids, types)
        half = np.array(lengths) / 2
        assert np.all(np.abs(r) <= half + 1e-12), "positions inside the box"

        g = traj[k]
        assert g.particles.N == n
        assert g.configuration.dimensions == dim
        assert list(g.configuration.box[:dim]) == pytest.approx(lengths)
        assert list(g.particles.types) == species
        # GSD rows are in tag order, positions are float32
        np.testing.assert_allclose(g.particles.position[:, :dim], r, rtol=0, atol=1e-5)
        np.testing.assert_array_equal(g.particles.typeid, types)

        vids, vpoints = read_vtp(out / "snapshots" / f"frame_{k:06d}.vtp")
        np.testing.assert_array_equal(by_tag(vids, vpoints)[:, :dim], r)

        atoms = xyz[k]
        assert len(atoms) == n
        assert atoms.cell.lengths()[:dim] == pytest.approx(lengths)
        assert [str(s) for s in atoms.arrays["type_name"]] == [species[t] for t in types]
        np.testing.assert_array_equal(by_tag(atoms.arrays["id"], atoms.positions)[:, :dim], r)

        table = np.loadtxt(out / "snapshots" / f"frame_{k:06d}.txt", ndmin=2)
        np.testing.assert_array_equal(by_tag(table[:, 0], table[:, 1:1 + dim]), r)

    # the hard-particle files carry what the engine has: masses and diameters by
    # species, velocities; no orientation chunk without directors
    last = traj[frames - 1]
    if species != ["A"]:
        small = last.particles.typeid == 0
        assert np.all(last.particles.diameter[small] == 1.0)
        assert np.all(last.particles.diameter[~small] == np.float32(1.6))
        assert np.all(last.particles.mass[~small] == 2.5)
        speeds = np.linalg.norm(last.particles.velocity, axis=1)
        assert np.all(np.isfinite(speeds)) and speeds.max() > 0
    else:
        q = last.particles.orientation
        assert np.allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-6)
        assert not np.allclose(q, [1, 0, 0, 0]), "directors are written as orientations"
    assert math.isfinite(float(last.configuration.step))
