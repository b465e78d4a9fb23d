// The equations of motion in the header, typeset by KaTeX without holding up the page. A
// robot's equations run to hundreds of kB of LaTeX (the "where" list of a tree's intermediates,
// a 21 × 21 mass matrix): typeset at once they would keep the page blank for seconds and fill
// it with hundreds of thousands of elements. Instead:
// - each block (a `% caption` and its formulas) is split into pieces of a few kB: the rows of
//   an align*-like environment are grouped into environments of their own;
// - a long block is collapsed behind a <details> whose summary counts what it holds ("865
//   intermediates", "21 × 21 mass matrix") and is typeset only when opened;
// - the pieces of open blocks are typeset a few at a time when the page is idle
//   (requestIdleCallback, else short setTimeout slices), those in view first
//   (IntersectionObserver), so the 3D view and the plots stay responsive meanwhile.
import katex from 'katex';
import { el } from './format.js';

// a block with more LaTeX than this (a few screens of typeset math) starts collapsed
export const kCollapseChars = 10000;
// rows of an environment are grouped into pieces of at most this much LaTeX (one row may be
// longer): about 50 ms of KaTeX each, one idle slice
const kPieceChars = 2500;
// environments whose rows can be typeset apart (the others stay whole)
const kRowEnvironments = new Set(['align*', 'align', 'gather*', 'gather', 'aligned', 'gathered']);

// rigid's LaTeX (`rigid eom --format latex`) is a list of blocks: a `% caption` line, then
// either one \begin{…}…\end{…} environment or one equation per line.
export function latexBlocks(latex) {
  const blocks = [];
  let block = null;
  let env = null;
  const open = (caption) => { block = { caption, formulas: [] }; blocks.push(block); };
  for (const raw of latex.split('\n')) {
    const line = raw.trim();
    if (env !== null) {
      env.push(raw);
      if (/^\\end\{/.test(line)) { block.formulas.push(env.join('\n')); env = null; }
      continue;
    }
    if (!line) continue;
    if (line.startsWith('%')) { open(line.slice(1).trim()); continue; }
    if (!block) open('');
    if (/^\\begin\{/.test(line) && !/\\end\{[^}]*\}\s*$/.test(line)) env = [raw];
    else block.formulas.push(line);
  }
  if (env !== null) block.formulas.push(env.join('\n'));
  return blocks;
}

/**
 * `tex` cut at `sep` (`\\` or `&`) where it stands outside every brace group and nested
 * environment; escaped characters (`\&`, `\{`) are not separators.
 */
export function splitTopLevel(tex, sep) {
  const parts = [];
  let depth = 0;
  let start = 0;
  for (let i = 0; i < tex.length; i += 1) {
    const c = tex[i];
    if (c === '\\') {
      if (tex[i + 1] === '\\' && sep === '\\\\' && depth === 0) {
        parts.push(tex.slice(start, i));
        start = i + 2;
      } else if (tex.startsWith('\\begin{', i)) {
        depth += 1;
      } else if (tex.startsWith('\\end{', i)) {
        depth -= 1;
      }
      i += 1;
    } else if (c === '{') {
      depth += 1;
    } else if (c === '}') {
      depth -= 1;
    } else if (c === '&' && sep === '&' && depth === 0) {
      parts.push(tex.slice(start, i));
      start = i + 1;
    }
  }
  parts.push(tex.slice(start));
  return parts;
}

// the body of the first \begin{env}…\end{env} after `from`, with its nested environments
function environmentBody(tex, env, from = 0) {
  const begin = `\\begin{${env}}`;
  const i = tex.indexOf(begin, from);
  if (i < 0) return null;
  let depth = 0;
  const re = /\\(begin|end)\{[^}]*\}/g;
  re.lastIndex = i;
  for (let m = re.exec(tex); m; m = re.exec(tex)) {
    depth += m[1] === 'begin' ? 1 : -1;
    if (depth === 0) return tex.slice(i + begin.length, m.index);
  }
  return null;
}

/** A formula's rows: an align*-like environment's rows, or the formula itself. */
export function formulaRows(formula) {
  const m = /^\s*\\begin\{([^}]+)\}([\s\S]*)\\end\{\1\}\s*$/.exec(formula);
  if (!m || !kRowEnvironments.has(m[1])) return { env: null, rows: [formula] };
  const rows = splitTopLevel(m[2], '\\\\').map((r) => r.trim()).filter((r) => r);
  return { env: m[1], rows };
}

// rows × columns of the pmatrix that `rowTex` (`\mathbf{X} &= \begin{pmatrix}…`) sets its
// left side to
function matrixSize(rowTex) {
  const body = environmentBody(rowTex, 'pmatrix');
  if (body === null) return null;
  const rows = splitTopLevel(body, '\\\\').filter((r) => r.trim());
  return [rows.length, splitTopLevel(rows[0] ?? '', '&').length];
}

const count = (n, one, many = `${one}s`) => `${n.toLocaleString('en-US')} ${n === 1 ? one : many}`;

/** What a collapsed block's summary says it holds. */
export function blockSummary(caption, rows) {
  if (/^where\b/i.test(caption)) return count(rows.length, 'intermediate');
  const parts = [];
  for (const row of rows) {
    const m = /^\\mathbf\{(\w+)\}\s*&?=/.exec(row);
    const size = m && matrixSize(row);
    if (!size) continue;
    if (m[1] === 'M') parts.push(`${size[0]} × ${size[1]} mass matrix`);
    else if (size[1] === 1) parts.push(`${m[1]}: ${count(size[0], 'entry', 'entries')}`);
    else parts.push(`${m[1]}: ${size[0]} × ${size[1]}`);
  }
  return parts.length ? parts.join(', ') : count(rows.length, 'equation');
}

/**
 * The pieces one formula is typeset as: its rows grouped into environments of at most
 * kPieceChars of LaTeX, or the formula whole.
 */
function pieces(env, rows) {
  if (env === null) return rows;
  const out = [];
  let group = [];
  let length = 0;
  const flush = () => {
    if (group.length) out.push(`\\begin{${env}}\n${group.join(' \\\\\n')}\n\\end{${env}}`);
    group = [];
    length = 0;
  };
  for (const row of rows) {
    if (group.length && length + row.length > kPieceChars) flush();
    group.push(row);
    length += row.length;
  }
  flush();
  return out;
}

// one slice of idle time: the callback gets a deadline ({timeRemaining()})
const idle = typeof requestIdleCallback === 'function'
  ? (f) => requestIdleCallback(f, { timeout: 200 })
  : (f) => setTimeout(() => { const end = performance.now() + 12; f({ timeRemaining: () => end - performance.now() }); }, 0);

/**
 * Typesets the pieces it is given, in idle slices: first those in (or near) the view, then
 * the others in page order; a piece inside a closed <details> waits until it is opened.
 */
class Typesetter {
  constructor() {
    this.pending = new Map(); // piece element → LaTeX, in page order
    this.visible = new Set();
    this.waiters = [];
    this.scheduled = false;
    this.observer = typeof IntersectionObserver === 'function'
      ? new IntersectionObserver((entries) => {
        for (const e of entries) {
          if (e.isIntersecting) this.visible.add(e.target);
          else this.visible.delete(e.target);
        }
        this.kick();
      }, { rootMargin: '50% 0px' })
      : null;
  }

  add(piece, tex) {
    this.pending.set(piece, tex);
    this.observer?.observe(piece);
    this.kick();
  }

  static isOpen(piece) {
    const details = piece.closest('details');
    return !details || details.open;
  }

  next() {
    for (const p of this.visible) if (Typesetter.isOpen(p)) return p;
    for (const p of this.pending.keys()) if (Typesetter.isOpen(p)) return p;
    return null;
  }

  kick() {
    if (this.scheduled) return;
    this.scheduled = true;
    idle((deadline) => this.slice(deadline));
  }

  slice(deadline) {
    this.scheduled = false;
    // at least one piece per slice, so that a page that is never idle still progresses
    for (let p = this.next(); p; p = deadline.timeRemaining() > 0 ? this.next() : null) this.typeset(p);
    if (this.next()) {
      this.kick();
    } else {
      for (const w of this.waiters.splice(0)) w();
    }
  }

  typeset(piece) {
    const tex = this.pending.get(piece);
    this.pending.delete(piece);
    this.visible.delete(piece);
    this.observer?.unobserve(piece);
    piece.classList.remove('pending');
    piece.style.minHeight = '';
    try {
      katex.render(tex, piece, { displayMode: true, throwOnError: true, output: 'html' });
    } catch (e) {
      // a formula KaTeX cannot typeset is shown as its source, with the reason
      piece.replaceChildren(el('p', { class: 'note', text: `KaTeX could not typeset this formula: ${e.message}` }),
        el('pre', { text: tex }));
    }
  }

  /** Resolves when every piece outside a closed <details> is typeset. */
  done() {
    if (!this.next()) return Promise.resolve();
    return new Promise((resolve) => { this.waiters.push(resolve); this.kick(); });
  }
}

/**
 * The equations' element, typeset lazily, and `typeset()`: a promise that resolves when every
 * formula of an open block is typeset (for tests and scripts; open a block, then call it).
 */
export function buildEquations(latex) {
  const box = el('div', { class: 'equations' });
  const typesetter = new Typesetter();
  for (const { caption, formulas } of latexBlocks(latex)) {
    const split = formulas.map(formulaRows);
    const rows = split.flatMap((s) => s.rows);
    const chars = formulas.reduce((n, f) => n + f.length, 0);
    let target = box;
    if (chars > kCollapseChars) {
      const summary = el('summary', { title: `${Math.ceil(chars / 1000)} kB of LaTeX, typeset when opened` },
        el('span', { class: 'caption', text: caption || 'equations' }),
        el('span', { class: 'count', text: ` — ${blockSummary(caption, rows)}` }));
      const details = el('details', { class: 'long-block' }, summary);
      details.addEventListener('toggle', () => typesetter.kick());
      box.append(details);
      target = details;
    } else if (caption) {
      box.append(el('p', { class: 'caption', text: caption }));
    }
    for (const { env, rows: formulaRowsOf } of split) {
      const texs = pieces(env, formulaRowsOf);
      for (const tex of texs) {
        // a placeholder about as tall as the typeset piece, so that the page does not jump
        const lines = tex.split('\\\\').length;
        const piece = el('div', { class: texs.length > 1 ? 'formula pending piece' : 'formula pending' });
        piece.style.minHeight = `${Math.min(lines, 60) * 1.6}em`;
        target.append(piece);
        typesetter.add(piece, tex);
      }
    }
  }
  return { box, typeset: () => typesetter.done() };
}
