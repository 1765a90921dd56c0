// What a run's config places in the box besides particles, drawn over them (docs/view.md):
// the box's walls (thick in 2D, translucent faces in 3D), containers (a sphere or a
// cylinder wall), harmonic traps and the direction of gravity. `info.scenery` holds only
// numbers (and the shape as the server's own word), checked by the server
// (src/pedesis/view/run_data.cpp); anything else is skipped here too.
import * as THREE from 'three';

const INK = 0x1a1a1a;
const finite = (x) => typeof x === 'number' && Number.isFinite(x);
const point = (p) => Array.isArray(p) && p.length === 3 && p.every(finite);

// Drawn over the particles whatever their depth: a marker must not hide behind them.
function onTop(object, order = 10) {
  object.renderOrder = order;
  object.traverse((o) => {
    if (o.material) Object.assign(o.material, { depthTest: false, depthWrite: false });
  });
  return object;
}

// A filled rectangle of the xy plane, from (x0, y0) to (x1, y1).
function rectangle(x0, y0, x1, y1, material) {
  const mesh = new THREE.Mesh(new THREE.PlaneGeometry(Math.abs(x1 - x0), Math.abs(y1 - y0)), material);
  mesh.position.set((x0 + x1) / 2, (y0 + y1) / 2, 0);
  return mesh;
}

// A circle of the plane through `centre` across `axis` (0, 1, 2), as a line loop.
function circle(centre, radius, axis, material) {
  const pts = [];
  for (let k = 0; k < 128; ++k) {
    const a = (2 * Math.PI * k) / 128, u = radius * Math.cos(a), v = radius * Math.sin(a);
    const p = [...centre];
    p[(axis + 1) % 3] += u;
    p[(axis + 2) % 3] += v;
    pts.push(new THREE.Vector3(...p));
  }
  return new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(pts), material);
}

function walls2d(info, t, group) {
  const [lo, L, periodic] = [info.box_lo, info.box_length, info.periodic];
  const ink = new THREE.MeshBasicMaterial({ color: INK });
  const hi = [lo[0] + L[0], lo[1] + L[1]];
  // just outside the box, so they hide no particle touching them; corners closed
  const ex = periodic[1] ? 0 : t, ey = periodic[0] ? 0 : t;
  if (!periodic[0]) {
    group.add(rectangle(lo[0] - t, lo[1] - ex, lo[0], hi[1] + ex, ink));
    group.add(rectangle(hi[0], lo[1] - ex, hi[0] + t, hi[1] + ex, ink));
  }
  if (!periodic[1]) {
    group.add(rectangle(lo[0] - ey, lo[1] - t, hi[0] + ey, lo[1], ink));
    group.add(rectangle(lo[0] - ey, hi[1], hi[0] + ey, hi[1] + t, ink));
  }
}

function walls3d(info, group) {
  const [lo, L, periodic] = [info.box_lo, info.box_length, info.periodic];
  const material = new THREE.MeshBasicMaterial({ color: 0x555555, transparent: true, opacity: 0.12,
    side: THREE.DoubleSide, depthWrite: false });
  for (let a = 0; a < 3; ++a) {
    if (periodic[a]) continue;
    const [u, v] = [(a + 1) % 3, (a + 2) % 3];
    for (const side of [0, 1]) {
      const face = new THREE.Mesh(new THREE.PlaneGeometry(L[u], L[v]), material);
      // PlaneGeometry lies in xy: turn its normal (z) onto axis a
      if (a === 0) face.rotation.set(0, Math.PI / 2, Math.PI / 2);
      if (a === 1) face.rotation.set(-Math.PI / 2, 0, -Math.PI / 2);
      const at = [lo[0] + L[0] / 2, lo[1] + L[1] / 2, lo[2] + L[2] / 2];
      at[a] = lo[a] + side * L[a];
      face.position.set(...at);
      group.add(face);
    }
  }
}

function container(info, c, t, group) {
  if (!c || !finite(c.radius) || !(c.radius > 0) || !point(c.centre) || ![0, 1, 2].includes(c.axis)) return false;
  const { box_lo: lo, box_length: L } = info;
  if (info.dimension === 2) {
    const ring = new THREE.Mesh(new THREE.RingGeometry(c.radius, c.radius + t, 128),
      new THREE.MeshBasicMaterial({ color: INK }));
    ring.position.set(c.centre[0], c.centre[1], 0);
    group.add(onTop(ring));
    return true;
  }
  const line = new THREE.LineBasicMaterial({ color: INK });
  if (c.shape === 'sphere') {
    for (let a = 0; a < 3; ++a) group.add(circle(c.centre, c.radius, a, line));
    const shell = new THREE.Mesh(new THREE.SphereGeometry(c.radius, 48, 24), new THREE.MeshBasicMaterial(
      { color: 0x555555, transparent: true, opacity: 0.08, depthWrite: false }));
    shell.position.set(...c.centre);
    group.add(shell);
    return true;
  }
  // a cylinder: circles at both ends of the box along its axis and half way, and four
  // lines along it
  const a = c.axis, ends = [lo[a], lo[a] + L[a] / 2, lo[a] + L[a]];
  for (const x of ends) {
    const at = [...c.centre];
    at[a] = x;
    group.add(circle(at, c.radius, a, line));
  }
  for (let k = 0; k < 4; ++k) {
    const p = [...c.centre];
    p[(a + 1) % 3] += c.radius * Math.cos((k * Math.PI) / 2);
    p[(a + 2) % 3] += c.radius * Math.sin((k * Math.PI) / 2);
    const q = [...p];
    p[a] = lo[a];
    q[a] = lo[a] + L[a];
    group.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(...p),
      new THREE.Vector3(...q)]), line));
  }
  return true;
}

// A trap: in 2D a ring with a cross through it; in 3D a dot with a cross along each axis.
function trap(info, centre, size, t, group) {
  if (!point(centre)) return false;
  const ink = new THREE.MeshBasicMaterial({ color: INK });
  const marker = new THREE.Group();
  if (info.dimension === 2) {
    marker.add(new THREE.Mesh(new THREE.RingGeometry(0.5 * size, 0.5 * size + t / 2, 48), ink));
    marker.add(rectangle(-size, -t / 4, size, t / 4, ink));
    marker.add(rectangle(-t / 4, -size, t / 4, size, ink));
  } else {
    marker.add(new THREE.Mesh(new THREE.SphereGeometry(0.3 * size, 16, 8), ink));
    const arms = [];
    for (let a = 0; a < 3; ++a) {
      const p = [0, 0, 0], q = [0, 0, 0];
      p[a] = -size;
      q[a] = size;
      arms.push(new THREE.Vector3(...p), new THREE.Vector3(...q));
    }
    marker.add(new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(arms),
      new THREE.LineBasicMaterial({ color: INK })));
  }
  marker.position.set(...centre);
  group.add(onTop(marker, 11));
  return true;
}

// Gravity: an arrow inside the box near its top right (2D) or top corner (3D), along the
// pull.
function pull(info, direction, index, size, t, group) {
  if (!point(direction)) return false;
  const { box_lo: lo, box_length: L } = info;
  const dir = new THREE.Vector3(...direction);
  if (!(dir.length() > 0)) return false;
  dir.normalize();
  const length = 3 * size;
  if (info.dimension === 2) {
    // centred 2.5 sizes in from the top right corner; more arrows to its left
    const cx = lo[0] + L[0] - 2.5 * size - index * 3.5 * size, cy = lo[1] + L[1] - 2.5 * size;
    const head = 0.4 * length, half = length / 2;
    const shape = new THREE.Shape();
    const u = dir, v = new THREE.Vector3(-dir.y, dir.x, 0); // along and across
    const at = (s, w) => [cx + s * u.x + w * v.x, cy + s * u.y + w * v.y];
    shape.moveTo(...at(-half, -t / 3));
    shape.lineTo(...at(half - head, -t / 3));
    shape.lineTo(...at(half - head, -head / 2));
    shape.lineTo(...at(half, 0));
    shape.lineTo(...at(half - head, head / 2));
    shape.lineTo(...at(half - head, t / 3));
    shape.lineTo(...at(-half, t / 3));
    shape.closePath();
    group.add(onTop(new THREE.Mesh(new THREE.ShapeGeometry(shape), new THREE.MeshBasicMaterial({ color: INK })), 12));
    return true;
  }
  // near the box's top corner; along its axis the arrow starts by the face it points away
  // from, and runs a quarter of the box
  const start = new THREE.Vector3(lo[0] + L[0] - 2 * size - index * 3 * size, lo[1] + L[1] - 2 * size,
    lo[2] + L[2] - 2 * size);
  for (let a = 0; a < 3; ++a)
    if (direction[a] !== 0) start.setComponent(a, direction[a] < 0 ? lo[a] + L[a] - size : lo[a] + size);
  const total = 0.25 * Math.max(L[0], L[1], L[2]);
  group.add(onTop(new THREE.ArrowHelper(dir, start, total, INK, 0.3 * total, 0.15 * total), 12));
  return true;
}

// Everything above as one group; its userData counts what it draws (walls: walled axes),
// for the tests.
export function sceneryGroup(info) {
  const group = new THREE.Group();
  group.name = 'scenery';
  const L = info.box_length;
  const extent = info.dimension === 2 ? Math.max(L[0], L[1]) : Math.max(L[0], L[1], L[2]);
  const t = 0.008 * extent; // a wall's thickness in 2D
  const size = (info.dimension === 2 ? 0.02 : 0.03) * extent; // a marker's
  const s = info.scenery || {};
  const list = (x) => (Array.isArray(x) ? x.slice(0, 16) : []);
  if (info.dimension === 2) walls2d(info, t, group); else walls3d(info, group);
  group.userData = {
    walls: info.periodic.slice(0, info.dimension).filter((p) => !p).length,
    containers: list(s.containers).filter((c) => container(info, c, t, group)).length,
    traps: list(s.traps).filter((c) => trap(info, c, size, t, group)).length,
    gravity: list(s.gravity).filter((d, k) => pull(info, d, k, size, t, group)).length,
  };
  if (info.dimension === 2) group.position.z = 0.02;
  return group;
}
