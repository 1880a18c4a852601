// The studio's latency: how long a parameter change takes to show its new
// plot and mesh in the page (docs/studio.md), in headless Chromium.
//   node bench/studio_latency.mjs [path/to/fabmesh] [CHANGES]
// For the golden cup (height), the CNC countertop (length) and the wash
// basin (its shell thickness, made a parameter in a copy), it starts
// `fabmesh studio --no-open`, opens the page, and moves the slider CHANGES
// times (default 50), each time to a new value, waiting for the page to show
// the new proven plot and mesh before the next. Prints, per design, the
// median, p95 and largest time from the slider's input event to the frame
// after the mesh's signature changed in the page (the request, the server's
// build, the plot's SVG, the GLB fetched and parsed, the scene drawn), and
// the server's own build_ms; for a design that gets drafts, both the time to
// the draft shown and to the proven mesh shown. Then the medians of the
// page's own times (window.fabmeshStudio.timings) and of the server's stages.
// Environment: STUDIO_DESIGNS=golden,basin (only the designs whose file names
// have one of these words), STUDIO_TRACE=DIR (a Chromium trace per design),
// STUDIO_TIMES=1 (every time, in the order measured).

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
console.log(`design                            changes  median ms  p95 ms  max ms  server build_ms (median)  WebGL`);
console.log(`load average: ${os.loadavg().map((x) => x.toFixed(2)).join(' ')}`);
// STUDIO_DESIGNS=golden,basin: only the designs whose file names have one of these words.
const only = process.env.STUDIO_DESIGNS?.split(',');
for (const d of designs.filter((x) => !only || only.some((w) => x.file.includes(w)))) {
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
  // The server's time of each answer (build_ms), and its parts: the job's
  // stages (report.timings_ms) and the studio's own (stages_ms).
  const buildMs = [], draftMs = [];
  const stages = {};
  page.on('response', async (r) => {
    if (!r.url().endsWith('/api/build') || r.status() !== 200) return;
    const answer = await r.json();
    (answer.draft ? draftMs : buildMs).push(answer.build_ms);
    const prefix = answer.draft ? 'draft.' : '';
    for (const [stage, ms] of Object.entries({...answer.report?.timings_ms, ...answer.stages_ms}))
      (stages[prefix + stage] ??= []).push(ms);
  });
  await page.goto(url);
  await page.waitForFunction(() => window.fabmeshStudio?.mesh, {timeout: 300000});
  const times = [], provenTimes = [];
  const phases = {};  // the page's own times of each change (window.fabmeshStudio.timings)
  if (process.env.STUDIO_TRACE) await page.tracing.start({path: `${process.env.STUDIO_TRACE}/${d.file}.json`});
  for (let i = 0; i < changes; ++i) {
    const value = d.lo + ((d.hi - d.lo) * ((i * 7) % changes + 1)) / (changes + 1);
    const ms = await page.evaluate(async (field, v) => {
      const s = window.fabmeshStudio;
      const before = s.meshSignature;
      const input = document.querySelector(`#field-${field} input[type=range]`);
      const frame = () => new Promise((r) => requestAnimationFrame(r));
      const start = performance.now();
      input.value = String(v);
      input.dispatchEvent(new Event('input'));
      const change = s.change;  // undefined for a page without drafts
      // First the new mesh, draft or proven, in the frame that shows it.
      while (s.meshSignature === before && !s.error) await frame();
      if (s.error) throw new Error(s.error.message);
      await frame();
      const shown = performance.now() - start;
      // Then the proven mesh and its verdict (the same when no draft came first).
      while (change !== undefined && s.provenChange < change && !s.error) await frame();
      if (s.error) throw new Error(s.error.message);
      if (change !== undefined && s.draft) throw new Error('a draft is still shown');
      const proven = performance.now() - start;
      return {shown, proven, timings: s.timings};
    }, d.field, value);
    times.push(ms.shown);
    provenTimes.push(ms.proven);
    for (const [phase, t] of Object.entries(ms.timings ?? {})) (phases[phase] ??= []).push(t);
  }
  if (process.env.STUDIO_TRACE) await page.tracing.stop();
  const rendered = await page.evaluate(() => window.fabmeshStudio.rendered);
  const sorted = (v) => [...v].sort((a, b) => a - b);
  const row = (name, v, server) => {
    const t = sorted(v), b = sorted(server);
    console.log(`${name.padEnd(34)}${String(t.length).padStart(7)}  ${quantile(t, 0.5).toFixed(1).padStart(9)}` +
                `  ${quantile(t, 0.95).toFixed(1).padStart(6)}  ${t[t.length - 1].toFixed(1).padStart(6)}` +
                `  ${(b.length ? quantile(b, 0.5).toFixed(1) : '-').padStart(24)}  ${rendered}`);
  };
  if (process.env.STUDIO_TIMES) console.log(JSON.stringify({shown: times.map(Math.round), proven: provenTimes.map(Math.round)}));
  if (draftMs.length > 0) {
    row(`${d.file} (draft)`, times, draftMs);
    row(`${d.file} (proven)`, provenTimes, buildMs);
  } else {
    row(d.file, times, buildMs);
  }
  // Where the time goes (medians): the page's times from the request, and the server's stages.
  const medians = (o) => Object.entries(o).map(([k, v]) => `${k} ${quantile(sorted(v), 0.5).toFixed(1)}`);
  console.log(`  page, proven build (ms from the request): ${medians(phases).join(', ')}`);
  console.log(`  server stages (ms): ${medians(stages).join(', ')}`);
  await page.close();
  server.kill('SIGTERM');
  await new Promise((r) => server.on('exit', r));
}
await browser.close();
fs.rmSync(work, {recursive: true, force: true});
