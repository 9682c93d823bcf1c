// What every browser test and the benchmark share: Debian's Chromium started headless through
// playwright-core (no browser download), the paths of the site and the CLI, and page helpers.
import { chromium } from 'playwright-core';
import { execFileSync } from 'node:child_process';
import { mkdirSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

export const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..');
/** The site the tests open; test.sh writes it with `whitted lessons --out` (WHITTED_SITE). */
export const SITE = resolve(process.env.WHITTED_SITE || join(ROOT, 'target', 'browser-site'));
/** The native CLI the page is compared with. */
export const BIN = resolve(process.env.WHITTED_BIN || join(ROOT, 'target', 'release', 'whitted'));
/** Where each state's screenshot is saved. */
export const SHOTS = resolve(process.env.WHITTED_SHOTS || join(ROOT, 'target', 'browser-shots'));

/** Chromium as root needs --no-sandbox; the rest keep it off this machine's closed network. */
const FLAGS = [
  '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
  '--disable-component-update', '--disable-sync',
];

export async function launch() {
  return chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', args: FLAGS, headless: true });
}

/** A page that records every console error and uncaught exception into `problems`. */
export async function open(browser, path, { width = 1280, height = 720 } = {}) {
  const page = await browser.newPage({ viewport: { width, height } });
  const problems = [];
  page.on('console', (m) => { if (m.type() === 'error') problems.push('console: ' + m.text()); });
  page.on('pageerror', (e) => problems.push('exception: ' + e.message));
  page.on('crash', () => problems.push('crash'));
  page.problems = problems;
  const [file, fragment] = path.split('#');
  await page.goto(pathToFileURL(join(SITE, file)).href + (fragment ? '#' + fragment : ''));
  return page;
}

/** Waits until the page's module is ready and every view has settled. */
export async function settled(page, timeout = 20000) {
  await page.waitForFunction(
    () => document.body.dataset.ready === 'true'
      && [...document.querySelectorAll('[data-whitted="view"]')].every((v) => v.dataset.busy === '0'),
    null, { timeout });
}

/** Saves a screenshot of the page as SHOTS/NAME.png, with `selector`'s first element (if given)
 *  scrolled to the top of the window. */
export async function shot(page, name, selector) {
  mkdirSync(SHOTS, { recursive: true });
  if (selector) await page.locator(selector).first().evaluate((e) => e.scrollIntoView({ block: 'start' }));
  const path = join(SHOTS, name + '.png');
  await page.screenshot({ path, fullPage: false });
  return path;
}

/** Runs the native CLI; returns stdout. */
export function whitted(args) {
  return execFileSync(BIN, args, { cwd: ROOT, encoding: 'utf8', maxBuffer: 1 << 28, stdio: ['ignore', 'pipe', 'pipe'] });
}

/** The narration cut at its numbered steps, as `doc::narrate::steps` cuts it. */
export function cutSteps(narration) {
  const out = [];
  for (const line of narration.replace(/\n$/, '').split('\n')) {
    const next = (out.length + 1) + '. ';
    const body = line.replace(/^ +/, '');
    const indent = line.length - body.length;
    if ((body.startsWith(next) && indent % 3 === 0) || out.length === 0) out.push(line);
    else out[out.length - 1] += '\n' + line;
  }
  return out;
}

/** A step's text without its nesting, as the page shows the current step beside the figure: its
 *  first line's indent taken off every line. */
export function dedent(text) {
  const indent = text.length - text.trimStart().length;
  return text.split('\n').map((line) => line.slice(Math.min(indent, line.length - line.trimStart().length))).join('\n');
}

/** Run in the page (`page.evaluate(liveViews)`): each view's state after it settled, and `live`
 *  when it shows what a live view shows: a rendered image, its cost, a figure and no refusal. */
export function liveViews() {
  return [...document.querySelectorAll('[data-whitted="view"]')].map((v) => {
    const state = {
      width: v.querySelector('canvas').width,
      stats: v.querySelector('[data-whitted="stats"]').textContent,
      figure: !!v.querySelector('[data-whitted="figure"] svg'),
      message: v.querySelector('[data-whitted="message"]').textContent,
    };
    return { ...state, live: state.width >= 1 && !!state.stats && state.figure && !state.message };
  });
}
