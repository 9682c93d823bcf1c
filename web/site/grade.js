// Checking a student's own numbers in a live view (docs/course.md, docs/grading.md "In the page"):
// a trace document pasted or opened is sent to the module's `grade` op, the same library code as
// `whitted grade`, and its verdict shown — the first divergence as a table, that step made current
// so that the figure lights its ray; and the exercise mode, which hides the current step's numbers,
// asks for the quantity the step computes (the module's `exercise` op says which) and checks the
// typed answer component by component with the grader's rule. Nothing is computed here: this
// script only sends text to the module and shows its answers.
//
// It hooks into whitted.js through `self.whitted` (the engines and the views) and the
// `whitted:step` event each view sends when its current step changes. A view's `data-checking`
// counts this script's calls in flight (whitted.js's `data-busy` counts its own).
'use strict';

(function () {
  const WORDS = JSON.parse(document.getElementById('whitted-words').textContent);
  /** The word `key` with `{name}` filled from `values` (as whitted.js's `say`). */
  function say(key, values) {
    return (WORDS[key] || key).replace(/\{(\w+)\}/g, (m, name) => (values && name in values ? values[name] : m));
  }
  /** How many significant digits an error is shown with. */
  const OFF_DIGITS = 3;

  /** The view object of a view's root, once whitted.js has made it. */
  function viewOf(root) {
    const views = (self.whitted && self.whitted.views) || [];
    return views.find((v) => v.root === root) || null;
  }

  /** The pixel a view follows: the one asked, else the one its figure picked. */
  function followed(view) {
    if (view.target && view.target.pixel) return view.target;
    return view.shown ? { pixel: view.shown } : view.target;
  }

  /** An element with text. */
  function el(tag, text, attrs) {
    const e = document.createElement(tag);
    if (text !== undefined && text !== null) e.textContent = text;
    for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
    return e;
  }

  /** A two-column table of (heading, value) rows; `caption` names it. */
  function table(caption, rows) {
    const t = el('table');
    t.append(el('caption', caption));
    for (const [head, value] of rows) {
      if (value === null || value === undefined || value === '') continue;
      const tr = el('tr');
      tr.append(el('th', head, { scope: 'row' }), el('td', value));
      t.append(tr);
    }
    return t;
  }

  // ---- The student's document and its verdict ----------------------------------------------

  class Grader {
    constructor(root) {
      this.root = root;
      this.part = (name) => root.querySelector('[data-whitted="' + name + '"]');
      this.text = this.part('student');
      this.verdict = this.part('verdict');
      this.part('check').addEventListener('click', () => this.check());
      this.part('student-file').addEventListener('change', async (event) => {
        const file = event.target.files[0];
        if (!file) return;
        this.text.value = await file.text();
        this.check();
      });
    }

    async check() {
      const view = viewOf(this.root);
      if (!view) return;
      const student = this.text.value;
      if (student.trim() === '') {
        this.verdict.replaceChildren(el('p', say('grade_empty')));
        return;
      }
      this.root.dataset.checking = String(Number(this.root.dataset.checking || 0) + 1);
      try {
        const answer = await self.whitted.engines.quick.call({ op: 'grade', ...view.base(), student });
        await this.show(view, answer);
      } finally {
        this.root.dataset.checking = String(Number(this.root.dataset.checking) - 1);
      }
    }

    async show(view, answer) {
      const box = this.verdict;
      box.replaceChildren();
      const g = answer.json;
      if (answer.status !== 0) {
        box.dataset.verdict = 'errors';
        box.append(el('p', say('grade_errors'), { class: 'bad' }));
        const list = el('ul', null, { class: 'errors' });
        for (const e of g.errors || [answer.text]) list.append(el('li', e));
        box.append(list);
        return;
      }
      // The document's pixel becomes the one followed, so that its steps are the ones shown.
      const now = followed(view);
      const same = now && now.pixel && now.pixel.join(',') === g.pixel.join(',');
      if (!same) box.append(el('p', say('grade_pixel', { pixel: g.pixel.join(', ') })));
      const lines = g.text.split('\n');
      if (g.ok) {
        box.dataset.verdict = 'ok';
        box.append(el('p', lines[1], { class: 'good' }));
      } else {
        box.dataset.verdict = 'divergence';
        const w = g.words;
        box.append(el('p', say('grade_first', { chain: w.chain, quantity: w.quantity }), { class: 'bad' }));
        box.append(table(lines[0], [
          [say('expected'), w.expected],
          [say('found'), w.found],
          [say('formula'), w.formula],
          [say('inputs'), w.inputs],
          [say('diagnosis'), w.diagnosis],
          [say('rule'), w.rule],
        ]));
        box.append(el('p', say('grade_after'), { class: 'hint' }));
      }
      if (g.not_checked.length) box.append(el('p', say('not_checked', { list: g.not_checked.join(', ') })));
      const step = g.page_step;
      if (step) {
        const go = el('button', say('grade_goto', { k: step }), { type: 'button', 'data-step': String(step) });
        go.addEventListener('click', () => view.go(view.steps.findIndex((s) => s.step === step)));
        box.dataset.step = String(step);
        box.prepend(el('p', say('grade_step', { k: step }), { class: 'step' }));
        box.querySelector('p.step').append(' ', go);
      }
      if (!same) {
        view.target = { pixel: g.pixel };
        view.wantedStep = step || 1;
        await view.retrace();
      } else if (step) {
        view.go(view.steps.findIndex((s) => s.step === step));
      }
    }
  }

  // ---- Exercise mode -------------------------------------------------------------------------

  /** The names of a quantity's components. */
  function components(asked) {
    if (asked.count === 1) return [asked.name];
    if (asked.quantity === 'colour' || asked.quantity === 'local') return ['r', 'g', 'b'];
    if (asked.quantity === 'window_point') return ['u', 'v'];
    return ['x', 'y', 'z'].slice(0, asked.count);
  }

  class Exercise {
    constructor(root) {
      this.root = root;
      this.part = (name) => root.querySelector('[data-whitted="' + name + '"]');
      this.toggle = this.part('exercise-mode');
      this.body = root.querySelector('.exercise-body');
      this.gen = 0;
      this.toggle.addEventListener('change', () => this.ask());
      this.part('answer-form').addEventListener('submit', (event) => {
        event.preventDefault();
        this.check();
      });
      this.part('reveal').addEventListener('click', () => {
        this.root.classList.add('revealed');
        this.part('reveal').disabled = true;
      });
      root.addEventListener('whitted:step', () => this.ask());
    }

    /** The request of the current step. */
    request(view, extra) {
      const step = view.steps[view.step];
      return { op: 'exercise', ...view.base(), target: followed(view), step: step.step, ...extra };
    }

    /** The current step's question, its numbers hidden (or everything shown when off). */
    async ask() {
      const on = this.toggle.checked;
      this.root.classList.toggle('exercising', on);
      this.root.classList.remove('revealed');
      this.body.hidden = !on;
      this.part('reveal').disabled = false;
      this.part('feedback').replaceChildren();
      this.part('answer').value = '';
      const view = viewOf(this.root);
      if (!on || !view || !view.steps.length) return;
      const gen = ++this.gen;
      this.root.dataset.checking = String(Number(this.root.dataset.checking || 0) + 1);
      try {
        const answer = await self.whitted.engines.quick.call(this.request(view));
        if (gen !== this.gen) return;
        const question = this.part('question');
        const k = view.steps[view.step].step;
        this.asked = answer.status === 0 ? answer.json.asked : null;
        this.tolerance = answer.status === 0 ? answer.json.tolerance : null;
        const form = this.part('answer-form');
        if (!this.asked) {
          question.textContent = say('ex_nothing', { k });
          form.hidden = true;
          return;
        }
        form.hidden = false;
        const a = this.asked;
        const example = a.count === 1 ? '0.5' : '(' + ['0.1', '−0.2', '0.3'].slice(0, a.count).join(', ') + ')';
        question.textContent = say('ask_' + a.quantity, { k, name: a.name }) + ' '
          + say(a.count === 1 ? 'ex_count_one' : 'ex_count', { count: a.count, example });
        this.root.dataset.asked = a.quantity;
      } finally {
        this.root.dataset.checking = String(Number(this.root.dataset.checking) - 1);
      }
    }

    /** Sends the typed answer; shows per component right, or how far off. */
    async check() {
      const view = viewOf(this.root);
      if (!view || !this.asked) return;
      const gen = this.gen;
      const typed = this.part('answer').value;
      this.root.dataset.checking = String(Number(this.root.dataset.checking || 0) + 1);
      try {
        const answer = await self.whitted.engines.quick.call(this.request(view, { answer: typed }));
        if (gen !== this.gen) return;
        const box = this.part('feedback');
        box.replaceChildren();
        if (answer.status !== 0) {
          box.dataset.verdict = 'error';
          box.append(el('p', (answer.json.errors || [answer.text]).join('\n'), { class: 'bad' }));
          return;
        }
        const r = answer.json;
        const names = components(this.asked);
        const right = r.components.filter((c) => c.right).length;
        box.dataset.verdict = r.ok ? 'right' : 'wrong';
        const tol = String(r.tolerance);
        box.append(el('p', r.ok ? say('ex_right', { tol })
          : say('ex_wrong', { right, n: r.components.length, tol }), { class: r.ok ? 'good' : 'bad' }));
        const t = el('table');
        const head = el('tr');
        for (const h of [say('component'), say('yours'), say('verdict')]) head.append(el('th', h, { scope: 'col' }));
        t.append(head);
        r.components.forEach((c, k) => {
          const tr = el('tr', null, { 'data-right': String(c.right) });
          const off = say('comp_off', { off: Number(c.off.toPrecision(OFF_DIGITS)).toString() });
          tr.append(el('th', names[k] || String(k + 1), { scope: 'row' }), el('td', String(c.found)),
            el('td', c.right ? say('comp_right') : off));
          t.append(tr);
        });
        box.append(t);
      } finally {
        this.root.dataset.checking = String(Number(this.root.dataset.checking) - 1);
      }
    }
  }

  function main() {
    for (const root of document.querySelectorAll('[data-whitted="view"]')) {
      if (root.querySelector('[data-whitted="student"]')) new Grader(root);
      if (root.querySelector('[data-whitted="exercise"]')) new Exercise(root);
    }
  }

  main();
})();
