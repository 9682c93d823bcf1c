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

  /** A figure kind as the page's figure menu names it in its language (the kind's own name when
   *  the words have none). */
  function kindName(kind) {
    return WORDS['kind_' + kind] || kind;
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

  /** The fragment `#pixel=I,J&step=K&depth=N&aa=MODE…` as a map; the parts that cannot be
   *  decoded (a broken percent escape) are listed in its `bad`, as written. */
  function readFragment() {
    const state = new Map();
    state.bad = [];
    for (const pair of location.hash.replace(/^#/, '').split('&')) {
      const at = pair.indexOf('=');
      if (at <= 0) continue;
      try {
        state.set(decodeURIComponent(pair.slice(0, at)), decodeURIComponent(pair.slice(at + 1)));
      } catch (error) {
        state.bad.push([pair.slice(0, at), pair.slice(at + 1)]);
      }
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

  /** The structure each figure kind draws, and the kind that draws each structure (issue 30
   *  item 2: a figure is narrated by the structure it draws). */
  const KIND_ACCEL = { 'slab-test': 'bounds', 'kay-kajiya': 'bounds', bvh: 'bvh', 'grid-dda': 'grid', octree: 'octree' };
  const ACCEL_KIND = { bounds: 'slab-test', bvh: 'bvh', grid: 'grid-dda', octree: 'octree' };
  /** What a figure kind needs in a pixel's trace (the words of its refusal), by kind. */
  const KIND_WANTS = {
    refraction: 'want_refraction', 'local-model': 'want_hit', shadows: 'want_shadow',
    'slab-test': 'want_volume', 'kay-kajiya': 'want_volume',
  };
  /** The kind a figure falls back to when the view's kind cannot draw a pixel: every ray of it. */
  const FALLBACK_KIND = 'rays';
  /** The kinds that draw one part of a pixel's trace (a row of primary rays, one hit's R and T,
   *  one hit's local model, the pixel's window point, its colour in a crop, one object's slabs)
   *  while the narration walks the whole tree: their view shows the pixel's ray tree under the
   *  figure (OVERVIEW_KIND), where every step lights the ray, light or node it names (issue 30
   *  item 3). */
  const OVERVIEW_KINDS = ['projections', 'refraction', 'local-model', 'uv-map', 'jagged-edges', 'slab-test', 'kay-kajiya'];
  const OVERVIEW_KIND = 'ray-tree';
  /** The overview's canvas, a slide's shape (16:9): drawn at the pane's width, its labels are
   *  then as large as the figure's (a flatter canvas would shrink them with its height). */
  const OVERVIEW_SIZE = [1280, 720];
  /** How far (in pixels) and how many candidates the search for a nearby pixel goes. */
  const NEAR_RADII = [2, 4, 8, 16, 32, 64];
  /** Beyond the rings, the points tried on the way to the lesson's pixel (which has it). */
  const NEAR_TOWARDS = 16;
  const NEAR_DIRECTIONS = [[1, 0], [0, 1], [-1, 0], [0, -1], [1, 1], [-1, 1], [-1, -1], [1, -1]];
  /** The deepest `--depth` the command line takes. */
  const DEPTH_MAX = 64;
  /** The bands an image is rendered in, to show its progress: of rows in 3D, of pixels in 2D. */
  const RENDER_BANDS = 10;

  /** A pixel as the page writes it: `i, j` (`i` in 2D). */
  const pixelText = (p) => p.join(', ');

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
      // Refusals by what was refused (scene, render, trace, link): each stays until that part of
      // the state changes, all shown at the top of the view.
      this.refusals = new Map();
      this.lessonKind = root.dataset.kind;
      this.lessonPixel = null; // the lesson's own pixel, once known (given, or the figure's pick)
      const d = root.dataset;
      if (d.pixel) this.target = { pixel: d.pixel.split(',').map(Number) };
      else if (d.ray) this.target = { ray: parseRay(d.ray) };
      if (this.target && this.target.pixel) this.lessonPixel = this.target.pixel;
      if (d.depth) this.part('depth').value = d.depth;
      if (d.grid) this.grid = d.grid.split(',').map(Number);
      // `data-busy` counts the work in flight, so that a test can wait for the view to settle.
      this.busy = 0;
      this.root.dataset.busy = '0';
      for (const name of ['rescene', 'rerender', 'retrace', 'render', 'seekNearby']) {
        const work = this[name].bind(this);
        this[name] = async (...args) => {
          this.root.dataset.busy = String(++this.busy);
          try {
            return await work(...args);
          } catch (error) {
            this.refuse('failed', say('failed', { e: error.message }));
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

    /** The fragment's state, each part checked: a part that cannot be used is replaced by the
     *  nearest valid value, and the view says what it corrected. */
    applyFragment(state) {
      const said = [];
      const bad = (part, given, used) => said.push(say('link_part', { part, given, used }));
      for (const [part, given] of state.bad || []) bad(part, given, '–');
      if (state.has('pixel')) {
        const pixel = parsePixel(state.get('pixel'));
        if (pixel) this.target = { pixel };
        else bad('pixel', state.get('pixel'), this.lessonPixel ? '(' + pixelText(this.lessonPixel) + ')' : '–');
        this.linkPixel = pixel ? state.get('pixel') : null;
      }
      for (const name of ['depth', 'aa', 'threshold', 'max_level', 'accel', 'kind']) {
        if (!state.has(name)) continue;
        const given = state.get(name);
        const control = this.part(name);
        if (control.tagName === 'SELECT') {
          if ([...control.options].some((o) => o.value === given)) control.value = given;
          else bad(name, given, control.value);
        } else if (name === 'depth') {
          // Past the limit the view keeps its own depth (the lesson's, else the scene's): a depth
          // near the limit could ask a glass scene for 2^64 rays.
          const depth = /^\d+$/.test(given) ? Number(given) : NaN;
          if (depth <= DEPTH_MAX) control.value = given;
          else bad(name, given, control.value || say('scene_depth'));
        } else if (name === 'max_level') {
          const level = /^\d+$/.test(given) ? Number(given) : NaN;
          const max = Number(control.max);
          if (level <= max) control.value = given;
          else bad(name, given, control.value);
        } else if (/^(inf|\d+(\.\d+)?)$/.test(given)) {
          control.value = given;
        } else {
          bad(name, given, control.value);
        }
      }
      if (state.has('kind') && state.has('accel') === false) this.matchAccel();
      this.wantedStep = state.has('step') ? Number(state.get('step')) : null;
      this.linkStep = state.has('step') ? state.get('step') : null;
      if (said.length) this.refusals.set('link', said.join('\n'));
      this.showMessages();
    }

    wire() {
      this.canvas.addEventListener('pointerdown', (event) => { this.pressed = this.offset(event); });
      this.canvas.addEventListener('click', (event) => this.clicked(event));
      this.part('pixel-form').addEventListener('submit', (event) => {
        event.preventDefault();
        const pixel = parsePixel(this.part('pixel').value);
        if (!pixel) {
          this.refuse('trace', say('pixel_format'));
          return;
        }
        // Enter traces, and gives ← and → back to the steps.
        this.part('pixel').blur();
        this.root.focus({ preventScroll: true });
        View.active = this;
        this.choose({ pixel });
      });
      this.part('back').addEventListener('click', () => this.go(this.step - 1));
      this.part('next').addEventListener('click', () => this.go(this.step + 1));
      this.part('steps').addEventListener('click', (event) => {
        const item = event.target.closest('[data-step]');
        if (item) this.go(this.steps.findIndex((s) => s.step === Number(item.dataset.step)));
      });
      this.part('follow').addEventListener('click', (event) => {
        const button = event.target.closest('button[data-pixel]');
        if (button) this.choose({ pixel: button.dataset.pixel.split(',').map(Number) });
      });
      for (const name of ['depth', 'aa', 'threshold', 'max_level', 'accel']) {
        this.part(name).addEventListener('change', () => {
          if (name === 'accel') this.matchKind();
          this.updateAdaptive();
          this.rerender();
        });
      }
      this.part('kind').addEventListener('change', () => {
        // A structure's figure is narrated by its structure: the control follows the figure.
        if (this.matchAccel()) this.rerender();
        else this.retrace();
      });
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

    /** The figure kind follows the structure chosen: a structure's own figure where the view
     *  shows one (its cells, nodes or slabs drawn), the lesson's figure otherwise. */
    matchKind() {
      const kind = this.part('kind');
      const accel = this.part('accel').value;
      if (!(kind.value in KIND_ACCEL)) return;
      const wanted = accel in ACCEL_KIND ? ACCEL_KIND[accel] : FALLBACK_KIND;
      kind.value = KIND_ACCEL[this.lessonKind] === accel ? this.lessonKind : wanted;
    }

    /** The structure follows the figure kind chosen; true when it changed. */
    matchAccel() {
      const accel = this.part('accel');
      const wanted = KIND_ACCEL[this.part('kind').value];
      if (!wanted || accel.value === wanted) return false;
      accel.value = wanted;
      return true;
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
      if (o.accel === 'bounds' && this.root.dataset.bounds) o.bounds = this.root.dataset.bounds;
      if (this.grid && o.accel === 'grid') o.grid = this.grid;
      return o;
    }

    base() {
      const name = this.root.dataset.path || this.root.dataset.scene;
      return { scene: this.scene, name, objs: this.objs, options: this.options(), lang: LANG };
    }

    /** Shows every refusal in force at the top of the view, and marks what they leave shown as
     *  the last good image and steps. */
    showMessages() {
      const lines = [...this.refusals.values()].filter(Boolean);
      const stale = ['scene', 'render', 'trace', 'failed'].some((k) => this.refusals.has(k));
      if (stale && !this.refusals.has('scene')) lines.push(say('last_good'));
      this.part('message').textContent = lines.join('\n');
      this.root.classList.toggle('stale', stale);
    }

    /** Says why `what` was refused; it stays until `what` succeeds again. */
    refuse(what, text) {
      this.refusals.set(what, text);
      this.showMessages();
    }

    /** `what` succeeded: its refusal goes. */
    accept(what) {
      if (this.refusals.delete(what)) this.showMessages();
    }

    /** A request's errors, or the engine's failure, in the page's words where the page has them. */
    complain(what, answer) {
      const errors = (answer.json && answer.json.errors) || [];
      const text = errors.join('\n');
      const large = /renders at most \d+ pixels .*got (\d+)x(\d+)/.exec(text);
      if (large) this.refuse(what, say('too_large', { w: large[1], h: large[2] }));
      else this.refuse(what, errors.length ? text : say('failed', { e: answer.text }));
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
        this.refuse('scene', say('stale'));
        return;
      }
      this.accept('scene');
      await this.rerender();
    }

    /** The options changed: size the image, render it, and trace again. */
    async rerender() {
      const info = await this.engines.quick.call({ op: 'info', ...this.base() });
      if (info.status !== 0) {
        this.complain('render', info);
        return;
      }
      this.info = info.json;
      this.part('depth').placeholder = String(this.info.max_depth);
      if (this.target && this.target.pixel && !this.inside(this.target.pixel)) {
        const given = this.linkPixel || pixelText(this.target.pixel);
        const nearest = this.nearest(this.target.pixel);
        if (this.linkPixel) {
          this.refusals.set('link', [this.refusals.get('link'),
            say('link_pixel', { given, w: this.info.width, h: this.info.height, pixel: pixelText(nearest) })]
            .filter(Boolean).join('\n'));
          this.target = { pixel: nearest };
        } else {
          this.target = null;
        }
        this.showMessages();
      }
      this.linkPixel = null;
      const tracing = this.retrace();
      await Promise.all([this.render(), tracing]);
    }

    inside(pixel) {
      const { width, height, dimension } = this.info;
      return pixel[0] < width && (dimension === 2 || (pixel.length === 2 && pixel[1] < height));
    }

    /** The pixel of the image nearest `pixel`. */
    nearest(pixel) {
      const { width, height, dimension } = this.info;
      const i = Math.min(width - 1, pixel[0]);
      return dimension === 2 ? [i] : [i, Math.min(height - 1, pixel.length > 1 ? pixel[1] : 0)];
    }

    /** The cost of a trace or a render (`rays` and `tests` by kind) in the page's words. */
    static cost(json) {
      const rays = json.rays || {};
      const tests = json.tests || {};
      const n = (x) => Number(x || 0).toLocaleString(LANG);
      const total = Object.values(rays).reduce((a, b) => a + b, 0);
      return say('cost', {
        rays: n(total), primary: n(rays.primary), reflected: n(rays.reflected), transmitted: n(rays.transmitted),
        shadow: n(rays.shadow), object: n(tests.object), bound: n(tests.bound), node: n(tests.node), voxel: n(tests.voxel),
      });
    }

    /** Renders the image in the render worker, a newer render's image replacing an older one's,
     *  in RENDER_BANDS bands in every sampling mode (issue 30 item 8): bands of rows of a 3D
     *  image, bands of pixels of a 2D scene's line (drawn down its strip), each drawn as it comes
     *  with the share done. The module gives each band the colours and counts of the whole
     *  render's same pixels (`render::band`), so the summed counts are the image's. */
    async render() {
      const gen = ++this.renderGen;
      const { width, height, dimension } = this.info;
      const progress = this.part('progress');
      const started = performance.now();
      progress.hidden = false;
      progress.removeAttribute('value');
      this.part('stats').textContent = say('rendering');
      const flat = dimension === 2;
      const field = flat ? 'columns' : 'rows';
      const total = flat ? width : height;
      const size = Math.max(1, Math.ceil(total / RENDER_BANDS));
      const cost = { rays: {}, tests: {} };
      for (let first = 0; first < total; first += size) {
        const answer = await this.engines.render.call({ op: 'render', ...this.base(), [field]: [first, size] });
        if (gen !== this.renderGen) return;
        if (answer.status !== 0) {
          progress.hidden = true;
          this.part('stats').textContent = '';
          this.complain('render', answer);
          return;
        }
        const context = this.canvas.getContext('2d');
        if (first === 0) {
          this.canvas.width = width;
          this.canvas.height = height;
          this.root.classList.toggle('strip', flat);
        }
        const band = answer.json[field][1];
        const pixels = new Uint8ClampedArray(answer.bytes.buffer, answer.bytes.byteOffset, answer.bytes.length);
        if (flat) {
          // A 2D scene's line: its band of pixels down every row of the strip.
          const line = new ImageData(pixels, band, 1);
          for (let y = 0; y < height; y++) context.putImageData(line, first, y);
        } else {
          context.putImageData(new ImageData(pixels, width, band), 0, first);
        }
        for (const part of ['rays', 'tests']) {
          for (const [key, n] of Object.entries(answer.json[part] || {})) cost[part][key] = (cost[part][key] || 0) + n;
        }
        const done = Math.min(total, first + band);
        progress.max = total;
        progress.value = done;
        if (done < total) this.part('stats').textContent = say('rendering_share', { p: Math.floor((100 * done) / total) });
      }
      progress.hidden = true;
      this.accept('render');
      // `rays` is by kind (primary, reflected, transmitted, shadow), as `render --json` gives it.
      const rays = Object.values(cost.rays).reduce((a, b) => a + b, 0);
      const ms = Math.round(performance.now() - started);
      this.part('stats').textContent = say('rendered', { w: width, h: height, rays: rays.toLocaleString(LANG), ms })
        + '\n' + say('cost_image', { cost: View.cost(cost) });
      this.mark();
    }

    /** Where a pointer event lands on the image, in fractional CSS pixels of its box. */
    offset(event) {
      const box = this.canvas.getBoundingClientRect();
      return { x: event.clientX - box.left, y: event.clientY - box.top, w: box.width, h: box.height };
    }

    /** A click at CSS offset (x, y) of the W×H image → i = ⌊x·Nx/W⌋, j = Ny − 1 − ⌊y·Ny/H⌋, with
     *  x and y in fractional CSS pixels: the pointer's own position where the browser gives it
     *  finer than the click's whole pixels (issue 30 item 7). */
    clicked(event) {
      if (!this.info) return;
      const at = this.offset(event);
      const pressed = this.pressed;
      this.pressed = null;
      // The press's position when it is the same click (a click's coordinates may be rounded).
      const p = pressed && Math.abs(pressed.x - at.x) < 1 && Math.abs(pressed.y - at.y) < 1 ? pressed : at;
      const { width, height, dimension } = this.info;
      const i = Math.min(width - 1, Math.max(0, Math.floor((p.x * width) / p.w)));
      const j = height - 1 - Math.min(height - 1, Math.max(0, Math.floor((p.y * height) / p.h)));
      this.choose({ pixel: dimension === 2 ? [i] : [i, j] });
    }

    choose(target) {
      this.target = target;
      this.wantedStep = 1;
      this.tracing = this.retrace(); // awaited by the benchmark
    }

    /** Traces the target again: narration and figure, together. The narration follows any pixel;
     *  where the view's figure kind cannot draw it, the figure shows the pixel's rays and says
     *  why, with a nearby pixel that the kind can draw and the lesson's own pixel a click away. */
    async retrace() {
      const gen = ++this.traceGen;
      const quick = this.engines.quick;
      const kind = this.part('kind').value;
      const base = this.base();
      let figure = null;
      let target = this.target;
      if (!target) {
        // The figure picks its pixel; the narration follows that pixel.
        figure = await quick.call({ op: 'figure', ...base, kind });
        if (gen !== this.traceGen) return;
        if (figure.status === 0 && figure.json.pixel) {
          target = { pixel: figure.json.pixel };
          if (!this.lessonPixel && kind === this.lessonKind) this.lessonPixel = figure.json.pixel;
        }
      }
      let narration = null;
      if (target) {
        const request = { ...base, target };
        [narration, figure] = await Promise.all([
          quick.call({ op: 'narrate', ...request }),
          figure ? Promise.resolve(figure) : quick.call({ op: 'figure', ...request, kind }),
        ]);
      }
      if (gen !== this.traceGen) return;
      let fallback = null;
      if (narration && narration.status === 0 && figure.status !== 0 && target.pixel) {
        // The kind cannot draw this pixel: its rays instead, and a nearby pixel that it can draw.
        fallback = { why: figure, kind };
        figure = await quick.call({ op: 'figure', ...base, target, kind: FALLBACK_KIND });
        if (gen !== this.traceGen) return;
      }
      // The pixel's ray tree under a figure that draws a part of it (a centre-sampled pixel: a
      // sampled one's steps are its samples, which its figure draws).
      let overview = null;
      if (!fallback && target && target.pixel && OVERVIEW_KINDS.includes(kind) && base.options.aa === 'center'
        && narration && narration.status === 0 && figure.status === 0) {
        overview = await quick.call({ op: 'figure', ...base, options: { ...base.options, size: OVERVIEW_SIZE },
          target, kind: OVERVIEW_KIND });
        if (gen !== this.traceGen) return;
      }
      const failed = narration && narration.status !== 0 ? narration : figure.status !== 0 ? figure : null;
      if (failed) {
        // Refused (a pixel outside the image, an option beyond its limits): the message says why,
        // and the last good trace stays, with its pixel, marked as the last good one.
        this.complain('trace', failed);
        this.target = this.good;
        this.saveState();
        return;
      }
      this.accept('trace');
      this.accept('failed');
      this.good = this.target;
      this.part('pick').textContent = figure.json.pick || '';
      this.shown = figure.json.pixel || (target && target.pixel) || null;
      this.showFigure(figure.json.svg, fallback ? FALLBACK_KIND : kind);
      this.showOverview(overview && overview.status === 0 ? overview.json.svg : null);
      this.follow(fallback, target);
      this.showSteps(narration ? narration.json : null);
      this.mark();
    }

    /** Inserts the figure's SVG: an image with a name, its labels never under LABEL_MIN_PX. */
    showFigure(svgText, kind) {
      const box = this.part('figure');
      box.innerHTML = isolateIds(svgText, 'v' + this.index + '-');
      const svg = box.querySelector('svg');
      if (!svg) return;
      svg.setAttribute('role', 'img');
      const pixel = this.shown ? pixelText(this.shown) : '–';
      svg.setAttribute('aria-label', say('figure_name', { kind: kindName(kind), pixel }));
      readable(svg);
    }

    /** The pixel's ray tree under the figure (`data-whitted="overview"`), or nothing. */
    showOverview(svgText) {
      const box = this.part('overview');
      box.innerHTML = svgText ? isolateIds(svgText, 'v' + this.index + 'o-') : '';
      const svg = box.querySelector('svg');
      box.hidden = !svg;
      if (!svg) return;
      svg.setAttribute('role', 'img');
      svg.setAttribute('aria-label', say('overview_name', { pixel: this.shown ? pixelText(this.shown) : '–' }));
      readable(svg);
    }

    /** The line under the view's top that says what the figure shows instead, and the pixels one
     *  click away: a nearby pixel the lesson's kind can draw, and the lesson's own. */
    follow(fallback, target) {
      const line = this.part('follow');
      line.replaceChildren();
      const pixel = target && target.pixel;
      const add = (text, p) => {
        const button = document.createElement('button');
        button.type = 'button';
        button.dataset.pixel = p.join(',');
        button.textContent = text;
        line.append(' ', button);
        return button;
      };
      if (fallback) {
        const kind = fallback.kind;
        const what = say(KIND_WANTS[kind] || 'want_other');
        const span = document.createElement('span');
        span.textContent = say('fallback', { pixel: pixelText(pixel), what, kind: kindName(kind) });
        line.append(span);
        const seeking = document.createElement('span');
        seeking.dataset.whitted = 'nearby';
        seeking.textContent = ' ' + say('searching');
        line.append(seeking);
        this.seekNearby(pixel, kind, seeking);
      }
      const lesson = this.lessonPixel;
      if (lesson && (!pixel || pixelText(lesson) !== pixelText(pixel))) {
        add(say('lesson_pixel', { pixel: pixelText(lesson) }), lesson);
      }
      line.hidden = line.childNodes.length === 0;
    }

    /** Looks around `pixel`, nearest first, for a pixel whose figure of `kind` can be drawn, and
     *  offers it in `where`; gives up when the view traces something else. */
    async seekNearby(pixel, kind, where) {
      const gen = this.traceGen;
      const { width, height, dimension } = this.info;
      if (!this.lessonPixel && kind === this.lessonKind && !this.root.dataset.ray) {
        // A view opened on a linked pixel has not met its own yet: the figure's pick is it.
        const pick = await this.engines.quick.call({ op: 'figure', ...this.base(), kind });
        if (gen !== this.traceGen) return;
        if (pick.status === 0 && pick.json.pixel) {
          this.lessonPixel = pick.json.pixel;
          const button = document.createElement('button');
          button.type = 'button';
          button.dataset.pixel = this.lessonPixel.join(',');
          button.textContent = say('lesson_pixel', { pixel: pixelText(this.lessonPixel) });
          where.after(' ', button);
        }
      }
      const seen = new Set();
      const candidates = [];
      for (const r of NEAR_RADII) {
        for (const [di, dj] of dimension === 2 ? [[1, 0], [-1, 0]] : NEAR_DIRECTIONS) {
          candidates.push([pixel[0] + di * r, dimension === 2 ? 0 : pixel[1] + dj * r]);
        }
      }
      const lesson = this.lessonPixel;
      if (lesson) {
        for (let k = 1; k <= NEAR_TOWARDS; k++) {
          const at = (a, b) => Math.round(a + ((b - a) * k) / NEAR_TOWARDS);
          candidates.push([at(pixel[0], lesson[0]), dimension === 2 ? 0 : at(pixel[1], lesson[1] || 0)]);
        }
      }
      for (const [i, j] of candidates) {
        if (i < 0 || j < 0 || i >= width || j >= height) continue;
        const candidate = dimension === 2 ? [i] : [i, j];
        if (seen.has(candidate.join())) continue;
        seen.add(candidate.join());
        const answer = await this.engines.quick.call({ op: 'figure', ...this.base(), target: { pixel: candidate }, kind });
        if (gen !== this.traceGen) return;
        if (answer.status === 0) {
          const button = document.createElement('button');
          button.type = 'button';
          button.dataset.pixel = candidate.join(',');
          button.textContent = say('nearby', { pixel: pixelText(candidate) });
          where.replaceChildren(' ', button);
          return;
        }
      }
      where.textContent = ' ' + say('none_nearby');
    }

    showSteps(narration) {
      const list = this.part('steps');
      list.replaceChildren();
      this.steps = narration ? narration.steps : [];
      this.part('command').textContent = narration ? narration.command : '';
      this.part('cost').textContent = narration && narration.stats ? say('cost_pixel', { cost: View.cost(narration.stats) }) : '';
      for (const s of this.steps) {
        const item = document.createElement('li');
        item.dataset.step = s.step;
        item.dataset.events = s.events.join(' ');
        const text = document.createElement('pre');
        text.textContent = s.text;
        item.append(text);
        list.append(item);
      }
      // A figure that follows no pixel (the discriminant's own rays, the cost plot, a heat map)
      // says why where the steps would be, until a pixel is clicked (issue 30 item 4).
      const none = this.part('nopixel');
      const why = WORDS['no_pixel_' + this.part('kind').value] ? say('no_pixel_' + this.part('kind').value) : say('no_steps');
      none.textContent = narration ? '' : why;
      none.hidden = Boolean(narration);
      if (!narration) this.part('current').textContent = why;
      const wanted = this.steps.findIndex((s) => s.step === this.wantedStep);
      if (this.wantedStep !== null && this.wantedStep !== undefined && wanted < 0 && this.linkStep !== null
        && this.linkStep !== undefined && this.steps.length) {
        const n = this.steps[this.steps.length - 1].step;
        this.refusals.set('link', [this.refusals.get('link'),
          say('link_step', { given: this.linkStep, k: Math.min(n, Math.max(1, Number(this.linkStep) || 1)), n })]
          .filter(Boolean).join('\n'));
        this.showMessages();
      }
      const fallbackStep = this.linkStep !== null && this.linkStep !== undefined && Number(this.linkStep) > 1
        ? this.steps.length - 1 : 0;
      this.linkStep = null;
      this.wantedStep = null;
      this.go(wanted >= 0 ? wanted : fallbackStep);
    }

    /** Makes step `k` (an index) current: aria-current, lit items, the text beside the figure,
     *  and, when the step names nothing the figure draws, a line saying so. */
    go(k) {
      const n = this.steps.length;
      const undrawn = this.part('undrawn');
      if (n === 0) {
        this.part('back').disabled = true;
        this.part('next').disabled = true;
        this.part('position').textContent = '';
        undrawn.hidden = true;
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
          // The list is positioned, so its items' offsets are from its own top.
          const top = item.offsetTop - (item.offsetParent === list ? 0 : list.offsetTop);
          if (top < list.scrollTop || top + item.offsetHeight > list.scrollTop + list.clientHeight) {
            list.scrollTop = top - list.clientHeight / 3;
          }
        } else {
          item.removeAttribute('aria-current');
        }
      }
      const events = new Set(current.events);
      const svg = this.part('figure').querySelector('svg');
      let lit = 0;
      // The figure's items and the overview's (the pixel's ray tree, where shown).
      for (const drawn of [svg, this.part('overview').querySelector('svg')]) {
        if (!drawn) continue;
        drawn.classList.add('stepping');
        for (const item of drawn.querySelectorAll('[data-events]')) {
          const on = [...eventSet(item.getAttribute('data-events'))].some((e) => events.has(e));
          item.classList.toggle('lit', on);
          if (on) lit++;
        }
      }
      // The step without its nesting: its first line's indent taken off every line.
      const indent = current.text.length - current.text.trimStart().length;
      const text = current.text.split('\n')
        .map((line) => line.slice(Math.min(indent, line.length - line.trimStart().length))).join('\n');
      const title = text.split('\n')[0].replace(/^\d+\.\s*/, '');
      undrawn.textContent = lit === 0 && svg ? say('undrawn', { what: title }) : '';
      undrawn.hidden = !(lit === 0 && svg);
      this.part('position').textContent = say('step_of', { k: current.step, n: this.steps[n - 1].step });
      this.part('current').textContent = text;
      this.part('back').disabled = k === 0;
      this.part('next').disabled = k === n - 1;
      this.saveState();
      // The hook of grade.js (exercise mode asks the new step's quantity).
      this.root.dispatchEvent(new CustomEvent('whitted:step', { detail: { step: current.step } }));
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

  /** The smallest a figure's label may be drawn, in CSS pixels (issue 30 item 6). */
  const LABEL_MIN_PX = 11;

  /** Keeps an SVG figure's smallest label at LABEL_MIN_PX or more on a narrow page: the figure is
   *  drawn at least as wide as that needs (`--figure-min`), and its box scrolls sideways. */
  function readable(svg) {
    const box = svg.viewBox && svg.viewBox.baseVal;
    if (!box || !box.width) return;
    let smallest = Infinity;
    for (const text of svg.querySelectorAll('text')) {
      const size = parseFloat(text.getAttribute('font-size') || getComputedStyle(text).fontSize);
      if (size > 0) smallest = Math.min(smallest, size);
    }
    if (!Number.isFinite(smallest)) return;
    // whitted.css applies it where the panes stack (a phone's width).
    svg.style.setProperty('--figure-min', Math.ceil((box.width * LABEL_MIN_PX) / smallest) + 'px');
  }

  /** ← and → walk the active view's steps, except while typing; on a select they walk the steps
   *  too instead of changing its value. */
  function keys(views) {
    document.addEventListener('keydown', (event) => {
      if (event.altKey || event.ctrlKey || event.metaKey) return;
      if (event.key !== 'ArrowRight' && event.key !== 'ArrowLeft') return;
      if (event.target.closest && event.target.closest('input, textarea')) return;
      const view = View.active || views[0];
      if (!view) return;
      if (event.key === 'ArrowRight') view.go(view.step + 1);
      else view.go(view.step - 1);
      event.preventDefault();
    }, true);
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
