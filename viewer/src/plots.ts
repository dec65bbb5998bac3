// The linked uPlot time plots. All share the time axis: the cursor is synchronised, a drag zooms
// every plot to the same interval (double-click zooms back out), a vertical line marks the playback
// time, a click seeks playback there, and each event is a dashed line with a flag whose tooltip
// names it (clicking the flag seeks to the event).
//
// The playback line and the event marks are DOM elements over the plot, not canvas drawing: moving
// one costs a style write, where redrawing a canvas of 1e5 points every frame would not keep up.

import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import { formatTick, plotDefs, type PlotDef } from './plotdata';
import type { Report } from './types';

const PLOT_HEIGHT = 190;
const SYNC_KEY = 'tumble-time';
/** Event marks drawn per plot; beyond that they would only hide the curves. */
export const MAX_EVENT_MARKS = 200;

interface PlotView {
  def: PlotDef;
  u: uPlot;
  box: HTMLElement;
  playhead: HTMLDivElement;
  marks: { t: number; line: HTMLDivElement; flag: HTMLDivElement }[];
}

export class Plots {
  private views: PlotView[] = [];
  private time: number;
  private x: Float64Array | Float32Array;
  /** Set while one plot's zoom is copied to the others, so the copies do not echo back. */
  private syncingScale = false;
  private resizeObserver: ResizeObserver;

  constructor(
    private container: HTMLElement,
    private report: Report,
    private onSeek: (t: number) => void,
    body: number,
  ) {
    this.time = report.t[0];
    this.x = report.t;
    for (const def of plotDefs(report, body)) this.views.push(this.makePlot(def));
    this.resizeObserver = new ResizeObserver(() => this.resize());
    this.resizeObserver.observe(container);
  }

  private width(box: HTMLElement): number {
    return Math.max(200, Math.floor(box.clientWidth || this.container.clientWidth || 400));
  }

  private makePlot(def: PlotDef): PlotView {
    const box = document.createElement('div');
    box.className = 'plot';
    box.dataset.plot = def.id;
    const title = document.createElement('div');
    title.className = 'plot-title';
    title.textContent = def.title;
    box.appendChild(title);
    this.container.appendChild(box);

    const hasY2 = def.series.some((s) => s.scale === 'y2');
    const tickValues = (_u: uPlot, splits: number[]) => {
      const step = splits.length > 1 ? splits[1] - splits[0] : 0;
      return splits.map((v) => formatTick(v, step));
    };
    const axisStroke = '#aab2bf';
    const grid = { stroke: '#343a45', width: 1 };
    const opts: uPlot.Options = {
      width: this.width(box),
      height: PLOT_HEIGHT,
      // uPlot's "time" scale means dates; these are seconds of simulated time.
      scales: { x: { time: false }, y: { auto: true }, ...(hasY2 ? { y2: { auto: true } } : {}) },
      series: [
        { label: 't (s)', value: (_u, v) => (v == null ? '–' : v.toPrecision(6)) },
        ...def.series.map((s) => ({
          label: s.label,
          stroke: s.color,
          width: 1.5,
          scale: s.scale,
          spanGaps: false,
          points: { show: false },
          value: (_u: uPlot, v: number | null) => (v == null ? '–' : v.toPrecision(6)),
        })),
      ],
      axes: [
        { stroke: axisStroke, grid, ticks: grid, label: 't (s)', labelSize: 18, size: 36 },
        { stroke: axisStroke, grid, ticks: grid, label: def.yLabel, labelSize: 18, size: 64, values: tickValues },
        ...(hasY2
          ? [{ scale: 'y2', side: 1, stroke: axisStroke, grid: { show: false }, ticks: grid, label: def.y2Label, labelSize: 18, size: 64, values: tickValues }]
          : []),
      ],
      cursor: {
        sync: { key: SYNC_KEY, setSeries: false },
        drag: { x: true, y: false, setScale: true },
        points: { show: false },
      },
      legend: { live: true },
      hooks: {
        setScale: [(u, key) => key === 'x' && this.scaleChanged(u)],
        setSize: [(u) => this.placeOverlays(u)],
        ready: [(u) => this.placeOverlays(u)],
      },
    };
    const data: uPlot.AlignedData = [this.x, ...def.series.map((s) => s.values)] as uPlot.AlignedData;
    const u = new uPlot(opts, data, box);

    const playhead = document.createElement('div');
    playhead.className = 'playhead';
    u.over.appendChild(playhead);

    const marks = this.report.events.slice(0, MAX_EVENT_MARKS).map((e) => {
      const line = document.createElement('div');
      line.className = 'event-line';
      const flag = document.createElement('div');
      flag.className = 'event-flag';
      const who = e.body === null ? '' : ` (${this.report.bodies[e.body].name})`;
      flag.title = `${e.name}${who} at t = ${Number(e.t.toPrecision(6))} s`;
      flag.addEventListener('mousedown', (ev) => ev.stopPropagation());
      flag.addEventListener('click', (ev) => {
        ev.stopPropagation();
        this.onSeek(e.t);
      });
      u.over.appendChild(line);
      u.over.appendChild(flag);
      return { t: e.t, line, flag };
    });

    // Click (not drag: a drag zooms) to seek. uPlot listens on `over` too; a click that moved less
    // than a few pixels is a click.
    let downX: number | null = null;
    u.over.addEventListener('mousedown', (ev) => (downX = ev.clientX));
    u.over.addEventListener('click', (ev) => {
      if (downX !== null && Math.abs(ev.clientX - downX) > 3) return;
      const rect = u.over.getBoundingClientRect();
      const t = u.posToVal(ev.clientX - rect.left, 'x');
      if (Number.isFinite(t)) this.onSeek(t);
    });

    const view: PlotView = { def, u, box, playhead, marks };
    this.placeMarks(view);
    return view;
  }

  /** A zoom (or a zoom reset) of one plot's time axis applies to all of them. */
  private scaleChanged(src: uPlot): void {
    const view = this.views.find((v) => v.u === src);
    if (view) this.placeOverlays(src);
    if (this.syncingScale) return;
    const { min, max } = src.scales.x;
    if (min == null || max == null) return;
    this.syncingScale = true;
    try {
      for (const v of this.views) if (v.u !== src) v.u.setScale('x', { min, max });
    } finally {
      this.syncingScale = false;
    }
  }

  private placeOverlays(u: uPlot): void {
    const view = this.views.find((v) => v.u === u);
    if (!view) return;
    this.placeMarks(view);
    this.placePlayhead(view);
  }

  private placeMarks(view: PlotView): void {
    const { u } = view;
    const { min, max } = u.scales.x;
    for (const m of view.marks) {
      const inside = min != null && max != null && m.t >= min && m.t <= max;
      m.line.style.display = m.flag.style.display = inside ? '' : 'none';
      if (!inside) continue;
      const left = `${u.valToPos(m.t, 'x')}px`;
      m.line.style.left = left;
      m.flag.style.left = left;
    }
  }

  private placePlayhead(view: PlotView): void {
    const { u, playhead } = view;
    const { min, max } = u.scales.x;
    const inside = min != null && max != null && this.time >= min && this.time <= max;
    playhead.style.display = inside ? '' : 'none';
    if (inside) playhead.style.transform = `translateX(${u.valToPos(this.time, 'x')}px)`;
  }

  /** Moves the playback line of every plot to `t`. */
  setTime(t: number): void {
    this.time = t;
    for (const v of this.views) this.placePlayhead(v);
  }

  /** Shows body `b` in the per-body plots (ω), keeping the current zoom. */
  setBody(b: number): void {
    const defs = plotDefs(this.report, b);
    for (const v of this.views) {
      if (!v.def.perBody) continue;
      const def = defs.find((d) => d.id === v.def.id);
      if (!def) continue;
      v.def = def;
      v.box.querySelector('.plot-title')!.textContent = def.title;
      // New values need a new y range; the time axis keeps the zoom the user chose.
      const { min, max } = v.u.scales.x;
      v.u.setData([this.x, ...def.series.map((s) => s.values)] as uPlot.AlignedData);
      if (min != null && max != null) v.u.setScale('x', { min, max });
    }
  }

  resize(): void {
    for (const v of this.views) {
      const w = this.width(v.box);
      if (w !== v.u.width) v.u.setSize({ width: w, height: PLOT_HEIGHT });
    }
  }

  count(): number {
    return this.views.length;
  }

  /** Points in the i-th plot shown (the length of its time axis). */
  pointCount(i: number): number {
    const v = this.views[i];
    return v ? v.u.data[0].length : 0;
  }

  ids(): string[] {
    return this.views.map((v) => v.def.id);
  }
}
