// The playback clock: the current time, playing or paused, and the speed (simulated seconds per wall
// second, so 1x is real time). It knows nothing of the DOM or three.js; the views subscribe to it
// and redraw when it changes. Advancing is driven by the render loop's timestamps, so a stalled tab
// resumes where it was instead of jumping.

import type { Timeline } from './timeline';

export const SPEEDS = [0.1, 0.25, 0.5, 1, 2, 5, 10] as const;

export type Listener = () => void;

export class Playback {
  private _time: number;
  private _playing = false;
  private _speedIndex = SPEEDS.indexOf(1);
  private lastWall: number | null = null;
  private listeners: Listener[] = [];

  constructor(readonly timeline: Timeline) {
    this._time = timeline.start;
  }

  get time(): number {
    return this._time;
  }
  get playing(): boolean {
    return this._playing;
  }
  get speed(): number {
    return SPEEDS[this._speedIndex];
  }
  get speedIndex(): number {
    return this._speedIndex;
  }

  /** Called on every change of time, play state or speed. */
  subscribe(f: Listener): void {
    this.listeners.push(f);
  }

  private emit(): void {
    for (const f of this.listeners) f();
  }

  seek(t: number): void {
    const tl = this.timeline;
    const clamped = Math.min(tl.end, Math.max(tl.start, Number.isFinite(t) ? t : tl.start));
    this._time = clamped;
    this.emit();
  }

  play(): void {
    if (this._playing) return;
    // Play at the end means play again from the start, as a video player does.
    if (this._time >= this.timeline.end) this._time = this.timeline.start;
    this._playing = true;
    this.lastWall = null;
    this.emit();
  }

  pause(): void {
    if (!this._playing) return;
    this._playing = false;
    this.emit();
  }

  toggle(): void {
    if (this._playing) this.pause();
    else this.play();
  }

  setSpeedIndex(i: number): void {
    this._speedIndex = Math.min(SPEEDS.length - 1, Math.max(0, i));
    this.emit();
  }

  faster(): void {
    this.setSpeedIndex(this._speedIndex + 1);
  }
  slower(): void {
    this.setSpeedIndex(this._speedIndex - 1);
  }

  stepForward(): void {
    this.pause();
    this.seek(this.timeline.t[this.timeline.nextIndex(this._time)]);
  }
  stepBack(): void {
    this.pause();
    this.seek(this.timeline.t[this.timeline.prevIndex(this._time)]);
  }
  toStart(): void {
    this.seek(this.timeline.start);
  }
  toEnd(): void {
    this.pause();
    this.seek(this.timeline.end);
  }

  /**
   * Advances by the wall time since the last tick (ms, e.g. a requestAnimationFrame timestamp). A
   * gap over 0.25 s (a hidden tab, a long GC) counts as 0.25 s so playback never leaps.
   */
  tick(wallMs: number): void {
    if (!this._playing) {
      this.lastWall = null;
      return;
    }
    if (this.lastWall === null) {
      this.lastWall = wallMs;
      return;
    }
    const dt = Math.min(0.25, Math.max(0, (wallMs - this.lastWall) / 1000));
    this.lastWall = wallMs;
    const next = this._time + dt * this.speed;
    if (next >= this.timeline.end) {
      this._time = this.timeline.end;
      this._playing = false;
    } else {
      this._time = next;
    }
    this.emit();
  }
}
