// The live part of the course's pages (docs/course.md). Every number comes from the WebAssembly
// build of the Rust library (web/, the ABI of web/README.md): this script only moves JSON in and
// out of it, draws the RGBA it returns on a canvas, inserts the SVG it returns, and keeps the
// state (pixel, step, options) in the controls and the URL. No ray is traced here.
//
// The module arrives as base64 in whitted-wasm.js (a page opened from file:// may not fetch), is
// compiled once, and runs in two workers made from a Blob URL: one for quick calls (check, info,
// trace, narrate, figure), one for renders, so that a long render never holds up a click nor the
// page. Where a worker cannot start, the same engine runs in the page.
'use strict';

(function () {
  const WORDS = JSON.parse(document.getElementById('whitted-words').textContent);
  const LANG = document.documentElement.lang === 'ro' ? 'ro' : 'en';
  /** Delay after the last keystroke in the scene editor before it is checked (ms). */
  const EDIT_DELAY_MS = 300;

  /** The word `key` with `{name}` filled from `values`. */
  function say(key, values) {
    return (WORDS[key] || key).replace(/\{(\w+)\}/g, (m, name) => (values && name in values ? values[name] : m));
  }

  // ---- The engine: the module's ABI, written once, run in a worker or in the page -------------

  /** Makes `call(request) → {status, text, bytes}` over an instance of the module. A trap (a
   *  panic, which would be a bug) aborts the instance: the next call gets a new one. */
  function makeEngine(module) {
    let exports = null;
    const encoder = new TextEncoder();
    const decoder = new TextDecoder();
    return function call(request) {
      exports = exports || new WebAssembly.Instance(module, {}).exports;
      try {
        return once(request);
      } catch (error) {
        exports = null;
        throw error;
      }
    };
    function once(request) {
      const input = encoder.encode(JSON.stringify(request));
      const at = exports.whitted_inbox(input.length);
      // 0: the request is too large; nothing is written and the call says so.
      if (at !== 0) new Uint8Array(exports.memory.buffer, at, input.length).set(input);
      const status = exports.whitted_call();
      const text = decoder.decode(
        new Uint8Array(exports.memory.buffer, exports.whitted_outbox(), exports.whitted_outbox_len()));
      const length = exports.whitted_bytes_len();
      const bytes = length ? new Uint8Array(exports.memory.buffer, exports.whitted_bytes(), length).slice() : null;
      return { status, text, bytes };
    }
  }

  /** The worker's body: the first message is the compiled module, then one answer per request. */
  function workerMain(makeEngine) {
    let call = null;
    self.onmessage = (event) => {
      const data = event.data;
      if (data.module) {
        call = makeEngine(data.module);
        return;
      }
      try {
        const answer = call(data.request);
        self.postMessage({ id: data.id, answer }, answer.bytes ? [answer.bytes.buffer] : []);
      } catch (error) {
        self.postMessage({ id: data.id, error: String(error && error.stack || error) });
      }
    };
  }

  /** A worker (or the page itself) answering requests one at a time, in order. */
  class Engine {
    constructor(module) {
      this.pending = new Map();
      this.next = 1;
      try {
        const source = '(' + workerMain.toString() + ')(' + makeEngine.toString() + ');';
        const url = URL.createObjectURL(new Blob([source], { type: 'text/javascript' }));
        this.worker = new Worker(url);
        this.worker.onmessage = (event) => this.settle(event.data);
        this.worker.onerror = (event) => this.fail(event.message || 'worker error');
        this.worker.postMessage({ module });
      } catch (error) {
        // A browser that refuses a Blob worker here: the same engine in the page.
        this.worker = null;
        this.local = makeEngine(module);
      }
    }

    /** Runs one request; resolves with `{status, json, bytes}`. */
    call(request) {
      if (!this.worker) {
        return new Promise((resolve) => {
          const answer = this.local(request);
          resolve({ status: answer.status, json: JSON.parse(answer.text), bytes: answer.bytes, text: answer.text });
        });
      }
      const id = this.next++;
      return new Promise((resolve, reject) => {
        this.pending.set(id, { resolve, reject });
        this.worker.postMessage({ id, request });
      });
    }

    settle(data) {
      const waiting = this.pending.get(data.id);
      if (!waiting) return;
      this.pending.delete(data.id);
      if (data.error) {
        waiting.reject(new Error(data.error));
      } else {
        const a = data.answer;
        waiting.resolve({ status: a.status, json: JSON.parse(a.text), bytes: a.bytes, text: a.text });
      }
    }

    fail(message) {
      for (const waiting of this.pending.values()) waiting.reject(new Error(message));
      this.pending.clear();
    }
  }

  /** The module's bytes from the base64 of whitted-wasm.js. */
  function moduleBytes() {
    const text = self.WHITTED_WASM;
    if (typeof Uint8Array.fromBase64 === 'function') return Uint8Array.fromBase64(text);
    const binary = atob(text);
    const bytes = new Uint8Array(binary.length);
    for (let k = 0; k < binary.length; k++) bytes[k] = binary.charCodeAt(k);
    return bytes;
  }

  // ---- Parsing what the reader types and what the page carries --------------------------------

  /** "i, j" or "i" → [i, j] or [i]; null when it is not whole numbers. */
  function parsePixel(text) {
    const parts = text.split(/[\s,]+/).filter((p) => p !== '');
    if (parts.length < 1 || parts.length > 2 || !parts.every((p) => /^\d+$/.test(p))) return null;
    return parts.map(Number);
  }

  /** "ox,oy(,oz):dx,dy(,dz)" → [[o…], [d…]]. */
  function parseRay(text) {
    const [o, d] = text.split(':').map((half) => half.split(',').map(Number));
    return [o, d];
  }

  /** The fragment `#pixel=I,J&step=K&depth=N&aa=MODE…` as a map. */
  function readFragment() {
    const state = new Map();
    for (const pair of location.hash.replace(/^#/, '').split('&')) {
      const at = pair.indexOf('=');
      if (at > 0) state.set(decodeURIComponent(pair.slice(0, at)), decodeURIComponent(pair.slice(at + 1)));
    }
    return state;
  }

  /** Space-separated indices → a Set of numbers. */
  function eventSet(text) {
    return new Set((text || '').split(' ').filter((x) => x !== '').map(Number));
  }

  /** Gives an SVG's ids a prefix so that several figures on one page do not share them. */
  function isolateIds(svg, prefix) {
    const ids = [...svg.matchAll(/\sid="([^"]+)"/g)].map((m) => m[1]);
    for (const id of ids) {
      svg = svg.split('id="' + id + '"').join('id="' + prefix + id + '"')
        .split('url(#' + id + ')').join('url(#' + prefix + id + ')')
        .split('href="#' + id + '"').join('href="#' + prefix + id + '"');
    }
    return svg.replace(/^<\?xml[^>]*>\s*/, '');
  }

  // ---- A live view --------------------------------------------------------------------------

  // One element with data-whitted="view": a click picks a pixel, which is narrated and drawn; the
  // narration's steps are shown one at a time (aria-current) with the figure items they name lit;
  // the options and the scene editor (checked as it is typed) change it; the URL fragment keeps it.
  class View {
    constructor(root, index, engines) {
      this.root = root;
      this.index = index;
      this.engines = engines;
      this.part = (name) => root.querySelector('[data-whitted="' + name + '"]');
      this.canvas = this.part('image');
      this.editor = this.part('scene');
      this.scene = this.editor.value;
      this.objs = {};
      this.info = null; // the scene's dimension and size, from the last good check
      this.target = null; // {pixel: [...]} or {ray: [...]}, or null where the figure picks
      this.steps = [];
      this.step = 0; // index into steps
      this.traceGen = 0;
      this.renderGen = 0;
      this.good = null; // the last target traced without a refusal
      const d = root.dataset;
      if (d.pixel) this.target = { pixel: d.pixel.split(',').map(Number) };
      else if (d.ray) this.target = { ray: parseRay(d.ray) };
      if (d.depth) this.part('depth').value = d.depth;
      if (d.grid) this.grid = d.grid.split(',').map(Number);
      // `data-busy` counts the work in flight, so that a test can wait for the view to settle.
      this.busy = 0;
      this.root.dataset.busy = '0';
      for (const name of ['rescene', 'rerender', 'retrace', 'render']) {
        const work = this[name].bind(this);
        this[name] = async (...args) => {
          this.root.dataset.busy = String(++this.busy);
          try {
            return await work(...args);
          } catch (error) {
            this.message(say('failed', { e: error.message }));
          } finally {
            this.root.dataset.busy = String(--this.busy);
          }
        };
      }
      this.wire();
    }

    /** Starts the view: the URL's state for the first view, then check, render, trace. */
    async start() {
      if (this.index === 0) this.applyFragment(readFragment());
      this.updateAdaptive();
      await this.rescene();
      performance.mark('whitted-view-' + this.index);
    }

    applyFragment(state) {
      if (state.has('pixel')) {
        const pixel = parsePixel(state.get('pixel'));
        if (pixel) this.target = { pixel };
      }
      for (const name of ['depth', 'aa', 'threshold', 'max_level', 'accel', 'kind']) {
        if (state.has(name)) this.part(name).value = state.get(name);
      }
      this.wantedStep = state.has('step') ? Number(state.get('step')) : null;
    }

    wire() {
      this.canvas.addEventListener('click', (event) => this.clicked(event));
      this.part('pixel-form').addEventListener('submit', (event) => {
        event.preventDefault();
        const pixel = parsePixel(this.part('pixel').value);
        if (!pixel) {
          this.message(say('pixel_format'));
          return;
        }
        this.choose({ pixel });
      });
      this.part('back').addEventListener('click', () => this.go(this.step - 1));
      this.part('next').addEventListener('click', () => this.go(this.step + 1));
      this.part('steps').addEventListener('click', (event) => {
        const item = event.target.closest('[data-step]');
        if (item) this.go(this.steps.findIndex((s) => s.step === Number(item.dataset.step)));
      });
      for (const name of ['depth', 'aa', 'threshold', 'max_level', 'accel']) {
        this.part(name).addEventListener('change', () => {
          this.updateAdaptive();
          this.rerender();
        });
      }
      this.part('kind').addEventListener('change', () => this.retrace());
      let timer = null;
      this.editor.addEventListener('input', () => {
        clearTimeout(timer);
        timer = setTimeout(() => {
          this.scene = this.editor.value;
          this.rescene();
        }, EDIT_DELAY_MS);
      });
      this.root.addEventListener('focusin', () => View.active = this);
      this.root.addEventListener('pointerdown', () => View.active = this);
    }

    updateAdaptive() {
      this.root.classList.toggle('adaptive', this.part('aa').value === 'adaptive');
    }

    /** The options of every request, as the CLI names them. */
    options() {
      const o = {};
      const depth = this.part('depth').value.trim();
      if (depth !== '') o.depth = Number(depth);
      o.aa = this.part('aa').value;
      if (o.aa === 'adaptive') {
        const t = this.part('threshold').value.trim();
        o.threshold = t === 'inf' ? 'inf' : Number(t);
        o.max_level = Number(this.part('max_level').value);
      }
      o.accel = this.part('accel').value;
      if (this.grid) o.grid = this.grid;
      return o;
    }

    base() {
      const name = this.root.dataset.path || this.root.dataset.scene;
      return { scene: this.scene, name, objs: this.objs, options: this.options(), lang: LANG };
    }

    message(text) {
      this.part('message').textContent = text || '';
    }

    /** A request's errors, or the engine's failure, as one message. */
    complain(answer) {
      const errors = answer.json && answer.json.errors;
      this.message(errors ? errors.join('\n') : say('failed', { e: answer.text }));
    }

    /** The scene changed (or the page opened): check it; if good, render and trace again. */
    async rescene() {
      const quick = this.engines.quick;
      const checked = await quick.call({ op: 'check', scene: this.scene, name: this.base().name, objs: this.objs });
      const list = this.part('errors');
      list.replaceChildren();
      if (!checked.json.ok) {
        for (const error of checked.json.errors || []) {
          const item = document.createElement('li');
          item.textContent = error;
          list.append(item);
        }
        this.root.classList.add('stale');
        this.message(say('stale'));
        return;
      }
      this.root.classList.remove('stale');
      this.message('');
      await this.rerender();
    }

    /** The options changed: size the image, render it, and trace again. */
    async rerender() {
      const info = await this.engines.quick.call({ op: 'info', ...this.base() });
      if (info.status !== 0) {
        this.complain(info);
        return;
      }
      this.message('');
      this.info = info.json;
      this.part('depth').placeholder = String(this.info.max_depth);
      if (this.target && this.target.pixel && !this.inside(this.target.pixel)) this.target = null;
      const tracing = this.retrace();
      await Promise.all([this.render(), tracing]);
    }

    inside(pixel) {
      const { width, height, dimension } = this.info;
      return pixel[0] < width && (dimension === 2 || (pixel.length === 2 && pixel[1] < height));
    }

    /** Renders the whole image in the render worker (the module renders a whole image per call),
     *  the progress bar running meanwhile; a newer render's image replaces an older one's. */
    async render() {
      const gen = ++this.renderGen;
      const { width, height } = this.info;
      const progress = this.part('progress');
      const started = performance.now();
      progress.hidden = false;
      progress.removeAttribute('value'); // indeterminate: the module reports no partial progress
      this.part('stats').textContent = say('rendering');
      const answer = await this.engines.render.call({ op: 'render', ...this.base() });
      if (gen !== this.renderGen) return;
      progress.hidden = true;
      if (answer.status !== 0) {
        this.part('stats').textContent = '';
        this.complain(answer);
        return;
      }
      this.canvas.width = width;
      this.canvas.height = height;
      const pixels = new Uint8ClampedArray(answer.bytes.buffer, answer.bytes.byteOffset, answer.bytes.length);
      this.canvas.getContext('2d').putImageData(new ImageData(pixels, width, height), 0, 0);
      this.root.classList.toggle('strip', this.info.dimension === 2);
      // `rays` is by kind (primary, reflected, transmitted, shadow), as `render --json` gives it.
      const rays = Object.values(answer.json.rays || {}).reduce((a, b) => a + b, 0);
      const ms = Math.round(performance.now() - started);
      this.part('stats').textContent = say('rendered', { w: width, h: height, rays: rays.toLocaleString(LANG), ms });
      this.mark();
    }

    /** A click at CSS offset (x, y) of the W×H image → i = ⌊x·Nx/W⌋, j = Ny − 1 − ⌊y·Ny/H⌋. */
    clicked(event) {
      if (!this.info) return;
      const box = this.canvas.getBoundingClientRect();
      const { width, height, dimension } = this.info;
      const x = event.clientX - box.left;
      const y = event.clientY - box.top;
      const i = Math.min(width - 1, Math.max(0, Math.floor((x * width) / box.width)));
      const j = height - 1 - Math.min(height - 1, Math.max(0, Math.floor((y * height) / box.height)));
      this.choose({ pixel: dimension === 2 ? [i] : [i, j] });
    }

    choose(target) {
      this.target = target;
      this.wantedStep = 1;
      this.tracing = this.retrace(); // awaited by the benchmark
    }

    /** Traces the target again: figure and narration, together. */
    async retrace() {
      const gen = ++this.traceGen;
      const quick = this.engines.quick;
      const kind = this.part('kind').value;
      const base = this.base();
      let figure;
      let narration = null;
      if (this.target) {
        const request = { ...base, target: this.target };
        [figure, narration] = await Promise.all([
          quick.call({ op: 'figure', ...request, kind }),
          quick.call({ op: 'narrate', ...request }),
        ]);
      } else {
        // The figure picks its pixel; the narration follows that pixel.
        figure = await quick.call({ op: 'figure', ...base, kind });
        if (figure.status === 0 && figure.json.pixel) {
          narration = await quick.call({ op: 'narrate', ...base, target: { pixel: figure.json.pixel } });
        }
      }
      if (gen !== this.traceGen) return;
      const failed = figure.status !== 0 ? figure : narration && narration.status !== 0 ? narration : null;
      if (failed) {
        // Refused (a pixel outside the image, an option beyond its limits): the message says why,
        // and the last good trace stays, with its pixel.
        this.complain(failed);
        this.target = this.good;
        this.saveState();
        return;
      }
      this.good = this.target;
      this.message('');
      this.part('pick').textContent = figure.json.pick || '';
      this.shown = figure.json.pixel || null;
      this.part('figure').innerHTML = isolateIds(figure.json.svg, 'v' + this.index + '-');
      this.showSteps(narration ? narration.json : null);
      this.mark();
    }

    showSteps(narration) {
      const list = this.part('steps');
      list.replaceChildren();
      this.steps = narration ? narration.steps : [];
      this.part('command').textContent = narration ? narration.command : '';
      for (const s of this.steps) {
        const item = document.createElement('li');
        item.dataset.step = s.step;
        item.dataset.events = s.events.join(' ');
        const text = document.createElement('pre');
        text.textContent = s.text;
        item.append(text);
        list.append(item);
      }
      if (!narration) this.part('current').textContent = say('no_steps');
      const wanted = this.steps.findIndex((s) => s.step === this.wantedStep);
      this.wantedStep = null;
      this.go(wanted >= 0 ? wanted : 0);
    }

    /** Makes step `k` (an index) current: aria-current, lit items, the text beside the figure. */
    go(k) {
      const n = this.steps.length;
      if (n === 0) {
        this.part('back').disabled = true;
        this.part('next').disabled = true;
        this.part('position').textContent = '';
        this.saveState();
        return;
      }
      k = Math.max(0, Math.min(n - 1, k));
      this.step = k;
      const current = this.steps[k];
      const list = this.part('steps');
      for (const item of list.children) {
        if (Number(item.dataset.step) === current.step) {
          item.setAttribute('aria-current', 'step');
          // Scroll the list, not the page.
          const top = item.offsetTop - list.offsetTop;
          if (top < list.scrollTop || top + item.offsetHeight > list.scrollTop + list.clientHeight) {
            list.scrollTop = top - list.clientHeight / 3;
          }
        } else {
          item.removeAttribute('aria-current');
        }
      }
      const events = new Set(current.events);
      const svg = this.part('figure').querySelector('svg');
      if (svg) {
        svg.classList.add('stepping');
        for (const item of svg.querySelectorAll('[data-events]')) {
          item.classList.toggle('lit', [...eventSet(item.getAttribute('data-events'))].some((e) => events.has(e)));
        }
      }
      this.part('position').textContent = say('step_of', { k: current.step, n: this.steps[n - 1].step });
      // The step without its nesting: its first line's indent taken off every line.
      const indent = current.text.length - current.text.trimStart().length;
      this.part('current').textContent = current.text.split('\n')
        .map((line) => line.slice(Math.min(indent, line.length - line.trimStart().length))).join('\n');
      this.part('back').disabled = k === 0;
      this.part('next').disabled = k === n - 1;
      this.saveState();
    }

    /** The chosen pixel's mark over the image. */
    mark() {
      const mark = this.part('mark');
      const pixel = (this.target && this.target.pixel) || this.shown;
      if (!this.info || !pixel || !this.inside(pixel)) {
        mark.hidden = true;
        return;
      }
      const { width, height, dimension } = this.info;
      const j = dimension === 2 ? 0 : pixel[1];
      mark.style.left = (100 * (pixel[0] + 0.5)) / width + '%';
      mark.style.top = dimension === 2 ? '50%' : (100 * (height - 1 - j + 0.5)) / height + '%';
      mark.hidden = false;
    }

    /** The first view's state in the URL, and the language link keeping it. */
    saveState() {
      if (this.index !== 0) return;
      const parts = [];
      const pixel = this.target && this.target.pixel;
      if (pixel) parts.push('pixel=' + pixel.join(','));
      if (this.steps.length) parts.push('step=' + this.steps[this.step].step);
      const o = this.options();
      if ('depth' in o) parts.push('depth=' + o.depth);
      parts.push('aa=' + o.aa);
      if (o.aa === 'adaptive') parts.push('threshold=' + o.threshold, 'max_level=' + o.max_level);
      parts.push('accel=' + o.accel, 'kind=' + this.part('kind').value);
      const hash = '#' + parts.join('&');
      if (location.hash !== hash) history.replaceState(null, '', hash);
      const link = document.querySelector('[data-whitted="lang"]');
      if (link) link.href = link.getAttribute('href').replace(/#.*$/, '') + hash;
    }
  }

  View.active = null;

  /** ← and → walk the active view's steps, except while typing. */
  function keys(views) {
    document.addEventListener('keydown', (event) => {
      if (event.altKey || event.ctrlKey || event.metaKey) return;
      if (event.target.closest && event.target.closest('input, textarea, select')) return;
      const view = View.active || views[0];
      if (!view) return;
      if (event.key === 'ArrowRight') view.go(view.step + 1);
      else if (event.key === 'ArrowLeft') view.go(view.step - 1);
      else return;
      event.preventDefault();
    });
  }

  /** The playground's file picker and examples replace the view's scene. */
  function playground(view) {
    const example = document.querySelector('[data-whitted="example"]');
    const file = document.querySelector('[data-whitted="file"]');
    if (!example || !file) return;
    const load = (name, text, objs) => {
      view.root.dataset.scene = name;
      delete view.root.dataset.path;
      view.editor.value = text;
      view.scene = text;
      view.objs = objs;
      view.target = null;
      view.rescene();
    };
    example.addEventListener('change', () => {
      const option = example.selectedOptions[0];
      load(option.value, option.dataset.text, {});
    });
    file.addEventListener('change', async () => {
      const files = [...file.files];
      const scene = files.find((f) => f.name.endsWith('.json')) || files[0];
      if (!scene) return;
      const objs = {};
      for (const f of files) if (f !== scene) objs[f.name] = await f.text();
      load(scene.name, await scene.text(), objs);
    });
  }

  async function main() {
    const status = document.querySelector('[data-whitted="module"]');
    const roots = [...document.querySelectorAll('[data-whitted="view"]')];
    if (!self.WHITTED_WASM) return; // the page already says the module is missing
    const started = performance.now();
    const module = await WebAssembly.compile(moduleBytes());
    const engines = { quick: new Engine(module), render: new Engine(module) };
    const views = roots.map((root, k) => new View(root, k, engines));
    keys(views);
    if (views.length === 1) playground(views[0]);
    self.whitted = { engines, views }; // for tests and the benchmark
    status.textContent = say('ready', { ms: Math.round(performance.now() - started) });
    status.classList.add('ready');
    performance.mark('whitted-module');
    // The first view alone first (the one a reader looks at, and the URL's), then the others.
    if (views.length) await views[0].start();
    await Promise.all(views.slice(1).map((v) => v.start()));
    document.body.dataset.readyMs = String(Math.round(performance.now()));
    document.body.dataset.ready = 'true';
  }

  main().catch((error) => {
    const status = document.querySelector('[data-whitted="module"]');
    status.textContent = say('failed', { e: error.message });
    status.classList.add('error');
  });
})();
