// Choosing a body: a list of their names, or, for a crowd, a field that takes a body's name or number.
// A <select> of 10⁵ options made every layout of the page take seconds (13 s before the first frame).

import type { Report } from './types';

/** Above this many bodies the page treats them as a crowd (instanced drawing, a field to pick one). */
export const CROWD = 1000;

/** A choice besides the bodies (a negative index): its label in the list, and what is typed for it in a crowd's field. */
export interface Choice {
  index: number;
  label: string;
  typed: string;
}

/**
 * A control that calls onPick(b) with the chosen body's index, or a choice's; `selected` is the
 * index chosen at first.
 */
export function bodyPicker(
  report: Report,
  selected: number,
  onPick: (b: number) => void,
  className: string,
  choices: Choice[] = [],
): HTMLSelectElement | HTMLInputElement {
  const names = report.bodies.map((b) => b.name);
  if (names.length <= CROWD) {
    const select = document.createElement('select');
    select.className = className;
    for (const c of choices) select.appendChild(new Option(c.label, String(c.index), c.index === selected, c.index === selected));
    names.forEach((n, i) => select.appendChild(new Option(n, String(i), i === selected, i === selected)));
    select.addEventListener('change', () => onPick(Number(select.value)));
    return select;
  }
  const input = document.createElement('input');
  input.type = 'text';
  input.className = className;
  input.placeholder = `a body's name or number (0–${names.length - 1})`;
  const hint = choices.map((c) => (c.typed ? `"${c.typed}": ${c.label}` : `empty: ${c.label}`)).join(', ');
  input.title = hint;
  input.value = selected >= 0 ? names[selected] : (choices.find((c) => c.index === selected)?.typed ?? '');
  let index: Map<string, number> | null = null; // built on first use
  input.addEventListener('change', () => {
    const text = input.value.trim();
    index ??= new Map(names.map((n, i) => [n, i]));
    let b = index.get(text);
    if (b === undefined && /^\d+$/.test(text) && Number(text) < names.length) b = Number(text);
    if (b === undefined) b = choices.find((c) => c.typed === text.toLowerCase())?.index;
    const ok = b !== undefined;
    input.classList.toggle('invalid', !ok);
    input.title = ok ? hint : `no body is named or numbered "${text}"${hint ? ` (${hint})` : ''}`;
    if (ok) {
      if (b! >= 0) input.value = names[b!];
      onPick(b!);
    }
  });
  return input;
}
