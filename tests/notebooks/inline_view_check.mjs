// An executed notebook's HTML (nbconvert) in Debian's chromium, headless: every inline
// view of pedesis.show draws its particles: inside each view's iframe, the view's picture
// (what its screenshot button saves) must hold at least MIN_PIXELS pixels of the first
// species' colour (#1f77b4), and the page must raise no error.
//   node inline_view_check.mjs WEB_VIEWER_DIR NOTEBOOK.html MIN_PIXELS
import { createRequire } from 'node:module';
import path from 'node:path';

const [webDir, htmlFile, minPixelsText] = process.argv.slice(2);
const require = createRequire(path.resolve(webDir, 'package.json'));
const { chromium } = require('playwright-core');
const minPixels = Number(minPixelsText);

const browser = await chromium.launch({ executablePath: '/usr/bin/chromium', headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
let failures = 0;
try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  // nothing from the network: the notebook's HTML and its views must work offline
  await page.route(/^https?:/, (route) => route.abort());
  await page.goto('file://' + path.resolve(htmlFile));
  const frames = async () => page.frames().filter((f) => f !== page.mainFrame());
  const deadline = Date.now() + 60000;
  while ((await frames()).length === 0 && Date.now() < deadline) await page.waitForTimeout(200);
  const views = await frames();
  if (views.length === 0) { console.log('FAILED: no inline view in the page'); failures++; }
  for (const [k, frame] of views.entries()) {
    // (Chromium does not lay out or draw an iframe off screen)
    const element = await frame.frameElement();
    await element.scrollIntoViewIfNeeded();
    let blue = 0;
    while (Date.now() < deadline) {
      blue = await frame.evaluate(async () => {
        // the view as its screenshot button saves it (WebGL and the disks' canvas together)
        if (!window.pedesisView) return 0;
        const img = new Image();
        img.src = window.pedesisView.pictureUrl();
        await img.decode();
        const c = document.createElement('canvas');
        c.width = img.width; c.height = img.height;
        const g = c.getContext('2d');
        g.drawImage(img, 0, 0);
        const d = g.getImageData(0, 0, c.width, c.height).data;
        let n = 0;
        for (let i = 0; i < d.length; i += 4)
          if (Math.abs(d[i] - 0x1f) < 8 && Math.abs(d[i + 1] - 0x77) < 8 && Math.abs(d[i + 2] - 0xb4) < 8) n++;
        return n;
      }).catch(() => 0);
      if (blue >= minPixels) break;
      await page.waitForTimeout(250);
    }
    const ok = blue >= minPixels;
    console.log(`${ok ? 'ok' : 'FAILED'}: inline view ${k}: ${blue} pixels of the first species' colour (at least ${minPixels})`);
    if (!ok) failures++;
  }
  for (const e of errors) { console.log('FAILED: page error:', e); failures++; }
} finally {
  await browser.close();
}
process.exit(failures ? 1 : 0);
