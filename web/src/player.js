// The time of the page: one frame index shared by the 3D view and the plots. Controls: play and
// pause, speed, a time slider, frame stepping; keys: space (play/pause), ← and → (one frame).
import { el, num } from './format.js';

const kSpeeds = [0.1, 0.25, 0.5, 1, 2, 5, 10, 20, 50, 100];

/** Index of the frame nearest to time t in the increasing times ts. */
export function nearestFrame(ts, t) {
  let lo = 0;
  let hi = ts.length - 1;
  if (!(t > ts[lo])) return 0;
  if (t >= ts[hi]) return hi;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (ts[mid] <= t) lo = mid; else hi = mid;
  }
  return t - ts[lo] <= ts[hi] - t ? lo : hi;
}

export class Player {
  constructor(ts, root) {
    this.ts = ts;
    this.index = 0;
    this.listeners = [];
    this.playing = false;
    this.playTime = ts[0];
    const span = ts[ts.length - 1] - ts[0];
    // a whole run plays in about 20 s at the default speed
    this.speed = kSpeeds.reduce((best, s) => (Math.abs(Math.log(span / 20 / s)) < Math.abs(Math.log(span / 20 / best)) ? s : best), 1);
    if (!(span > 0)) this.speed = 1;

    this.button = el('button', { type: 'button', class: 'play', title: 'play / pause (space)', text: 'play' });
    this.prev = el('button', { type: 'button', title: 'previous frame (←)', text: '‹ frame' });
    this.next = el('button', { type: 'button', title: 'next frame (→)', text: 'frame ›' });
    this.slider = el('input', { type: 'range', min: '0', max: String(ts.length - 1), step: '1', value: '0', class: 'time-slider', 'aria-label': 'time' });
    this.label = el('span', { class: 'time-label' });
    this.speedSelect = el('select', { title: 'speed (simulated seconds per second)', 'aria-label': 'speed' },
      ...kSpeeds.map((s) => {
        const o = el('option', { value: String(s), text: `×${s}` });
        if (s === this.speed) o.selected = true;
        return o;
      }));
    // the row of controls; others (the 3D view's recorder) append theirs to it
    this.bar = el('div', { class: 'player' }, this.button, this.prev, this.next, this.slider, this.label, this.speedSelect);
    root.append(this.bar);

    this.button.addEventListener('click', () => this.toggle());
    this.prev.addEventListener('click', () => this.step(-1));
    this.next.addEventListener('click', () => this.step(1));
    this.slider.addEventListener('input', () => { this.pause(); this.setIndex(Number(this.slider.value)); });
    this.speedSelect.addEventListener('change', () => { this.speed = Number(this.speedSelect.value); });
    document.addEventListener('keydown', (e) => {
      if (e.target instanceof HTMLInputElement && e.target.type !== 'range') return;
      if (e.target instanceof HTMLSelectElement) return;
      if (e.key === ' ') { e.preventDefault(); this.toggle(); }
      else if (e.key === 'ArrowLeft') { e.preventDefault(); this.pause(); this.step(-1); }
      else if (e.key === 'ArrowRight') { e.preventDefault(); this.pause(); this.step(1); }
    });
    this.updateLabel();
  }

  onChange(f) { this.listeners.push(f); }

  time() { return this.ts[this.index]; }

  setIndex(i) {
    const j = Math.max(0, Math.min(this.ts.length - 1, Math.round(i)));
    this.index = j;
    this.playTime = this.ts[j];
    this.slider.value = String(j);
    this.updateLabel();
    for (const f of this.listeners) f(j);
  }

  setTime(t) { this.setIndex(nearestFrame(this.ts, t)); }

  step(d) { this.setIndex(this.index + d); }

  updateLabel() {
    this.label.textContent = `t = ${num(this.ts[this.index], 5)} s  (frame ${this.index + 1}/${this.ts.length})`;
  }

  toggle() { if (this.playing) this.pause(); else this.play(); }

  pause() {
    this.playing = false;
    this.button.textContent = 'play';
  }

  play() {
    if (this.index >= this.ts.length - 1) this.setIndex(0);
    this.playing = true;
    this.button.textContent = 'pause';
    let last = performance.now();
    const tick = (now) => {
      if (!this.playing) return;
      this.playTime += ((now - last) / 1000) * this.speed;
      last = now;
      const j = nearestFrame(this.ts, this.playTime);
      const t = this.playTime;
      if (j !== this.index) this.setIndex(j);
      this.playTime = t;
      if (t >= this.ts[this.ts.length - 1]) { this.pause(); return; }
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }
}
