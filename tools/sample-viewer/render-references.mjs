#!/usr/bin/env node
// Renders tests/data/sample-viewer/<Model>.png (and tonemap-none/<Model>.png) with the Khronos glTF
// Sample Viewer in Debian's headless Chromium, using the cameras and lights of views.json.
// Usage: node render-references.mjs [--assets DIR] [--out DIR] [--only Name[,Name...]] [--keep-going]
// See docs/SAMPLE_VIEWER.md.
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { expandInstancing, injectView } from './gltf-util.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const arg = (name, def) => { const i = process.argv.indexOf(name); return i > 0 ? process.argv[i + 1] : def; };
const assets = path.resolve(arg('--assets', path.resolve(here, '../../../shared/assets')));
const outDir = path.resolve(arg('--out', path.resolve(here, '../../tests/data/sample-viewer')));
const only = arg('--only', null)?.split(',');
const keepGoing = process.argv.includes('--keep-going');
const chromiumPath = process.env.CHROMIUM ?? '/usr/bin/chromium';
const viewerDist = path.join(here, 'node_modules/@khronosgroup/gltf-viewer/dist');
const pageDir = path.join(here, 'page');
const manifest = JSON.parse(fs.readFileSync(path.join(here, 'views.json'), 'utf8'));
const TONEMAP_NEUTRAL = 'Khronos PBR Neutral';
const TONEMAP_NONE = 'None (Linear mapping, clamped at 1.0)';

// ---------- PNG (8-bit RGB, no ancillary chunks) ----------
const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});
function crc32(buf) {
  let c = 0xffffffff;
  for (const b of buf) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}
function chunk(type, data) {
  const len = Buffer.alloc(4); len.writeUInt32BE(data.length);
  const td = Buffer.concat([Buffer.from(type, 'ascii'), data]);
  const crc = Buffer.alloc(4); crc.writeUInt32BE(crc32(td));
  return Buffer.concat([len, td, crc]);
}
// rgba: WebGL readPixels order (bottom row first) -> PNG rows top to bottom, alpha dropped
function encodePng(rgba, w, h) {
  const raw = Buffer.alloc((w * 3 + 1) * h);
  for (let y = 0; y < h; ++y) {
    const src = (h - 1 - y) * w * 4, dst = y * (w * 3 + 1);
    raw[dst] = 0;
    for (let x = 0; x < w; ++x) {
      raw[dst + 1 + x * 3] = rgba[src + x * 4];
      raw[dst + 2 + x * 3] = rgba[src + x * 4 + 1];
      raw[dst + 3 + x * 3] = rgba[src + x * 4 + 2];
    }
  }
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(w, 0); ihdr.writeUInt32BE(h, 4);
  ihdr[8] = 8; ihdr[9] = 2; ihdr[10] = 0; ihdr[11] = 0; ihdr[12] = 0;
  return Buffer.concat([
    Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]),
    chunk('IHDR', ihdr), chunk('IDAT', zlib.deflateSync(raw, { level: 9 })), chunk('IEND', Buffer.alloc(0)),
  ]);
}

// ---------- LICENSE.md of the output folder, from each model's metadata.json ----------
function writeLicense() {
  const lines = [
    '# Licences of the reference images in this folder',
    '',
    'Each `<Model>.png` (and `tonemap-none/<Model>.png`) is a render, made by `tools/sample-viewer/render-references.mjs`',
    'with the Khronos glTF Sample Viewer, of the Khronos glTF sample model of the same name (copied in',
    '`shared/assets/<Model>/`). A render is an adaptation of the model, so each image is under the licence of its',
    'model, listed below from the model\'s `metadata.json` (see also its `LICENSE.md`; licence texts in',
    '`shared/assets/LICENSES/`). CC-BY-4.0 models need credit to their owners wherever their images are shown;',
    'LicenseRef-CC-BY-TM is CC-BY-4.0 with Cesium\'s trademark limitations (the Cesium logo is not licensed as a mark).',
    '`views.json`, the scripts and this file are part of fe.',
    '',
    '| Image | Licence (SPDX) | Credit: owner (artist), year: what |',
    '| --- | --- | --- |',
  ];
  for (const view of manifest.models) {
    const metaPath = path.join(assets, view.name, 'metadata.json');
    const legal = fs.existsSync(metaPath) ? JSON.parse(fs.readFileSync(metaPath, 'utf8')).legal ?? [] : [];
    const spdx = [...new Set(legal.map(l => l.spdx ?? l.license))].join(', ') || 'see LICENSE.md';
    const credit = legal.map(l => `${l.owner}${l.artist && l.artist !== l.owner ? ` (${l.artist})` : ''}, ${l.year}: ${l.what}`).join('; ');
    lines.push(`| ${view.reference} | ${spdx} | ${credit.replace(/\|/g, '\\|')} |`);
  }
  lines.push('');
  fs.writeFileSync(path.join(outDir, 'LICENSE.md'), lines.join('\n'));
}

// ---------- local HTTP server: page, viewer bundle, assets, and the per-model edited .gltf ----------
const virtualFiles = new Map();          // URL path -> Buffer (the edited glTF JSON)
const MIME = {
  '.html': 'text/html; charset=utf-8', '.mjs': 'text/javascript', '.js': 'text/javascript', '.wasm': 'application/wasm',
  '.json': 'application/json', '.gltf': 'model/gltf+json', '.bin': 'application/octet-stream', '.glb': 'model/gltf-binary',
  '.png': 'image/png', '.jpg': 'image/jpeg', '.jpeg': 'image/jpeg', '.webp': 'image/webp', '.ktx2': 'image/ktx2',
};
function resolveUnder(root, rel) {
  const p = path.resolve(root, '.' + path.posix.normalize('/' + rel));
  return p === root || p.startsWith(root + path.sep) ? p : null;
}
const server = http.createServer((req, res) => {
  let pathname;
  try { pathname = decodeURIComponent(new URL(req.url, 'http://x').pathname); } catch { res.writeHead(400); res.end(); return; }
  const send = (status, body, type) => { res.writeHead(status, { 'Content-Type': type ?? 'text/plain', 'Cache-Control': 'no-store' }); res.end(body); };
  if (virtualFiles.has(pathname)) return send(200, virtualFiles.get(pathname), MIME['.gltf']);
  let file = null;
  if (pathname === '/' || pathname === '/index.html') file = path.join(pageDir, 'index.html');
  else if (pathname.startsWith('/page/')) file = resolveUnder(pageDir, pathname.slice(6));
  else if (pathname === '/render-page.mjs') file = path.join(pageDir, 'render-page.mjs');
  else if (pathname.startsWith('/viewer/')) file = resolveUnder(viewerDist, pathname.slice(8));
  else if (pathname.startsWith('/assets/')) file = resolveUnder(assets, pathname.slice(8));
  if (!file || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
    if (pathname !== '/favicon.ico') console.warn(`  404 ${pathname}`);
    return send(404, 'not found');
  }
  send(200, fs.readFileSync(file), MIME[path.extname(file).toLowerCase()] ?? 'application/octet-stream');
});
await new Promise(r => server.listen(0, '127.0.0.1', r));
const base = `http://127.0.0.1:${server.address().port}`;
const urlOf = p => base + p.split('/').map(encodeURIComponent).join('/');

// ---------- Chromium ----------
const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'fe-sample-viewer-'));
const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath: chromiumPath,
  headless: true,
  viewport: { width: 320, height: 240 },
  deviceScaleFactor: 1,
  args: [
    '--no-sandbox', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync',
    '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
    '--force-color-profile=srgb',
  ],
});

// A black 16x8 Radiance panorama (flat RGBE scanlines) for the environment the renderer insists on,
// and a 1x1 black PNG for the sheen-E LUT (the npm package does not ship the viewer app's LUT images;
// only KHR_materials_sheen reads it, and no model here uses sheen).
function blackHdr(w = 16, h = 8) {
  return Buffer.concat([Buffer.from(`#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y ${h} +X ${w}\n`, 'ascii'), Buffer.alloc(w * h * 4)]);
}
virtualFiles.set('/fe/black.hdr', blackHdr());
virtualFiles.set('/fe/lut_sheen_E_placeholder.png', encodePng(new Uint8Array(4), 1, 1));

fs.mkdirSync(path.join(outDir, 'tonemap-none'), { recursive: true });
writeLicense();
let failures = 0, rendered = 0;
const log = [];
const page = await context.newPage();
let consoleLines = [];
page.on('console', m => { if (m.type() === 'error' || m.type() === 'warning') consoleLines.push(`${m.type()}: ${m.text()}`); });
page.on('pageerror', e => consoleLines.push(`pageerror: ${e.message}`));
// the KTX/Draco "could not initialise" lines are expected (see page/index.html)
const noise = /KTXDecoder|DracoDecoder|draco library|ktx library/i;
try {
  await page.goto(base + '/index.html');
  await page.waitForFunction(() => window.feReady === true, null, { timeout: 60000 });
  const init = await page.evaluate(i => window.feInit(i), { envUrl: base + '/fe/black.hdr', sheenLutUrl: base + '/fe/lut_sheen_E_placeholder.png' });
  console.log(`renderer: ${init.renderer}; environment prefiltered in ${init.environmentSeconds.toFixed(1)} s; devicePixelRatio ${init.devicePixelRatio}`);
  const initMessages = consoleLines.filter(l => !noise.test(l));
  if (initMessages.length) console.log(`  ${initMessages.join('\n  ')}`);
  for (const view of manifest.models) {
    if (only && !only.includes(view.name)) continue;
    consoleLines = [];
    const t0 = Date.now();
    const gltfPath = path.join(assets, view.gltf);
    const json = JSON.parse(fs.readFileSync(gltfPath, 'utf8'));
    expandInstancing(json, path.dirname(gltfPath));
    const injected = injectView(json, view);
    const vpath = '/assets/' + path.posix.join(path.posix.dirname(view.gltf), '__fe_reference_view.gltf');
    virtualFiles.set(vpath, Buffer.from(JSON.stringify(injected.json)));
    try {
      const result = await page.evaluate(opts => window.feRender(opts), {
        url: urlOf(vpath), sceneIndex: view.scene, cameraIndex: injected.cameraIndex, toneMaps: [TONEMAP_NEUTRAL, TONEMAP_NONE],
      });
      if (result.width !== manifest.image.width || result.height !== manifest.image.height)
        throw new Error(`canvas is ${result.width}x${result.height}`);
      for (const img of result.images) {
        const png = encodePng(Buffer.from(img.rgba, 'base64'), result.width, result.height);
        const rel = img.toneMap === TONEMAP_NEUTRAL ? view.reference : view.referenceToneMapNone;
        fs.writeFileSync(path.join(outDir, rel), png);
      }
      const rgba = Buffer.from(result.images[0].rgba, 'base64');
      let lit = 0;
      for (let i = 0; i < rgba.length; i += 4) if (rgba[i] | rgba[i + 1] | rgba[i + 2]) ++lit;
      const messages = consoleLines.filter(l => !noise.test(l));
      console.log(`${view.name}: ${((Date.now() - t0) / 1000).toFixed(1)} s, ${(100 * lit / (rgba.length / 4)).toFixed(1)}% non-black, `
        + `repeat ${result.repeatIdentical ? 'identical' : 'DIFFERS'}, ${result.stats?.faceCount ?? '?'} faces`
        + (messages.length ? `\n    ${messages.join('\n    ')}` : ''));
      log.push({ name: view.name, nonBlack: lit, repeatIdentical: result.repeatIdentical, messages });
      if (lit === 0) console.warn(`  WARNING ${view.name}: the image is all black`);
      ++rendered;
    } catch (e) {
      ++failures;
      console.error(`${view.name}: FAILED: ${e.message}\n    ${consoleLines.join('\n    ')}`);
      if (!keepGoing) throw e;
    } finally {
      virtualFiles.delete(vpath);
    }
  }
} finally {
  await page.close();
  await context.close();
  server.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}
console.log(`${rendered} rendered, ${failures} failed, into ${outDir}`);
process.exit(failures ? 1 : 0);
