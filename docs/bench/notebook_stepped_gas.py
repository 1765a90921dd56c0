#!/usr/bin/python3
"""Times the kinetic-theory notebook's time-stepped gas (seed 003) on N molecules.

A replica of the notebook's per-step work, written for this benchmark: one Python
object per molecule with getters and setters, and in every step

  1. collision pairs from the N x N distance matrix (np.argwhere), duplicates removed by
     comparing each pair with every pair kept so far, and for each approaching pair the
     elastic velocity update of the notebook's Figure 1;
  2. a loop over the molecules: move by v dt, check the walls, reflect and count the
     wall momentum;
  3. make_matrices(): positions and velocities copied out of the objects, and the
     distance matrix rebuilt with a double Python loop over all N^2 pairs calling
     np.linalg.norm, as the notebook does.

Step 3 dominates: it is O(N^2) Python-level work. The matrices before the first step
are built with a vectorised expression instead (setup, not timed; the result is the
same matrix), so that only the per-step cost is measured. Times are CPU seconds of this
process (time.process_time), comparable with `pedesis bench stepped`, which prints the
same.

    /usr/bin/python3 docs/bench/notebook_stepped_gas.py --n 10000 --steps 1
"""
import argparse
import math
import time

import numpy as np


class Molecule:
    def __init__(self, position, velocity, mass=1.0):
        self.position = np.array(position, dtype=float)
        self.velocity = np.array(velocity, dtype=float)
        self.mass = mass

    def get_position(self):
        return self.position

    def set_position(self, position):
        self.position = np.array([x for x in position])

    def get_velocity(self):
        return self.velocity

    def set_velocity(self, velocity):
        self.velocity = np.array([v for v in velocity])

    def get_mass(self):
        return self.mass


class NotebookGas:
    def __init__(self, n, box, dt, radius, rng):
        self.box = list(box)
        self.dim = len(box)
        self.dt = dt
        self.radius = radius
        pos = rng.uniform(low=[0.0] * self.dim, high=self.box, size=(n, self.dim))
        vel = rng.normal(loc=0.0, scale=1.0, size=(n, self.dim))
        signs = np.where(rng.uniform(size=vel.shape) > 0.5, -1.0, 1.0)
        vel *= signs
        self.molecules = [Molecule(pos[i], vel[i]) for i in range(n)]
        self.n = n
        self.wall_momentum = 0.0
        self.wall_collisions = 0
        self.copy_out()
        # setup only: the same matrix the loop below builds, computed at once
        d = self.positions[:, None, :] - self.positions[None, :, :]
        self.distance_matrix = np.sqrt((d * d).sum(axis=2))
        np.fill_diagonal(self.distance_matrix, 1e5)

    def copy_out(self):
        self.positions = np.zeros((self.n, self.dim))
        self.velocities = np.zeros((self.n, self.dim))
        self.masses = np.zeros(self.n)
        for i, m in enumerate(self.molecules):
            self.positions[i, :] = m.get_position()
            self.velocities[i, :] = m.get_velocity()
            self.masses[i] = m.get_mass()
        self.velocities_norm = np.linalg.norm(self.velocities, axis=1)

    def make_matrices(self):
        self.copy_out()
        self.distance_matrix = np.zeros((self.n, self.n))
        for i in range(self.n):
            for j in range(self.n):
                self.distance_matrix[i, j] = np.linalg.norm(self.positions[i, :] - self.positions[j, :])
        np.fill_diagonal(self.distance_matrix, 1e5)

    def collide_pairs(self):
        found = np.argwhere(self.distance_matrix < 2 * self.radius)
        kept = []
        for pair in found:
            if not any(set(p) == set(pair) for p in kept):
                kept.append(pair)
        for a, b in kept:
            m1, m2 = self.molecules[a], self.molecules[b]
            x1, x2 = m1.get_position(), m2.get_position()
            u1, u2 = m1.get_velocity(), m2.get_velocity()
            if np.sign(np.dot(u1 - u2, x2 - x1)) == 1:
                k1, k2 = m1.get_mass(), m2.get_mass()
                d2 = np.linalg.norm(x1 - x2) ** 2
                v1 = u1 - 2 * k2 / (k1 + k2) * np.dot(u1 - u2, x1 - x2) / d2 * (x1 - x2)
                v2 = u2 - 2 * k1 / (k1 + k2) * np.dot(u2 - u1, x2 - x1) / d2 * (x2 - x1)
                m1.set_velocity(v1)
                m2.set_velocity(v2)
        return len(kept)

    def move_and_reflect(self):
        upper = np.array(self.box)
        for m in self.molecules:
            x, v, mass = m.get_position(), m.get_velocity(), m.get_mass()
            new = x + v * self.dt
            over = new - upper
            if over[over >= 0].shape[0] > 0:
                self.wall_collisions += 1
                for c in np.argwhere(over > 0):
                    v[c] = -v[c]
                    self.wall_momentum += 2 * mass * np.abs(v[c])
                m.set_velocity(v)
                new = x + v * self.dt
            if new[new <= 0].shape[0] > 0:
                self.wall_collisions += 1
                for c in np.argwhere(new < 0):
                    v[c] = -v[c]
                    self.wall_momentum += 2 * mass * np.abs(v[c])
                m.set_velocity(v)
                new = x + v * self.dt
            m.set_position(new)

    def update(self):
        pairs = self.collide_pairs()
        self.move_and_reflect()
        self.make_matrices()
        return pairs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=10000)
    ap.add_argument("--steps", type=int, default=1)
    ap.add_argument("--eta", type=float, default=0.05, help="packing fraction (as pedesis bench)")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    radius = 0.5
    dim = 2
    L = math.sqrt(args.n * math.pi * radius * radius / args.eta)
    rng = np.random.default_rng(args.seed)
    gas = NotebookGas(args.n, [L, L], 0.02, radius, rng)
    per_step = []
    for k in range(args.steps):
        t0 = time.process_time()
        pairs = gas.update()
        per_step.append(time.process_time() - t0)
        v_rms = np.sum(gas.velocities_norm) / gas.n  # the notebook's printed "V_RMS"
        print(f"step {k + 1}: {per_step[-1]:.3f} cpu s, {pairs} pairs, V_RMS {v_rms:.4f}", flush=True)
    mean = sum(per_step) / len(per_step)
    print(f"notebook: dim {dim} N {args.n} box {L:.3f} steps {args.steps}")
    print(f"seconds_per_step: {mean:.4g}")
    print(f"particle_steps_per_second: {args.n / mean:.4g}")


if __name__ == "__main__":
    main()
