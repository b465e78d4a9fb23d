// Number formatting and small DOM helpers shared by the page's parts.

/** A number with 6 significant digits, in exponent form when very small or large. */
export function num(x, digits = 6) {
  if (x === null || x === undefined) return '—';
  if (typeof x !== 'number') return String(x);
  if (!Number.isFinite(x)) return String(x);
  if (x === 0) return '0';
  const a = Math.abs(x);
  if (a < 1e-3 || a >= 1e6) return x.toExponential(Math.max(0, digits - 4)).replace('e', '·10^').replace('^+', '^');
  return String(Number(x.toPrecision(digits)));
}

export function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k === 'text') e.textContent = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) {
    if (c === null || c === undefined) continue;
    e.append(c instanceof Node ? c : String(c));
  }
  return e;
}

export function vec(v, unit = '') {
  return `(${Array.from(v, (x) => num(x)).join(', ')})${unit ? ` ${unit}` : ''}`;
}

/** A table from a header row and rows of cells (strings or nodes). */
export function table(head, rows, cls = '') {
  return el('table', { class: cls },
    el('thead', {}, el('tr', {}, ...head.map((h) => el('th', { text: h })))),
    el('tbody', {}, ...rows.map((r) => el('tr', {}, ...r.map((c) => el('td', {}, c))))));
}

/** Saves a data: URL (or a blob: URL) as a file named `name`, through a link's download. */
export function saveDataUrl(url, name) {
  const a = el('a', { href: url, download: name });
  document.body.append(a);
  a.click();
  a.remove();
}
