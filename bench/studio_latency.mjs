// The studio's latency: how long a parameter change takes to show its new
// plot and mesh in the page (docs/studio.md), in headless Chromium.
//   node bench/studio_latency.mjs [path/to/fabmesh] [CHANGES]
// For the golden cup (height), the CNC countertop (length) and the wash
// basin (its shell thickness, made a parameter in a copy), it starts
// `fabmesh studio --no-open`, opens the page, and moves the slider CHANGES
// times (default 50), each time to a new value, waiting for the page to show
// the new plot and mesh before the next. Prints, per design, the median, p95
// and largest time from the slider's input event to the mesh's signature
// changing in the page (the request, the server's build, the plot's SVG, the
// GLB fetched and parsed, the scene drawn), and the server's own build_ms.

import {spawn} from 'node:child_process';
import fs from 'node:fs';
import {createRequire} from 'node:module';
import os from 'node:os';
import path from 'node:path';
import {fileURLToPath} from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const fabmesh = process.argv[2] ?? path.join(root, 'build/pipeline/fabmesh');
const changes = Number(process.argv[3] ?? 50);
const puppeteer = createRequire(path.join(root, 'tools/node/package.json'))('puppeteer-core');
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'fabmesh-studio-bench-'));
const example = (name) => fs.readFileSync(path.join(root, 'configs/examples', name), 'utf8');

const basin = example('surface_basin_shell.yaml')
                  .replace('thickness: 6', 'thickness: "=shell"')
                  .replace('kind: surface\n', 'kind: surface\nparameters:\n  shell: {value: 6, min: 3, max: 12, step: 0.5}\n');
const designs = [
  {file: 'vessel_golden_solid.yaml', text: example('vessel_golden_solid.yaml'), field: 'height', lo: 3, hi: 6},
  {file: 'countertop_cnc.yaml', text: example('countertop_cnc.yaml'), field: 'length', lo: 2000, hi: 3000},
  {file: 'surface_basin_shell.yaml', text: basin, field: 'shell', lo: 4, hi: 10},
];

const quantile = (sorted, q) => sorted[Math.min(sorted.length - 1, Math.ceil(q * sorted.length) - 1)];

const browser = await puppeteer.launch({
  executablePath: '/usr/bin/chromium', headless: true,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
         '--disable-background-networking', '--disable-component-update', '--disable-sync',
         '--use-angle=swiftshader', '--enable-unsafe-swiftshader', `--user-data-dir=${path.join(work, 'profile')}`],
});
console.log(`design                      changes  median ms  p95 ms  max ms  server build_ms (median)  WebGL`);
for (const d of designs) {
  const file = path.join(work, d.file);
  fs.writeFileSync(file, d.text);
  const server = spawn(fabmesh, ['studio', '--no-open', file, '-o', path.join(work, 'out')],
                       {stdio: ['ignore', 'pipe', 'inherit']});
  const url = await new Promise((resolve) => {
    let out = '';
    server.stdout.on('data', (x) => { out += x; if (out.includes('\n')) resolve(out.split('\n')[0]); });
  });
  const page = await browser.newPage();
  await page.setViewport({width: 1400, height: 900});
  // The server's build time of each answer.
  const buildMs = [];
  page.on('response', async (r) => {
    if (r.url().endsWith('/api/build') && r.status() === 200) buildMs.push((await r.json()).build_ms);
  });
  await page.goto(url);
  await page.waitForFunction(() => window.fabmeshStudio?.mesh, {timeout: 300000});
  const times = [];
  for (let i = 0; i < changes; ++i) {
    const value = d.lo + ((d.hi - d.lo) * ((i * 7) % changes + 1)) / (changes + 1);
    const ms = await page.evaluate(async (field, v) => {
      const s = window.fabmeshStudio;
      const before = s.meshSignature;
      const input = document.querySelector(`#field-${field} input[type=range]`);
      const start = performance.now();
      input.value = String(v);
      input.dispatchEvent(new Event('input'));
      while (s.meshSignature === before && !s.error) await new Promise((r) => requestAnimationFrame(r));
      if (s.error) throw new Error(s.error.message);
      await new Promise((r) => requestAnimationFrame(r));  // the frame that shows it
      return performance.now() - start;
    }, d.field, value);
    times.push(ms);
  }
  const rendered = await page.evaluate(() => window.fabmeshStudio.rendered);
  times.sort((a, b) => a - b);
  buildMs.sort((a, b) => a - b);
  console.log(`${d.file.padEnd(28)}${String(changes).padStart(7)}  ${quantile(times, 0.5).toFixed(1).padStart(9)}` +
              `  ${quantile(times, 0.95).toFixed(1).padStart(6)}  ${times[times.length - 1].toFixed(1).padStart(6)}` +
              `  ${quantile(buildMs, 0.5).toFixed(1).padStart(24)}  ${rendered}`);
  await page.close();
  server.kill('SIGTERM');
  await new Promise((r) => server.on('exit', r));
}
await browser.close();
fs.rmSync(work, {recursive: true, force: true});
