#!/usr/bin/env node
// Browser tests: the built report in headless Chromium, opened from file:// as a user would.
//
//   node tests/browser.mjs [REPORT.html]      (or TUMBLE_REPORT=REPORT.html)
//
// With a report, checks that report (as the C++ CLI made it). Without, builds reports from
// dist/report.html (running `npm run build` if it is missing) and a SYNTHETIC data set whose
// orientations are known in closed form (tests/synthetic.mjs), and also checks the raw template,
// a malformed report and a 1e5-sample report (size and time to ready).
//
// Ends with "N passed, M failed" and exits non-zero on any failure.

import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { launch } from '../scripts/chromium.mjs';
import { injectReport } from '../scripts/inject.mjs';
import { expectedQuaternion, syntheticReport } from './synthetic.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const outDir = resolve(root, 'test-output');
const template = resolve(root, 'dist/report.html');
const BACKGROUND = [0x1d, 0x20, 0x26]; // src/colors.ts COLORS.background

let passed = 0;
let failed = 0;
function check(name, ok, detail = '') {
  if (ok) passed++;
  else failed++;
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${name}${detail ? ` — ${detail}` : ''}`);
}

/** The report's JSON, read back out of the HTML the way the page reads it. */
function embeddedJson(html) {
  const m = html.match(/<script id="tumble-data" type="application\/json">([\s\S]*?)<\/script>/);
  if (!m) throw new Error('no data element');
  return JSON.parse(m[1]);
}

function decode(a) {
  const b = Buffer.from(a.base64, 'base64');
  const buf = b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength);
  return { f32: new Float32Array(buf), f64: new Float64Array(buf), u32: new Uint32Array(buf) }[a.dtype];
}

/** 1 - |<a, b>| after normalising both: 0 for the same rotation whatever the sign. */
function quatError(a, b) {
  const na = Math.hypot(...a);
  const nb = Math.hypot(...b);
  const dot = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]) / (na * nb);
  // Component-wise distance up to sign: more sensitive than 1 - |dot| for small errors.
  const plus = Math.max(...a.map((x, i) => Math.abs(x / na - b[i] / nb)));
  const minus = Math.max(...a.map((x, i) => Math.abs(x / na + b[i] / nb)));
  return dot >= 0 ? plus : minus;
}

/** Opens a report and records console errors and any request that is not file: or data:. */
async function open(context, file, fragment = '') {
  const page = await context.newPage();
  const errors = [];
  const external = [];
  page.on('console', (m) => {
    if (m.type() === 'error') errors.push(m.text());
  });
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('request', (r) => {
    const u = r.url();
    if (!u.startsWith('file:') && !u.startsWith('data:')) external.push(u);
  });
  const started = Date.now();
  // 'commit': do not wait for the load event, poll for "ready" from the start.
  await page.goto(pathToFileURL(file).href + fragment, { waitUntil: 'commit' });
  await page.waitForFunction(() => window.__tumble && (window.__tumble.ready || window.__tumble.error !== null), null, {
    timeout: 60000,
    polling: 20,
  });
  const readyMs = Date.now() - started;
  return { page, errors, external, readyMs };
}

const frames = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

/** Grabs the 3D canvas (after the next frames) under `key`; returns how much of it is not background. */
async function grab(page, key) {
  await frames(page);
  return page.evaluate(
    ({ key, bg }) => {
      const c = document.querySelector('#view canvas');
      const cv = document.createElement('canvas');
      cv.width = c.width;
      cv.height = c.height;
      const ctx = cv.getContext('2d');
      ctx.drawImage(c, 0, 0);
      const d = ctx.getImageData(0, 0, cv.width, cv.height).data;
      (window.__grabs ||= {})[key] = d;
      let nonBackground = 0;
      const colors = new Set();
      for (let i = 0; i < d.length; i += 4) {
        if (Math.abs(d[i] - bg[0]) + Math.abs(d[i + 1] - bg[1]) + Math.abs(d[i + 2] - bg[2]) > 12) nonBackground++;
        if (colors.size < 5000) colors.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
      }
      return { width: cv.width, height: cv.height, nonBackground, colors: colors.size };
    },
    { key, bg: BACKGROUND },
  );
}

const pixelsDiffering = (page, a, b) =>
  page.evaluate(
    ({ a, b }) => {
      const x = window.__grabs[a];
      const y = window.__grabs[b];
      let n = 0;
      for (let i = 0; i < x.length; i += 4) if (Math.abs(x[i] - y[i]) + Math.abs(x[i + 1] - y[i + 1]) + Math.abs(x[i + 2] - y[i + 2]) > 12) n++;
      return n;
    },
    { a, b },
  );

/** Every check that holds for any report; `synthetic` adds the closed-form ones. */
async function checkReport(context, file, { synthetic = false } = {}) {
  const html = readFileSync(file, 'utf8');
  const data = embeddedJson(html);
  const t = decode(data.t);
  const T = t.length;
  const N = data.bodies.length;
  const q = decode(data.series.quaternion);
  const t0 = t[0];
  const tEnd = t[T - 1];

  const { page, errors, external } = await open(context, file);
  const state = await page.evaluate(() => ({ ready: window.__tumble.ready, error: window.__tumble.error }));
  check('report loads from file:// and gets ready', state.ready && state.error === null, JSON.stringify(state));
  if (!state.ready) return;

  // The canvas draws something, and something else at another time.
  const first = await grab(page, 'start');
  // Flat shading without antialiasing (software GL) draws a lone body in a handful of colours.
  check('3D canvas is not blank', first.nonBackground > 0.005 * first.width * first.height && first.colors >= 4,
    `${first.nonBackground} of ${first.width * first.height} pixels drawn, ${first.colors} colours`);
  await page.evaluate((x) => window.__tumble.seek(x), t0 + 0.37 * (tEnd - t0));
  await grab(page, 'later');
  const changed = await pixelsDiffering(page, 'start', 'later');
  check('pixels change when seeking', changed > 100, `${changed} pixels differ`);

  // The orientation drawn is the data's, at samples and (synthetic) between them.
  let worst = 0;
  const picks = [...new Set([0, 1, Math.floor(T / 3), Math.floor(T / 2) + 1, T - 2, T - 1])].filter((k) => k >= 0 && k < T);
  // Every body of a few; of a crowd, the first, the last and some between (a call per body).
  const bodies = N <= 50 ? [...Array(N).keys()] : [0, 1, Math.floor(N / 3), Math.floor(N / 2) + 7, N - 2, N - 1];
  for (const k of picks) {
    await page.evaluate((x) => window.__tumble.seek(x), t[k]);
    for (const b of bodies) {
      const drawn = await page.evaluate((i) => window.__tumble.bodyQuaternion(i), b);
      const stored = Array.from(q.subarray((k * N + b) * 4, (k * N + b) * 4 + 4));
      worst = Math.max(worst, quatError(drawn, stored));
    }
  }
  check('bodyQuaternion at sample times equals the data (float32, sign-insensitive)', worst < 2e-6, `max error ${worst.toExponential(2)}`);
  if (synthetic) {
    let worstBetween = 0;
    for (let k = 0; k < 25; k++) {
      const x = t0 + ((k + 0.5) / 25) * (tEnd - t0) + 0.123 * (tEnd - t0) / T;
      await page.evaluate((v) => window.__tumble.seek(v), x);
      const drawn = await page.evaluate(() => window.__tumble.bodyQuaternion(0));
      worstBetween = Math.max(worstBetween, quatError(drawn, expectedQuaternion(x)));
    }
    check('bodyQuaternion between samples equals the closed form (slerp)', worstBetween < 2e-6, `max error ${worstBetween.toExponential(2)}`);
  }

  // A crowd (10⁵ bodies, rendered in software here at seconds a frame): what is its own is checked
  // above; the controls, plots and fragments are the same code as for every other report.
  if (N > 1000) {
    check('no console errors', errors.length === 0, errors.slice(0, 3).join(' | '));
    check('no network requests', external.length === 0, external.slice(0, 3).join(' '));
    await page.close();
    return;
  }

  // Plots: one point per sample shown.
  const plots = await page.evaluate(() => {
    const h = window.__tumble;
    return Array.from({ length: h.plotCount() }, (_, i) => h.plotPointCount(i));
  });
  const shown = data.meta?.samples_shown ?? T;
  check('every plot has as many points as samples shown', plots.length > 0 && plots.every((n) => n === shown && n === T),
    `${plots.length} plots: [${plots.join(', ')}], samples_shown ${shown}, T ${T}`);
  if (synthetic) check('all five plots are shown', plots.length === 5, `${plots.length}`);

  // Clicking a plot seeks there.
  await page.evaluate(() => window.__tumble.pause());
  const over = page.locator('.plot .u-over').first();
  await over.scrollIntoViewIfNeeded();
  const box = await over.boundingBox();
  await page.mouse.click(box.x + box.width * 0.7, box.y + box.height * 0.5);
  const clicked = await page.evaluate(() => window.__tumble.time());
  const expected = t0 + 0.7 * (tEnd - t0);
  check('clicking a plot seeks to the clicked time', Math.abs(clicked - expected) < 0.02 * (tEnd - t0),
    `clicked ${clicked.toFixed(4)} s, expected about ${expected.toFixed(4)} s`);

  // Paused: the fragment follows the time, so the link can be copied.
  await page.evaluate((x) => window.__tumble.seek(x), t[Math.floor(T / 4)]);
  await page.waitForTimeout(400);
  const hash = await page.evaluate(() => location.hash);
  check('the fragment is updated while paused', hash === `#t=${t[Math.floor(T / 4)]}`, hash);

  // Keys: → steps to the next sample, Space plays and pauses.
  await page.evaluate((x) => window.__tumble.seek(x), t[2]);
  await page.keyboard.press('ArrowRight');
  const stepped = await page.evaluate(() => window.__tumble.time());
  await page.keyboard.press('Home');
  const home = await page.evaluate(() => window.__tumble.time());
  check('→ steps to the next sample, Home to the start', stepped === t[Math.min(3, T - 1)] && home === t0, `${stepped}, ${home}`);
  await page.keyboard.press('Space');
  await page.waitForTimeout(400);
  const during = await page.evaluate(() => window.__tumble.time());
  await page.keyboard.press('Space');
  const after1 = await page.evaluate(() => window.__tumble.time());
  await page.waitForTimeout(200);
  const after2 = await page.evaluate(() => window.__tumble.time());
  check('Space plays (time advances) and pauses (time stops)', during > t0 && after1 === after2, `${during}, ${after1}, ${after2}`);

  check('no console errors', errors.length === 0, errors.slice(0, 3).join(' | '));
  check('no network requests', external.length === 0, external.slice(0, 3).join(' '));
  await page.close();

  // The camera keeps the bodies in view over the whole run (a lone body is followed, several are kept
  // in view together when they leave their start): opened at several times, every body's centre of
  // mass is drawn inside the view, and the view is not empty.
  for (const f of [0.05, 0.35, 0.65, 1]) {
    const at = t[Math.min(T - 1, Math.round(f * (T - 1)))];
    const opened = await open(context, file, `#t=${at}`);
    const outside = [];
    for (const b of bodies) {
      const [x, y, z] = await opened.page.evaluate((i) => window.__tumble.bodyOnScreen(i), b);
      if (!(Math.abs(x) <= 1 && Math.abs(y) <= 1 && z > -1 && z < 1)) outside.push(`${data.bodies[b].name} at (${x.toFixed(2)}, ${y.toFixed(2)}, ${z.toFixed(2)})`);
    }
    const drawn = await grab(opened.page, `at-${f}`);
    check(`at #t=${at} every body is in view`, outside.length === 0 && drawn.nonBackground > 0.001 * drawn.width * drawn.height,
      `${outside.length ? `outside: ${outside.slice(0, 3).join(', ')}; ` : ''}${drawn.nonBackground} pixels drawn`);
    await opened.page.close();
  }

  // #t= opens paused at that time; &play=1 plays from there.
  const at = t[Math.floor(T / 2)];
  const paused = await open(context, file, `#t=${at}`);
  const p0 = await paused.page.evaluate(() => window.__tumble.time());
  await paused.page.waitForTimeout(300);
  const p1 = await paused.page.evaluate(() => window.__tumble.time());
  const pq = await paused.page.evaluate(() => window.__tumble.bodyQuaternion(0));
  const k = Math.floor(T / 2);
  check('#t= opens paused at that time', p0 === at && p1 === at && quatError(pq, Array.from(q.subarray(k * N * 4, k * N * 4 + 4))) < 2e-6,
    `${p0} then ${p1}, wanted ${at}`);
  await paused.page.close();
  const playing = await open(context, file, `#t=${t0 + 0.1 * (tEnd - t0)}&play=1`);
  await playing.page.waitForTimeout(400);
  const pl = await playing.page.evaluate(() => window.__tumble.time());
  check('#t=…&play=1 plays from there', pl > t0 + 0.1 * (tEnd - t0), `${pl}`);
  check('no console errors with a fragment', paused.errors.length + playing.errors.length === 0, [...paused.errors, ...playing.errors].join(' | '));
  await playing.page.close();
}

/** When the page set "ready", from the start of navigation, by the page's own clock. */
function pageReadyMs(page) {
  return page.evaluate(() => {
    const m = performance.getEntriesByName('tumble:ready')[0];
    return m ? Math.round(m.startTime + m.duration) : Infinity;
  });
}

async function main() {
  const given = process.argv[2] || process.env.TUMBLE_REPORT;
  const { context, close } = await launch();
  try {
    if (given) {
      await checkReport(context, resolve(given));
      // TUMBLE_REPORT_READY_MS: how soon the report must be ready (the CLI's 1e5-sample test).
      const limit = Number(process.env.TUMBLE_REPORT_READY_MS || 0);
      if (limit > 0) {
        const { page, readyMs } = await open(context, resolve(given));
        const pageMs = await pageReadyMs(page);
        check(`the report is ready in under ${limit} ms`, pageMs < limit, `ready at ${pageMs} ms after navigation start (test waited ${readyMs} ms)`);
        await page.close();
      }
      return;
    }
    if (!existsSync(template)) {
      console.log('dist/report.html missing: building it');
      execFileSync('npm', ['run', 'build'], { cwd: root, stdio: 'inherit' });
    }
    mkdirSync(outDir, { recursive: true });
    const tpl = readFileSync(template, 'utf8');
    check('the built template holds the placeholder exactly once', tpl.split('__TUMBLE_DATA__').length === 2);
    check('the built template references nothing outside itself',
      !/<(script|link)[^>]+(src|href)="(?!data:)/i.test(tpl) && !/sourceMappingURL/.test(tpl));

    // The raw template: a friendly message, not a blank page or an error.
    {
      const { page, errors, external } = await open(context, template);
      const msg = await page.evaluate(() => ({ text: document.getElementById('message').textContent, hidden: document.getElementById('message').hidden }));
      check('the raw template says it has no data', !msg.hidden && msg.text === 'no data: this is the report template', JSON.stringify(msg));
      check('the raw template: no console errors or requests', errors.length === 0 && external.length === 0, [...errors, ...external].join(' | '));
      await page.close();
    }

    // A report that breaks the contract: the reason on the page.
    {
      const bad = syntheticReport({ T: 20 });
      bad.series.position.dtype = 'f16';
      const file = resolve(outDir, 'bad.html');
      writeFileSync(file, injectReport(tpl, JSON.stringify(bad)));
      const { page } = await open(context, file);
      const r = await page.evaluate(() => ({ error: window.__tumble.error, text: document.getElementById('message').textContent }));
      check('a malformed report shows the reason on the page', /series\.position: unknown dtype "f16"/.test(r.text) && r.error !== null, r.text);
      await page.close();
    }

    // Only what the contract requires (t, position, quaternion): the bodies, no plots, no errors.
    {
      const j = syntheticReport({ T: 50 });
      for (const k of ['omega_world', 'omega_principal']) delete j.series[k];
      delete j.system;
      delete j.events;
      const file = resolve(outDir, 'minimal.html');
      writeFileSync(file, injectReport(tpl, JSON.stringify(j)));
      const { page, errors, external } = await open(context, file);
      const r = await page.evaluate(() => ({
        ready: window.__tumble.ready,
        plots: window.__tumble.plotCount(),
        section: document.getElementById('plots-section').hidden,
      }));
      const drawn = await grab(page, 'minimal');
      check('a minimal report draws its bodies and hides the plots', r.ready && r.plots === 0 && r.section && drawn.nonBackground > 1000,
        `${JSON.stringify(r)}, ${drawn.nonBackground} pixels drawn`);
      check('a minimal report: no console errors or requests', errors.length + external.length === 0, [...errors, ...external].join(' | '));
      await page.close();
    }

    // The synthetic T-handle with a particle on a spring: every check.
    {
      const file = resolve(outDir, 'synthetic.html');
      writeFileSync(file, injectReport(tpl, JSON.stringify(syntheticReport({ T: 501, duration: 10, samplesTotal: 10001 }))));
      await checkReport(context, file, { synthetic: true });
      const { page } = await open(context, file);
      const note = await page.evaluate(() => document.querySelector('.samples-note')?.textContent);
      check('the facts say when samples were thinned', note === 'showing 501 of 10,001 samples', String(note));
      await page.close();
    }

    // 1e5 samples: small enough to mail, quick enough to open.
    {
      const file = resolve(outDir, 'large.html');
      writeFileSync(file, injectReport(tpl, JSON.stringify(syntheticReport({ T: 100000, duration: 1000, particle: false }))));
      const mb = statSync(file).size / 1e6;
      check('a 1e5-sample report is under 20 MB', mb < 20, `${mb.toFixed(1)} MB`);
      const { page, errors, readyMs } = await open(context, file);
      // When the page set "ready", from the start of navigation by the page's own clock (file read
      // and HTML parse included). The wall time the test waited is printed too: it also holds the
      // browser's own work after that (compositing the first frame), and its polling.
      const pageMs = await pageReadyMs(page);
      check('a 1e5-sample report is ready in under 3 s', pageMs < 3000, `ready at ${pageMs} ms after navigation start (test waited ${readyMs} ms)`);
      const counts = await page.evaluate(() => Array.from({ length: window.__tumble.plotCount() }, (_, i) => window.__tumble.plotPointCount(i)));
      check('a 1e5-sample report plots every sample', counts.length === 5 && counts.every((n) => n === 100000), counts.join(', '));
      check('a 1e5-sample report: no console errors', errors.length === 0, errors.join(' | '));
      await page.close();
    }
  } finally {
    await close();
  }
}

try {
  await main();
} catch (e) {
  failed++;
  console.log(`FAIL ${e.stack || e}`);
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
