// node sha256.mjs FILE...: writes FILE.sha256 next to each FILE, holding the CSP source
// expression of its bytes ('sha256-' and the base64 of their SHA-256), with which the
// single file of `pedesis view --export` allows its inline script and style
// (src/pedesis/view/export_page.cpp).
import { createHash } from 'node:crypto';
import fs from 'node:fs';

for (const file of process.argv.slice(2))
  fs.writeFileSync(`${file}.sha256`, `sha256-${createHash('sha256').update(fs.readFileSync(file)).digest('base64')}`);
