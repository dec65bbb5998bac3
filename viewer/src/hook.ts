// window.__tumble: the handle the browser tests (and anyone at the devtools console) use to drive the
// report and read back what it draws. bodyQuaternion reads the three.js object, not the data, so a
// test comparing it with the data checks the whole path (decoding, w-first order, interpolation).

import type { QuatWXYZ } from './types';

export interface TumbleHook {
  /** True once the data are decoded, the scene and plots built and the first frame drawn. */
  ready: boolean;
  time(): number;
  seek(t: number): void;
  play(): void;
  pause(): void;
  /** Body i's orientation as drawn, [w, x, y, z]. */
  bodyQuaternion(i: number): QuatWXYZ;
  /** Body i's centre of mass as drawn, in normalised device coordinates: on screen when |x|, |y| ≤ 1. */
  bodyOnScreen(i: number): [number, number, number];
  /** Points in plot i (the samples shown) and the number of plots shown. */
  plotPointCount(plotIndex: number): number;
  plotCount(): number;
  /** Why the report cannot be shown (also on the page), or null. */
  error: string | null;
}

declare global {
  interface Window {
    __tumble: TumbleHook;
  }
}

const notReady = (): never => {
  throw new Error('the report is not ready');
};

/** Installed at once (not ready, no error), so a test can poll it from the first moment. */
export function installHook(): TumbleHook {
  const hook: TumbleHook = {
    ready: false,
    error: null,
    time: notReady,
    seek: notReady,
    play: notReady,
    pause: notReady,
    bodyQuaternion: notReady,
    bodyOnScreen: notReady,
    plotPointCount: notReady,
    plotCount: notReady,
  };
  window.__tumble = hook;
  return hook;
}
