// Entry point: reads the embedded data, builds the views and ties them to one playback clock.
// Every failure ends in a message on the page (and in window.__tumble.error), never a blank page.

import { bodyPicker } from './bodypicker';
import './style.css';
import { bodyColor } from './colors';
import { readEmbedded } from './data';
import { buildFacts } from './facts';
import { formatFragment, parseFragment } from './fragment';
import { defaultFollow, runFraming } from './framing';
import { installHook } from './hook';
import { Playback } from './playback';
import { Plots } from './plots';
import { Scene3D } from './scene3d';
import { Timeline } from './timeline';
import type { Report } from './types';
import { Controls, installKeys } from './ui';

const TEMPLATE_MESSAGE = 'no data: this is the report template';

const hook = installHook();

function showMessage(text: string, kind: 'info' | 'error'): void {
  const box = document.getElementById('message')!;
  box.className = kind;
  box.textContent = text;
  box.hidden = false;
}

function fail(message: string): void {
  hook.error = message;
  showMessage(`This report cannot be shown: ${message}`, 'error');
  console.warn(`tumble report: ${message}`);
}

/** The first rigid body (the ω plots have nothing to show for a particle), else body 0. */
function defaultPlotBody(r: Report): number {
  const i = r.bodies.findIndex((b) => b.kind === 'body');
  return i < 0 ? 0 : i;
}

/**
 * Writes "#t=…" for the paused time, at most every 250 ms: dragging the slider would otherwise call
 * replaceState hundreds of times a second, which browsers throttle with a console warning.
 */
function fragmentWriter(): (t: number) => void {
  let timer: ReturnType<typeof setTimeout> | null = null;
  let pending = 0;
  return (t: number) => {
    pending = t;
    if (timer !== null) return;
    timer = setTimeout(() => {
      timer = null;
      const hash = formatFragment(pending);
      if (location.hash === hash) return;
      try {
        history.replaceState(history.state, '', hash);
      } catch {
        // Some browsers refuse history changes on file:// pages; the link is then just not updated.
      }
    }, 250);
  };
}

function start(report: Report): void {
  performance.mark('tumble:start');
  document.getElementById('app')!.hidden = false;
  const scenePath = report.meta.scene_path;
  document.getElementById('title-scene')!.textContent = scenePath ? `— ${scenePath}` : '';
  if (scenePath) document.title = `tumble report — ${scenePath}`;

  const timeline = new Timeline(report.t);
  const framing = runFraming(report);
  const follow = defaultFollow(report, framing);
  const playback = new Playback(timeline);
  let scene: Scene3D | null = null;

  // The text parts first: the canvas and the plots are sized to the layout they leave, and a later
  // change of layout would redraw every plot (1e5 points each) a second time.
  buildFacts(document.getElementById('facts')!, report, (t) => playback.seek(t), bodyColor);
  new Controls(document.getElementById('controls')!, report, playback, {
    onTrails: (on) => scene?.setTrails(on),
    onFollow: (b) => scene?.setFollow(b),
    follow,
  });
  installKeys(playback);
  let plotBody = defaultPlotBody(report);
  const hasOmegaPlots = !!(report.series.omega_world || report.series.omega_principal);
  let plots: Plots | null = null;
  if (hasOmegaPlots && report.bodies.length > 1) {
    const label = document.createElement('label');
    label.textContent = 'ω plots for ';
    const pick = (b: number) => {
      plotBody = b;
      plots?.setBody(plotBody);
    };
    label.appendChild(bodyPicker(report, plotBody, pick, 'plot-body'));
    document.getElementById('plots-header')!.appendChild(label);
  }

  const viewEl = document.getElementById('view')!;
  try {
    scene = new Scene3D(viewEl, report, framing);
    scene.setFollow(follow);
  } catch (e) {
    // No WebGL (blocked, or a machine without it): the plots and facts still work.
    const note = document.createElement('div');
    note.className = 'view-error';
    note.textContent = `3D view unavailable: ${(e as Error).message}`;
    viewEl.appendChild(note);
  }
  const timeLabel = document.createElement('div');
  timeLabel.className = 'time-label';
  viewEl.appendChild(timeLabel);
  performance.measure('tumble:scene', 'tumble:start');

  performance.mark('tumble:plots');
  plots = new Plots(document.getElementById('plots')!, report, (t) => playback.seek(t), plotBody);
  // A report with none of the plotted series (they are optional) shows no empty plot area.
  if (plots.count() === 0) document.getElementById('plots-section')!.hidden = true;
  performance.measure('tumble:plots', 'tumble:plots');

  const writeFragment = fragmentWriter();
  let started = false;
  // Everything that depends on the time, applied synchronously so that a seek is visible to the
  // next read of window.__tumble (the frame itself is drawn on the next animation frame).
  const apply = () => {
    const seg = timeline.locate(playback.time);
    scene?.update(seg);
    plots!.setTime(playback.time);
    timeLabel.textContent = `t = ${playback.time.toFixed(3)} s`;
    if (started && !playback.playing) writeFragment(playback.time);
  };
  playback.subscribe(apply);

  const openAt = (hash: string) => {
    const f = parseFragment(hash);
    if (f.t !== null) playback.seek(f.t);
    if (f.play) playback.play();
    else playback.pause();
  };
  openAt(location.hash);
  apply();
  window.addEventListener('hashchange', () => openAt(location.hash));

  hook.time = () => playback.time;
  hook.seek = (t) => playback.seek(t);
  hook.play = () => playback.play();
  hook.pause = () => playback.pause();
  hook.bodyQuaternion = (i) => {
    if (!scene) throw new Error('no 3D view');
    return scene.bodyQuaternion(i);
  };
  hook.bodyOnScreen = (i) => {
    if (!scene) throw new Error('no 3D view');
    return scene.bodyOnScreen(i);
  };
  hook.plotCount = () => plots!.count();
  hook.plotPointCount = (i) => plots!.pointCount(i);

  // The first frame is drawn now, not on the first animation frame (which waits for the layout of
  // the whole page): "ready" then means the canvas shows the opening time.
  scene?.render(true);
  started = true;
  // uPlot draws in microtasks queued when the plots were made; this one runs after them, so
  // "ready" also means the plots are drawn.
  queueMicrotask(() => {
    hook.ready = true;
    performance.measure('tumble:ready', 'tumble:start');
  });

  const loop = (now: number) => {
    playback.tick(now);
    scene?.render();
    requestAnimationFrame(loop);
  };
  requestAnimationFrame(loop);
}

function main(): void {
  let embedded;
  try {
    performance.mark('tumble:read');
    const element = document.getElementById('tumble-data');
    embedded = readEmbedded(element?.textContent);
    // The text (tens of MB for a long run) is decoded now; dropping it halves the page's memory.
    if (element && embedded.kind === 'report') element.textContent = '';
    performance.measure('tumble:read', 'tumble:read');
  } catch (e) {
    fail(`internal error while reading the data: ${(e as Error).message}`);
    console.error(e);
    return;
  }
  if (embedded.kind === 'template') {
    hook.error = TEMPLATE_MESSAGE;
    showMessage(TEMPLATE_MESSAGE, 'info');
    return;
  }
  if (embedded.kind === 'error') {
    fail(embedded.message);
    return;
  }
  try {
    start(embedded.report);
  } catch (e) {
    fail(`internal error: ${(e as Error).message}`);
    console.error(e);
  }
}

main();
