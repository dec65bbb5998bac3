// The playback controls and keyboard shortcuts. The controls only talk to the Playback clock and
// mirror its state; what to draw at a time is main.ts's business.

import { bodyPicker, CROWD } from './bodypicker';
import { COLORS } from './colors';
import { lSource } from './derived';
import { FOLLOW_ALL, FREE_CAMERA } from './framing';
import { SPEEDS, type Playback } from './playback';
import type { Report } from './types';

function el<K extends keyof HTMLElementTagNameMap>(tag: K, props: Partial<HTMLElementTagNameMap[K]> = {}): HTMLElementTagNameMap[K] {
  return Object.assign(document.createElement(tag), props);
}

export const HELP =
  'Keys: Space play/pause · ←/→ previous/next sample · Home/End start/end · +/− speed. ' +
  'Drag in the view to orbit (right-drag pans, wheel zooms). In a plot: click to seek, drag to zoom, double-click to zoom out.';

export function formatSpeed(s: number): string {
  return `${s}×`;
}

export interface ControlsOptions {
  onTrails: (on: boolean) => void;
  onFollow: (body: number) => void;
  /** What the camera follows at first: a body's index, FOLLOW_ALL or FREE_CAMERA (framing.ts). */
  follow: number;
}

export class Controls {
  private playButton: HTMLButtonElement;
  private scrubber: HTMLInputElement;
  private readout: HTMLSpanElement;
  private speed: HTMLSelectElement;
  private scrubbing = false;

  constructor(
    root: HTMLElement,
    report: Report,
    private playback: Playback,
    opts: ControlsOptions,
  ) {
    const tl = playback.timeline;
    const row = el('div', { className: 'controls-row' });

    this.playButton = el('button', { className: 'play', title: 'play/pause (Space)' });
    this.playButton.addEventListener('click', () => playback.toggle());
    const prev = el('button', { textContent: '◀︎|', title: 'previous sample (←)' });
    prev.addEventListener('click', () => playback.stepBack());
    const next = el('button', { textContent: '|▶︎', title: 'next sample (→)' });
    next.addEventListener('click', () => playback.stepForward());

    // step="any": the scrubber reaches every time, not only a grid of steps.
    this.scrubber = el('input', { type: 'range', className: 'scrubber', step: 'any', title: 'time' });
    this.scrubber.min = String(tl.start);
    this.scrubber.max = String(tl.end);
    // While dragged, the slider is the source of the time: do not write its value back under the
    // pointer (the release may land outside it, hence the window listener).
    this.scrubber.addEventListener('pointerdown', () => (this.scrubbing = true));
    window.addEventListener('pointerup', () => (this.scrubbing = false));
    this.scrubber.addEventListener('input', () => playback.seek(Number(this.scrubber.value)));

    this.readout = el('span', { className: 'readout' });

    this.speed = el('select', { title: 'playback speed (+/−)' });
    SPEEDS.forEach((s, i) => this.speed.appendChild(el('option', { value: String(i), textContent: formatSpeed(s) })));
    this.speed.addEventListener('change', () => playback.setSpeedIndex(Number(this.speed.value)));

    row.append(this.playButton, prev, next, this.scrubber, this.readout, this.speed);

    const row2 = el('div', { className: 'controls-row' });
    const trailsLabel = el('label');
    const trails = el('input', { type: 'checkbox' });
    trails.addEventListener('change', () => opts.onTrails(trails.checked));
    trailsLabel.append(trails, ' trails');
    // A crowd draws axes, arrows and the trail of the followed body only (scene3d.ts).
    if (report.bodies.length > CROWD) trailsLabel.title = "the followed body's trail (one of a crowd)";

    const followLabel = el('label', { textContent: 'follow ' });
    const cameras = [{ index: FREE_CAMERA, label: '— free camera —', typed: '' }];
    if (report.bodies.length > 1) cameras.push({ index: FOLLOW_ALL, label: '— all bodies —', typed: 'all' });
    followLabel.appendChild(bodyPicker(report, opts.follow, opts.onFollow, 'follow', cameras));

    const legend = el('span', { className: 'legend' });
    const key = (color: string, text: string) => {
      const k = el('span', { className: 'key', textContent: `━ ${text}` });
      k.style.color = color;
      return k;
    };
    // Only the vectors this report has (ω and L need optional series).
    if (report.series.omega_world || report.series.omega_principal) legend.append(key(COLORS.omega, 'ω'), ' ');
    if (report.bodies.some((_, i) => lSource(report, i) !== null)) legend.append(key(COLORS.L, 'L'), ' ');
    legend.append('principal axes ', ...COLORS.axes.map((c, k) => key(c, String(k + 1))));
    row2.append(trailsLabel, followLabel, legend);

    const help = el('div', { className: 'help', textContent: HELP });
    root.append(row, row2, help);

    playback.subscribe(() => this.refresh());
    this.refresh();
  }

  /** Mirrors the clock: button label, slider, time text, speed. */
  refresh(): void {
    const p = this.playback;
    this.playButton.textContent = p.playing ? '❚❚ pause' : '▶︎ play';
    if (!this.scrubbing) this.scrubber.value = String(p.time);
    const tl = p.timeline;
    const { i } = tl.locate(p.time);
    this.readout.textContent = `t = ${p.time.toFixed(3)} s / ${tl.end.toFixed(3)} s · sample ${i + 1} of ${tl.count}`;
    if (this.speed.value !== String(p.speedIndex)) this.speed.value = String(p.speedIndex);
  }
}

/** Space, ←/→, Home/End, +/−: on the whole page, except while typing in a text field. */
export function installKeys(playback: Playback): void {
  document.addEventListener('keydown', (e) => {
    const target = e.target as HTMLElement | null;
    if (target && (target.tagName === 'TEXTAREA' || (target.tagName === 'INPUT' && (target as HTMLInputElement).type === 'text'))) return;
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    let handled = true;
    switch (e.key) {
      case ' ':
        playback.toggle();
        break;
      case 'ArrowLeft':
        playback.stepBack();
        break;
      case 'ArrowRight':
        playback.stepForward();
        break;
      case 'Home':
        playback.toStart();
        break;
      case 'End':
        playback.toEnd();
        break;
      case '+':
      case '=':
        playback.faster();
        break;
      case '-':
      case '_':
        playback.slower();
        break;
      default:
        handled = false;
    }
    if (handled) {
      e.preventDefault();
      // A focused button would also "click" on Space; blur keeps one action per key press.
      if (target instanceof HTMLButtonElement || target instanceof HTMLSelectElement) target.blur();
    }
  });
}
