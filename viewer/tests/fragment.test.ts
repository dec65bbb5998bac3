import { describe, expect, it } from 'vitest';
import { formatFragment, parseFragment } from '../src/fragment';

describe('URL fragment', () => {
  it('reads t and play', () => {
    expect(parseFragment('#t=2.5')).toEqual({ t: 2.5, play: false });
    expect(parseFragment('#t=2.5&play=1')).toEqual({ t: 2.5, play: true });
    expect(parseFragment('play=1&t=1e-3')).toEqual({ t: 0.001, play: true });
    expect(parseFragment('')).toEqual({ t: null, play: false });
    expect(parseFragment('#')).toEqual({ t: null, play: false });
  });

  it('ignores what it cannot read', () => {
    expect(parseFragment('#t=abc')).toEqual({ t: null, play: false });
    expect(parseFragment('#t=')).toEqual({ t: null, play: false });
    expect(parseFragment('#t=Infinity')).toEqual({ t: null, play: false });
    expect(parseFragment('#t=1&play=0&x=y')).toEqual({ t: 1, play: false });
  });

  it('writes a fragment that reads back as the same time', () => {
    for (const t of [0, 4.6, 1 / 3, 1e-7, 12345.678901234]) {
      expect(parseFragment(formatFragment(t)).t).toBe(t);
    }
    expect(formatFragment(4.6)).toBe('#t=4.6');
    expect(formatFragment(1, true)).toBe('#t=1&play=1');
  });
});
