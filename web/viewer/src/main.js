// The page of `pedesis view` (docs/view.md): a run's particles drawn with three.js
// (one point sprite per particle, a disk or a shaded sphere at its true radius: one
// vertex a particle, so that 10^6 draw in software WebGL), a time slider
// and playback over the frames, colour by species or any number per particle (speed,
// polarity angle, energy, a column of the file's own) with a colour bar, director
// arrows, and the run's log plotted with uPlot beside it, with a cursor at the frame's
// time. Walls, containers, traps and gravity are drawn from the run's config
// (scenery.js). Frames come from the server as binary typed arrays (src/pedesis/view),
// and only a window of frames around the cursor is kept.
//
// Every string from the run or the server (species and column names, the run's name,
// messages) reaches the document as text only (textContent, new Option), never as markup,
// and styles are set through element.style: the page runs under a Content-Security-Policy
// without 'unsafe-inline' (page_security_policy in src/pedesis/view/page_files.cpp).
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import uPlot from 'uplot';
import { sceneryGroup } from './scenery.js';
import 'uplot/dist/uPlot.min.css';
import './viewer.css';

const $ = (id) => document.getElementById(id);
const KEEP = 6; // frames kept on each side of the cursor
const AHEAD = 3; // frames fetched ahead while playing
const PALETTE = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2',
  '#7f7f7f', '#bcbd22', '#17becf'];
// How the colour menu and bar name the numbers the server derives (others: their names).
const LABELS = { speed: 'speed |v|', angle: 'polarity angle', kinetic_energy: 'kinetic energy m v²/2',
  vx: 'velocity x', vy: 'velocity y', vz: 'velocity z' };
// A new element with the given class and children (strings become text nodes, never markup).
function element(tag, className, ...children) {
  const e = document.createElement(tag);
  if (className) e.className = className;
  e.append(...children);
  return e;
}
// viridis at 0, 1/4, 1/2, 3/4, 1
const VIRIDIS = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];

// An exported page (pedesis view --export) carries the run inside: the same answers as
// the server's, from a JSON data block (<script type="application/json">, never run as a
// script) instead of HTTP.
const EXPORTED = (() => {
  const data = document.getElementById('pedesis-export');
  return data ? JSON.parse(data.textContent) : null;
})();

function fromBase64(text, Type) {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return new Type(bytes.buffer);
}

function exported(path, Type) {
  if (path === 'api/info') return EXPORTED.info;
  if (path === 'api/log') return EXPORTED.log;
  const m = path.match(/^api\/frame\/(\d+)\/([^/]+)$/);
  const f = m ? EXPORTED.frames[Number(m[1])] : null;
  const name = m ? decodeURIComponent(m[2]) : '';
  if (!f || !f[name]) throw new Error(`${path}: not in this exported page`);
  return { data: fromBase64(f[name], Type), time: f.time === null ? '' : String(f.time),
    step: f.step === null ? '' : String(f.step) };
}

async function fetchJson(path) {
  if (EXPORTED) return exported(path);
  const r = await fetch(path);
  const body = await r.json();
  if (!r.ok) throw new Error(body.error || r.statusText);
  return body;
}

async function fetchArray(path, Type) {
  if (EXPORTED) return exported(path, Type);
  const r = await fetch(path);
  if (!r.ok) {
    const body = await r.json().catch(() => ({}));
    throw new Error(body.error || `${path}: ${r.status}`);
  }
  return { data: new Type(await r.arrayBuffer()), time: r.headers.get('X-Pedesis-Time'),
    step: r.headers.get('X-Pedesis-Step') };
}

function viridis(t, out) {
  const x = Math.min(Math.max(t, 0), 1) * (VIRIDIS.length - 1);
  const k = Math.min(Math.floor(x), VIRIDIS.length - 2);
  const f = x - k;
  const c = VIRIDIS[k].map((v, a) => (v + f * (VIRIDIS[k + 1][a] - v)) / 255);
  return out.setRGB(c[0], c[1], c[2], THREE.SRGBColorSpace);
}

// angle in (-pi, pi] round the colour wheel, so that opposite directors differ most
function wheel(angle, out) {
  return out.setHSL((angle / (2 * Math.PI) + 1) % 1, 0.85, 0.5, THREE.SRGBColorSpace);
}

// Whether to draw 2D disks on the CPU: where WebGL is software (SwiftShader, llvmpipe: no
// GPU), unless the address says ?draw=gl (or ?draw=cpu to force it).
function drawsOnCpu(renderer) {
  const asked = new URLSearchParams(window.location.search).get('draw');
  if (asked === 'cpu' || asked === 'gl') return asked === 'cpu';
  const gl = renderer.getContext();
  const debug = gl.getExtension('WEBGL_debug_renderer_info');
  const name = debug ? String(gl.getParameter(debug.UNMASKED_RENDERER_WEBGL)) : '';
  return /swiftshader|llvmpipe|softpipe|software/i.test(name);
}

class Viewer {
  constructor(info) {
    this.info = info;
    this.dim = info.dimension;
    this.frames = info.frames;
    this.cache = new Map();
    this.index = 0;
    this.mode = 'species';
    this.arrows = false;
    this.playing = false;
    this.follow = false; // show each new frame as it comes (a run still going)
    this.wanted = 0; // the last frame asked for: a slower answer for another is dropped

    const view = $('view');
    this.renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true, alpha: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.renderer.domElement.style.position = 'relative'; // over the disks' canvas
    view.prepend(this.renderer.domElement);
    this.scene = new THREE.Scene();
    // In 2D without a GPU the page draws the disks itself, on a canvas under WebGL's,
    // which then draws only the box, the scenery and the director lines on a transparent
    // ground.
    this.cpuDisks = this.dim === 2 && drawsOnCpu(this.renderer);
    this.renderer.setClearColor(0xffffff, this.cpuDisks ? 0 : 1);
    if (this.cpuDisks) {
      this.disksCanvas = document.createElement('canvas');
      Object.assign(this.disksCanvas.style, { position: 'absolute', left: '0', top: '0', width: '100%',
        height: '100%' });
      view.prepend(this.disksCanvas);
      this.disksImage = null;
    }

    const L = info.box_length;
    const lo = info.box_lo;
    this.centre = new THREE.Vector3(lo[0] + L[0] / 2, lo[1] + L[1] / 2, lo[2] + L[2] / 2);
    if (this.dim === 2) {
      this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, -100, 100);
      this.camera.position.set(this.centre.x, this.centre.y, 10);
    } else {
      const size = Math.max(L[0], L[1], L[2]);
      this.camera = new THREE.PerspectiveCamera(40, 1, size / 100, size * 20);
      // (placed by fitCamera, once the view's shape is known)
    }
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.copy(this.centre);
    // until the user moves the camera, a 3D view keeps the whole box in sight as it resizes
    this.cameraMoved = false;
    this.controls.addEventListener('start', () => { this.cameraMoved = true; });
    if (this.dim === 2) {
      this.controls.enableRotate = false;
      this.controls.screenSpacePanning = true;
      this.controls.mouseButtons = { LEFT: THREE.MOUSE.PAN, MIDDLE: THREE.MOUSE.DOLLY,
        RIGHT: THREE.MOUSE.PAN };
      this.controls.zoomToCursor = true;
    }
    this.controls.addEventListener('change', () => this.requestRender());
    this.scene.add(this.boxOutline(lo, L));
    // walls, containers, traps and gravity (scenery.js), over the particles
    this.scenery = sceneryGroup(info);
    this.scene.add(this.scenery);

    this.capacity = 0;
    this.mesh = null;
    this.arrowLines = null;
    new ResizeObserver(() => this.resize()).observe(view);
    this.resize();
  }

  boxOutline(lo, L) {
    const material = new THREE.LineBasicMaterial({ color: 0x444444 });
    if (this.dim === 2) {
      const z = 0;
      const pts = [[lo[0], lo[1]], [lo[0] + L[0], lo[1]], [lo[0] + L[0], lo[1] + L[1]],
        [lo[0], lo[1] + L[1]]].map(([x, y]) => new THREE.Vector3(x, y, z));
      return new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(pts), material);
    }
    const box = new THREE.LineSegments(
      new THREE.EdgesGeometry(new THREE.BoxGeometry(L[0], L[1], L[2])), material);
    box.position.copy(this.centre);
    return box;
  }

  // One point per particle, drawn as a disk (2D) or a shaded sphere (3D) of its radius in
  // world units; the buffers grow when a frame holds more particles. Colours are sRGB
  // values written as they are (the shader does no colour-space conversion).
  ensureCapacity(n) {
    if (n <= this.capacity) return;
    if (this.mesh) this.scene.remove(this.mesh);
    const geometry = new THREE.BufferGeometry();
    for (const [name, size] of [['position', 3], ['radius', 1], ['tint', 3]]) {
      const attribute = new THREE.BufferAttribute(new Float32Array(size * n), size);
      attribute.setUsage(THREE.DynamicDrawUsage);
      geometry.setAttribute(name, attribute);
    }
    const material = new THREE.ShaderMaterial({
      uniforms: { pixelsPerUnit: { value: 1 }, perspective: { value: this.dim === 3 },
        shaded: { value: this.dim === 3 } },
      vertexShader: `
        attribute float radius;
        attribute vec3 tint;
        uniform float pixelsPerUnit;
        uniform bool perspective;
        varying vec3 vTint;
        void main() {
          vec4 mv = modelViewMatrix * vec4(position, 1.0);
          gl_Position = projectionMatrix * mv;
          gl_PointSize = max(2.0 * radius * (perspective ? pixelsPerUnit / -mv.z : pixelsPerUnit), 1.0);
          vTint = tint;
        }`,
      fragmentShader: `
        uniform bool shaded;
        varying vec3 vTint;
        void main() {
          vec2 p = 2.0 * gl_PointCoord - 1.0;
          float r2 = dot(p, p);
          if (r2 > 1.0) discard;
          vec3 c = vTint;
          if (shaded) {
            vec3 normal = vec3(p.x, -p.y, sqrt(1.0 - r2));
            c *= 0.35 + 0.65 * max(dot(normal, normalize(vec3(0.4, 0.6, 1.0))), 0.0);
          }
          gl_FragColor = vec4(c, 1.0);
        }`,
    });
    this.mesh = new THREE.Points(geometry, material);
    this.mesh.frustumCulled = false;
    this.scene.add(this.mesh);
    this.capacity = n;
  }

  // Point sizes follow the zoom: pixels per world unit at the target's distance.
  updatePointScale() {
    if (!this.mesh) return;
    const height = this.renderer.getDrawingBufferSize(new THREE.Vector2()).y;
    this.mesh.material.uniforms.pixelsPerUnit.value = this.dim === 2
      ? (height * this.camera.zoom) / (this.camera.top - this.camera.bottom)
      : (this.camera.projectionMatrix.elements[5] * height) / 2;
  }

  resize() {
    const view = $('view');
    const w = view.clientWidth || 1, h = view.clientHeight || 1;
    this.renderer.setSize(w, h, false);
    const aspect = w / h;
    if (this.dim === 2) {
      const L = this.info.box_length;
      const half = 0.55 * Math.max(L[1], L[0] / aspect);
      Object.assign(this.camera, { left: -half * aspect, right: half * aspect, top: half,
        bottom: -half });
    } else {
      this.camera.aspect = aspect;
      if (!this.cameraMoved) this.fitCamera();
    }
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  // The 3D camera looks at the box's centre from a corner's side, far enough that the
  // sphere round the box (and so all of its edges) fits both the height and the width of
  // the view, with a margin of 5 %.
  fitCamera() {
    const L = this.info.box_length;
    const radius = 0.5 * Math.hypot(L[0], L[1], L[2]);
    const vertical = THREE.MathUtils.degToRad(this.camera.fov);
    const horizontal = 2 * Math.atan(Math.tan(vertical / 2) * this.camera.aspect);
    const distance = (1.05 * radius) / Math.sin(Math.min(vertical, horizontal) / 2);
    this.camera.position.copy(this.centre)
      .addScaledVector(new THREE.Vector3(1.2, 0.9, 1.6).normalize(), distance);
    this.camera.far = Math.max(this.camera.far, distance + 4 * radius);
    this.controls.target.copy(this.centre);
    this.controls.update();
  }

  requestRender() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => { this.pending = false; this.render(); });
  }

  render() {
    this.controls.update();
    this.updatePointScale();
    if (this.cpuDisks && this.mesh) this.drawDisksOnCpu();
    this.renderer.render(this.scene, this.camera);
  }

  // The disks drawn on the CPU into the canvas under WebGL's: what the sprites would draw
  // (each pixel whose centre lies within a disk takes its colour, the later particle on
  // top, at least the pixel of the centre), from the same buffers. Software WebGL spends
  // about a microsecond on each sprite; this loop a small fraction of that (docs/view.md,
  // Speed).
  drawDisksOnCpu() {
    const size = this.renderer.getDrawingBufferSize(new THREE.Vector2());
    const W = size.x, H = size.y;
    const canvas = this.disksCanvas;
    if (canvas.width !== W || canvas.height !== H || !this.disksImage) {
      canvas.width = W;
      canvas.height = H;
      this.disksImage = canvas.getContext('2d').createImageData(W, H);
    }
    this.mesh.visible = false;
    const pixels = new Uint32Array(this.disksImage.data.buffer);
    pixels.fill(0xffffffff); // white
    const cam = this.camera;
    const x0 = cam.position.x + cam.left / cam.zoom, y0 = cam.position.y + cam.bottom / cam.zoom;
    const scale = (W * cam.zoom) / (cam.right - cam.left); // pixels per unit (square pixels)
    const g = this.mesh.geometry;
    const pos = g.attributes.position.array, rad = g.attributes.radius.array, tint = g.attributes.tint.array;
    const n = Math.min(g.drawRange.count, this.capacity);
    for (let i = 0; i < n; ++i) {
      // y counts pixels up from the bottom of the view; the image's rows go down
      const cx = (pos[3 * i] - x0) * scale, cy = (pos[3 * i + 1] - y0) * scale;
      const r = Math.max(rad[i] * scale, 0.5);
      if (cx + r < 0 || cx - r > W || cy + r < 0 || cy - r > H) continue;
      const colour = (0xff000000 | (Math.round(255 * tint[3 * i + 2]) << 16) |
        (Math.round(255 * tint[3 * i + 1]) << 8) | Math.round(255 * tint[3 * i])) >>> 0;
      const xa = Math.max(0, Math.ceil(cx - r - 0.5)), xb = Math.min(W - 1, Math.floor(cx + r - 0.5));
      const ya = Math.max(0, Math.ceil(cy - r - 0.5)), yb = Math.min(H - 1, Math.floor(cy + r - 0.5));
      const r2 = r * r;
      for (let y = ya; y <= yb; ++y) {
        const dy = y + 0.5 - cy, row = (H - 1 - y) * W;
        for (let x = xa; x <= xb; ++x) {
          const dx = x + 0.5 - cx;
          if (dx * dx + dy * dy <= r2) pixels[row + x] = colour;
        }
      }
      const px = Math.floor(cx), py = Math.floor(cy);
      if (px >= 0 && px < W && py >= 0 && py < H) pixels[(H - 1 - py) * W + px] = colour;
    }
    canvas.getContext('2d').putImageData(this.disksImage, 0, 0);
  }

  // The view as one canvas (the screenshot): WebGL's, over the disks' where the CPU draws
  // them.
  picture() {
    this.render();
    const gl = this.renderer.domElement;
    if (!this.cpuDisks) return gl;
    const out = document.createElement('canvas');
    out.width = gl.width;
    out.height = gl.height;
    const ctx = out.getContext('2d');
    ctx.drawImage(this.disksCanvas, 0, 0);
    ctx.drawImage(gl, 0, 0);
    return out;
  }

  needsField() {
    return this.mode === 'species' ? null : this.mode;
  }

  async load(k) {
    let f = this.cache.get(k);
    if (!f) {
      const base = `api/frame/${k}/`;
      const [pos, species, radius] = await Promise.all([
        fetchArray(base + 'position', Float32Array), fetchArray(base + 'species', Uint32Array),
        fetchArray(base + 'radius', Float32Array)]);
      f = { pos: pos.data, species: species.data, radius: radius.data, fields: {},
        time: pos.time === null || pos.time === '' ? null : Number(pos.time),
        step: pos.step === null || pos.step === '' ? null : Number(pos.step) };
      this.cache.set(k, f);
    }
    const wanted = [this.needsField(), this.arrows ? 'director' : null].filter((x) => x);
    for (const name of wanted)
      if (!f.fields[name]) {
        f.fields[name] = (await fetchArray(`api/frame/${k}/${encodeURIComponent(name)}`, Float32Array)).data;
      }
    return f;
  }

  forgetFarFrames() {
    for (const k of this.cache.keys())
      if (Math.abs(k - this.index) > KEEP) this.cache.delete(k);
  }

  async show(k) {
    this.wanted = k;
    const f = await this.load(k);
    if (this.wanted !== k) return; // another frame was asked for meanwhile
    this.index = k;
    this.draw(f);
    this.forgetFarFrames();
    $('slider').value = String(k);
    const t = f.time !== null ? `t = ${f.time.toPrecision(6)}` : '';
    const s = f.step !== null ? `step ${f.step}` : '';
    $('clock').textContent = `frame ${k} / ${this.frames - 1}  ${t}  ${s}`;
    if (this.onFrame) this.onFrame(f);
  }

  draw(f) {
    const n = f.species.length;
    this.ensureCapacity(n);
    const c = new THREE.Color(), rgb = {};
    const field = this.needsField() ? f.fields[this.needsField()] : null;
    // the colour bar spans this frame's finite values; speed and energy from 0 (to 1 where
    // every one is 0), another field a width of 1 round its value where all are equal
    let lo = 0, hi = 1;
    if (field && this.mode !== 'angle') {
      const fromZero = this.mode === 'speed' || this.mode === 'kinetic_energy';
      lo = fromZero ? 0 : Infinity;
      hi = -Infinity;
      for (let i = 0; i < n; ++i)
        if (Number.isFinite(field[i])) { lo = Math.min(lo, field[i]); hi = Math.max(hi, field[i]); }
      if (!(hi > lo)) {
        if (fromZero || !Number.isFinite(lo)) { lo = 0; hi = 1; } else { lo -= 0.5; hi = lo + 1; }
      }
    }
    const g = this.mesh.geometry;
    g.attributes.position.array.set(f.pos.subarray(0, 3 * n));
    g.attributes.radius.array.set(f.radius.subarray(0, n));
    const tint = g.attributes.tint.array;
    for (let i = 0; i < n; ++i) {
      if (this.mode === 'angle') wheel(field[i], c);
      else if (field) viridis((field[i] - lo) / (hi - lo), c);
      else c.setStyle(PALETTE[f.species[i] % PALETTE.length], THREE.SRGBColorSpace);
      c.getRGB(rgb, THREE.SRGBColorSpace);
      tint[3 * i] = rgb.r;
      tint[3 * i + 1] = rgb.g;
      tint[3 * i + 2] = rgb.b;
    }
    g.setDrawRange(0, n);
    for (const name of ['position', 'radius', 'tint']) g.attributes[name].needsUpdate = true;
    this.drawArrows(f, n);
    this.colourBar(lo, hi);
    this.requestRender();
  }

  // A line from each centre along its director, one radius and a half long.
  drawArrows(f, n) {
    if (this.arrowLines) { this.scene.remove(this.arrowLines); this.arrowLines = null; }
    const d = f.fields.director;
    if (!this.arrows || !d) return;
    const xyz = new Float32Array(6 * n);
    for (let i = 0; i < n; ++i)
      for (let a = 0; a < 3; ++a) {
        xyz[6 * i + a] = f.pos[3 * i + a];
        xyz[6 * i + 3 + a] = f.pos[3 * i + a] + 1.5 * f.radius[i] * d[3 * i + a];
      }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
    this.arrowLines = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: 0x000000 }));
    this.arrowLines.position.z = this.dim === 2 ? 0.01 : 0;
    this.scene.add(this.arrowLines);
  }

  // The strip under the view: the species legend, or the colour bar with its two ends.
  colourBar(lo, hi) {
    const strip = $('colourbar');
    if (this.mode === 'species') {
      strip.replaceChildren(...this.info.species.map((s, k) => {
        const swatch = element('span', 'swatch', '●');
        swatch.style.color = PALETTE[k % PALETTE.length];
        return element('span', 'species', swatch, element('span', 'name', String(s.name)));
      }));
      return;
    }
    const stops = [];
    const c = new THREE.Color();
    for (let k = 0; k <= 10; ++k) {
      if (this.mode !== 'angle') viridis(k / 10, c); else wheel(-Math.PI + (2 * Math.PI * k) / 10, c);
      stops.push(`#${c.getHexString(THREE.SRGBColorSpace)}`);
    }
    const [a, b] = this.mode !== 'angle' ? [lo.toPrecision(3), hi.toPrecision(3)] : ['−π', 'π'];
    const bar = element('span', 'bar');
    bar.style.background = `linear-gradient(to right, ${stops.join(', ')})`;
    strip.replaceChildren(element('span', 'label', String(LABELS[this.mode] || this.mode)),
      element('span', 'lo', a), bar, element('span', 'hi', b));
  }

  async setColour(mode) {
    this.mode = mode;
    await this.show(this.index);
  }

  async setArrows(on) {
    this.arrows = on;
    await this.show(this.index);
  }

  // Following: each new frame of a run still going is shown as the page learns of it.
  setFollow(on) {
    this.follow = on;
    $('follow').checked = on;
    if (on && this.playing) this.play();
    if (on) return this.show(this.frames - 1);
    return Promise.resolve();
  }

  async play() {
    if (this.follow && !this.playing) this.setFollow(false);
    this.playing = !this.playing;
    $('play').textContent = this.playing ? '❚❚' : '▶';
    while (this.playing) {
      const started = performance.now();
      const next = (this.index + 1) % this.frames;
      await this.show(next);
      for (let k = 1; k <= AHEAD; ++k)
        if (next + k < this.frames) this.load(next + k).catch(() => {});
      const wait = 1000 / Number($('fps').value) - (performance.now() - started);
      await new Promise((done) => setTimeout(done, Math.max(0, wait)));
    }
  }

  // The CSS-pixel position of particle i's centre in the page (for tests).
  project(i) {
    return this.projectPoint(new THREE.Vector3().fromBufferAttribute(this.mesh.geometry.attributes.position, i));
  }

  projectPoint(point) {
    const p = point.clone().project(this.camera);
    const rect = this.renderer.domElement.getBoundingClientRect();
    return { x: rect.left + ((p.x + 1) / 2) * rect.width, y: rect.top + ((1 - p.y) / 2) * rect.height };
  }
}

// The log beside the view: one column against time (or step), with the frame's instant.
class LogPlot {
  constructor(viewer) {
    this.viewer = viewer;
    this.plot = null;
    this.log = null;
    $('column').addEventListener('change', () => this.draw());
  }

  async refresh() {
    this.log = await fetchJson('api/log');
    const select = $('column');
    const x = this.xColumn();
    const others = this.log.columns.filter((c) => c !== x && c !== 'step');
    if (select.options.length !== others.length) {
      const keep = select.value;
      select.replaceChildren(...others.map((c) => new Option(String(c), String(c))));
      const preferred = ['temperature', 'pressure', 'polar_order'].find((c) => others.includes(c));
      select.value = others.includes(keep) ? keep : (preferred || others[0] || '');
    }
    this.draw();
  }

  xColumn() {
    return this.log.columns.includes('time') ? 'time' : 'step';
  }

  draw() {
    if (!this.log || !this.log.columns.length) return;
    const xi = this.log.columns.indexOf(this.xColumn());
    const yi = this.log.columns.indexOf($('column').value);
    if (yi < 0) return;
    const data = [this.log.rows.map((r) => r[xi]), this.log.rows.map((r) => r[yi])];
    const el = $('plot');
    if (this.plot) this.plot.destroy();
    const cursor = (u) => {
      const f = this.viewer.cache.get(this.viewer.index);
      const at = f ? (this.xColumn() === 'time' ? f.time : f.step) : null;
      if (at === null || at === undefined) return;
      const x = u.valToPos(at, 'x', true);
      const ctx = u.ctx;
      ctx.save();
      ctx.strokeStyle = '#d62728';
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(x, u.bbox.top);
      ctx.lineTo(x, u.bbox.top + u.bbox.height);
      ctx.stroke();
      ctx.restore();
    };
    this.plot = new uPlot({ width: el.clientWidth || 400, height: 280,
      series: [{ label: this.xColumn() }, { label: $('column').value, stroke: '#1f77b4' }],
      scales: { x: { time: false } }, hooks: { draw: [cursor] } }, data, el);
  }
}

async function main() {
  let info = await fetchJson('api/info');
  // a run started with --view may not have written its first frame yet
  let waited = false;
  while (info.frames === 0) {
    waited = true;
    $('message').textContent = 'waiting for the run\'s first frame…';
    await new Promise((done) => setTimeout(done, 1000));
    info = await fetchJson('api/info');
  }
  $('message').textContent = '';
  document.title = `pedesis view: ${info.run}`;
  $('title').textContent = `${info.run} (${info.dimension}D, N = ${info.particles})`;
  const viewer = new Viewer(info);
  const plot = new LogPlot(viewer);
  viewer.onFrame = () => { if (plot.plot) plot.plot.redraw(false); };

  const colour = $('colour');
  colour.replaceChildren(...['species', ...(info.colour_by || [])]
    .map((m) => new Option(String(LABELS[m] || m), String(m))));
  colour.addEventListener('change', () => viewer.setColour(colour.value).catch(report));
  $('arrows-label').style.display = info.fields.includes('director') ? '' : 'none';
  $('arrows').addEventListener('change', (e) => viewer.setArrows(e.target.checked).catch(report));
  const slider = $('slider');
  slider.max = String(info.frames - 1);
  slider.addEventListener('input', () => {
    if (viewer.follow) viewer.setFollow(false);
    viewer.show(Number(slider.value)).catch(report);
  });
  // A run still going (pedesis run --view lists what it lets change; pedesis view reads its
  // .part file; or the page waited for its first frame) is followed from the start: the
  // page shows its newest frame and each new one, until the user scrubs, plays or unticks.
  const live = !EXPORTED && (Array.isArray(info.steerable) || waited || /\.part\b/.test(String(info.source || '')));
  $('follow-label').hidden = !!EXPORTED;
  $('follow').addEventListener('change', (e) => viewer.setFollow(e.target.checked).catch(report));
  viewer.follow = live;
  $('follow').checked = live;
  $('play').addEventListener('click', () => viewer.play().catch(report));
  document.addEventListener('keydown', (e) => {
    if (e.code === 'Space' && e.target === document.body) { e.preventDefault(); viewer.play().catch(report); }
  });
  $('shot').addEventListener('click', () => {
    viewer.picture().toBlob((blob) => {
      const a = document.createElement('a');
      a.href = URL.createObjectURL(blob);
      a.download = `${info.run}_frame${viewer.index}.png`;
      a.click();
    }, 'image/png');
  });

  if (info.steerable && info.steerable.length)
    steeringControls(info.steerable, new URLSearchParams(window.location.search).get('token'));
  await viewer.show(viewer.follow ? info.frames - 1 : 0);
  await plot.refresh();
  // a run still going writes more frames and rows: look again now and then
  if (!EXPORTED) setInterval(async () => {
    try {
      const now = await fetchJson('api/info');
      if (now.frames !== viewer.frames) {
        viewer.frames = now.frames;
        slider.max = String(now.frames - 1);
        if (viewer.follow) await viewer.show(now.frames - 1);
        await plot.refresh();
      }
    } catch (e) { /* the server has stopped: keep what is shown */ }
  }, 2000);

  // What the tests read back (tests/browser): the page's state, not its pixels alone.
  window.pedesisView = {
    info, frames: () => viewer.frames, frameIndex: () => viewer.index,
    instanceCount: () => viewer.mesh.geometry.drawRange.count,
    drawsOnCpu: () => viewer.cpuDisks,
    scenery: () => viewer.scenery.userData,
    // the screenshot's canvas, as a PNG data URL
    pictureUrl: () => viewer.picture().toDataURL('image/png'),
    setFrame: (k) => viewer.show(k), setColour: (m) => viewer.setColour(m),
    drawnPositions: () => {
      const a = viewer.mesh.geometry.attributes.position.array, out = [];
      for (let i = 0; i < viewer.mesh.geometry.drawRange.count; ++i) out.push([a[3 * i], a[3 * i + 1], a[3 * i + 2]]);
      return out;
    },
    instanceColour: (i) => {
      const t = viewer.mesh.geometry.attributes.tint.array;
      return new THREE.Color().setRGB(t[3 * i], t[3 * i + 1], t[3 * i + 2], THREE.SRGBColorSpace)
        .getHexString(THREE.SRGBColorSpace);
    },
    project: (i) => viewer.project(i),
    projectPoint: (x, y, z) => viewer.projectPoint(new THREE.Vector3(x, y, z)),
    following: () => viewer.follow,
    logPoints: () => (plot.plot ? plot.plot.data[0].length : 0),
    renderNow: () => viewer.render(),
    // For scripts/bench_viewer.mjs: milliseconds per drawn frame over `count` redraws with
    // the camera moving (each waits for its pixels), and per scrub to frame k (fetch,
    // decode, upload, draw).
    benchRender: (count) => {
      const gl = viewer.renderer.getContext(), px = new Uint8Array(4);
      const t0 = performance.now();
      for (let k = 0; k < count; ++k) {
        // a pan: the camera and its target move together
        viewer.camera.position.x += 1e-3 * viewer.info.box_length[0];
        viewer.controls.target.x += 1e-3 * viewer.info.box_length[0];
        viewer.render();
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
        // (a pixel read back makes the 2D canvas finish its drawing too)
        if (viewer.cpuDisks) viewer.disksCanvas.getContext('2d').getImageData(0, 0, 1, 1);
      }
      return (performance.now() - t0) / count;
    },
    benchShow: async (k) => {
      const gl = viewer.renderer.getContext(), px = new Uint8Array(4);
      const t0 = performance.now();
      await viewer.show(k);
      viewer.render();
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
      return performance.now() - t0;
    },
  };
  window.pedesisReady = true;
}

// Sliders for what the running simulation lets change (pedesis run --view): each change
// is sent with the address's token and applies from the run's next step.
function steeringControls(parameters, token) {
  const box = $('steer');
  box.replaceChildren(element('h3', '', 'change the run'));
  if (!token)
    box.append(element('p', '', 'read-only: open the address ', element('code', '', 'pedesis run --view'),
      ' printed (with its token) to change the run'));
  for (const { name: rawName, value, min, max } of parameters) {
    const name = String(rawName);
    // The slider spans a practical range: a restitution coefficient [0, 1], J [-top, top],
    // another parameter [0, top], top 4 times its start (at least 1), each cut to the
    // range the server allows (/api/info's min and max, where it gives them). The number
    // box beside it takes any value of the allowed range, and the slider widens to it.
    const allowedLo = Number.isFinite(min) ? min : -Infinity;
    const allowedHi = Number.isFinite(max) ? max : Infinity;
    const guess = name.endsWith('restitution') ? 1 : Math.max(4 * Math.abs(value), 1);
    const hi = Math.min(guess, allowedHi);
    const lo = Math.max(name === 'J' ? -guess : 0, allowedLo);
    const slider = document.createElement('input');
    Object.assign(slider, { type: 'range', id: `steer-${name}`, disabled: !token });
    const setRange = (a, b) => Object.assign(slider, { min: String(a), max: String(b), step: String((b - a) / 200) });
    setRange(lo, hi > lo ? hi : lo + 1);
    slider.value = String(value);
    const exact = document.createElement('input');
    Object.assign(exact, { type: 'number', className: 'exact', step: 'any', value: String(value), disabled: !token });
    if (Number.isFinite(allowedLo)) exact.min = String(allowedLo);
    if (Number.isFinite(allowedHi)) exact.max = String(allowedHi);
    box.append(element('label', '', `${name} `, slider, ' ', exact));
    const send = async (v) => {
      const r = await fetch('api/set', { method: 'POST', headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify({ token, parameter: name, value: v }) });
      const answer = await r.json().catch(() => ({}));
      $('steer-status').textContent = r.ok ? `${name} = ${v} from the next step`
        : `refused: ${answer.error || r.status}`;
    };
    slider.addEventListener('input', () => { exact.value = slider.value; });
    slider.addEventListener('change', () => {
      exact.value = slider.value;
      send(Number(slider.value)).catch(report);
    });
    exact.addEventListener('change', () => {
      const v = Number(exact.value);
      if (exact.value === '' || !Number.isFinite(v) || !exact.checkValidity()) {
        $('steer-status').textContent = `${name}: a number${Number.isFinite(allowedLo) ? ` from ${allowedLo}` : ''}` +
          `${Number.isFinite(allowedHi) ? ` to ${allowedHi}` : ''}`;
        return;
      }
      if (v < Number(slider.min) || v > Number(slider.max))
        setRange(Math.min(v, Number(slider.min)), Math.max(v, Number(slider.max)));
      slider.value = String(v);
      send(v).catch(report);
    });
  }
  const status = document.createElement('p');
  status.id = 'steer-status';
  box.appendChild(status);
}

function report(e) {
  $('message').textContent = String(e.message || e);
}

main().catch(report);
