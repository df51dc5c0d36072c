// End-to-end tests of the explorer in headless Chromium (run: npm test): the page served by
// `bentstraw explore`, or with EXPLORE_ON=site the same page from the static site (cargo xtask
// site) served by a plain static server, every answer computed by the engine in WebAssembly.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { mkdtempSync, readFileSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { startServer, startStaticServer, launch, openPage, waitReady, runCli, ROOT } from "./harness.mjs";

/** The page from the static site (its engine in WebAssembly) instead of `bentstraw explore`. */
const ON_SITE = process.env.EXPLORE_ON === "site";
/** What only the server has (its HTTP API, its command line) is tested with the server. */
const SERVER_ONLY = { skip: ON_SITE && "the static site has no server" };
/** Where a screenshot goes: the README's pictures come from the server's page. */
const shot = (name) => (ON_SITE ? path.join(tmpdir(), "bentstraw-site-" + name) : path.join(ROOT, "docs", name));

let server, browser;
before(async () => { server = ON_SITE ? await startStaticServer() : await startServer(); browser = await launch(); });
after(async () => { await browser?.close(); server?.stop(); });

const REF2 = { observer: "0.1,0,0.1", straw: "0.02,0.01", he: "0.15" };
/** A digest of the picture's pixels. */
const pictureDigest = (page) => page.evaluate(() => {
  const f = window.bentstraw.frame;
  let h = 2166136261;
  for (let i = 0; i < f.rgba.length; i += 7) h = Math.imul(h ^ f.rgba[i], 16777619);
  return `${f.header.width}x${f.header.height}:${h >>> 0}`;
});
/** simulate's CSV rows as [x, y, z, color] numbers. */
const csvRows = (text) => text.trim().split("\n").slice(1).map((l) => l.split(",").map(Number));

test("the page loads offline, with no console error and no failed request", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  const s = await page.evaluate(() => ({ n: window.bentstraw.frame.header.n, w: window.bentstraw.frame.header.width }));
  assert.ok(s.n >= 20000, `${s.n} points`);
  assert.ok(s.w > 300);
  assert.deepEqual(problems, []);
  await context.close();
});

test("dragging in the picture moves the observer and changes the picture", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  const before = await page.evaluate(() => window.bentstraw.state.observer.slice());
  const digest = await pictureDigest(page);
  const box = await page.locator("#picture").boundingBox();
  const frames = await page.evaluate(() => window.bentstraw.frames);
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  for (let i = 1; i <= 15; i++) { await page.mouse.move(box.x + box.width / 2 + 8 * i, box.y + box.height / 2 - 2 * i); await page.waitForTimeout(16); }
  await page.mouse.up();
  await waitReady(page, frames);
  const afterObs = await page.evaluate(() => window.bentstraw.state.observer.slice());
  assert.notDeepEqual(afterObs, before);
  // The distance to the glass's middle is kept by an orbit.
  const dist = (o) => Math.hypot(o[0], o[1], o[2] - 0.1);
  assert.ok(Math.abs(dist(afterObs) - dist(before)) < 1e-3);
  assert.notEqual(await pictureDigest(page), digest);
  assert.match(page.url(), new RegExp("observer=" + afterObs.map(String).join("%2C")));
  assert.deepEqual(problems, []);
  await context.close();
});

test("a preset loads a reference simulation whose points are simulate's", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url + "#observer=0.3,0,0.05&straw=0,0&water-height=0.1");
  await waitReady(page);
  const frames = await page.evaluate(() => window.bentstraw.frames);
  await page.selectOption("#preset", { label: "Reference 3: eye above, (0.1, 0, 0.3)" });
  await waitReady(page, frames);
  const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-"));
  const csv = path.join(dir, "sim3.csv");
  const r = await runCli(["simulate", "--observer", "0.1,0,0.3", "--straw", "0.02,0.01", "--water-height", "0.2", "--points", "20000", "--output", csv]);
  assert.equal(r.code, 0, r.stderr);
  const rows = csvRows(readFileSync(csv, "utf8"));
  const pts = await page.evaluate(() => ({ xyz: Array.from(window.bentstraw.frame.xyz), color: Array.from(window.bentstraw.frame.color) }));
  assert.equal(pts.color.length, rows.length);
  rows.forEach(([x, y, z, c], i) => {
    assert.equal(pts.color[i], c);
    // The page gets single-precision coordinates: equal to the file's after rounding to f32.
    assert.deepEqual(pts.xyz.slice(3 * i, 3 * i + 3), [Math.fround(x), Math.fround(y), Math.fround(z)]);
  });
  // The exported CSV is the very file simulate wrote.
  const exported = await page.evaluate(async () => {
    const q = new URLSearchParams(location.hash.slice(1));
    q.set("format", "csv");
    return (await engineFetch("test", "/api/export", q.toString())).text();
  });
  assert.equal(exported, readFileSync(csv, "utf8"));
  // The page's command line for the points is the one just run.
  const cmd = await page.evaluate(() => window.bentstraw.frame.header.simulate);
  assert.equal(cmd, "bentstraw simulate --observer 0.1,0,0.3 --straw 0.02,0.01 --water-height 0.2 --points 20000 --output view.csv");
  await page.click("#show-commands");
  assert.match(await page.textContent("#cmd-render"), /^bentstraw render --observer 0\.1,0,0\.3 .*--mode fresnel --backdrop checker --output view\.png$/);
  await page.selectOption("#color-by", "path");
  await page.screenshot({ path: shot("explorer-paths.png") });
  assert.deepEqual(problems, []);
  await context.close();
});

test("the eye and stereo models come quickly, then whole, and are simulate's", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url + "#observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&points=6000");
  await waitReady(page);
  const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-"));
  for (const m of ["eye", "stereo"]) {
    // Seen first with every 4th point, then with all of them.
    const sizes = await page.evaluate(async (m) => {
      const seen = [];
      document.getElementById("show-" + m).click();
      for (;;) {
        const x = window.bentstraw.models[m];
        if (x && !x.pending && seen[seen.length - 1] !== x.color.length) seen.push(x.color.length);
        if (x && x.all) return seen;
        await new Promise((r) => setTimeout(r, 1));
      }
    }, m);
    const csv = path.join(dir, m + ".csv");
    const r = await runCli(["simulate", "--observer", "0.1,0,0.1", "--straw", "0.02,0.01", "--water-height", "0.15", "--points", "6000", "--image-model", m, "--output", csv]);
    assert.equal(r.code, 0, r.stderr);
    // The points the model places (a row without a position has empty coordinates).
    const placed = readFileSync(csv, "utf8").trim().split("\n").slice(1).map((l) => l.split(",")).filter((c) => c[0] !== "").map((c) => c.slice(0, 3).map(Number));
    assert.ok(placed.length > 1000, `${m}: ${placed.length} points placed`);
    const got = await page.evaluate((m) => Array.from(window.bentstraw.models[m].xyz), m);
    assert.equal(got.length, 3 * placed.length, `${m}: ${got.length / 3} points in the page, ${placed.length} in the file`);
    placed.forEach((q, i) => assert.deepEqual(got.slice(3 * i, 3 * i + 3), q.map(Math.fround)));
    assert.ok(sizes.length >= 2 && sizes[0] < sizes[sizes.length - 1], `${m}: sizes ${sizes}`);
  }
  assert.deepEqual(problems, []);
  await context.close();
});

test("clicking a point of the cloud shows its path with simulate's numbers", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url + "#observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&points=20000&view=-60,12,1.25");
  await waitReady(page);
  const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-"));
  const csv = path.join(dir, "sim2.csv");
  const r = await runCli(["simulate", "--observer", REF2.observer, "--straw", REF2.straw, "--water-height", REF2.he, "--output", csv]);
  assert.equal(r.code, 0, r.stderr);
  const rows = csvRows(readFileSync(csv, "utf8"));
  const K = 1234;
  assert.ok(await page.evaluate(() => window.bentstraw.frame.color.length) > K);
  await page.evaluate((k) => window.bentstraw.pickPoint(k), K);
  await page.waitForFunction((k) => document.body.dataset.picked === "point:" + k, K);
  const p = await page.evaluate(() => window.bentstraw.path);
  assert.deepEqual(p.image_point, rows[K].slice(0, 3));
  assert.equal(p.color, rows[K][3]);
  // The broken path: L = sum of its straight pieces, and the image point is O + L·u0.
  const pts = [p.observer, ...p.events.map((e) => e.point), p.straw_point];
  let L = 0;
  for (let i = 1; i < pts.length; i++) L += Math.hypot(...pts[i].map((v, j) => v - pts[i - 1][j]));
  assert.ok(Math.abs(L - p.path_length) < 1e-12, `${L} vs ${p.path_length}`);
  assert.ok(p.events.every((e) => ["refraction", "total reflection"].includes(e.event)));
  const table = await page.textContent("#readout");
  assert.match(table, /path length L/);
  assert.match(table, /s_h, s_v/);
  // A click in the picture traces the ray of that pixel.
  const box = await page.locator("#picture").boundingBox();
  await page.mouse.click(box.x + box.width * 0.52, box.y + box.height * 0.55);
  await page.waitForFunction(() => (document.body.dataset.picked || "").startsWith("px:"));
  // A real click on the cloud picks the point drawn there (one made by a total reflection).
  // (One the legend does not cover, inside the view.)
  const hit = await page.evaluate(() => {
    const f = window.bentstraw.frame;
    const c = document.getElementById("cloud").getBoundingClientRect();
    const l = document.getElementById("legend").getBoundingClientRect();
    const clear = ([x, y]) => x > c.left + 10 && x < c.right - 10 && y > c.top + 10 && y < c.bottom - 10 && !(x > l.left - 10 && x < l.right + 10 && y > l.top - 10 && y < l.bottom + 10);
    const total = (i) => /total/.test(f.header.paths[f.kind[i]].words);
    let best = -1;
    for (let i = 0; i < f.color.length; i += 7) {
      if (!clear(window.bentstraw.screenOfPoint(i))) continue;
      if (best < 0) best = i;
      if (total(i)) { best = i; break; }
    }
    return window.bentstraw.screenOfPoint(best);
  });
  await page.mouse.click(hit[0], hit[1]);
  await page.waitForFunction(() => (document.body.dataset.picked || "").startsWith("point:") && document.body.dataset.picked !== "point:1234");
  assert.equal(await page.evaluate(() => window.bentstraw.path.outcome), "straw");
  await page.screenshot({ path: shot("explorer.png") });
  assert.deepEqual(problems, []);
  await context.close();
});

test("the scene chooser shows a gallery scene whose points and paths are simulate's", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  await page.waitForFunction(() => Number(document.body.dataset.scenes || 0) >= 6);
  const frames = await page.evaluate(() => window.bentstraw.frames);
  await page.selectOption("#scene", "reversing-arrow");
  await waitReady(page, frames);
  assert.match(page.url(), /scene=reversing-arrow/);
  // The points are simulate's for the same scene file and eye, codes 7 (card) and 8 (arrow).
  const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-"));
  const csv = path.join(dir, "arrow.csv");
  const r = await runCli(["simulate", "--scene", path.join(ROOT, "scenes/reversing-arrow.toml"), "--points", "20000", "--output", csv]);
  assert.equal(r.code, 0, r.stderr);
  const rows = csvRows(readFileSync(csv, "utf8"));
  const pts = await page.evaluate(() => ({ xyz: Array.from(window.bentstraw.frame.xyz), color: Array.from(window.bentstraw.frame.color) }));
  assert.equal(pts.color.length, rows.length);
  rows.forEach(([x, y, z, c], i) => {
    assert.equal(pts.color[i], c);
    assert.deepEqual(pts.xyz.slice(3 * i, 3 * i + 3), [Math.fround(x), Math.fround(y), Math.fround(z)]);
  });
  assert.ok(pts.color.includes(8) && pts.color.includes(7));
  // A point of the arrow seen through the water: its path length and image point are the file's.
  const k = rows.findIndex(([, , , c]) => c === 8);
  await page.evaluate((i) => window.bentstraw.pickPoint(i), k);
  await page.waitForFunction(() => window.bentstraw.path !== null);
  const p = await page.evaluate(() => window.bentstraw.path);
  assert.equal(p.color, 8);
  assert.equal(p.color_name, "arrow");
  const [x, y, z] = rows[k];
  const o = [0.3, 0, 0.1];
  assert.ok(Math.abs(p.path_length - Math.hypot(x - o[0], y - o[1], z - o[2])) < 1e-12, `${p.path_length}`);
  p.image_point.forEach((v, i) => assert.ok(Math.abs(v - [x, y, z][i]) < 1e-12));
  // The water's sliders belong to the assignment's glass: off for a gallery scene.
  assert.equal(await page.locator("#he").isDisabled(), true);
  await page.screenshot({ path: shot("explorer-gallery.png") });
  // Back to the glass: the sliders are live again.
  const f2 = await page.evaluate(() => window.bentstraw.frames);
  await page.selectOption("#scene", "");
  await waitReady(page, f2);
  assert.equal(await page.locator("#he").isDisabled(), false);
  assert.deepEqual(problems, []);
  await context.close();
});

test("a copied link reproduces the state in a fresh page", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url + "#observer=0.12,0.05,0.14&straw=0.01,-0.01&water-height=0.12&n-water=1.5&mode=course&color=path&models=course,eye&view=20,10,1.5");
  await waitReady(page);
  await page.click("#copy-link");
  const link = await page.evaluate(() => document.body.dataset.link);
  const state = await page.evaluate(() => JSON.stringify(window.bentstraw.state));
  const digest = await pictureDigest(page);
  const fresh = await openPage(browser, server.url);
  await fresh.page.goto(link);
  await waitReady(fresh.page);
  assert.equal(await fresh.page.evaluate(() => JSON.stringify(window.bentstraw.state)), state);
  assert.equal(await pictureDigest(fresh.page), digest);
  assert.deepEqual([...problems, ...fresh.problems], []);
  await fresh.context.close();
  await context.close();
});

test("an invalid parameter in the address shows the command line's message", async () => {
  const r = await runCli(["simulate", "--observer", "0.1,0,0.1", "--straw", "0.02,0.01", "--water-height", "0.3", "--output", "/tmp/never.csv"]);
  assert.equal(r.code, 2);
  const message = r.stderr.trim().replace(/^error: /, "");
  const { page, context } = await openPage(browser, server.url);
  await page.goto(server.url + "#observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.3");
  await page.waitForFunction(() => !document.getElementById("error").hidden);
  assert.equal(await page.textContent("#error"), message);
  // Then a good value brings a view back and clears the message.
  await page.evaluate(() => { location.hash = "observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15"; });
  await waitReady(page);
  assert.equal(await page.isHidden("#error"), true);
  // A bad slider value keeps the last good picture.
  const digest = await pictureDigest(page);
  await page.evaluate(() => { location.hash = "observer=0.1,0,0.1&straw=0.039,0.01&water-height=0.15"; });
  await page.waitForFunction(() => !document.getElementById("error").hidden);
  assert.match(await page.textContent("#error"), /does not fit in the glass/);
  assert.equal(await pictureDigest(page), digest);
  await context.close();
});

test("the server survives a burst of malformed requests", SERVER_ONLY, async () => {
  const base = server.url;
  const good = "observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&size=64x48&points=500";
  const bad = [
    "api/frame?observer=abc", "api/frame?" + good.replace("0.15", "NaN"), "api/frame?" + good.replace("64x48", "999999x999999"),
    "api/frame?" + good.replace("500", "1e30"), "api/frame?" + good + "&max-events=100000", "api/frame?%zz",
    "api/ray?" + good + "&point=-1", "api/ray?" + good + "&row=1e308&col=0", "api/export?" + good + "&format=exe",
    "api/model?" + good + "&model=x", "api/nothing", "nothing", "api/frame?" + "a=1&".repeat(100), "api/frame?" + "x".repeat(5000),
  ];
  const statuses = await Promise.all(Array.from({ length: 120 }, (_, i) => fetch(base + bad[i % bad.length]).then((r) => r.status, () => 0)));
  assert.ok(statuses.every((s) => s >= 400 && s < 600), statuses.join(","));
  const posted = await fetch(base + "api/frame?" + good, { method: "POST", body: "x" });
  assert.equal(posted.status, 405);
  // Many good ones at once: answered, or refused as busy, never dropped.
  const burst = await Promise.all(Array.from({ length: 24 }, () => fetch(base + "api/frame?" + good).then((r) => r.status)));
  assert.ok(burst.every((s) => s === 200 || s === 503), burst.join(","));
  assert.ok(burst.includes(200));
  const after = await fetch(base + "api/frame?" + good);
  assert.equal(after.status, 200);
});

test("a busy port is named in one line, exit code 2; Ctrl-C stops the server", SERVER_ONLY, async () => {
  const port = new URL(server.url).port;
  const r = await runCli(["explore", "--no-open", "--port", port]);
  assert.equal(r.code, 2);
  assert.equal(r.stderr.trim().split("\n").length, 1);
  assert.match(r.stderr, new RegExp(`port ${port} on 127\\.0\\.0\\.1 is busy`));
  const bad = await runCli(["explore", "--no-open", "--port", "0", "--water-height", "0.5"]);
  assert.equal(bad.code, 2);
  assert.match(bad.stderr, /water height 0\.5 m is outside the glass/);
  const other = await startServer();
  const ended = new Promise((resolve) => other.child.on("exit", (code, signal) => resolve({ code, signal })));
  other.stop();
  const how = await ended;
  assert.ok(how.signal === "SIGINT" || how.code === 0 || how.code === 130, JSON.stringify(how));
});
