// `pedesis view` in a real browser: Debian's chromium, headless, driven by playwright-core
// (from web/viewer's npm packages), software WebGL (SwiftShader), localhost only.
//
//   node viewer_test.mjs PEDESIS_BINARY WEB_VIEWER_DIR SCRATCH_DIR [SCREENSHOT.png]
//
// For small runs of each engine (soft 2D and 3D, event 2D, stepped 3D) it checks what the
// page draws against the run's own extended XYZ file, read here (an independent reader
// of a second output): the instance count is N; after scrubbing to the last frame the
// drawn centres are that frame's positions; in 2D the pixel at the projected centre of
// every particle that no other covers has its species' colour in the PNG the screenshot
// button saves; colouring by speed changes the colours; the plot has a point per row of
// log.csv. Runs written by hand with walls, a container, a trap and gravity in their
// config.toml show them where they are (2D and 3D, served and exported). And it sends the
// server bad requests: each a 4xx with a message.
//
// Every page is watched for errors: uncaught exceptions, console errors (a resource that
// failed to load, a Content-Security-Policy violation) and securitypolicyviolation events.
// A run whose every string holds markup and script (species names, log columns, the
// directory's name) is opened served and exported: nothing of it runs, and the page shows
// it as text.
import { spawn, execFileSync } from 'node:child_process';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';

const [binary, webDir, scratch, screenshotOut] = process.argv.slice(2);
const require = createRequire(path.join(webDir, 'package.json'));
const { chromium } = require('playwright-core');
const CHROMIUM = '/usr/bin/chromium';
const PALETTE = ['1f77b4', 'ff7f0e', '2ca02c', 'd62728'];

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures += 1;
}

function gasConfig(dimension, dynamics) {
  const engine = dynamics === 'stepped' ? 'dynamics = "stepped"\n[stepped]\ndt = 0.02' : 'dynamics = "event"';
  return `dimension = ${dimension}\nseed = 7\n${engine}\n[box]\nlength = ${dimension === 2 ? 30 : 12}.0\n` +
    '[[species]]\nname = "A"\ncount = 150\nradius = 0.5\n' +
    '[[species]]\nname = "B"\ncount = 50\nradius = 0.7\nmass = 3.0\n' +
    '[initial]\nvelocities = "normal"\nsigma = 1.0\n[run]\ntime = 2.0\n' +
    '[output]\nlog_interval = 0.25\nsnapshot_interval = 0.5\nformats = ["gsd", "xyz"]\n';
}

function softConfig(dimension) {
  return `dimension = ${dimension}\ndynamics = "brownian"\nseed = 3\n[box]\nlength = ${dimension === 2 ? 24 : 9}.0\n` +
    '[[species]]\nname = "A"\ncount = 150\nradius = 0.5\n' +
    '[[species]]\nname = "B"\ncount = 50\nradius = 0.8\n' +
    '[initial]\npositions = "random"\nmin_distance = 1.0\n' +
    '[[force]]\nname = "harmonic"\nk = 20.0\n[[force]]\nname = "self_propulsion"\nalpha = 1.0\n' +
    '[[integrator]]\nname = "brownian"\nT = 0.05\ngamma = 1.0\n' +
    '[[integrator]]\nname = "brownian_rotation"\nT = 0.1\ngamma = 1.0\n' +
    '[run]\ndt = 0.005\nsteps = 400\n[output]\nlog_every = 20\nsnapshot_every = 100\n' +
    'formats = ["gsd", "xyz"]\nprogress = false\n';
}

// Extended XYZ frames: positions and species names per particle.
function readXyz(file) {
  const lines = fs.readFileSync(file, 'utf8').split('\n');
  const frames = [];
  for (let at = 0; at < lines.length && lines[at].trim();) {
    const n = Number(lines[at]);
    const rows = lines.slice(at + 2, at + 2 + n).map((l) => l.trim().split(/\s+/));
    frames.push({ species: rows.map((r) => r[0]), pos: rows.map((r) => r.slice(1, 4).map(Number)) });
    at += 2 + n;
  }
  return frames;
}

// Collects what goes wrong in a page (returned array; filled as it happens).
async function watch(page) {
  const errors = [];
  page.on('pageerror', (e) => errors.push(`exception: ${e}`));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  // (an init script runs before the page's own, whatever its policy)
  await page.addInitScript(() => {
    document.addEventListener('securitypolicyviolation', (e) => {
      console.error(`CSP violation: ${e.violatedDirective} ${e.blockedURI}`);
    });
  });
  return errors;
}

// Waits for fn in the page; false (instead of an exception) after `timeout` ms.
async function waitFor(page, fn, arg, timeout = 10000) {
  try {
    await page.waitForFunction(fn, arg, { timeout });
    return true;
  } catch (e) {
    return false;
  }
}

function startServer(dir) {
  return new Promise((resolve, reject) => {
    const server = spawn(binary, ['view', dir, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    server.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) resolve({ server, url: m[0] });
    });
    server.stderr.on('data', (d) => process.stderr.write(d));
    server.on('exit', (code) => reject(new Error(`pedesis view exited (${code}): ${out}`)));
  });
}

// Puts window.decodePng(url) in the page: a PNG data URL's RGBA bytes, width and height.
async function installPngDecoder(page) {
  await page.evaluate(() => {
    window.decodePng = async (url) => {
      const img = new Image();
      await new Promise((done) => { img.onload = done; img.src = url; });
      const c = document.createElement('canvas');
      c.width = img.width;
      c.height = img.height;
      const ctx = c.getContext('2d');
      ctx.drawImage(img, 0, 0);
      return { data: ctx.getImageData(0, 0, img.width, img.height).data, width: img.width, height: img.height };
    };
  });
}

// The PNG of the screenshot button's path (the canvas as image/png), read back at (x, y).
async function pngPixels(page, points, whole = false) {
  await installPngDecoder(page);
  return page.evaluate(async ([pts, whole]) => {
    const canvas = document.querySelector('#view canvas[style*="relative"]'); // WebGL's
    const url = window.pedesisView.pictureUrl();
    const { data, width, height } = await window.decodePng(url);
    const rect = canvas.getBoundingClientRect();
    const sx = width / rect.width, sy = height / rect.height;
    const pixels = pts.map(({ x, y }) => {
      const at = 4 * (Math.floor((y - rect.top) * sy) * width + Math.floor((x - rect.left) * sx));
      return Array.from(data.slice(at, at + 4));
    });
    return whole ? { pixels, image: url } : pixels;
  }, [points, whole]);
}

// The share of pixels (any channel off by more than 6 of 255) in which two PNG data URLs
// differ, decoded in the page.
async function pngDifference(page, a, b) {
  await installPngDecoder(page);
  return page.evaluate(async ([a, b]) => {
    const [x, y] = [(await window.decodePng(a)).data, (await window.decodePng(b)).data];
    if (x.length !== y.length) return `images of ${x.length / 4} and ${y.length / 4} pixels`;
    let differ = 0;
    for (let k = 0; k < x.length; k += 4)
      if (Math.abs(x[k] - y[k]) > 6 || Math.abs(x[k + 1] - y[k + 1]) > 6 || Math.abs(x[k + 2] - y[k + 2]) > 6) differ += 1;
    return differ / (x.length / 4);
  }, [a, b]);
}

// In a 2D view: the PNG's pixel at the projected centre of each particle of `free` (no
// other covers it) has its species' colour. Returns the PNG as a data URL.
async function speciesAtCentres(page, name, way, f, free, names) {
  // one size for the view in both pages (the panels beside it settle at their own pace);
  // through the CSSOM, which the page's policy allows (a <style> element it refuses)
  await page.evaluate(() => {
    const view = document.querySelector('#view');
    for (const [property, value] of [['width', '800px'], ['height', '520px'], ['flex', 'none']])
      view.style.setProperty(property, value, 'important');
  });
  await page.waitForFunction(() => {
    const c = document.querySelector('#view canvas[style*="relative"]');
    return c.width === 800 && c.height === 520;
  }, null, { timeout: 10000 });
  const points = await page.evaluate((ids) => ids.map((i) => window.pedesisView.project(i)), free);
  const { pixels, image } = await pngPixels(page, points, true);
  let matching = 0;
  free.forEach((i, k) => {
    const want = hexToRgb(PALETTE[names.indexOf(f.species[i])]);
    if (want.every((c, a) => Math.abs(c - pixels[k][a]) <= 6)) matching += 1;
    else console.log(`     particle ${i}: pixel ${pixels[k].slice(0, 3)} against ${want}`);
  });
  check(free.length >= 10 && matching === free.length,
    `${name} (${way}): ${matching} of ${free.length} uncovered particles show their species' colour at their centre in the PNG`);
  return image;
}

function hexToRgb(h) {
  return [0, 2, 4].map((k) => parseInt(h.slice(k, k + 2), 16));
}

async function checkRun(browser, name, dimension, dir) {
  const xyz = readXyz(path.join(dir, 'trajectory.xyz'));
  const log = fs.readFileSync(path.join(dir, 'log.csv'), 'utf8').trim().split('\n');
  const { server, url } = await startServer(dir);
  try {
    const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
    const errors = await watch(page);
    await page.goto(url);
    await page.waitForFunction(() => window.pedesisReady === true, null, { timeout: 60000 });
    const n = xyz[0].pos.length;
    // the legend (and colour bar) lie beside the drawing, never over particles
    const overlap = await page.evaluate(() => {
      const a = document.querySelector('#colourbar').getBoundingClientRect();
      const b = document.querySelector('#view canvas[style*="relative"]').getBoundingClientRect();
      const x = Math.min(a.right, b.right) - Math.max(a.left, b.left);
      const y = Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top);
      return { shown: a.height > 0 && a.width > 0, area: Math.max(x, 0) * Math.max(y, 0) };
    });
    check(overlap.shown && overlap.area === 0,
      `${name}: the species legend is shown and does not cover the drawing (${overlap.area} px² shared)`);
    if (dimension === 3) {
      // the first view holds the whole box: its 8 corners project inside the canvas
      const inside = await page.evaluate(() => {
        const { box_lo: lo, box_length: L } = window.pedesisView.info;
        const r = document.querySelector('#view canvas[style*="relative"]').getBoundingClientRect();
        let count = 0;
        for (let c = 0; c < 8; ++c) {
          const p = window.pedesisView.projectPoint(lo[0] + (c & 1) * L[0], lo[1] + ((c >> 1) & 1) * L[1],
            lo[2] + ((c >> 2) & 1) * L[2]);
          if (p.x >= r.left && p.x <= r.right && p.y >= r.top && p.y <= r.bottom) count += 1;
        }
        return count;
      });
      check(inside === 8, `${name}: the first 3D view shows the whole box (${inside} of its 8 corners)`);
    }
    check(await page.evaluate(() => window.pedesisView.instanceCount()) === n,
      `${name}: draws N = ${n} instances`);
    check(await page.evaluate(() => window.pedesisView.frames()) === xyz.length,
      `${name}: knows the ${xyz.length} frames`);

    const last = xyz.length - 1;
    await page.evaluate((k) => window.pedesisView.setFrame(k), last);
    const drawn = await page.evaluate(() => window.pedesisView.drawnPositions());
    let worst = 0;
    for (let i = 0; i < n; ++i)
      for (let a = 0; a < 3; ++a) worst = Math.max(worst, Math.abs(drawn[i][a] - xyz[last].pos[i][a]));
    // float32 on the wire: 1e-7 relative of positions up to 15
    check(worst < 1e-4, `${name}: after scrubbing to frame ${last} the drawn centres are its positions (worst ${worst.toExponential(2)})`);

    const rows = log.length - 1;
    check(await page.evaluate(() => window.pedesisView.logPoints()) === rows,
      `${name}: the plot has the ${rows} rows of log.csv`);

    const names = [...new Set(xyz[0].species)];
    if (dimension === 2) {
      // particles whose centre no other particle covers (drawn later or earlier)
      const f = xyz[last], radius = (s) => (s === 'A' ? 0.5 : (name.startsWith('soft') ? 0.8 : 0.7));
      const free = [];
      for (let i = 0; i < n && free.length < 40; ++i) {
        let covered = false;
        for (let j = 0; j < n && !covered; ++j) {
          if (j === i) continue;
          const dx = f.pos[i][0] - f.pos[j][0], dy = f.pos[i][1] - f.pos[j][1];
          covered = Math.hypot(dx, dy) < radius(f.species[j]) + 0.05;
        }
        if (!covered) free.push(i);
      }
      // software WebGL: the page draws the disks on the CPU; ?draw=gl draws the sprites
      check(await page.evaluate(() => window.pedesisView.drawsOnCpu()) === true,
        `${name}: in software WebGL the page draws the 2D disks on the CPU`);
      const cpuImage = await speciesAtCentres(page, name, 'CPU', f, free, names);
      const gl = await browser.newPage({ viewport: { width: 1100, height: 700 } });
      await gl.goto(url + '?draw=gl');
      await gl.waitForFunction(() => window.pedesisReady === true, null, { timeout: 60000 });
      // (the plot beside the view changes the layout when it arrives: wait for it, as above)
      await gl.waitForFunction(() => window.pedesisView.logPoints() > 0, null, { timeout: 60000 });
      await gl.evaluate((k) => window.pedesisView.setFrame(k), last);
      check(await gl.evaluate(() => window.pedesisView.drawsOnCpu()) === false, `${name}: ?draw=gl draws sprites`);
      const glImage = await speciesAtCentres(gl, name, 'sprites', f, free, names);
      // the two ways draw the same picture, up to the edge pixels of disks
      const share = await pngDifference(gl, cpuImage, glImage);
      await gl.close();
      check(typeof share === 'number' && share < 0.02,
        `${name}: the CPU's and the sprites' images differ in ${typeof share === 'number' ? (100 * share).toFixed(2) : share} % of the pixels (edges)`);
      if (screenshotOut && name === 'soft 2D') {
        await page.evaluate(() => window.pedesisView.renderNow());
        await page.screenshot({ path: screenshotOut });
      }
    }

    if (await page.evaluate(() => window.pedesisView.info.fields.includes('speed'))) {
      const before = await page.evaluate((k) => Array.from({ length: k }, (_, i) => window.pedesisView.instanceColour(i)), n);
      await page.evaluate(() => window.pedesisView.setColour('speed'));
      const after = await page.evaluate((k) => Array.from({ length: k }, (_, i) => window.pedesisView.instanceColour(i)), n);
      const changed = after.filter((c, i) => c !== before[i]).length;
      const distinct = new Set(after).size;
      check(changed > n / 2 && distinct > 10, `${name}: colour by speed changes ${changed} of ${n} colours (${distinct} distinct)`);
    }
    check(errors.length === 0, `${name}: no error in the page (nor CSP violation) ${errors.join('; ')}`);
    await page.close();
    return url;
  } finally {
    server.kill('SIGINT');
  }
}

async function checkBadRequests(dir) {
  const { server, url } = await startServer(dir);
  try {
    const cases = [
      ['api/frame/999/position', 404, 'past the end'],
      ['api/frame/0/colour', 404, "no field 'colour' (it has: position, radius, species, director, speed"],
      ['api/frame/99999999999999999999/position', 404, 'no such resource'],
      ['api/nothing', 404, 'no such resource'],
    ];
    for (const [p, status, text] of cases) {
      const r = await fetch(url + p);
      const body = await r.json().catch(() => ({}));
      check(r.status === status && String(body.error).includes(text),
        `bad request ${p}: ${r.status} "${body.error}"`);
    }
    const ok = await fetch(url + 'api/frame/0/position');
    check(ok.status === 200, 'the server still answers after bad requests');
  } finally {
    server.kill('SIGINT');
  }
}

// --export: one HTML file that opens from disk with every network request refused, and
// shows the first and the last frame (here every second frame: 0, 2, 4 of 5).
async function checkExport(browser, dir) {
  const file = path.join(scratch, 'exported.html');
  execFileSync(binary, ['view', dir, '--export', file, '--every', '2'], { stdio: 'ignore' });
  const xyz = readXyz(path.join(dir, 'trajectory.xyz'));
  const context = await browser.newContext({ viewport: { width: 1100, height: 700 } });
  let refused = 0;
  await context.route('**/*', (route) => {
    if (route.request().url().startsWith('file:')) return route.continue();
    refused += 1;
    return route.abort();
  });
  const page = await context.newPage();
  const errors = await watch(page);
  await page.goto('file://' + file);
  await page.waitForFunction(() => window.pedesisReady === true, null, { timeout: 60000 });
  check(await page.evaluate(() => window.pedesisView.frames()) === 3, 'export: holds frames 0, 2 and 4');
  for (const [k, original] of [[0, 0], [2, xyz.length - 1]]) {
    await page.evaluate((i) => window.pedesisView.setFrame(i), k);
    const drawn = await page.evaluate(() => window.pedesisView.drawnPositions());
    let worst = 0;
    xyz[original].pos.forEach((p, i) => p.forEach((c, a) => { worst = Math.max(worst, Math.abs(drawn[i][a] - c)); }));
    check(drawn.length === xyz[original].pos.length && worst < 1e-4,
      `export: frame ${k} shows the run's frame ${original} (worst ${worst.toExponential(2)})`);
  }
  check(refused === 0 && errors.length === 0, `export: no network request (${refused}) and no error ${errors.join('; ')}`);
  await context.close();
}

// Moves the page's steering slider of `parameter` to `value`, as a user would, and waits
// until the page says the server queued the change.
async function moveSlider(page, parameter, value) {
  await page.evaluate(([name, v]) => {
    const slider = document.querySelector(`#steer-${name}`);
    slider.value = v;
    slider.dispatchEvent(new Event('change'));
  }, [parameter, value]);
  await page.waitForFunction(() => /from the next step/.test(document.querySelector('#steer-status').textContent),
    null, { timeout: 10000 });
}

// `pedesis run CONFIG --view` in the background: resolves once it prints its address.
async function startLiveRun(config, dir) {
  const run = spawn(binary, ['run', config, '--out', dir, '--view', '--view-port', '0'],
    { stdio: ['ignore', 'pipe', 'inherit'], env: { ...process.env, OMP_NUM_THREADS: '1' } });
  const ended = new Promise((done) => run.on('exit', done));
  let out = '';
  run.stdout.on('data', (d) => { out += d; });
  const url = await new Promise((resolve, reject) => {
    run.stdout.on('data', () => {
      const m = out.match(/watch the run at (http:\/\/127\.0\.0\.1:\d+\/\?token=[0-9a-f]{32})/);
      if (m) resolve(m[1]);
    });
    run.on('exit', (code) => reject(new Error(`pedesis run --view exited (${code}): ${out}`)));
  });
  return { run, ended, url, base: url.split('?')[0], token: url.split('token=')[1], output: () => out };
}

// A run still going, served by itself (`pedesis run --view`): the page waits for the
// first frame, the frame count grows as the run writes frames; the page's temperature
// slider changes the running simulation (the log's ideal pressure n T follows), bad
// requests are refused, and the record steering.csv, replayed by --steering on the same
// config, reproduces the run's trajectory and log byte for byte.
async function checkLive(browser) {
  const live = softConfig(2).replace('snapshot_every = 100', 'snapshot_every = 2000')
    .replace('log_every = 20', 'log_every = 500');
  const config = path.join(scratch, 'live.toml');
  fs.writeFileSync(config, live.replace('steps = 400', 'steps = 100000000'));
  const dir = path.join(scratch, 'live');
  const { run, ended, url, base, token } = await startLiveRun(config, dir);
  let stopped = false;
  try {
    const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
    const errors = await watch(page);
    await page.goto(url);
    await page.waitForFunction(() => window.pedesisReady === true, null, { timeout: 60000 });
    const [first, opened] = await page.evaluate(() => [window.pedesisView.frames(), window.pedesisView.frameIndex()]);
    check(opened === first - 1 && await page.evaluate(() => document.querySelector('#follow').checked
      && !document.querySelector('#follow-label').hidden),
    `live: the page opens at the newest frame (${opened} of ${first}), "follow" shown and ticked`);
    await new Promise((done) => setTimeout(done, 2500));
    const later = await page.evaluate(() => window.pedesisView.frames());
    check(first >= 1 && later > first, `live (run --view): the page's frame count grows from ${first} to ${later}`);
    const followed = await waitFor(page, (k) => window.pedesisView.frames() > k
      && window.pedesisView.frameIndex() === window.pedesisView.frames() - 1, first, 6000);
    const at = await page.evaluate(() => [window.pedesisView.frameIndex(), window.pedesisView.frames()]);
    check(followed, `live: it follows the newest frame as the run writes them (frame ${at[0]} of ${at[1]})`);
    // scrubbing stops following: the page stays where the user put it
    await page.evaluate(() => {
      const slider = document.querySelector('#slider');
      slider.value = '0';
      slider.dispatchEvent(new Event('input'));
    });
    await new Promise((done) => setTimeout(done, 2500));
    const [stayed, following, ticked] = await page.evaluate(() => [window.pedesisView.frameIndex(),
      window.pedesisView.following(), document.querySelector('#follow').checked]);
    check(stayed === 0 && !following && !ticked,
      `live: scrubbing to frame 0 stops following (at frame ${stayed}; "follow" ${ticked ? '' : 'un'}ticked)`);

    // the slider lies within the range the server allows, and the number box beside it
    // takes that whole range
    const range = await page.evaluate(() => {
      const t = window.pedesisView.info.steerable.find((p) => p.name === 'temperature');
      const slider = document.querySelector('#steer-temperature');
      const exact = slider.parentElement.querySelector('input.exact');
      return { min: t.min, max: t.max, slider: [Number(slider.min), Number(slider.max)], exact: [exact.min, exact.max] };
    });
    check(Number.isFinite(range.min) && Number.isFinite(range.max) && range.slider[0] >= range.min
      && range.slider[1] <= range.max && range.exact[0] === String(range.min) && range.exact[1] === String(range.max),
    `live: temperature's slider spans [${range.slider}] within the allowed [${range.min}, ${range.max}], its number box all of it`);
    // the page's control, as a user would move it
    await moveSlider(page, 'temperature', '0.5');
    check(true, 'live: the temperature slider sent T = 0.5 and the server queued it');
    const post = (body) => fetch(base + 'api/set', { method: 'POST', body })
      .then(async (r) => [r.status, (await r.json()).error]);
    const bad = [
      [JSON.stringify({ token: 'f'.repeat(32), parameter: 'temperature', value: 1 }), 403],
      [JSON.stringify({ parameter: 'temperature', value: 1 }), 403],
      [JSON.stringify({ token, parameter: 'viscosity', value: 1 }), 400],
      [JSON.stringify({ token, parameter: 'temperature', value: -1 }), 400],
      [`{"token": "${token}", "parameter": "temperature", "value": "nan"}`, 400],
      [`{"token": "${token}", "parameter": "temperature", "value": NaN}`, 400],
      ['{"token": ', 400],
    ];
    for (const [body, status] of bad) {
      const [got, error] = await post(body);
      check(got === status && error, `live: ${body.slice(0, 60)} -> ${got} "${error}"`);
    }
    const readOnly = await browser.newPage();
    await readOnly.goto(base);
    await readOnly.waitForFunction(() => window.pedesisReady === true, null, { timeout: 60000 });
    check(await readOnly.evaluate(() => document.querySelector('#steer-temperature').disabled),
      'live: without the token the page shows the controls disabled');
    await readOnly.close();
    await new Promise((done) => setTimeout(done, 1500));
    check(errors.length === 0, `live: no error in the page (nor CSP violation) ${errors.join('; ')}`);
    await page.close();
    run.kill('SIGTERM');
    stopped = true;
    await ended;
  } finally {
    if (!stopped) run.kill('SIGTERM');
  }
  const record = fs.readFileSync(path.join(dir, 'steering.csv'), 'utf8').trim().split('\n');
  check(record.length === 2 && /^\d+,[^,]+,temperature,0\.5$/.test(record[1]),
    `live: steering.csv records the one change: ${record[1]}`);
  const rows = fs.readFileSync(path.join(dir, 'log.csv'), 'utf8').trim().split('\n');
  const header = rows[0].split(','), last = rows[rows.length - 1].split(',');
  const ideal = Number(last[header.indexOf('pressure_ideal')]);
  check(Math.abs(ideal - (0.5 * 200) / (24 * 24)) < 1e-9,
    `live: the log's last ideal pressure n T is ${ideal} (T = 0.5: ${(0.5 * 200) / 576})`);

  const steps = JSON.parse(fs.readFileSync(path.join(dir, 'summary.json'), 'utf8')).steps;
  const replayConfig = path.join(scratch, 'replay.toml');
  fs.writeFileSync(replayConfig, live.replace('steps = 400', `steps = ${steps}`));
  execFileSync(binary, ['run', replayConfig, '--out', path.join(scratch, 'replay'), '--steering',
    path.join(dir, 'steering.csv')], { stdio: 'ignore', env: { ...process.env, OMP_NUM_THREADS: '1' } });
  for (const file of ['trajectory.xyz', 'log.csv', 'steering.csv'])
    check(fs.readFileSync(path.join(scratch, 'replay', file), 'utf8') === fs.readFileSync(path.join(dir, file), 'utf8'),
      `replay: ${file} of the replayed record is the live run's, byte for byte (${steps} steps)`);
}

// The event engine live: its restitution slider makes an elastic gas (energy fraction 1,
// to the log's 10 digits, exactly conserved up to rounding) inelastic from the next log
// row on (the energy then falls and never rises; the TC model, tc = 1e-4, keeps a long
// cooling from inelastic collapse); the record holds the change with its time,
// and replaying it on the same config gives the same log, row for row, up to the last row
// of the time grid. Out-of-range values are refused, and so is any change once the run
// has ended (its page stays open).
async function checkLiveEvent(browser) {
  const gas = `dimension = 2\nseed = 5\n[box]\nlength = 80.0\n[[species]]\nname = "A"\ncount = 2000\n` +
    'radius = 0.5\n[event]\ntc = 1e-4\n[run]\ntime = TIME\n[output]\nlog_interval = 5.0\nsnapshot_interval = 1000.0\n' +
    'formats = ["xyz"]\nprogress = false\n';
  const config = path.join(scratch, 'live_event.toml');
  fs.writeFileSync(config, gas.replace('TIME', '1.0e9'));
  const dir = path.join(scratch, 'live_event');
  const { run, ended, url, base, token } = await startLiveRun(config, dir);
  const post = (body) => fetch(base + 'api/set', { method: 'POST', body: JSON.stringify(body) })
    .then(async (r) => [r.status, (await r.json()).error]);
  try {
    const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
    await page.goto(url);
    await page.waitForFunction(() => window.pedesisReady === true, null, { timeout: 60000 });
    const [status, error] = await post({ token, parameter: 'restitution', value: 1.5 });
    check(status === 400 && /\[0, 1\]/.test(error), `live event: restitution 1.5 -> ${status} "${error}"`);
    await moveSlider(page, 'restitution', '0.9');
    await new Promise((done) => setTimeout(done, 2000));
    await page.close();
  } finally {
    run.kill('SIGTERM');
    await ended;
  }
  const record = fs.readFileSync(path.join(dir, 'steering.csv'), 'utf8').trim().split('\n');
  const change = record.length === 2 ? record[1].split(',') : [];
  check(change[2] === 'restitution' && change[3] === '0.9',
    `live event: steering.csv records the one change: ${record[1]}`);
  const rows = fs.readFileSync(path.join(dir, 'log.csv'), 'utf8').trim().split('\n');
  const header = rows[0].split(','), col = header.indexOf('energy_fraction');
  const t = rows.slice(1).map((r) => Number(r.split(',')[0]));
  const energy = rows.slice(1).map((r) => Number(r.split(',')[col]));
  const changedAt = Number(change[1]);
  const before = energy.filter((_, k) => t[k] <= changedAt), after = energy.filter((_, k) => t[k] > changedAt);
  check(before.length > 1 && before.every((e) => e === 1),
    `live event: the energy fraction is 1 on all ${before.length} rows up to the change at t = ${changedAt}`);
  // (a cold gas late in the run may see no collision between two rows: never a rise)
  check(after.length > 2 && after[0] < 1 && after.every((e, k) => e <= (k ? after[k - 1] : 1)),
    `live event: it falls from the first row after and never rises over the ${after.length} rows after (last ${after[after.length - 1]})`);

  const grid = rows.slice(0, -1); // the last row is the instant the signal came
  const last = t[t.length - 2];
  const replayConfig = path.join(scratch, 'replay_event.toml');
  fs.writeFileSync(replayConfig, gas.replace('TIME', String(last)));
  execFileSync(binary, ['run', replayConfig, '--out', path.join(scratch, 'replay_event'), '--steering',
    path.join(dir, 'steering.csv')], { stdio: 'ignore' });
  const replay = fs.readFileSync(path.join(scratch, 'replay_event', 'log.csv'), 'utf8').trim().split('\n');
  check(replay.join('\n') === grid.join('\n'),
    `replay event: the log of the replayed record is the live run's, row for row (${grid.length - 1} rows to t = ${last})`);

  // a short run that ends while its page stays: a change is refused after the end
  const shortConfig = path.join(scratch, 'ended_event.toml');
  fs.writeFileSync(shortConfig, gas.replace('TIME', '10.0'));
  const short = await startLiveRun(shortConfig, path.join(scratch, 'ended_event'));
  try {
    for (let k = 0; k < 100 && !/the run is done/.test(short.output()); ++k)
      await new Promise((done) => setTimeout(done, 100));
    const answer = await fetch(short.base + 'api/set', { method: 'POST',
      body: JSON.stringify({ token: short.token, parameter: 'restitution', value: 0.5 }) });
    const why = (await answer.json()).error;
    check(answer.status === 400 && /ended/.test(why), `ended event run: a change -> ${answer.status} "${why}"`);
  } finally {
    short.run.kill('SIGTERM');
    await short.ended;
  }
}

// A file of the user's own: an extended XYZ with a column pedesis does not write
// ("energy"). The colour menu offers it, and colouring by it paints each particle's
// centre in the PNG with viridis at its place between the frame's least and largest
// value (-1, 0.5, 2: the ends and the middle of the bar).
async function checkOwnColumn(browser) {
  const dir = path.join(scratch, 'own_column');
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(path.join(dir, 'trajectory.xyz'), '3\n' +
    'Lattice="12 0 0 0 12 0 0 0 1" Origin="-6 -6 -0.5" pbc="T T F" ' +
    'Properties=species:S:1:pos:R:3:radius:R:1:energy:R:1 Time=0\n' +
    'A -3 0 0 1.0 -1\nA 0 0 0 1.0 0.5\nA 3 0 0 1.0 2\n');
  const { server, url } = await startServer(dir);
  try {
    const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
    await page.goto(url);
    await page.waitForFunction(() => window.pedesisReady === true, null, { timeout: 60000 });
    const options = await page.evaluate(() => [...document.querySelectorAll('#colour option')].map((o) => o.value));
    check(options.includes('energy'), `own column: the colour menu offers it (${options.join(', ')})`);
    await page.selectOption('#colour', 'energy');
    await page.waitForFunction(() => /energy/.test(document.querySelector('#colourbar').textContent), null,
      { timeout: 10000 });
    const points = await page.evaluate(() => [0, 1, 2].map((i) => window.pedesisView.project(i)));
    const pixels = await pngPixels(page, points);
    const want = [[68, 1, 84], [33, 145, 140], [253, 231, 37]];
    const ok = want.every((w, k) => w.every((c, a) => Math.abs(c - pixels[k][a]) <= 6));
    check(ok, `own column: the centres show viridis at energy -1, 0.5, 2: ${pixels.map((p) => p.slice(0, 3).join(' ')).join(' | ')}`);
    await page.close();
  } finally {
    server.kill('SIGINT');
  }
}

// A run's walls, container, trap and gravity (issue 50), from a config.toml and an extended
// XYZ written by hand (the frames give the walls, the config the rest): the page counts
// what it draws, and the PNG of the screenshot button is dark where the container's wall
// line, the box's walls, the trap's marker and the gravity arrow are, where the same
// frames without the config are not. In 3D the trap and the arrow's head show through
// the particles. The exported page draws them too.
function sceneryRun(name, dimension, pbc, particles, config) {
  const dir = path.join(scratch, name);
  fs.mkdirSync(dir, { recursive: true });
  const lattice = dimension === 2 ? 'Lattice="20 0 0 0 20 0 0 0 1" Origin="-10 -10 -0.5"'
    : 'Lattice="12 0 0 0 12 0 0 0 12" Origin="-6 -6 -6"';
  fs.writeFileSync(path.join(dir, 'trajectory.xyz'), `${particles.length}\n${lattice} pbc="${pbc}" ` +
    `Properties=species:S:1:pos:R:3:radius:R:1 Time=0\n${particles.map((p) => `A ${p.join(' ')} 0.5\n`).join('')}`);
  if (config) fs.writeFileSync(path.join(dir, 'config.toml'), config);
  return dir;
}

// The PNG's pixels at the projections of world points, in a page opened at `url`.
async function sceneryPixels(browser, url, points) {
  const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
  const errors = await watch(page);
  await page.goto(url);
  await page.waitForFunction(() => window.pedesisReady === true, null, { timeout: 60000 });
  const drawn = await page.evaluate(() => window.pedesisView.scenery());
  const projected = await page.evaluate((pts) => pts.map(([x, y, z]) => window.pedesisView.projectPoint(x, y, z)), points);
  const pixels = await pngPixels(page, projected);
  const info = await page.evaluate(() => window.pedesisView.info);
  await page.close();
  return { drawn, pixels, info, errors };
}

async function checkScenery(browser) {
  const dark = (p) => p[0] + p[1] + p[2] < 3 * 90;
  const light = (p) => p[0] + p[1] + p[2] > 3 * 200;
  const scenery2d = '[[force]]\nname = "wall"\npotential = "wca"\n' +
    '[[force]]\nname = "wall"\npotential = "wca"\nshape = "sphere"\nradius = 6.0\ncentre = [1.0, -1.0]\n' +
    '[[force]]\nname = "harmonic_trap"\nk = {A = 1.0}\ncentre = [-5.0, 4.0]\n' +
    '[[force]]\nname = "gravity"\nforce = 1.0\n';
  const far2d = [[-8, -8, 0], [8, -8, 0], [-8, 8, 0]];
  const withDir = sceneryRun('scenery_2d', 2, 'F T F', far2d,
    `dimension = 2\n[box]\nlength = 20.0\nboundary = ["wall", "periodic"]\n${scenery2d}`);
  const plainDir = sceneryRun('plain_2d', 2, 'T T F', far2d, null);
  // (the wall's thickness and the marker's size: 0.8 % and 2 % of the box, scenery.js)
  const t = 0.16, size = 0.4;
  const marks = { 'container line (right)': [1 + 6 + t / 2, -1, 0], 'container line (top)': [1, 5 + t / 2, 0],
    'trap centre': [-5, 4, 0], 'trap cross arm': [-5 + 0.8 * size, 4, 0],
    // the arrow, centred 2.5 sizes in from the top right corner, 3 sizes long, pointing down
    'gravity arrow head': [9, 9 - 0.25, 0], 'gravity arrow shaft': [9, 9 + 0.4, 0],
    'left wall': [-10 - t / 2, 0, 0], 'right wall': [10 + t / 2, 3, 0] };
  const quiet = { 'inside the container': [1, -1 + 3, 0], 'beyond the periodic top edge': [0, 10 + t, 0],
    'beside the arrow\'s shaft (a head is wider)': [9 + 0.15, 9 + 0.4, 0] };
  const points = [...Object.values(marks), ...Object.values(quiet)];
  const names = [...Object.keys(marks), ...Object.keys(quiet)];
  const served = async (dir) => {
    const { server, url } = await startServer(dir);
    try { return await sceneryPixels(browser, url, points); } finally { server.kill('SIGINT'); }
  };
  const seen = await served(withDir), plain = await served(plainDir);
  const sent = seen.info.scenery, c = sent.containers[0] || {};
  check(sent.containers.length === 1 && c.shape === 'sphere' && c.radius === 6 && String(c.centre) === '1,-1,0'
    && String(sent.traps) === '-5,4,0' && String(sent.gravity) === '0,-1,0',
  `scenery 2D: /api/info sends it as numbers: ${JSON.stringify(sent)}`);
  check(JSON.stringify(seen.drawn) === JSON.stringify({ walls: 1, containers: 1, traps: 1, gravity: 1 }),
    `scenery 2D: the page draws one walled axis, container, trap and arrow: ${JSON.stringify(seen.drawn)}`);
  const markCount = Object.keys(marks).length;
  names.forEach((name, k) => {
    const want = k < markCount ? dark : light;
    check(want(seen.pixels[k]) && light(plain.pixels[k]),
      `scenery 2D: ${name} is ${k < markCount ? 'dark' : 'clear'} in the PNG (${seen.pixels[k].slice(0, 3)}), clear without the config (${plain.pixels[k].slice(0, 3)})`);
  });
  check(seen.errors.length === 0 && plain.errors.length === 0, `scenery 2D: no error in the page ${[...seen.errors, ...plain.errors].join('; ')}`);

  // 3D: walls on z, a sphere, a trap off centre, gravity along -z (the default axis)
  const far3d = [[-5, -5, -5], [5, 5, -5], [-5, 5, 5]];
  const scenery3d = '[[force]]\nname = "wall"\npotential = "wca"\nshape = "sphere"\nradius = 3.0\n' +
    '[[force]]\nname = "harmonic_trap"\nk = [1.0, 1.0, 2.0]\ncentre = [2.0, -2.0, 1.0]\n' +
    '[[force]]\nname = "gravity"\nforce = 2.0\n';
  const with3d = sceneryRun('scenery_3d', 3, 'T T F', far3d,
    `dimension = 3\n[box]\nlength = 12.0\nboundary = ["periodic", "periodic", "wall"]\n${scenery3d}`);
  const plain3d = sceneryRun('plain_3d', 3, 'T T T', far3d, null);
  // the arrow (scenery.js, s = 3 % of the box): from (6 - 2 s, 6 - 2 s, 6 - s) down a
  // quarter of the box, its head the last 0.3 of that
  const s3 = 0.36, tip = 6 - s3 - 3;
  const points3d = [[2, -2, 1], [6 - 2 * s3, 6 - 2 * s3, tip + 0.36]];
  const served3d = async (dir) => {
    const { server, url } = await startServer(dir);
    try { return await sceneryPixels(browser, url, points3d); } finally { server.kill('SIGINT'); }
  };
  const seen3d = await served3d(with3d), plainSeen3d = await served3d(plain3d);
  check(JSON.stringify(seen3d.drawn) === JSON.stringify({ walls: 1, containers: 1, traps: 1, gravity: 1 }),
    `scenery 3D: the page draws one walled axis, the sphere, the trap and the arrow: ${JSON.stringify(seen3d.drawn)}`);
  ['trap centre', 'gravity arrow head'].forEach((name, k) => check(dark(seen3d.pixels[k]) && light(plainSeen3d.pixels[k]),
    `scenery 3D: the ${name} is dark in the PNG (${seen3d.pixels[k].slice(0, 3)}), clear without the config (${plainSeen3d.pixels[k].slice(0, 3)})`));
  check(seen3d.errors.length === 0, `scenery 3D: no error in the page ${seen3d.errors.join('; ')}`);

  const file = path.join(scratch, 'scenery.html');
  execFileSync(binary, ['view', withDir, '--export', file], { stdio: 'ignore' });
  const exported = await sceneryPixels(browser, 'file://' + file, points);
  check(JSON.stringify(exported.drawn) === JSON.stringify(seen.drawn)
    && exported.pixels.every((p, k) => (k < markCount ? dark(p) : light(p))),
  `scenery export: the exported page draws them too: ${JSON.stringify(exported.drawn)}`);
}

// A run whose strings are markup and script: species names, log.csv's column names and the
// run directory's name, in an extended XYZ file and a log written by hand (four disks at
// rest). Served (pedesis view) and exported (--export), the page runs none of it
// (window.__pwned stays unset), shows every name as literal text in the legend, the plot's
// menu and the title, and its policy reports no violation; the server sends its
// Content-Security-Policy with the page, and the exported file carries one and names no
// path of this machine. Coloured by speed, the all-zero frame is the bar's low end, 0. Its
// config.toml puts markup in the scenery's words and numbers: none of it is sent or drawn.
const HOSTILE = ['<img/src/onerror=window.__pwned=1>', '</script><script>window.__pwned=2</script>',
  '<!--<script>', 'a&amp;b'];

async function hostilePage(page, name) {
  await page.waitForFunction(() => window.pedesisReady === true, null, { timeout: 60000 });
  const shown = await page.evaluate(() => ({
    pwned: window.__pwned,
    legend: [...document.querySelectorAll('#colourbar .name')].map((e) => e.textContent),
    images: document.querySelectorAll('#colourbar img, #colourbar script, #column img').length,
    title: document.querySelector('#title').textContent,
  }));
  check(shown.pwned === undefined && shown.images === 0, `${name}: no script of the run's strings ran (window.__pwned ${shown.pwned})`);
  check(JSON.stringify(shown.legend) === JSON.stringify(HOSTILE),
    `${name}: the legend shows the species names as text: ${JSON.stringify(shown.legend)}`);
  check(shown.title.includes('hostile<b>run'), `${name}: the title shows the run's name as text: ${shown.title}`);
  const scenery = await page.evaluate(() => [window.pedesisView.info.scenery, window.pedesisView.scenery()]);
  check(['containers', 'traps', 'gravity'].every((k) => Array.isArray(scenery[0][k]) && scenery[0][k].length === 0)
    && scenery[1].containers + scenery[1].traps + scenery[1].gravity === 0,
  `${name}: markup in the config's scenery sends and draws none of it: ${JSON.stringify(scenery)}`);
  const columns = await page.evaluate(() => (window.pedesisView.logPoints(), [...document.querySelectorAll('#column option')].map((o) => o.text)));
  check(HOSTILE.every((h) => columns.includes(h)), `${name}: the plot's menu shows log.csv's columns as text: ${JSON.stringify(columns)}`);
  await page.evaluate(() => window.pedesisView.setColour('speed'));
  const bar = await page.evaluate(() => [document.querySelector('#colourbar .lo')?.textContent,
    document.querySelector('#colourbar .hi')?.textContent,
    [0, 1, 2, 3].map((i) => window.pedesisView.instanceColour(i))]);
  check(Number(bar[0]) === 0 && Number(bar[1]) > 0 && bar[2].every((c) => c === '440154'),
    `${name}: every speed 0: the bar reads ${bar[0]} to ${bar[1]} and the disks are its low end (${bar[2].join(' ')})`);
}

async function checkHostile(browser) {
  const dir = path.join(scratch, 'hostile<b>run');
  fs.mkdirSync(dir, { recursive: true });
  fs.writeFileSync(path.join(dir, 'trajectory.xyz'), '4\n' +
    'Lattice="12 0 0 0 12 0 0 0 1" Origin="-6 -6 -0.5" pbc="T T F" ' +
    'Properties=species:S:1:pos:R:3:radius:R:1:velo:R:3 Time=0\n' +
    HOSTILE.map((h, k) => `${h} ${3 * k - 4.5} 0 0 1.0 0 0 0\n`).join(''));
  fs.writeFileSync(path.join(dir, 'log.csv'), `time,step,${HOSTILE.join(',')}\n0,0,1,2,3,4\n1,10,2,3,4,5\n`);
  // and a config whose scenery holds markup where words and numbers belong
  fs.writeFileSync(path.join(dir, 'config.toml'), 'dimension = 2\n' +
    `[[force]]\nname = "wall"\nshape = "sphere"\nradius = ${JSON.stringify(HOSTILE[0])}\n` +
    `[[force]]\nname = "wall"\nshape = ${JSON.stringify(HOSTILE[1])}\nradius = 2.0\n` +
    `[[force]]\nname = "harmonic_trap"\nk = 1.0\ncentre = [${JSON.stringify(HOSTILE[2])}, 0.0]\n` +
    `[[force]]\nname = "gravity"\nforce = 1.0\naxis = ${JSON.stringify(HOSTILE[1])}\n`);
  const { server, url } = await startServer(dir);
  try {
    const index = await fetch(url);
    const policy = index.headers.get('content-security-policy') || '';
    check(/script-src 'self'/.test(policy) && !/unsafe/.test(policy),
      `served page: index.html comes with its Content-Security-Policy: ${policy}`);
    const icon = await fetch(url + 'favicon.ico');
    check(icon.status === 200 && /^image\//.test(icon.headers.get('content-type')),
      `served page: /favicon.ico is ${icon.status} ${icon.headers.get('content-type')}`);
    const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
    const errors = await watch(page);
    await page.goto(url);
    await hostilePage(page, 'hostile names (served)');
    check(errors.length === 0, `hostile names (served): no error in the page, nor CSP violation ${errors.join('; ')}`);
    await page.close();
  } finally {
    server.kill('SIGINT');
  }

  const file = path.join(scratch, 'hostile.html');
  execFileSync(binary, ['view', dir, '--export', file], { stdio: 'ignore' });
  const html = fs.readFileSync(file, 'utf8');
  const home = path.resolve(scratch);
  check(/<meta http-equiv="Content-Security-Policy" content="default-src 'none'; script-src 'sha256-[A-Za-z0-9+/=]+'/.test(html)
    && !/unsafe/.test(html.match(/<meta http-equiv="Content-Security-Policy"[^>]*>/)[0]),
  'hostile export: the file carries a Content-Security-Policy that runs only its own script, by its hash');
  check(!html.includes(home), `hostile export: it names no path of this machine (${home})`);
  check(HOSTILE.every((h) => !html.includes(h)) && !html.includes('<img'),
    'hostile export: no name stands in it unescaped (the run is JSON data with every < written \\u003c)');
  const context = await browser.newContext({ viewport: { width: 1100, height: 700 } });
  await context.route('**/*', (route) => (route.request().url().startsWith('file:') ? route.continue() : route.abort()));
  const page = await context.newPage();
  const errors = await watch(page);
  await page.goto('file://' + file);
  await hostilePage(page, 'hostile names (export)');
  check(errors.length === 0, `hostile names (export): no error in the page, nor CSP violation ${errors.join('; ')}`);
  await context.close();
}

async function main() {
  if (!fs.existsSync(CHROMIUM)) throw new Error(`${CHROMIUM} is missing: install Debian's chromium (make deps)`);
  const runs = [
    ['soft 2D', 2, softConfig(2)], ['soft 3D', 3, softConfig(3)],
    ['event 2D', 2, gasConfig(2, 'event')], ['stepped 3D', 3, gasConfig(3, 'stepped')],
  ];
  fs.rmSync(scratch, { recursive: true, force: true });
  fs.mkdirSync(scratch, { recursive: true });
  for (const [name, , config] of runs) {
    const file = path.join(scratch, `${name.replace(' ', '_')}.toml`);
    fs.writeFileSync(file, config);
    execFileSync(binary, ['run', file, '--out', path.join(scratch, name.replace(' ', '_'))],
      { stdio: ['ignore', 'ignore', 'inherit'], env: { ...process.env, OMP_NUM_THREADS: '1' } });
  }
  const browser = await chromium.launch({ executablePath: CHROMIUM, headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
  try {
    for (const [name, dimension] of runs)
      await checkRun(browser, name, dimension, path.join(scratch, name.replace(' ', '_')));
    await checkExport(browser, path.join(scratch, 'soft_2D'));
    await checkOwnColumn(browser);
    await checkScenery(browser);
    await checkHostile(browser);
    await checkLive(browser);
    await checkLiveEvent(browser);
  } finally {
    await browser.close();
  }
  await checkBadRequests(path.join(scratch, 'soft_2D'));
  console.log(failures ? `${failures} check(s) failed` : 'all checks passed');
  process.exit(failures ? 1 : 0);
}

main().catch((e) => { console.error(e); process.exit(1); });
