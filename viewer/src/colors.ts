// One palette for the 3D view, the plots and the legends, so a colour means the same thing
// everywhere: ω amber, L magenta, principal axes 1/2/3 red/green/blue (as x/y/z conventionally are).

export const COLORS = {
  omega: '#ffb300',
  L: '#e040fb',
  axes: ['#ff5252', '#69f0ae', '#448aff'] as const,
  background: '#1d2026',
};

/** Body i's colour: hues a golden angle apart never repeat and stay far apart for a few bodies. */
export function bodyColor(i: number): string {
  const hue = Math.round(((0.08 + i * 0.381966) % 1) * 360);
  return `hsl(${hue}, 55%, 58%)`;
}
