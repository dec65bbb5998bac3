import { describe, expect, it } from 'vitest';
import { Playback, SPEEDS } from '../src/playback';
import { Timeline } from '../src/timeline';

const make = () => new Playback(new Timeline([0, 1, 2, 3, 4]));

describe('Playback', () => {
  it('advances by wall time times speed, 1x being real time', () => {
    const p = make();
    p.play();
    p.tick(1000); // first tick only starts the clock
    p.tick(1100);
    expect(p.time).toBeCloseTo(0.1, 12);
    p.setSpeedIndex(SPEEDS.indexOf(10));
    p.tick(1200);
    expect(p.time).toBeCloseTo(1.1, 12);
  });

  it('caps a long gap (hidden tab) and stops at the end', () => {
    const p = make();
    p.play();
    p.tick(0);
    p.tick(60_000);
    expect(p.time).toBeCloseTo(0.25, 12);
    p.setSpeedIndex(SPEEDS.length - 1);
    for (let k = 1; k < 10; k++) p.tick(60_000 + 250 * k);
    expect(p.time).toBe(4);
    expect(p.playing).toBe(false);
    p.play(); // from the end: again from the start
    expect(p.time).toBe(0);
  });

  it('clamps seeks, steps by samples and changes speed within the list', () => {
    const p = make();
    p.seek(9);
    expect(p.time).toBe(4);
    p.seek(1.5);
    p.stepForward();
    expect(p.time).toBe(2);
    p.seek(1.5);
    p.stepBack();
    expect(p.time).toBe(1);
    p.stepBack();
    expect(p.time).toBe(0);
    expect(p.speed).toBe(1);
    for (let k = 0; k < 20; k++) p.faster();
    expect(p.speed).toBe(10);
    for (let k = 0; k < 20; k++) p.slower();
    expect(p.speed).toBe(0.1);
  });

  it('notifies listeners and pauses when stepping', () => {
    const p = make();
    let calls = 0;
    p.subscribe(() => calls++);
    p.play();
    p.stepForward();
    expect(p.playing).toBe(false);
    expect(calls).toBeGreaterThanOrEqual(2);
  });
});
