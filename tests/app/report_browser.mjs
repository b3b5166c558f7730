// Opens a `bounce bench` report (DIR/report.html) in headless Chromium (Debian's package, driven by
// playwright-core from package.json) and checks it as a reader would use it. Exit status 0 when every
// check holds; otherwise each failure is printed and the status is 1.
//
//   node tests/app/report_browser.mjs DIR [--screenshot FILE.png [--scene NAME]]
//
// The expectations come from DIR/results.json and the image files, read here, not from the page:
// - the page loads with no console error, no uncaught exception and no failed request (a broken link or
//   script fails), and every link on it names a file that exists;
// - each scene's speed-against-error plot holds one point per row of that scene in results.json;
// - flipping (key f) changes the displayed pixels, and flipping back restores them;
// - the error map of an image against itself is the colour map's zero (viridis' first colour) everywhere,
//   and that of a render against its reference is not;
// - a camera-path run (its record's "sequence") plots its error and frame time, and its player shows the
//   measured frames beside their references: a step shows the next frame's image and reference, a step
//   back the one before, and play advances on its own until paused.
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { chromium } from 'playwright-core';

const args = process.argv.slice(2);
const dir = args[0];
const shotAt = args.indexOf('--screenshot');
const screenshot = shotAt >= 0 ? args[shotAt + 1] : null;
const sceneAt = args.indexOf('--scene');
const shotScene = sceneAt >= 0 ? args[sceneAt + 1] : null;
if (!dir || !fs.existsSync(path.join(dir, 'report.html'))) {
  console.error('usage: node report_browser.mjs DIR [--screenshot FILE.png [--scene NAME]] (DIR holds report.html)');
  process.exit(2);
}
const executablePath = process.env.BOUNCE_CHROMIUM || '/usr/bin/chromium';
if (!fs.existsSync(executablePath)) {
  console.error(`${executablePath} is missing: scripts/install-deps.sh installs Debian's chromium`);
  process.exit(1);
}

const results = JSON.parse(fs.readFileSync(path.join(dir, 'results.json'), 'utf8'));
const failures = [];
const check = (ok, what) => { if (!ok) failures.push(what); };
const ZERO = [68, 1, 84]; // the error map's colour for 0: viridis' first

const browser = await chromium.launch({ executablePath, headless: true, args: ['--no-sandbox'] });
try {
  await checkPage();
} catch (e) {
  failures.push(e.message);
} finally {
  await browser.close();
}
for (const f of failures) console.error('FAIL: ' + f);
console.log(failures.length ? `${failures.length} checks failed` : 'report.html: every check holds');
process.exit(failures.length ? 1 : 0);

async function checkPage() {
  const page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  page.on('console', (m) => { if (m.type() === 'error') failures.push('console error: ' + m.text()); });
  page.on('pageerror', (e) => failures.push('uncaught exception: ' + e.message));
  page.on('requestfailed', (r) => failures.push('request failed: ' + r.url()));
  await page.goto(pathToFileURL(path.resolve(dir, 'report.html')).href);
  // The viewer marks the body loaded ("true") or not ("error": an image that did not load) after each change.
  const loaded = async () => {
    await page.waitForSelector('body[data-loaded="true"], body[data-loaded="error"]', { timeout: 20000 });
    if ((await page.getAttribute('body', 'data-loaded')) !== 'true') throw new Error('an image did not load');
  };
  await loaded();

  // The canvas' pixels, as an array of [r, g, b] strings' counts would lose order: the raw RGBA bytes.
  const pixels = () => page.evaluate(() => {
    const c = document.getElementById('view');
    return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);
  });

  const scenes = [...new Set(results.map((r) => r.scene))];
  const buttons = await page.locator('#scenes button').allTextContents();
  check(JSON.stringify(buttons) === JSON.stringify(scenes), `scene buttons ${buttons} are not the scenes ${scenes}`);
  for (const scene of scenes) {
    await page.locator('#scenes button', { hasText: scene }).first().click();
    await loaded();
    const points = await page.locator('#plot circle.run').count();
    // Camera-path runs are not on the speed plot: their error is of moving frames, not of an image.
    const rows = results.filter((r) => r.scene === scene && !r.sequence).length;
    check(points === rows, `${scene}: the plot holds ${points} points for ${rows} rows`);
    for (const r of results.filter((x) => x.scene === scene))
      for (const id of [r.image, ...Object.values(r.references || {}),
        ...(r.sequence ? r.sequence.frames.flatMap((f) => f.image ? [f.image, f.reference] : []) : [])])
        for (const ext of ['.exr', '.png', '.js'])
          check(id && fs.existsSync(path.join(dir, id + ext)), `${scene}: ${id}${ext} is missing`);
  }

  // The camera-path runs' plots and players.
  async function checkSequences() {
    for (const r of results.filter((x) => x.sequence)) {
      const index = results.indexOf(r);
      await page.locator('#scenes button', { hasText: r.scene }).first().click();
      await loaded();
      await page.locator(`#run-table tr.run-row[data-index="${index}"]`).click();
      await loaded();
      const shown = r.sequence.frames.filter((f) => f.image);
      const plots = await page.locator('#sequence svg.sequence-plot').count();
      check(plots === 2, `sequence #${index}: ${plots} plots instead of error and frame time`);
      const points = await page.locator('#sequence svg.sequence-plot').first().locator('circle').count();
      check(points === shown.length, `sequence #${index}: the error plot holds ${points} points for ${shown.length} frames`);
      const at = async () => [await page.inputValue('#image-a'), await page.inputValue('#image-b')];
      const expect = (f) => [f.image, f.reference];
      const last = shown[shown.length - 1];
      check(JSON.stringify(await at()) === JSON.stringify(expect(last)), `sequence #${index} opens on ${await at()}, not its last frame`);
      await page.click('#sequence-next');
      await loaded();
      check(JSON.stringify(await at()) === JSON.stringify(expect(shown[0])), `sequence #${index}: a step from the last frame shows ${await at()}`);
      await page.click('#sequence-next');
      await loaded();
      check(JSON.stringify(await at()) === JSON.stringify(expect(shown[1 % shown.length])), `sequence #${index}: a step shows ${await at()}`);
      await page.click('#sequence-back');
      await loaded();
      check(JSON.stringify(await at()) === JSON.stringify(expect(shown[0])), `sequence #${index}: a step back shows ${await at()}`);
      await page.click('#sequence-play');
      await page.waitForFunction((first) => document.getElementById('image-a').value !== first, shown[0].image,
        { timeout: 5000 }).catch(() => failures.push(`sequence #${index}: play did not advance`));
      await page.click('#sequence-play');
      await loaded();
      const paused = await at();
      await page.waitForTimeout(1200);
      check(JSON.stringify(await at()) === JSON.stringify(paused), `sequence #${index}: pause did not stop the player`);
    }
  }

  // Links: every href and src on the page (EXRs and PNGs of the images, the stylesheet, the scripts)
  // names a file.
  const hrefs = await page.evaluate(() => [...document.querySelectorAll('[href], [src]')]
    .map((e) => e.getAttribute('href') || e.getAttribute('src')));
  for (const h of hrefs) check(fs.existsSync(path.join(dir, h)), `link ${h} names no file`);
  check(hrefs.some((h) => h.endsWith('.png')), 'the page shows no PNG');
  check(hrefs.some((h) => h.endsWith('.exr')), 'the viewer links no EXR');

  // Decoding: at exposure 0 the viewer's A is the bench's own tone-mapped PNG of the same image (C++,
  // core/image.cpp), up to the half floats' rounding.
  await page.selectOption('#mode', 'a');
  const shownA = await page.inputValue('#image-a');
  const png = 'data:image/png;base64,' + fs.readFileSync(path.join(dir, shownA + '.png')).toString('base64');
  const fromPng = await page.evaluate(async (url) => {
    const img = new Image();
    img.src = url;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width;
    c.height = img.height;
    c.getContext('2d').drawImage(img, 0, 0);
    return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);
  }, png);
  const shown = await pixels();
  const off = shown.filter((v, i) => Math.abs(v - fromPng[i]) > 1).length;
  check(shown.length === fromPng.length && off === 0, `${shownA}: ${off} channel values differ from its PNG by more than 1`);

  // Flip: A (a render) and B (its reference) differ, so the pixels change, and flip back restores them.
  await page.selectOption('#mode', 'a');
  const a = await pixels();
  await page.keyboard.press('f');
  const b = await pixels();
  await page.keyboard.press('f');
  const again = await pixels();
  check(a.length > 0 && a.some((v, i) => v !== b[i]), 'flipping A and B left the displayed pixels unchanged');
  check(a.every((v, i) => v === again[i]), 'flipping twice did not restore the displayed pixels');

  // The error map: a render against its reference is not zero everywhere...
  await page.keyboard.press('e');
  const differs = await pixels();
  const isZero = (px, i) => i % 4 === 3 || px[i] === ZERO[i % 4];
  check(!differs.every((v, i) => isZero(differs, i)), 'the error map of a render against its reference is all zero');
  // ...and an image against itself is zero at every pixel.
  const imageA = await page.inputValue('#image-a');
  await page.selectOption('#image-b', imageA);
  await loaded();
  await page.selectOption('#mode', 'error');
  const self = await pixels();
  const bad = self.filter((v, i) => !isZero(self, i)).length;
  check(self.length > 0 && bad === 0, `the error map of ${imageA} against itself is not zero at ${bad} channel values`);

  await checkSequences();

  if (screenshot) {
    // The README's picture: a scene afresh (its first render beside the full reference), split, the best
    // run of the scene hovered.
    const scene = shotScene || scenes[0];
    await page.locator('#scenes button', { hasText: scene }).first().click();
    await loaded();
    const best = results.filter((r) => r.scene === scene && r.technique !== 'path-tracer' && r.image)
      .sort((a, b) => Number(a.error.full.relativeRmse) - Number(b.error.full.relativeRmse))[0];
    if (best) {
      await page.locator(`#plot circle.run[data-index="${results.indexOf(best)}"]`).click();
      await loaded();
      await page.locator(`#plot circle.run[data-index="${results.indexOf(best)}"]`).hover();
    }
    await page.selectOption('#mode', 'split');
    await page.screenshot({ path: screenshot, fullPage: false });
  }
}
