// The facts panel: how the run was made (integrator, formulation, step, duration, wall time, tumble
// version), its warnings (highlighted: they say the numbers may not be trusted), the bodies, the
// events (click to seek) and the scene file itself (collapsed: it can be long).

import { CROWD } from './bodypicker';
import { samplesNote } from './derived';
import type { Report } from './types';

function el<K extends keyof HTMLElementTagNameMap>(tag: K, cls?: string, text?: string): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (text !== undefined) e.textContent = text;
  return e;
}

/** A number in 4 significant digits, exponential when tiny or huge (moments of inertia span both). */
export function formatNumber(v: number): string {
  if (!Number.isFinite(v)) return String(v);
  if (v === 0) return '0';
  const a = Math.abs(v);
  return a < 1e-3 || a >= 1e6 ? v.toExponential(3) : String(Number(v.toPrecision(4)));
}

/** Seconds for people: "1.5 ms", "12.3 s", "2 min 5 s". */
export function formatSeconds(s: number | null): string {
  if (s === null || !Number.isFinite(s)) return '–';
  if (s === 0) return '0 s';
  const a = Math.abs(s);
  if (a < 1e-3) return `${Number((s * 1e6).toPrecision(4))} µs`;
  if (a < 1) return `${Number((s * 1e3).toPrecision(4))} ms`;
  if (a < 120) return `${Number(s.toPrecision(4))} s`;
  const m = Math.floor(a / 60);
  return `${s < 0 ? '-' : ''}${m} min ${Math.round(a - 60 * m)} s`;
}

/** `colorOf(i)` is body i's CSS colour, the one it is drawn in. */
export function buildFacts(
  panel: HTMLElement,
  r: Report,
  onSeek: (t: number) => void,
  colorOf: (i: number) => string,
): void {
  const m = r.meta;
  panel.replaceChildren();
  panel.appendChild(el('h2', undefined, 'Run'));

  if (m.warnings.length) {
    const ul = el('ul', 'warnings');
    for (const w of m.warnings) ul.appendChild(el('li', 'warning', w));
    panel.appendChild(ul);
  }

  const dl = el('dl', 'facts-list');
  const add = (k: string, v: string) => {
    dl.appendChild(el('dt', undefined, k));
    dl.appendChild(el('dd', undefined, v));
  };
  add('scene', m.scene_path || '–');
  add('integrator', m.integrator);
  add('formulation', m.formulation);
  add('time step', formatSeconds(m.timestep));
  add('duration', formatSeconds(m.duration));
  add('wall time', formatSeconds(m.wall_time_s));
  add('tumble', m.tumble_version);
  add('samples', `${r.t.length.toLocaleString('en-US')}`);
  panel.appendChild(dl);
  const note = samplesNote(m);
  if (note) panel.appendChild(el('p', 'samples-note', note));

  panel.appendChild(el('h2', undefined, 'Bodies'));
  const table = el('table', 'bodies');
  const head = el('tr');
  for (const h of ['', 'name', 'kind', 'I₁, I₂, I₃ (kg m²)']) head.appendChild(el('th', undefined, h));
  table.appendChild(head);
  // A crowd's first CROWD rows: a table of 10⁵ rows made every layout of the page take seconds.
  r.bodies.slice(0, CROWD).forEach((b, i) => {
    const tr = el('tr');
    const sw = el('td');
    const swatch = sw.appendChild(el('span', 'swatch'));
    swatch.style.background = colorOf(i);
    tr.appendChild(sw);
    tr.appendChild(el('td', undefined, b.name));
    tr.appendChild(el('td', undefined, b.kind));
    tr.appendChild(el('td', 'num', b.kind === 'body' ? b.principal_moments.map(formatNumber).join(', ') : '–'));
    table.appendChild(tr);
  });
  panel.appendChild(table);
  if (r.bodies.length > CROWD) {
    const more = r.bodies.length - CROWD;
    panel.appendChild(
      el('p', 'samples-note', `… and ${more.toLocaleString('en-US')} more bodies: follow one by its name or number`),
    );
  }

  if (r.events.length) {
    panel.appendChild(el('h2', undefined, `Events (${r.events.length})`));
    const ul = el('ul', 'events');
    for (const e of r.events.slice(0, 500)) {
      const li = el('li');
      const a = el('button', 'linklike', `${e.name}${e.body === null ? '' : ` (${r.bodies[e.body]?.name})`}`);
      a.title = 'seek to this event';
      a.addEventListener('click', () => onSeek(e.t));
      li.appendChild(a);
      li.appendChild(el('span', 'event-time', ` t = ${formatSeconds(e.t)}`));
      ul.appendChild(li);
    }
    panel.appendChild(ul);
  }

  if (m.scene_text) {
    const details = el('details', 'scene');
    details.appendChild(el('summary', undefined, `Scene file ${m.scene_path}`));
    details.appendChild(el('pre', undefined, m.scene_text));
    panel.appendChild(details);
  }
}
