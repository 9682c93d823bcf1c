// Issue 31 item 5 in headless Chromium: a student's trace document pasted into a live view is
// graded by the module (the library code of `whitted grade`): a correct one agrees, one with a
// mistake names its first divergence, whose step becomes current and lights its ray in the
// figure, and a malformed one lists its errors with their JSON paths; exercise mode hides the
// step's numbers, asks for its quantity and says which components of a typed answer are right.
// One page load serves every check (the suite's budget); nothing waits on a timer.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { ROOT, launch, open, settled, shot } from './support.mjs';

const require = createRequire(import.meta.url);
const AXE = require.resolve('axe-core/axe.min.js');
/** The lesson's first view follows Whitted's scene, which the student's tracer reads from here. */
const SCENE = join(ROOT, 'scenes', 'whitted.json');
const TRACER = join(ROOT, 'examples', 'student', 'tracer.py');
const PAGE_MS = 120000;
const PHONE = 390;
const VIEW = '[data-whitted="view"]';
/** The window heights of the screenshots: the verdict at 1280 and 390 px, the exercise at 1280. */
const SHOT_HEIGHT = [1900, 2300, 960];

let browser;
before(async () => { browser = await launch(); });
after(async () => { await browser?.close(); });

/** The student tracer's document of `pixel` (i,j), with a mistake or none. */
function student(pixel, mistake) {
  const args = [TRACER, SCENE, '--pixel', pixel];
  if (mistake) args.push('--mistake', mistake);
  return execFileSync('python3', args, { encoding: 'utf8' });
}

/** Waits until the first view and this script's calls have settled. */
async function idle(page) {
  await settled(page, PAGE_MS);
  await page.waitForFunction((sel) => {
    const root = document.querySelector(sel);
    return (root.dataset.checking || '0') === '0' && root.dataset.busy === '0';
  }, VIEW, { timeout: PAGE_MS });
}

/** Pastes `text` as the student's document and checks it; returns the verdict as shown. */
async function check(page, text) {
  await page.locator(`${VIEW} [data-whitted="student"]`).first().fill(text);
  await page.evaluate((sel) => { document.querySelector(sel + ' [data-whitted="verdict"]').dataset.verdict = ''; }, VIEW);
  await page.locator(`${VIEW} [data-whitted="check"]`).first().click();
  await page.waitForFunction((sel) => document.querySelector(sel + ' [data-whitted="verdict"]').dataset.verdict !== '',
    VIEW, { timeout: PAGE_MS });
  await idle(page);
  return page.evaluate((sel) => {
    const root = document.querySelector(sel);
    const part = (n) => root.querySelector(`[data-whitted="${n}"]`);
    const verdict = part('verdict');
    const current = part('steps').querySelector('[aria-current="step"]');
    const step = current ? Number(current.dataset.step) : null;
    const events = new Set((current ? current.dataset.events : '').split(' ').filter(Boolean));
    const lit = [...part('figure').querySelectorAll('svg .lit')].map((g) => g.getAttribute('data-events'));
    return {
      kind: verdict.dataset.verdict,
      step: verdict.dataset.step ? Number(verdict.dataset.step) : null,
      text: verdict.innerText,
      cells: Object.fromEntries([...verdict.querySelectorAll('tr')].map((tr) =>
        [tr.querySelector('th').textContent, tr.querySelector('td').textContent])),
      errors: [...verdict.querySelectorAll('li')].map((li) => li.textContent),
      current: step,
      currentText: current ? current.textContent : '',
      litMeetsStep: lit.some((e) => e.split(' ').some((x) => events.has(x))),
      stepInList: Boolean(current) && current.offsetTop >= part('steps').scrollTop
        && current.offsetTop < part('steps').scrollTop + part('steps').clientHeight,
    };
  }, VIEW);
}

/** The exercise's question and whether the step's numbers are hidden. */
async function question(page) {
  return page.evaluate((sel) => {
    const root = document.querySelector(sel);
    return {
      question: root.querySelector('[data-whitted="question"]').textContent,
      asked: root.dataset.asked,
      currentShown: getComputedStyle(root.querySelector('[data-whitted="current"]')).display !== 'none',
      stepHidden: getComputedStyle(root.querySelector('[data-whitted="steps"] [aria-current="step"] pre')).visibility === 'hidden',
    };
  }, VIEW);
}

/** Types an answer and waits for the verdict on it. */
async function answer(page, text) {
  await page.evaluate((sel) => { document.querySelector(sel + ' [data-whitted="feedback"]').dataset.verdict = ''; }, VIEW);
  await page.locator(`${VIEW} [data-whitted="answer"]`).first().fill(text);
  await page.locator(`${VIEW} [data-whitted="answer"]`).first().press('Enter');
  await page.waitForFunction((sel) => document.querySelector(sel + ' [data-whitted="feedback"]').dataset.verdict !== '',
    VIEW, { timeout: PAGE_MS });
  return page.evaluate((sel) => {
    const box = document.querySelector(sel + ' [data-whitted="feedback"]');
    return {
      verdict: box.dataset.verdict,
      text: box.innerText,
      rows: [...box.querySelectorAll('tr[data-right]')].map((tr) => tr.dataset.right === 'true'),
    };
  }, VIEW);
}

async function axe(page) {
  await page.addScriptTag({ path: AXE });
  return page.evaluate(async () => {
    const r = await self.axe.run(document, { resultTypes: ['violations'] });
    return r.violations.map((v) => `${v.id} (${v.impact}): ${v.nodes[0] && v.nodes[0].target.join(' ')}`);
  });
}

test('a student document is graded in the page: agreement, the first divergence lit, errors with paths; exercise mode', { timeout: 10 * PAGE_MS }, async () => {
  const page = await open(browser, 'en/secondary-rays.html');
  await idle(page);
  const pixel = await page.evaluate(() => {
    const v = self.whitted.views[0];
    return ((v.target && v.target.pixel) || v.shown).join(',');
  });
  await page.locator(`${VIEW} details.grade summary`).first().click();

  // The correct document agrees, and says how many quantities it checked.
  const ok = await check(page, student(pixel));
  assert.equal(ok.kind, 'ok', ok.text);
  const agreed = /Everything agrees: (\d+) quantities checked/.exec(ok.text);
  assert.ok(agreed && Number(agreed[1]) > 20, ok.text);

  // R built with the wrong sign: R₁'s direction diverges, its step is current and lit.
  const wrong = await check(page, student(pixel, 'reflect-sign'));
  assert.equal(wrong.kind, 'divergence', wrong.text);
  assert.match(wrong.text, /First divergence: P → R₁, direction/);
  assert.match(wrong.cells['diagnosis'], /R was built with the wrong sign of V/);
  assert.match(wrong.cells['expected (whitted)'], /^\(0\.\d+, /);
  assert.match(wrong.cells['found (yours)'], /^\(−0\.\d+, /);
  assert.equal(wrong.current, wrong.step, 'the divergence\'s step is the current one');
  assert.match(wrong.currentText, /Reflected ray R₁ at I₁/);
  assert.ok(wrong.litMeetsStep, 'the figure lights the step\'s ray');
  assert.ok(wrong.stepInList, 'the steps list is scrolled to the marked step');
  // Tall windows, so that one picture holds the lit figure, the marked step and the verdict.
  await page.setViewportSize({ width: 1280, height: SHOT_HEIGHT[0] });
  await shot(page, 'grade-verdict-1280', `${VIEW} .panes`);
  await page.setViewportSize({ width: PHONE, height: SHOT_HEIGHT[1] });
  await shot(page, 'grade-verdict-390', `${VIEW} .figure-pane`);
  const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
  assert.ok(overflow <= 0, `the page is ${overflow} px wider than a phone`);
  await page.setViewportSize({ width: 1280, height: 720 });

  // A malformed document: every error with its JSON path.
  const bad = await check(page, `{"pixel": [${pixel}], "ray": {"origin": [0, 0.8, 5], "direction": "down"}, "colour": [1, 2]}`);
  assert.equal(bad.kind, 'errors', bad.text);
  assert.ok(bad.errors.some((e) => /^student\.json: ray\.direction/.test(e)), bad.errors.join('\n'));
  assert.ok(bad.errors.some((e) => /colour/.test(e)), bad.errors.join('\n'));

  // Exercise mode at the R₁ step: its numbers hidden, R₁ asked; the narration's own R₁ is right.
  const worked = await page.evaluate((sel) => document.querySelector(sel + ' [data-whitted="current"]').textContent, VIEW);
  const r1 = /R₁ = (\([^)]*\))/.exec(worked)[1];
  await page.locator(`${VIEW} [data-whitted="exercise-mode"]`).first().check();
  await page.waitForFunction((sel) => document.querySelector(sel).dataset.asked, VIEW, { timeout: PAGE_MS });
  await idle(page);
  const q = await question(page);
  assert.equal(q.asked, 'direction');
  assert.match(q.question, /compute the unit direction R₁/);
  assert.ok(!q.currentShown && q.stepHidden, 'the step\'s numbers are hidden');
  const right = await answer(page, r1);
  assert.equal(right.verdict, 'right', right.text);
  assert.deepEqual(right.rows, [true, true, true]);
  // The sign of x flipped: x is wrong, y and z right, and x is off by 2|x|.
  const flipped = r1.replace('(', '(−');
  const off = await answer(page, flipped);
  assert.equal(off.verdict, 'wrong', off.text);
  assert.deepEqual(off.rows, [false, true, true]);
  assert.match(off.text, /2 of 3 right/);
  assert.match(off.text, /off by 1\.6/);
  await page.setViewportSize({ width: 1280, height: SHOT_HEIGHT[2] });
  await shot(page, 'grade-exercise-1280', `${VIEW} .figure-pane`);
  await page.locator(`${VIEW} [data-whitted="reveal"]`).first().click();
  assert.ok((await question(page)).currentShown, 'the worked step is shown on request');
  await page.setViewportSize({ width: PHONE, height: 844 });
  await page.locator(`${VIEW} [data-whitted="next"]`).first().click();
  await page.waitForFunction((sel) => document.querySelector(sel).dataset.asked === 'direction'
    && (document.querySelector(sel).dataset.checking || '0') === '0', VIEW, { timeout: PAGE_MS });
  await answer(page, '(0.8, 0.5, 0.3)');
  await shot(page, 'grade-exercise-390', `${VIEW} .figure-pane`);
  await page.setViewportSize({ width: 1280, height: 720 });

  assert.deepEqual(page.problems, []);
  // (axe reads the style sheet, which a file:// page may not fetch: after the problems' check.)
  assert.deepEqual(await axe(page), [], 'axe finds no violation with the verdict and exercise shown');
  await page.close();
});
