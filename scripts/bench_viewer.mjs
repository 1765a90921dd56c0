#!/usr/bin/env node
// How fast `pedesis view` draws and scrubs, in Debian's Chromium, headless, with software
// WebGL (SwiftShader: the CPU draws; the pessimistic case). Prints, for 10^5 and 10^6
// disks (2D: as the page draws them there, on the CPU, and as sprites with ?draw=gl) and
// 10^5 spheres (3D), the milliseconds and frames per second of a redraw with the camera
// panning (the median of 5 series of 5), and for 10^5 disks the time to
// scrub to frames the page has not seen (fetch, decode, upload and draw; median and
// largest of 10 random frames of a 1,000-frame trajectory).
//
//   node scripts/bench_viewer.mjs [build/pedesis] [scratch directory]
import { spawn, execFileSync } from 'node:child_process';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const binary = path.resolve(process.argv[2] || path.join(root, 'build', 'pedesis'));
const scratch = process.argv[3] || fs.mkdtempSync(path.join(os.tmpdir(), 'bench-viewer-'));
fs.mkdirSync(scratch, { recursive: true });
const require = createRequire(path.join(root, 'web', 'viewer', 'package.json'));
const { chromium } = require('playwright-core');

function config(dimension, n, steps, every) {
  const phi = 0.4;
  const length = dimension === 2 ? Math.sqrt((n * Math.PI * 0.25) / phi)
    : Math.cbrt((n * (4 / 3) * Math.PI * 0.125) / phi);
  return `dimension = ${dimension}\ndynamics = "brownian"\nseed = 1\n[box]\nlength = ${length}\n` +
    `[[species]]\nname = "A"\ncount = ${n}\nradius = 0.5\n[initial]\npositions = "random"\n` +
    '[[force]]\nname = "harmonic"\nk = 10.0\n[[force]]\nname = "self_propulsion"\nalpha = 1.0\n' +
    '[[integrator]]\nname = "brownian"\nT = 0.1\ngamma = 1.0\n' +
    '[[integrator]]\nname = "brownian_rotation"\nT = 0.1\ngamma = 1.0\n' +
    `[run]\ndt = 0.002\nsteps = ${steps}\n[output]\nlog_every = ${every}\nsnapshot_every = ${every}\n` +
    'formats = ["gsd"]\nprogress = false\n';
}

function serve(dir) {
  return new Promise((resolve, reject) => {
    const server = spawn(binary, ['view', dir, '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
    let out = '';
    server.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) resolve({ server, url: m[0] });
    });
    server.on('exit', (code) => reject(new Error(`pedesis view exited (${code})`)));
  });
}

const median = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];

async function measure(browser, name, dir, scrub, query = '') {
  const { server, url } = await serve(dir);
  try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    const t0 = Date.now();
    await page.goto(url + query);
    await page.waitForFunction(() => window.pedesisReady === true, null, { timeout: 300000 });
    const load = (Date.now() - t0) / 1000;
    const series = [];
    for (let k = 0; k < 5; ++k) series.push(await page.evaluate(() => window.pedesisView.benchRender(5)));
    const ms = median(series);
    const way = await page.evaluate(() => (window.pedesisView.drawsOnCpu() ? 'disks drawn on the CPU' : 'sprites'));
    console.log(`${name} (${way}): first frame after ${load.toFixed(2)} s; redraw ${ms.toFixed(1)} ms ` +
      `(${(1000 / ms).toFixed(1)} frames/s; series ${series.map((x) => x.toFixed(0)).join(', ')} ms)`);
    if (scrub) {
      const frames = await page.evaluate(() => window.pedesisView.frames());
      const times = [];
      for (let k = 0; k < 10; ++k) {
        const target = 1 + Math.floor(Math.random() * (frames - 1));
        times.push(await page.evaluate((f) => window.pedesisView.benchShow(f), target));
      }
      console.log(`${name}: scrub to an unseen frame of ${frames}: median ${median(times).toFixed(0)} ms, ` +
        `largest ${Math.max(...times).toFixed(0)} ms`);
    }
    await page.close();
  } finally {
    server.kill('SIGINT');
  }
}

async function main() {
  const cases = [['1e5 disks', 2, 100000, 999, 1, true], ['1e6 disks', 2, 1000000, 1, 1, false],
    ['1e5 spheres', 3, 100000, 1, 1, false]];
  for (const [name, dim, n, steps, every] of cases) {
    const dir = path.join(scratch, name.replace(' ', '_'));
    const file = `${dir}.toml`;
    if (fs.existsSync(path.join(dir, 'summary.json'))) continue; // from an earlier sitting
    fs.writeFileSync(file, config(dim, n, steps, every));
    console.log(`running ${name} (${steps} steps, a frame every ${every}) into ${dir}`);
    execFileSync(binary, ['run', file, '--out', dir], { stdio: 'ignore' });
  }
  const browser = await chromium.launch({ executablePath: '/usr/bin/chromium', headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
  try {
    for (const [name, dim, , , , scrub] of cases) {
      const dir = path.join(scratch, name.replace(' ', '_'));
      await measure(browser, name, dir, scrub);
      // 2D: the sprites too (what a GPU draws; the page chose the CPU in software WebGL)
      if (dim === 2) await measure(browser, name, dir, false, '?draw=gl');
    }
  } finally {
    await browser.close();
  }
  console.log(`(trajectories left in ${scratch})`);
}

main().catch((e) => { console.error(e); process.exit(1); });
