#!/usr/bin/env node
// make-report.mjs DATA.json OUT.html [TEMPLATE.html]
// Builds a report from a JSON data file the way the C++ CLI will (scripts/inject.mjs), from the
// built template (default: dist/report.html next to this script's package).

import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { injectReport } from './inject.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const [data, out, template = resolve(here, '../dist/report.html')] = process.argv.slice(2);
if (!data || !out) {
  console.error('usage: node scripts/make-report.mjs DATA.json OUT.html [TEMPLATE.html]');
  process.exit(2);
}
const json = readFileSync(data, 'utf8');
// Fail here on malformed JSON rather than in the browser.
JSON.parse(json);
writeFileSync(out, injectReport(readFileSync(template, 'utf8'), json));
console.log(`wrote ${out}`);
