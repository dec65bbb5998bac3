// The URL fragment: `#t=SECONDS` opens the report paused at that time, `#t=SECONDS&play=1` plays from
// there. A fragment (not a query) because it works from file:// and never reloads the page.

export interface FragmentState {
  /** Playback time in seconds, or null when the fragment names none (or an unreadable one). */
  t: number | null;
  play: boolean;
}

/** Parses "#t=1.5&play=1" (with or without the '#'); unknown keys are ignored. */
export function parseFragment(hash: string): FragmentState {
  const text = hash.startsWith('#') ? hash.slice(1) : hash;
  const params = new URLSearchParams(text);
  const raw = params.get('t');
  let t: number | null = null;
  if (raw !== null && raw.trim() !== '') {
    const v = Number(raw);
    if (Number.isFinite(v)) t = v;
  }
  const play = params.get('play');
  return { t, play: play === '1' || play === 'true' };
}

/**
 * "#t=…" for a time. String(t) is the shortest text that reads back as the same double, so a copied
 * link seeks to exactly the same frame (and a sample time such as 4.6 stays "4.6").
 */
export function formatFragment(t: number, play = false): string {
  return `#t=${String(t)}${play ? '&play=1' : ''}`;
}
