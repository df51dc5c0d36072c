// The pages `bentstraw grade` writes, opened from the disk in headless Chromium as a teacher or
// a student opens them: on a desktop and on a phone, in English and in French.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { mkdtempSync, mkdirSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { pathToFileURL } from "node:url";
import { launch, runCli } from "./harness.mjs";

const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-grade-"));
const REF1 = ["--observer", "0,0.1,0.1", "--straw", "0.02,0.01", "--water-height", "0.15"];
const REF2 = ["--observer", "0.1,0,0.1", "--straw", "0.02,0.01", "--water-height", "0.15"];
let browser;

/** A class of three: Ada's first case right, Bob's the other view's points, Carl's unreadable. */
before(async () => {
  for (const s of ["ada", "bob", "carl"]) mkdirSync(path.join(dir, "class", s), { recursive: true });
  for (const [who, flags] of [["ada", REF1], ["bob", REF2]]) {
    const r = await runCli(["simulate", ...flags, "--points", "3000", "--output", path.join(dir, "class", who, "sim1.csv")]);
    assert.equal(r.code, 0, r.stderr);
  }
  writeFileSync(path.join(dir, "class", "carl", "sim1.csv"), "x,y,z,color\n0,0,oops,1\n");
  for (const [out, lang] of [["en", "en"], ["fr", "fr"]]) {
    const r = await runCli(["grade", "class", "--out", out, "--lang", lang], dir);
    assert.equal(r.code, 0, r.stderr);
  }
  browser = await launch();
});
after(async () => { await browser?.close(); });

/** Opens `file` (under the output) in a page of `viewport`; the page and its console errors. */
async function open(file, viewport) {
  const context = await browser.newContext({ viewport, ...(viewport.width < 500 ? { isMobile: true, hasTouch: true } : {}) });
  const page = await context.newPage();
  const problems = [];
  page.on("console", (m) => { if (m.type() === "error") problems.push(m.text()); });
  page.on("pageerror", (e) => problems.push(e.message));
  await page.goto(pathToFileURL(path.join(dir, file)).href);
  await page.waitForLoadState("load");
  return { page, context, problems };
}

/** The figures of the page, decoded: their natural sizes. */
const figures = (page) => page.$$eval("figure img", (imgs) => imgs.map((i) => [i.complete, i.naturalWidth, i.naturalHeight]));

for (const [device, viewport] of [["a desktop", { width: 1280, height: 900 }], ["a phone", { width: 390, height: 844 }]]) {
  test(`the class page leads to each student's feedback, figures drawn, on ${device}`, async () => {
    const { page, context, problems } = await open("en/index.html", viewport);
    assert.match(await page.locator("h1").innerText(), /class/i);
    const body = await page.locator("body").innerText();
    assert.match(body, /3 students/);
    // The class's page fits the screen's width: nothing to scroll sideways.
    assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= innerWidth + 1), "the class page is wider than the screen");
    await page.screenshot({ path: path.join(tmpdir(), `bentstraw-grade-class-${viewport.width}.png`), fullPage: true });
    await Promise.all([page.waitForEvent("load"), page.getByRole("link", { name: "bob" }).click()]);
    assert.match(await page.locator("h1").innerText(), /bob/);
    const text = await page.locator("body").innerText();
    assert.match(text, /fail/);
    assert.match(text, /points wrong/);
    // Bob's one read case has its check figure, decoded and as wide as the page allows.
    const shown = await figures(page);
    assert.equal(shown.length, 1);
    assert.deepEqual(shown[0].slice(0, 1), [true]);
    assert.ok(shown[0][1] >= 800 && shown[0][2] >= 800, `figure ${shown[0]}`);
    // The case's name leads to it.
    await page.getByRole("link", { name: "sim1" }).click();
    await page.waitForFunction(() => location.hash === "#figure-sim1");
    assert.ok(await page.locator("#figure-sim1").isVisible());
    const width = await page.locator("figure img").evaluate((i) => i.getBoundingClientRect().width);
    assert.ok(width <= viewport.width, `the figure is ${width} px wide on a ${viewport.width} px screen`);
    assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= innerWidth + 1), "the feedback page is wider than the screen");
    await page.screenshot({ path: path.join(tmpdir(), `bentstraw-grade-bob-${viewport.width}.png`), fullPage: true });
    assert.deepEqual(problems, []);
    await context.close();
  });
}

test("an unreadable file's feedback says why, with no figure; in French too", async () => {
  const { page, context, problems } = await open("en/carl/index.html", { width: 1280, height: 900 });
  const text = await page.locator("body").innerText();
  assert.match(text, /unreadable/);
  assert.match(text, /line 2/);
  assert.deepEqual(await figures(page), []);
  await context.close();
  const fr = await open("fr/bob/index.html", { width: 390, height: 844 });
  assert.equal(await fr.page.getAttribute("html", "lang"), "fr");
  const words = await fr.page.locator("body").innerText();
  assert.match(words, /échoué/);
  assert.match(words, /points faux sur/);
  assert.equal((await figures(fr.page)).length, 1);
  await fr.page.screenshot({ path: path.join(tmpdir(), "bentstraw-grade-bob-fr.png"), fullPage: true });
  assert.deepEqual([...problems, ...fr.problems], []);
  await fr.context.close();
});
