#!/usr/bin/env node
// screenshot.mjs REPORT.html OUT.png [#fragment]
// A PNG of a report as a person would see it (for docs), once it is ready and has drawn a frame.

import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { launch } from './chromium.mjs';

const [report, out, fragment = ''] = process.argv.slice(2);
if (!report || !out) {
  console.error('usage: node scripts/screenshot.mjs REPORT.html OUT.png [#fragment]');
  process.exit(2);
}
const url = pathToFileURL(resolve(report)).href + (fragment && !fragment.startsWith('#') ? `#${fragment}` : fragment);
const { context, close } = await launch();
try {
  const page = await context.newPage();
  page.on('console', (m) => m.type() === 'error' && console.error(`page: ${m.text()}`));
  await page.goto(url);
  await page.waitForFunction(() => window.__tumble && (window.__tumble.ready || window.__tumble.error), null, { timeout: 30000 });
  // Two animation frames: the one that draws the current time, then one more to be sure it is shown.
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.screenshot({ path: out, fullPage: true });
  console.log(`wrote ${out}`);
} finally {
  await close();
}
