// End-to-end tests of the explorer in headless Chromium (run: npm test): the page served by
// `bentstraw explore`, or with EXPLORE_ON=site the same page from the static site (cargo xtask
// site) served by a plain static server, every answer computed by the engine in WebAssembly on
// as many threads as the machine has cores.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync, mkdtempSync, readdirSync, readFileSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import jsQR from "jsqr";
import { startServer, startStaticServer, launch, openPage, waitReady, runCli, ROOT } from "./harness.mjs";

/** The page from the static site (its engine in WebAssembly) instead of `bentstraw explore`. */
const ON_SITE = process.env.EXPLORE_ON === "site";
/** What only the server has (its HTTP API, its command line) is tested with the server. */
const SERVER_ONLY = { skip: ON_SITE && "the static site has no server" };
/** Where a screenshot goes: the documentation's pictures come from the server's page. */
const shot = (name) => (ON_SITE ? path.join(tmpdir(), "bentstraw-site-" + name) : path.join(ROOT, "docs", name));

let server, browser;
// The site from a host that makes it cross-origin isolated, so that its engine runs on threads
// from the first load (site.test.mjs covers the first load's one thread).
before(async () => { server = ON_SITE ? await startStaticServer(undefined, { isolated: true }) : await startServer(); browser = await launch(); });
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

test("the 3D view draws the scene's axes, each in its own colour", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  // Pixels of each axis's colour (its line and its letter): none of the straw's, the paths' or
  // the wireframe's colours comes within the tolerance.
  const counts = await page.evaluate(() => {
    const c = document.getElementById("cloud");
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    const want = { x: [190, 30, 60], y: [20, 130, 70], z: [40, 60, 190] };
    const n = { x: 0, y: 0, z: 0 };
    for (let i = 0; i < d.length; i += 4) {
      for (const [k, w] of Object.entries(want)) {
        if (Math.abs(d[i] - w[0]) + Math.abs(d[i + 1] - w[1]) + Math.abs(d[i + 2] - w[2]) < 12) n[k]++;
      }
    }
    return n;
  });
  for (const k of ["x", "y", "z"]) assert.ok(counts[k] >= 10, `axis ${k}: ${counts[k]} pixels of its colour`);
  assert.deepEqual(problems, []);
  await context.close();
});

test("the map from above runs x to the right and y up, as the report's top views", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  // Where the eye's black dot is on the map from above, against the map's centre (the glass's axis).
  const eyeOffset = () => page.evaluate(() => {
    const c = document.getElementById("map-top");
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let sx = 0, sy = 0, n = 0;
    for (let y = 20; y < c.height; y++) for (let x = 0; x < c.width; x++) {
      const i = 4 * (y * c.width + x);
      if (d[i + 3] > 250 && d[i] < 20 && d[i + 1] < 20 && d[i + 2] < 20) { sx += x; sy += y; n++; }
    }
    return { dx: sx / n - c.width / 2, dy: sy / n - c.height / 2, n };
  });
  for (const [observer, sign] of [["0.1,0,0.1", [1, 0]], ["0,0.1,0.1", [0, -1]], ["-0.1,0,0.1", [-1, 0]]]) {
    await page.goto(`${server.url}#observer=${observer}&straw=0.02,0.01&water-height=0.15`);
    await page.reload(); // a new address, not only a new fragment
    await waitReady(page);
    const { dx, dy, n } = await eyeOffset();
    assert.ok(n > 20, `the eye's dot: ${n} pixels`);
    // +x to the right, +y up (the canvas's y grows downwards).
    for (const [got, want] of [[dx, sign[0]], [dy, sign[1]]]) {
      if (want === 0) assert.ok(Math.abs(got) < 4, `${observer}: ${dx}, ${dy}`);
      else assert.ok(Math.sign(got) === want && Math.abs(got) > 20, `${observer}: ${dx}, ${dy}`);
    }
  }
  assert.deepEqual(problems, []);
  await context.close();
});

test("a kind of light path has the same colour in every view, whatever its share", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  const legend = () => page.evaluate(() => [...document.querySelectorAll("#legend li")].map((li) => [
    li.children[1].textContent, getComputedStyle(li.children[0]).backgroundColor]));
  const seen = new Map();
  // Reference 2 (mostly through the wall) and an eye above the water (mostly through the surface).
  for (const observer of ["0.1,0,0.1", "0.05,0,0.3", "0.3,0,0.05"]) {
    await page.goto(`${server.url}#observer=${observer}&straw=0.02,0.01&water-height=0.15&color=path`);
    await page.reload();
    await waitReady(page);
    for (const [words, colour] of await legend()) {
      if (seen.has(words)) assert.equal(colour, seen.get(words), `${words} from ${observer}`);
      seen.set(words, colour);
    }
  }
  assert.equal(seen.get("through the side wall"), "rgb(255, 127, 14)");
  assert.ok(seen.size >= 3, [...seen.keys()].join("; "));
  assert.equal(new Set(seen.values()).size, seen.size, "one colour per kind");
  assert.deepEqual(problems, []);
  await context.close();
});

test("the 3D view's legend covers none of its points", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  for (const hash of ["", "#observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&color=path", "#scene=reversing-arrow&observer=0.3,0,0.1"]) {
    await page.goto(server.url + hash);
    await page.reload();
    await waitReady(page);
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    const covered = await page.evaluate(() => {
      const l = document.getElementById("legend").getBoundingClientRect();
      const n = window.bentstraw.frame.color.length;
      let inside = 0;
      for (let i = 0; i < n; i += 5) {
        const [x, y] = window.bentstraw.screenOfPoint(i);
        if (x >= l.left && x <= l.right && y >= l.top && y <= l.bottom) inside++;
      }
      return inside;
    });
    assert.equal(covered, 0, `${hash || "the first view"}: ${covered} points under the legend`);
  }
  assert.deepEqual(problems, []);
  await context.close();
});

test("Save writes the scene file with the eye the view has now; a view from the list keeps one's scene", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url + "#scene=two-straws&observer=0.25,0,0.17");
  await waitReady(page);
  // One's own scene file (with a comment), the box open while the eye is dragged.
  const own = "# my two straws\n" + (await page.evaluate(() => window.bentstraw.scene()));
  await page.evaluate((t) => window.bentstraw.setScene(t), own);
  await waitReady(page);
  await page.click("#scene-edit summary");
  const box = await page.locator("#picture").boundingBox();
  const frames = await page.evaluate(() => window.bentstraw.frames);
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(box.x + box.width / 2 + 10 * i, box.y + box.height / 2);
  await page.mouse.up();
  await waitReady(page, frames);
  const eye = await page.evaluate(() => window.bentstraw.state.observer.slice());
  assert.notDeepEqual(eye, [0.25, 0, 0.17]);
  const [download] = await Promise.all([page.waitForEvent("download"), page.click("#scene-save")]);
  const saved = readFileSync(await download.path(), "utf8");
  const boxText = await page.inputValue("#scene-text");
  assert.equal(boxText, own);
  // The box's text, its comment included, but for the observer's position.
  const position = /\[observer\][^[]*?position = \[([^\]]*)\]/.exec(saved)[1].split(",").map(Number);
  for (let i = 0; i < 3; i++) assert.ok(Math.abs(position[i] - eye[i]) < 1e-7, `${position} against ${eye}`);
  const without = (t) => t.replace(/position = \[[^\]]*\]/g, "");
  assert.equal(without(saved), without(boxText));
  // The file saved shows the same view.
  const frames2 = await page.evaluate(() => window.bentstraw.frames);
  await page.evaluate((t) => window.bentstraw.setScene(t), saved);
  await waitReady(page, frames2);
  const again = await page.evaluate(() => window.bentstraw.state.observer.slice());
  for (let i = 0; i < 3; i++) assert.ok(Math.abs(again[i] - eye[i]) < 1e-7);
  // A view chosen from the list keeps one's own scene and moves the eye only.
  const frames3 = await page.evaluate(() => window.bentstraw.frames);
  await page.selectOption("#preset", "0");
  await waitReady(page, frames3);
  assert.equal(await page.evaluate(() => window.bentstraw.state.file), saved);
  assert.notDeepEqual(await page.evaluate(() => window.bentstraw.state.observer.slice()), again);
  assert.deepEqual(problems, []);
  await context.close();
});

test("a size that looks like centimetres written as metres gets the command line's hint, in the page's language", async () => {
  const cm = '[container]\nshape = "glass"\nradius = 4\nheight = 0.2\n[[liquid]]\nname = "water"\nindex = 1.333\ntop = 0.15\n[[straw]]\nx = 0\ny = 0\n[observer]\nposition = [9, 0, 0.1]\n';
  for (const locale of ["en-GB", "fr-FR"]) {
    const { page, context, problems } = await openPage(browser, server.url, undefined, { locale });
    await page.goto(server.url);
    await waitReady(page);
    assert.ok(await page.locator("#notice").isHidden());
    const frames = await page.evaluate(() => window.bentstraw.frames);
    await page.evaluate((t) => window.bentstraw.setScene(t), cm);
    await waitReady(page, frames);
    const notice = await page.textContent("#notice");
    assert.equal(notice, locale === "fr-FR"
      ? "container.radius = 4 : les longueurs sont en mètres, c'est donc 4 m ; si vous vouliez 4 cm, écrivez 0,04"
      : "container.radius = 4: lengths are in metres, so this is 4 m; if you meant 4 cm, write 0.04");
    if (locale === "en-GB") {
      // The command line's own words for the same file.
      const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-cm-"));
      writeFileSync(path.join(dir, "cm.toml"), cm);
      const cli = await runCli(["simulate", "--scene", "cm.toml", "--points", "100", "--output", "p.csv"], dir);
      assert.ok(cli.stderr.includes(notice), cli.stderr);
    }
    assert.deepEqual(problems, []);
    await context.close();
  }
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

test("quick frames are as fine as the engine draws them in time: full resolution when fast enough, coarser when not", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  // The rule, as the page runs it, on made-up times.
  const chosen = await page.evaluate(async () => {
    const { QuickScale, QUICK_BUDGET_MS: budget, QUICK_RETRY_FRAMES: retry } = await import("./quickscale.js");
    const fast = new QuickScale(), slow = new QuickScale(), seen = [fast.next()];
    // Each quick frame timed, then the scale of the next.
    for (const [scale, share] of [[4, 1 / 8], [2, 1 / 5], [1, 1.5], [2, 1 / 5]]) { fast.timed(scale, share * budget); seen.push(fast.next()); }
    for (let k = 0; k < retry; k++) fast.timed(2, budget / 5);
    seen.push(fast.next());
    slow.timed(4, 0.6 * budget);
    seen.push(slow.next());
    return seen;
  });
  // Coarsest before any time is known; finer while four times the time fits twice the budget;
  // back to coarser when too slow, and finer again only after a while (the slow frame may have
  // been a moment's delay); a slow engine stays coarse.
  assert.deepEqual(chosen, [4, 2, 1, 2, 2, 1, 4]);
  // A drag: its quick frames are painted at the scales the rule chose.
  await page.evaluate(() => { window.bentstraw.latencies.length = 0; });
  const frames = await page.evaluate(() => window.bentstraw.frames);
  const box = await page.locator("#picture").boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) { await page.mouse.move(box.x + box.width / 2 + 8 * i, box.y + box.height / 2); await page.waitForTimeout(16); }
  await page.mouse.up();
  await waitReady(page, frames);
  const { scales, allowed } = await page.evaluate(async () => ({
    scales: window.bentstraw.latencies.filter((l) => l.quick).map((l) => l.scale),
    allowed: (await import("./quickscale.js")).QUICK_SCALES,
  }));
  assert.ok(scales.length > 0 && scales.every((s) => allowed.includes(s)), JSON.stringify(scales));
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
    // Asked through the page's own engine module, as the page asks.
    const { engineFetch } = await import(new URL("engine.js", document.baseURI).href);
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

test("the eye and stereo models come quickly, then whole, from the frame's points, and are simulate's", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url + "#observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&points=6000");
  await waitReady(page);
  const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-"));
  const reused = () => page.evaluate(() => Number(document.body.dataset.modelsReused || 0));
  for (const m of ["eye", "stereo"]) {
    const before = await reused();
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
    // Its answers started from the points of the frame drawn, not traced again (the page's own
    // engine included: the models are computed in the worker that holds the frame).
    assert.ok(await reused() > before, `${m}: ${await reused()} answers from the frame's points, ${before} before`);
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

test("a clicked ray is drawn on the picture and on both maps, each event marked", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url + "#observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15");
  await waitReady(page);
  // Pixels of the events' marks (a refraction's #1f77b4, a total reflection's #d62728) on each
  // canvas, before and after the click.
  const marks = () => page.evaluate(() => Object.fromEntries(["picture", "map-side", "map-top"].map((id) => {
    const c = document.getElementById(id);
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    const near = (i, [r, g, b]) => Math.abs(d[i] - r) + Math.abs(d[i + 1] - g) + Math.abs(d[i + 2] - b) < 10;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (near(i, [31, 119, 180]) || near(i, [214, 39, 40])) n++;
    return [id, n];
  })));
  const before = await marks();
  // A point seen through the wall after a total reflection: three events at least.
  const k = await page.evaluate(() => {
    const f = window.bentstraw.frame;
    for (let i = 0; i < f.color.length; i++) if (/total/.test(f.header.paths[f.kind[i]].words)) return i;
    return 0;
  });
  await page.evaluate((k) => window.bentstraw.pickPoint(k), k);
  await page.waitForFunction((k) => document.body.dataset.picked === "point:" + k, k);
  const p = await page.evaluate(() => window.bentstraw.path);
  assert.ok(p.events.some((e) => e.event === "total reflection"), JSON.stringify(p.events));
  const after = await marks();
  for (const id of ["picture", "map-side", "map-top"]) assert.ok(after[id] >= before[id] + 10, `${id}: ${before[id]} → ${after[id]}`);
  // Each event gives both angles: of incidence and of the ray leaving (Snell's law between them).
  for (const e of p.events.filter((e) => e.event === "refraction")) {
    const [a, b] = [e.incidence_deg, e.outgoing_deg].map((x) => x * Math.PI / 180);
    assert.ok(Math.abs(e.n1 * Math.sin(a) - e.n2 * Math.sin(b)) < 1e-12, JSON.stringify(e));
  }
  assert.match(await page.textContent("#readout"), /incidence [0-9.]+° → [0-9.]+°/);
  await page.screenshot({ path: path.join(tmpdir(), (ON_SITE ? "bentstraw-site-" : "bentstraw-") + "clicked-ray.png") });
  assert.deepEqual(problems, []);
  await context.close();
});

/** Taps (or clicks) the picture on the first pixel showing the straw's red section below the
 * water, and waits for that ray's path. */
async function tapTheStraw(page, touch) {
  const [col, row] = await page.evaluate(() => {
    const f = window.bentstraw.frame, w = f.header.width, d = f.rgba;
    for (let i = d.length / 4 - 1; i >= 0; i--) if (d[4 * i] > 200 && d[4 * i + 1] < 40 && d[4 * i + 2] < 40) return [i % w, Math.floor(i / w)];
    return null;
  });
  await page.locator("#picture").scrollIntoViewIfNeeded();
  const box = await page.locator("#picture").boundingBox();
  const k = await page.evaluate(() => window.bentstraw.frame.header.width) / box.width;
  const [x, y] = [box.x + (col + 0.5) / k, box.y + (row - 3) / k];
  if (touch) await page.touchscreen.tap(x, y); else await page.mouse.click(x, y);
  await page.waitForFunction(() => document.body.dataset.picked && window.bentstraw.pathMarks);
}

/** Pixels of the picture inside `box` [x, y, w, h] near each colour of `colours` (name → RGB). */
const pixelsNear = (page, box, colours) => page.evaluate(([box, colours]) => {
  const c = document.getElementById("picture");
  const d = c.getContext("2d").getImageData(...box.map(Math.round)).data;
  const n = Object.fromEntries(Object.keys(colours).map((k) => [k, 0]));
  for (let i = 0; i < d.length; i += 4) {
    for (const [k, [r, g, b]] of Object.entries(colours)) if (Math.abs(d[i] - r) + Math.abs(d[i + 1] - g) + Math.abs(d[i + 2] - b) < 30) n[k]++;
  }
  return n;
}, [box, colours]);

test("a clicked ray's geometry is read on the picture: the light's arrows, each event's normal and angles with their values, on a laptop and a French phone", async () => {
  for (const [name, viewport, options] of [["laptop", { width: 1366, height: 768 }, {}], ["phone", { width: 390, height: 844 }, { ...PHONE, locale: "fr-FR" }]]) {
    const { page, context, problems } = await openPage(browser, server.url, viewport, options);
    await page.goto(server.url + `#observer=${REF2.observer}&straw=${REF2.straw}&he=${REF2.he}`);
    await waitReady(page);
    await tapTheStraw(page, name === "phone");
    const [p, marks] = await page.evaluate(() => [window.bentstraw.path, window.bentstraw.pathMarks]);
    assert.equal(p.outcome, "straw");
    // A drawing for each event, with its normal (blue), both angles' arcs (red on the eye's side,
    // green on the other) and the light's two arrows (orange).
    assert.equal(marks.boxes.length, p.events.length);
    for (const box of marks.boxes) {
      const n = await pixelsNear(page, box, { arrow: [243, 156, 18], normal: [31, 119, 180], first: [192, 57, 43], second: [30, 132, 73] });
      for (const [k, count] of Object.entries(n)) assert.ok(count >= 15, `${name}: ${k} ${count} in ${box}`);
    }
    // The arrows point the light's way: inside each box, the leaving arrow is on the eye's side.
    assert.ok(marks.arrows.length >= 2 * p.events.length);
    // Each angle's value and each index, written as the page's language writes numbers.
    const e = p.events[0], fmt = (x, d) => (d === undefined ? String(x) : x.toFixed(d)).replace(".", name === "phone" ? "," : ".");
    for (const text of [`${fmt(e.incidence_deg, 1)}°`, `${fmt(e.outgoing_deg, 1)}°`, `n ${fmt(e.n1)}`, `n ${fmt(e.n2)}`]) assert.ok(marks.texts.includes(text), `${name}: ${text} in ${marks.texts}`);
    // Snell–Descartes between the two values drawn.
    const [a, b] = [e.incidence_deg, e.outgoing_deg].map((x) => x * Math.PI / 180);
    assert.ok(Math.abs(e.n1 * Math.sin(a) - e.n2 * Math.sin(b)) < 1e-9);
    // Where the straw really is, marked in the picture.
    assert.ok(marks.real);
    // On a phone the ray's words are right under the picture, not below the other views.
    if (name === "phone") {
      const [pic, words] = [await page.locator("#picture").boundingBox(), await page.locator("#readout").boundingBox()];
      assert.ok(words.y - (pic.y + pic.height) < 200, `${words.y} after ${pic.y + pic.height}`);
      assert.match(await page.textContent("#readout"), /réfraction à la paroi/);
    }
    await page.locator("#eye-panel").screenshot({ path: shot(`explorer-ray-${name}.png`) });
    assert.deepEqual(problems, []);
    await context.close();
  }
});

test("\"Where it really is\" draws the objects' outline over the picture, and takes it away again", async () => {
  const { page, context, problems } = await openPage(browser, server.url, { width: 1366, height: 768 });
  /** Pixels of the picture's canvas that differ from the frame the engine sent. */
  const drawnOver = () => page.evaluate(() => {
    const c = document.getElementById("picture"), d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data, f = window.bentstraw.frame.rgba;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - f[i]) + Math.abs(d[i + 1] - f[i + 1]) + Math.abs(d[i + 2] - f[i + 2]) > 30) n++;
    return n;
  });
  for (const hash of ["", "#scene=leaning-straw"]) {
    await page.goto(server.url + hash);
    await waitReady(page);
    assert.equal(await drawnOver(), 0);
    await page.click("#outline");
    assert.equal(await page.getAttribute("#outline", "aria-pressed"), "true");
    await page.waitForFunction(() => window.bentstraw.outlinePoints > 0);
    // The straw's rings and lines: hundreds of pixels over the picture.
    assert.ok(await drawnOver() > 300, hash);
    await page.click("#outline");
    assert.equal(await page.evaluate(() => window.bentstraw.outlinePoints), 0);
    assert.equal(await drawnOver(), 0);
  }
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
  // The water's sliders belong to the assignment's glass: off for a gallery scene, showing the
  // scene's own bottom liquid.
  assert.equal(await page.locator("#he").isDisabled(), true);
  await page.waitForFunction(() => document.getElementById("n-out").textContent === "1.333");
  assert.equal(await page.textContent("#he-out"), "0.19 m");
  await page.screenshot({ path: shot("explorer-gallery.png") });
  // Oil on water: the water below, its own values.
  const f1 = await page.evaluate(() => window.bentstraw.frames);
  await page.selectOption("#scene", "oil-on-water");
  await waitReady(page, f1);
  await page.waitForFunction(() => document.getElementById("he-out").textContent === "0.1 m");
  // Each layer tinted on the map from the side, in its own colour: the water blue, the oil amber;
  // from above, the top layer (the oil).
  const tinted = (id) => page.evaluate((id) => {
    const c = document.getElementById(id);
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    // (Water in the maps' blue; the oil in the colour its file gives it, as in the picture.)
    const want = { water: [74, 127, 193], oil: [0xec, 0xd2, 0x7a] }, n = { water: 0, oil: 0 };
    for (let i = 0; i < d.length; i += 4) {
      if (d[i + 3] < 60 || d[i + 3] > 100) continue; // the tints' opacity, not the lines'
      for (const [k, w] of Object.entries(want)) {
        if (Math.abs(d[i] - w[0]) + Math.abs(d[i + 1] - w[1]) + Math.abs(d[i + 2] - w[2]) < 16) n[k]++;
      }
    }
    return n;
  }, id);
  await page.waitForFunction(() => window.bentstraw.state.scene === "oil-on-water");
  let side = await tinted("map-side");
  // (The oil is a layer 5 cm thick over 10 cm of water; a few of their pixels go to the straw's
  // and the glass's lines, more or fewer with the eye's azimuth.)
  for (let i = 0; i < 20 && (side.water < 150 || side.oil < 50); i++) {
    await page.waitForTimeout(100);
    side = await tinted("map-side");
  }
  await page.locator("#map-side").screenshot({ path: path.join(tmpdir(), "bentstraw-liquids-side.png") });
  assert.ok(side.water >= 150 && side.oil >= 50, `side map: ${JSON.stringify(side)}`);
  const top = await tinted("map-top");
  assert.ok(top.oil >= 200 && top.water < top.oil / 10, `map from above: ${JSON.stringify(top)}`);
  // Back to the glass: the sliders are live again.
  const f2 = await page.evaluate(() => window.bentstraw.frames);
  await page.selectOption("#scene", "");
  await waitReady(page, f2);
  assert.equal(await page.locator("#he").isDisabled(), false);
  assert.deepEqual(problems, []);
  await context.close();
});

/** The text of the QR code the page shows (#qr), decoded by jsQR from its pixels. */
async function scanQr(page) {
  const { data, width, height } = await page.evaluate(() => {
    const img = document.getElementById("qr"), c = document.createElement("canvas");
    c.width = img.naturalWidth; c.height = img.naturalHeight;
    const ctx = c.getContext("2d");
    ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, c.width, c.height); ctx.drawImage(img, 0, 0);
    return { data: [...ctx.getImageData(0, 0, c.width, c.height).data], width: c.width, height: c.height };
  });
  const code = jsQR(Uint8ClampedArray.from(data), width, height);
  return code && code.data;
}

test("a copied link reproduces the state in a fresh page", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url + "#observer=0.12,0.05,0.14&straw=0.01,-0.01&water-height=0.12&n-water=1.5&mode=course&color=path&models=course,eye&view=20,10,1.5");
  await waitReady(page);
  await page.click("#copy-link");
  const link = await page.evaluate(() => document.body.dataset.link);
  const state = await page.evaluate(() => JSON.stringify(window.bentstraw.state));
  const digest = await pictureDigest(page);
  // Its QR code, shown over the picture, read back by an independent decoder: the same link.
  await page.waitForFunction(() => document.body.dataset.qr === "shown" && document.getElementById("qr").complete);
  assert.equal(await scanQr(page), link);
  const qrBox = await page.locator("#qr").boundingBox();
  assert.ok(qrBox.width >= 200, `${qrBox.width} px`);
  await page.click("#qr-close");
  assert.ok(await page.isHidden("#qr-panel"));
  const fresh = await openPage(browser, server.url);
  await fresh.page.goto(link);
  await waitReady(fresh.page);
  assert.equal(await fresh.page.evaluate(() => JSON.stringify(window.bentstraw.state)), state);
  assert.equal(await pictureDigest(fresh.page), digest);
  assert.deepEqual([...problems, ...fresh.problems], []);
  await fresh.context.close();
  await context.close();
});

/** Opens `link` in a fresh page (of `options`' locale or device) and waits until the page has
 * refused it: its alert shown, and `bentstraw.scene()` rejected. Resolves to what it said and
 * whether a frame was drawn. */
async function refusedLink(link, options = {}) {
  const { page, context, problems } = await openPage(browser, server.url, options.viewport, options.context);
  await page.goto(link);
  await page.waitForFunction(() => !document.getElementById("error").hidden);
  const rejected = await page.evaluate(() => window.bentstraw.scene().then(() => null, (e) => e.message));
  const shown = await page.evaluate(() => ({
    alert: document.getElementById("error").textContent,
    role: document.getElementById("error").getAttribute("role"),
    frames: document.body.dataset.frames || "0",
  }));
  return { ...shown, rejected, page, context, problems };
}

test("a damaged or cut link is refused in an alert, in the page's language; no other scene is drawn in its place", async () => {
  // A teacher's own scene, her eye moved, a ray clicked: the link she copies.
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url + "#scene=coin-in-glass&observer=0.15,0,0.35");
  await waitReady(page);
  const toml = (await page.evaluate(() => window.bentstraw.scene())).replace("radius = 0.0115", "radius = 0.013");
  await page.evaluate((t) => window.bentstraw.setScene(t), toml);
  await waitReady(page);
  const link = await page.evaluate(() => window.bentstraw.link());
  assert.match(link, /#sum=[0-9a-f]{8}&/);
  assert.ok(link.length > 300, `${link.length} characters`);
  assert.deepEqual(problems, []);
  await context.close();
  // Characters lost at the end of the scene file's code, or the whole address cut at 300.
  const file = /[#&]file=([^&]*)/.exec(link);
  const at = file.index + file[0].length;
  const damaged = [1, 5, 20, 144].map((n) => link.slice(0, at - n) + link.slice(at));
  damaged.push(link.slice(0, 300));
  for (const bad of damaged) {
    const r = await refusedLink(bad);
    assert.equal(r.role, "alert");
    assert.match(r.alert, /this link is damaged/);
    assert.equal(r.rejected, r.alert);
    assert.equal(r.frames, "0", "a scene was drawn in place of the damaged link's");
    assert.deepEqual(r.problems, []);
    await r.context.close();
  }
  // In French, on a phone: said in French.
  const fr = await refusedLink(link.replace("lang=en", "lang=fr").slice(0, 300), {
    viewport: { width: 390, height: 844 }, context: { locale: "fr-FR", isMobile: true, hasTouch: true, deviceScaleFactor: 2 },
  });
  assert.match(fr.alert, /ce lien est abîmé/);
  assert.equal(fr.frames, "0");
  await fr.page.screenshot({ path: shot("explorer-damaged-link-fr.png") });
  await fr.context.close();
  // The whole link opens the teacher's scene; a link written by hand (no sum) is read as before.
  const whole = await openPage(browser, server.url);
  await whole.page.goto(link);
  await waitReady(whole.page);
  assert.match(await whole.page.evaluate(() => window.bentstraw.scene()), /radius = 0\.013/);
  assert.ok(await whole.page.evaluate(() => document.getElementById("error").hidden));
  assert.deepEqual(whole.problems, []);
  await whole.context.close();
});

test("a gallery scene named without an eye is seen from the eye the scene is meant for", async () => {
  const own = readFileSync(path.join(ROOT, "scenes", "leaning-straw.toml"), "utf8");
  const eye = /\[observer\][^[]*?position\s*=\s*\[([^\]]*)\]/.exec(own)[1].split(",").map(Number);
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url + "#scene=leaning-straw");
  await waitReady(page);
  assert.deepEqual(await page.evaluate(() => window.bentstraw.state.observer), eye);
  // An eye the link gives is kept.
  await page.goto(server.url + "#scene=leaning-straw&observer=0.3,0,0.1");
  await page.reload();
  await waitReady(page);
  assert.deepEqual(await page.evaluate(() => window.bentstraw.state.observer), [0.3, 0, 0.1]);
  assert.deepEqual(problems, []);
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

test("a large scene file (a hundred coins, 300 KB with its comments) opens in explore: sent once, named by a key", SERVER_ONLY, async () => {
  const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-large-"));
  const file = path.join(dir, "coins.toml");
  let text = "# A hundred coins at the bottom of a wide tank.\n" + "# comment line to make the file large\n".repeat(7500);
  text += '[container]\nshape = "glass"\nradius = 0.5\nheight = 0.3\n[[liquid]]\nname = "water"\nindex = 1.333\ntop = 0.2\n';
  for (let k = 0; k < 100; k++) text += `[[coin]]\nx = ${((k % 10) * 0.05 - 0.225).toFixed(3)}\ny = ${(Math.floor(k / 10) * 0.05 - 0.225).toFixed(3)}\nradius = 0.01\nthickness = 0.002\n`;
  text += "[observer]\nposition = [0.8, 0.0, 0.6]\ntarget = [0.0, 0.0, 0.0]\n";
  writeFileSync(file, text);
  assert.ok(text.length > 250000);
  const own = await startServer(["--scene", file]);
  try {
    const { page, context, problems } = await openPage(browser, own.url);
    const api = [];
    page.on("request", (r) => { if (r.url().includes("/api/")) api.push({ method: r.method(), url: r.url() }); });
    await page.goto(own.url);
    await waitReady(page);
    const shown = await page.evaluate(() => ({ n: window.bentstraw.frame.header.n, colours: window.bentstraw.frame.header.points_per_color.filter((c) => c > 0).length }));
    assert.ok(shown.n > 1000 && shown.colours >= 1, JSON.stringify(shown));
    // The text went once; every view's address is short.
    const posts = api.filter((r) => r.method === "POST");
    assert.equal(posts.length, 1, JSON.stringify(posts));
    assert.ok(api.every((r) => r.url.length < 2048), api.map((r) => r.url.length).join(","));
    assert.deepEqual(problems, []);
    await context.close();
    // A key the server no longer has is answered 410 (the page then sends the text again).
    assert.equal((await fetch(own.url + "api/frame?scene-key=0123&observer=1,0,0.3")).status, 410);
    // More than the command line's 1 MB is refused before it is read.
    const huge = await fetch(own.url + "api/keep", { method: "POST", body: "#".repeat((1 << 20) + 1) });
    assert.equal(huge.status, 413);
  } finally {
    own.stop();
  }
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

// ---- languages: English and French ----
/** The page's texts marked data-i18n / data-i18n-title against language `lang`'s table:
 * a list of the differences (empty if none). */
const i18nMismatches = (page, lang) => page.evaluate(async (lang) => {
  // The page's own module: the tables and the touch-screen rule it uses.
  const { I18N, touchKey } = await import(new URL("i18n.js", document.baseURI).href);
  const wrong = [];
  const table = I18N[lang];
  for (const el of document.querySelectorAll("[data-i18n]")) {
    const key = touchKey(el.dataset.i18n);
    const text = el.textContent;
    if (!text.trim()) wrong.push(`${key}: empty`);
    else if (text !== table[key]) wrong.push(`${key}: "${text}", not "${table[key]}"`);
    else if (I18N.en[key] !== I18N.fr[key] && text === I18N[lang === "fr" ? "en" : "fr"][key]) wrong.push(`${key}: left in the other language`);
  }
  for (const el of document.querySelectorAll("[data-i18n-title]")) {
    const key = el.dataset.i18nTitle;
    if (el.title !== table[key]) wrong.push(`title ${key}: "${el.title}", not "${table[key]}"`);
  }
  return wrong;
}, lang);

test("a French browser gets the page in French; EN switches it to English, remembered", async () => {
  const { page, context, problems } = await openPage(browser, server.url, undefined, { locale: "fr-FR" });
  await page.goto(server.url + "#observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&points=20000");
  await waitReady(page);
  assert.equal(await page.evaluate(() => document.documentElement.lang), "fr");
  assert.equal(await page.inputValue("#lang"), "fr");
  assert.equal(await page.title(), "bentstraw explore — la paille dans le verre, en direct");
  const text = (sel) => page.locator(sel).first().textContent();
  assert.equal(await text('[data-i18n="eye.heading"]'), "Ce que voit l'œil");
  assert.equal(await text('[data-i18n="cloud.heading"]'), "Où la paille apparaît");
  assert.equal(await text('[data-i18n="readout.heading"]'), "Le chemin de la lumière");
  assert.equal(await text("#copy-link"), "Copier le lien");
  assert.equal(await text('#mode option[value="course"]'), "cours (un seul rayon)");
  assert.equal(await text('#preset option[value="2"]'), "Référence 3 : œil au-dessus, (0,1 ; 0 ; 0,3)");
  assert.equal(await page.getAttribute('label:has(#he)', "title"), "Hauteur d'eau he, de 0 à 0,2 m");
  assert.equal(await text("#he-out"), "0,15 m");
  assert.match(await text("#readout"), /Cliquer sur l'image ou sur un point du nuage/);
  assert.match(await text("#status"), /points images issus de \d+ rayons, champ de vision/);
  assert.deepEqual(await i18nMismatches(page, "fr"), []);
  // The readout of a clicked ray and the legend, in French.
  await page.evaluate(() => window.bentstraw.pickPoint(1234));
  await page.waitForFunction(() => document.body.dataset.picked === "point:1234");
  const table = await text("#readout");
  assert.match(table, /longueur du chemin L/);
  assert.match(table, /événement 1(réfraction|réflexion totale) (à la paroi|à la surface libre|au fond), angle d'incidence/);
  assert.match(table, /point image \(cours\)\(-?0,\d{4} ; /);
  assert.match(await text("#legend"), /1 rouge/);
  await page.selectOption("#color-by", "path");
  assert.match(await text("#legend"), /par la paroi latérale/);
  // EN: every text back in English, the readout too; the choice goes into the address and is kept.
  await page.selectOption("#lang", "en");
  assert.equal(await page.evaluate(() => document.documentElement.lang), "en");
  assert.deepEqual(await i18nMismatches(page, "en"), []);
  assert.equal(await text('[data-i18n="eye.heading"]'), "What the eye sees");
  assert.match(await text("#readout"), /path length L/);
  assert.match(await text("#legend"), /through the side wall/);
  assert.match(await text("#status"), /image points from \d+ rays/);
  assert.equal(await text("#he-out"), "0.15 m");
  assert.match(page.url(), /[#&]lang=en(&|$)/);
  assert.match(await page.evaluate(() => window.bentstraw.link()), /[#&]lang=en(&|$)/);
  const again = await context.newPage();
  await again.goto(server.url);
  await waitReady(again);
  assert.equal(await again.evaluate(() => document.documentElement.lang), "en");
  // A link copied in French opens in French.
  await again.evaluate(() => { location.hash = location.hash.replace(/lang=en/, "") + "&lang=fr"; });
  await again.waitForFunction(() => document.documentElement.lang === "fr");
  assert.deepEqual(await i18nMismatches(again, "fr"), []);
  assert.deepEqual(problems, []);
  await context.close();
});

test("a French phone user sees no English: the lesson, the menu, a ray's words, the objects, a broken file's reader words", async () => {
  const { page, context, problems } = await openPage(browser, server.url, { width: 390, height: 844 }, { ...PHONE, locale: "fr-FR" });
  await page.goto(server.url + "#scene=oil-on-water&observer=0.3,0.05,0.12");
  await waitReady(page);
  await page.waitForFunction(() => !document.getElementById("lesson").hidden);
  assert.equal(await page.textContent("#lesson-title"), "De l'huile sur de l'eau");
  await page.click("#menu");
  assert.equal(await page.getAttribute("#menu", "aria-expanded"), "true");
  await page.evaluate(() => window.bentstraw.pickPoint(100));
  await page.waitForFunction(() => document.body.dataset.picked);
  await page.click("#scene-objects summary");
  await page.waitForFunction(() => document.querySelectorAll("#objects fieldset").length >= 3);
  // Everything written on the page, its tooltips and its menus' entries too (the scene file's
  // keys, file names and commands are the file's and the command line's own words).
  const words = () => page.evaluate(() => {
    const parts = [document.body.innerText];
    for (const el of document.querySelectorAll("[title]")) parts.push(el.title);
    for (const el of document.querySelectorAll("option")) parts.push(el.textContent);
    return parts.join("\n").replace(/bentstraw [a-z]+( --[a-z-]+)*|scene\.toml|\b[a-z_]+(\[\d+\])?\.[a-z_]+\b|`[^`]*`/g, "");
  });
  const english = /\b(the|and|of|is|are|water|straw|glass|click|drag|wall|bottom|picture|rays|view|missing|unknown|expected|invalid|lesson|light|path|from|with|oil|coin|card|save|open|undo|redo|copy|link|side|above|top|model|colour|color|events|through|reflection|refraction|outcome|length|string|key|duplicate|unclosed)\b/i;
  const left = (text) => text.split("\n").filter((l) => english.test(l));
  assert.deepEqual(left(await words()), []);
  // A scene file typed with a wrong value: the reader's own message, in French too.
  await page.click("#scene-edit summary");
  const text = await boxText(page);
  await page.fill("#scene-text", text.replace(/^index = 1\.47$/m, 'index = "heavy"'));
  await page.waitForFunction(() => !document.getElementById("scene-errors").hidden);
  assert.match(await page.textContent("#scene-errors"), /type invalide : chaîne "heavy", attendu : un nombre/);
  assert.deepEqual(left(await words()), []);
  await page.screenshot({ path: shot("explorer-phone-fr.png") });
  assert.deepEqual(problems.filter((p) => !/status of 400/.test(p)), []);
  await context.close();
});

test("the English and French tables have the same keys, and hold every text the page asks for", async () => {
  const { page, context } = await openPage(browser, server.url);
  await page.goto(server.url);
  // The page's own tables, from its i18n module.
  const I18N = await page.evaluate(async () => (await import(new URL("i18n.js", document.baseURI).href)).I18N);
  const [en, fr] = [Object.keys(I18N.en).sort(), Object.keys(I18N.fr).sort()];
  assert.deepEqual(fr, en);
  const empty = Object.entries(I18N).flatMap(([l, tb]) => Object.entries(tb).filter(([k, v]) => !v && !k.startsWith("focus.in_front")).map(([k]) => `${l} ${k}`));
  assert.deepEqual(empty, []);
  // Every key the page's modules and index.html name is in the table.
  const dir = path.join(ROOT, "crates/bentstraw-explore/page");
  const modules = readdirSync(dir).filter((f) => f.endsWith(".js") && f !== "i18n.js");
  const js = modules.map((f) => readFileSync(path.join(dir, f), "utf8")).join("\n"), html = readFileSync(path.join(dir, "index.html"), "utf8");
  const named = [...js.matchAll(/\bt\("([^"]+)"/g), ...js.matchAll(/\bkey: "([^"]+)"/g), ...html.matchAll(/data-i18n(?:-title)?="([^"]+)"/g)].map((m) => m[1]);
  assert.ok(named.length > 50, `${named.length} keys named`);
  // (A key made up at run time, t("colour." + code), is checked by its beginning.)
  assert.deepEqual(named.filter((k) => (k.endsWith(".") ? !en.some((e) => e.startsWith(k)) : !en.includes(k))), []);
  await context.close();
});

// ---- phones ----
const PHONE = { isMobile: true, hasTouch: true, deviceScaleFactor: 3 };

/** One finger from (x0, y0) to (x1, y1) in `steps` moves, through the browser's touch input. */
async function swipe(cdp, page, [x0, y0], [x1, y1], steps = 12) {
  await cdp.send("Input.dispatchTouchEvent", { type: "touchStart", touchPoints: [{ x: x0, y: y0 }] });
  for (let i = 1; i <= steps; i++) {
    const k = i / steps;
    await cdp.send("Input.dispatchTouchEvent", { type: "touchMove", touchPoints: [{ x: x0 + k * (x1 - x0), y: y0 + k * (y1 - y0) }] });
    await page.waitForTimeout(16);
  }
  await cdp.send("Input.dispatchTouchEvent", { type: "touchEnd", touchPoints: [] });
}

test("on a phone: no sideways scrolling, controls a finger can hit, a swipe scrolls, a pinch zooms", async () => {
  const { page, context, problems } = await openPage(browser, server.url, { width: 390, height: 844 }, PHONE);
  await page.goto(server.url);
  await waitReady(page);
  assert.ok(await page.evaluate(() => window.matchMedia("(pointer: coarse)").matches));
  assert.ok(await page.evaluate(() => document.scrollingElement.scrollWidth) <= 390);
  // Every visible control at least 44x44 px (a checkbox by its label, which a tap on toggles it),
  // with the header's menu folded (a short header) and unfolded.
  const tooSmall = () => page.evaluate(() => [...document.querySelectorAll("button, select, input[type=range], input[type=text], label:has(input[type=checkbox]), summary")]
    .filter((el) => el.getClientRects().length && getComputedStyle(el).visibility !== "hidden")
    .map((el) => { const r = el.getBoundingClientRect(); return [el.id || el.textContent.trim().slice(0, 20), Math.round(r.width), Math.round(r.height)]; })
    .filter(([, w, h]) => w < 44 || h < 44));
  assert.deepEqual(await tooSmall(), []);
  const header = await page.locator("header").boundingBox();
  assert.ok(header.height <= 130, `the folded header is ${header.height} px tall`);
  assert.ok(await page.isHidden("#n"));
  await page.click("#menu");
  assert.ok(await page.isVisible("#n") && await page.isVisible("#export-png") && await page.isVisible("#lang"));
  assert.deepEqual(await tooSmall(), []);
  assert.ok(await page.evaluate(() => document.scrollingElement.scrollWidth) <= 390);
  await page.click("#menu");
  // The hints name the touch gestures.
  assert.match(await page.textContent('[data-i18n="eye.hint"]'), /drag sideways .* pinch/);
  // The picture at the screen's resolution: its box times the density (3 here, capped at 2).
  const sizes = await page.evaluate(() => {
    const c = document.getElementById("picture"), r = c.getBoundingClientRect();
    return { w: c.width, h: c.height, cw: r.width, ch: r.height, dpr: devicePixelRatio };
  });
  assert.equal(sizes.dpr, 3);
  assert.ok(Math.abs(sizes.w - Math.round(sizes.cw * 2)) <= 1 && Math.abs(sizes.h - Math.round(sizes.ch * 2)) <= 1, JSON.stringify(sizes));
  const cloud = await page.evaluate(() => { const c = document.getElementById("cloud"); return [c.width, Math.round(c.getBoundingClientRect().width * 3)]; });
  assert.equal(cloud[0], cloud[1]);
  // A vertical swipe on the picture scrolls the page and leaves the eye where it is.
  const cdp = await context.newCDPSession(page);
  const box = await page.locator("#picture").boundingBox();
  const command = await page.evaluate(() => window.bentstraw.command());
  const observer = await page.evaluate(() => window.bentstraw.state.observer.slice());
  const frames = await page.evaluate(() => window.bentstraw.frames);
  const cx = box.x + box.width / 2, cy = box.y + box.height * 0.8;
  await swipe(cdp, page, [cx, cy], [cx, cy - 300]);
  await page.waitForTimeout(400);
  assert.ok(await page.evaluate(() => window.scrollY) > 100, "the page did not scroll");
  assert.deepEqual(await page.evaluate(() => window.bentstraw.state.observer), observer);
  assert.equal(await page.evaluate(() => window.bentstraw.frames), frames);
  assert.deepEqual(await page.evaluate(() => window.bentstraw.command()), command);
  // A sideways drag turns the eye round the glass, at the same distance. First back to the top,
  // once the swipe's own scrolling has ended: the page stays there ten frames running.
  await page.evaluate(() => new Promise((done) => {
    let still = 0;
    const tick = () => {
      if (window.scrollY !== 0) { window.scrollTo(0, 0); still = 0; } else still += 1;
      if (still >= 10) done(); else requestAnimationFrame(tick);
    };
    tick();
  }));
  const b2 = await page.locator("#picture").boundingBox();
  const my = b2.y + b2.height / 2;
  await swipe(cdp, page, [b2.x + 60, my], [b2.x + 260, my]);
  await waitReady(page, frames);
  const turned = await page.evaluate(() => window.bentstraw.state.observer.slice());
  const dist = (o) => Math.hypot(o[0], o[1], o[2] - 0.1);
  assert.notDeepEqual(turned, observer);
  assert.ok(Math.abs(dist(turned) - dist(observer)) < 1e-3);
  assert.equal(await page.evaluate(() => window.scrollY), 0);
  // Two fingers spreading bring the eye nearer.
  const f2 = await page.evaluate(() => window.bentstraw.frames);
  const mx = b2.x + b2.width / 2;
  await cdp.send("Input.dispatchTouchEvent", { type: "touchStart", touchPoints: [{ x: mx - 30, y: my, id: 1 }, { x: mx + 30, y: my, id: 2 }] });
  for (let i = 1; i <= 10; i++) {
    await cdp.send("Input.dispatchTouchEvent", { type: "touchMove", touchPoints: [{ x: mx - 30 - 8 * i, y: my, id: 1 }, { x: mx + 30 + 8 * i, y: my, id: 2 }] });
    await page.waitForTimeout(16);
  }
  await cdp.send("Input.dispatchTouchEvent", { type: "touchEnd", touchPoints: [] });
  await waitReady(page, f2);
  const nearer = await page.evaluate(() => window.bentstraw.state.observer.slice());
  assert.ok(dist(nearer) < 0.8 * dist(turned), `${dist(nearer)} vs ${dist(turned)}`);
  // The same in the 3D view: its zoom grows.
  const zoom = await page.evaluate(() => window.bentstraw.state.view[2]);
  await page.locator("#cloud").scrollIntoViewIfNeeded();
  const c = await page.locator("#cloud").boundingBox();
  const [qx, qy] = [c.x + c.width / 2, c.y + c.height / 2];
  await cdp.send("Input.dispatchTouchEvent", { type: "touchStart", touchPoints: [{ x: qx - 20, y: qy, id: 1 }, { x: qx + 20, y: qy, id: 2 }] });
  for (let i = 1; i <= 10; i++) {
    await cdp.send("Input.dispatchTouchEvent", { type: "touchMove", touchPoints: [{ x: qx - 20 - 6 * i, y: qy, id: 1 }, { x: qx + 20 + 6 * i, y: qy, id: 2 }] });
    await page.waitForTimeout(16);
  }
  await cdp.send("Input.dispatchTouchEvent", { type: "touchEnd", touchPoints: [] });
  assert.ok(await page.evaluate(() => window.bentstraw.state.view[2]) > 1.5 * zoom);
  await page.screenshot({ path: path.join(tmpdir(), (ON_SITE ? "bentstraw-site-" : "bentstraw-") + "phone.png") });
  assert.deepEqual(problems, []);
  await context.close();
});

test("the picture goes full screen and back, with its label in the page's language", async () => {
  const { page, context, problems } = await openPage(browser, server.url, undefined, { locale: "fr-FR" });
  await page.goto(server.url);
  await waitReady(page);
  assert.equal(await page.textContent("#fullscreen"), "Plein écran");
  // (The label changes with the fullscreenchange event, which may come a moment after the
  // element has become full screen.)
  const width = await page.evaluate(() => window.bentstraw.frame.header.width);
  await page.click("#fullscreen");
  await page.waitForFunction(() => document.fullscreenElement?.id === "eye-panel");
  await page.waitForFunction(() => document.getElementById("fullscreen").textContent === "Quitter le plein écran");
  // The picture is asked for again, at the whole screen's size.
  await page.waitForFunction((w) => window.bentstraw.frame.header.width > w && !window.bentstraw.busy(), width);
  await page.click("#fullscreen");
  await page.waitForFunction(() => document.fullscreenElement === null);
  await page.waitForFunction(() => document.getElementById("fullscreen").textContent === "Plein écran");
  assert.deepEqual(problems, []);
  await context.close();
});

// ---- the scene file's text box ----
/** The box's text, once the page has shown the view's scene in it. */
async function boxText(page) {
  const expected = await page.evaluate(() => (window.bentstraw.state.file || window.bentstraw.scene()));
  await page.waitForFunction((t) => document.getElementById("scene-text").value === t, expected);
  return expected;
}
/** `simulate --scene FILE --points 20000` on `text` saved to a file: its CSV, or its refusal. */
async function simulateText(text, extra = []) {
  const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-edit-"));
  writeFileSync(path.join(dir, "scene.toml"), text);
  const csv = path.join(dir, "view.csv");
  // Run in its folder, so that its messages name the file scene.toml, as the page's do.
  const r = await runCli(["simulate", "--scene", "scene.toml", "--points", "20000", "--output", csv, ...extra], dir);
  return r.code === 0 ? { csv: readFileSync(csv, "utf8") } : { code: r.code, message: r.stderr.trim().replace(/^error: /, "") };
}

test("the scene file's box: the view follows a typed scene (simulate's points), refuses a broken one, undoes, saves, opens", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  await page.click("#scene-edit summary");
  // The assignment's glass is a scene file too: the box shows it.
  const glass = await boxText(page);
  assert.match(glass, /\[container\]/);
  assert.match(glass, /index = 1\.333/);
  // A slider: the box follows the view.
  let frames = await page.evaluate(() => window.bentstraw.frames);
  await page.locator("#n").fill("1.5");
  await waitReady(page, frames);
  assert.match(await boxText(page), /index = 1\.5\b/);
  // A gallery scene: the box follows the menu.
  await page.waitForFunction(() => Number(document.body.dataset.scenes || 0) >= 6);
  frames = await page.evaluate(() => window.bentstraw.frames);
  await page.selectOption("#scene", "two-straws");
  await waitReady(page, frames);
  const gallery = await boxText(page);
  assert.notEqual(gallery, glass);
  const galleryPoints = await page.evaluate(() => window.bentstraw.points());
  // Typed: the second straw moved, a denser liquid. The view follows, its points simulate's.
  const edited = gallery.replace("index = 1.333", "index = 1.45").replace(/y = 0\.024\b/, "y = 0.015");
  assert.notEqual(edited, gallery);
  frames = await page.evaluate(() => window.bentstraw.frames);
  await page.fill("#scene-text", edited);
  await page.waitForFunction((t) => window.bentstraw.state.file === t, edited);
  await waitReady(page, frames);
  const editedPoints = await page.evaluate(() => window.bentstraw.points());
  const sim = await simulateText(edited);
  assert.ok(sim.csv, sim.message);
  assert.equal(editedPoints, sim.csv);
  assert.notEqual(editedPoints, galleryPoints);
  assert.equal(await page.inputValue("#scene-text"), edited);
  // Broken: the command line's message under the box; the view and the box's text stay.
  const broken = edited.replace("index = 1.45", "index = 0.8").replace(/radius = 0\.04\b/, "radius = -0.04");
  const refusal = await simulateText(broken);
  assert.equal(refusal.code, 2);
  const refusedBefore = await page.evaluate(() => Number(document.body.dataset.refused || 0));
  const framesBefore = await page.evaluate(() => window.bentstraw.frames);
  await page.fill("#scene-text", broken);
  await page.waitForFunction(() => !document.getElementById("scene-errors").hidden);
  const lines = await page.locator("#scene-errors li").allTextContents();
  assert.deepEqual(lines, refusal.message.split("\n").filter((l) => l.trim()));
  assert.equal(await page.evaluate(() => Number(document.body.dataset.refused)), refusedBefore + 1);
  assert.equal(await page.inputValue("#scene-text"), broken);
  assert.equal(await page.evaluate(() => window.bentstraw.state.file), edited);
  assert.equal(await page.evaluate(() => window.bentstraw.frames), framesBefore);
  assert.equal(await page.evaluate(() => window.bentstraw.points()), editedPoints);
  // Undo (the button): the gallery scene, its text and its points again; redo (Ctrl+Shift+Z
  // outside the box): the typed scene.
  frames = await page.evaluate(() => window.bentstraw.frames);
  await page.click("#scene-undo");
  await waitReady(page, frames);
  assert.equal(await page.evaluate(() => window.bentstraw.state.scene), "two-straws");
  assert.equal(await page.inputValue("#scene-text"), gallery);
  assert.ok(await page.locator("#scene-errors").isHidden());
  assert.equal(await page.evaluate(() => window.bentstraw.points()), galleryPoints);
  frames = await page.evaluate(() => window.bentstraw.frames);
  await page.locator("#picture").focus();
  await page.evaluate(() => document.activeElement.blur());
  await page.keyboard.press("Control+Shift+Z");
  await waitReady(page, frames);
  assert.equal(await page.evaluate(() => window.bentstraw.state.file), edited);
  assert.equal(await page.inputValue("#scene-text"), edited);
  assert.equal(await page.evaluate(() => window.bentstraw.points()), editedPoints);
  // Ctrl+Z: back to the gallery's scene.
  frames = await page.evaluate(() => window.bentstraw.frames);
  await page.keyboard.press("Control+Z");
  await waitReady(page, frames);
  assert.equal(await page.evaluate(() => window.bentstraw.state.scene), "two-straws");
  assert.equal(await page.inputValue("#scene-text"), gallery);
  // Save: the box's text, as scene.toml.
  const [download] = await Promise.all([page.waitForEvent("download"), page.click("#scene-save")]);
  assert.equal(download.suggestedFilename(), "scene.toml");
  assert.equal(readFileSync(await download.path(), "utf8"), gallery);
  // Open: a file of this computer, into the box and the view.
  frames = await page.evaluate(() => window.bentstraw.frames);
  await page.setInputFiles("#scene-input", { name: "mine.toml", mimeType: "text/plain", buffer: Buffer.from(edited) });
  await page.waitForFunction((t) => window.bentstraw.state.file === t, edited);
  await waitReady(page, frames);
  assert.equal(await page.inputValue("#scene-text"), edited);
  assert.equal(await page.evaluate(() => window.bentstraw.points()), editedPoints);
  // A file over 1 MB is not opened: the page's message, the view as it was.
  await page.setInputFiles("#scene-input", { name: "huge.toml", mimeType: "text/plain", buffer: Buffer.alloc((1 << 20) + 1, 35) });
  await page.waitForFunction(() => !document.getElementById("scene-errors").hidden);
  assert.equal(await page.textContent("#scene-errors"), "huge.toml is larger than 1 MB: it was not opened");
  assert.equal(await page.inputValue("#scene-text"), edited);
  // (The refused text's answer, 400, is the browser's only complaint.)
  assert.deepEqual(problems.filter((p) => !/status of 400/.test(p)), []);
  await context.close();
});

test("the wavelength slider and white light: a flint prism's points at 450 nm are simulate's, its picture in colour and its points in white light simulate's with their wavelengths, the link keeps both, a law's slip is refused in French", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  await page.waitForFunction(() => Number(document.body.dataset.scenes || 0) >= 6);
  let frames = await page.evaluate(() => window.bentstraw.frames);
  await page.selectOption("#scene", "prism");
  await waitReady(page, frames);
  await page.click("#scene-edit summary");
  const box = await boxText(page);
  const at = box.indexOf("[[prism]]");
  const flint = box.slice(0, at) + box.slice(at).replace(/index = 1\.5\b/, 'material = "f2"');
  assert.match(flint, /material = "f2"/);
  frames = await page.evaluate(() => window.bentstraw.frames);
  await page.fill("#scene-text", flint);
  await page.waitForFunction((t) => window.bentstraw.state.file === t, flint);
  await waitReady(page, frames);
  const yellow = await page.evaluate(() => window.bentstraw.points());
  assert.equal(yellow, (await simulateText(flint)).csv, "the d line without a wavelength");
  frames = await page.evaluate(() => window.bentstraw.frames);
  await page.locator("#wavelength").fill("450");
  await waitReady(page, frames);
  assert.equal(await page.locator("#wavelength-out").textContent(), "450 nm");
  const blue = await page.evaluate(() => window.bentstraw.points());
  assert.notEqual(blue, yellow);
  assert.equal(blue, (await simulateText(flint, ["--wavelength", "450"])).csv);
  assert.ok((await page.evaluate(() => window.bentstraw.command())).join(" ").includes("--wavelength 450"));
  // White light: the prism's edges in colour, the points simulate's in white light (each with its
  // band's wavelength, the legend a line per band), the link keeping it.
  const oneColour = await pictureDigest(page);
  frames = await page.evaluate(() => window.bentstraw.frames);
  await page.selectOption("#light", "white");
  await waitReady(page, frames);
  assert.notEqual(await pictureDigest(page), oneColour);
  const white = await page.evaluate(() => window.bentstraw.points());
  assert.match(white, /^x,y,z,color,wavelength\n/);
  assert.equal(white, (await simulateText(flint, ["--wavelength", "450", "--light", "white"])).csv);
  const legend = await page.locator("#legend li").allTextContents();
  for (const nm of [405, 455, 505, 555, 605, 655, 705, 755]) assert.ok(legend.some((l) => l.startsWith(`${nm} nm`)), `${nm} nm in ${legend}`);
  await page.locator("#cloud").screenshot({ path: path.join(tmpdir(), (ON_SITE ? "bentstraw-site-" : "bentstraw-") + "white-light-cloud.png") });
  const link = await page.evaluate(() => window.bentstraw.link());
  assert.match(link, /wavelength=450/);
  assert.match(link, /light=white/);
  const again = await openPage(browser, server.url);
  await again.page.goto(link);
  await waitReady(again.page);
  assert.equal(await again.page.evaluate(() => window.bentstraw.state.wavelength), 450);
  assert.equal(await again.page.evaluate(() => window.bentstraw.state.light), "white");
  assert.equal(await again.page.evaluate(() => window.bentstraw.points()), white);
  await again.context.close();
  assert.deepEqual(problems, []);
  await context.close();
  // In French, a material's slip gets its rule and the nearest name.
  const fr = await openPage(browser, server.url + "#lang=fr", { width: 1400, height: 900 }, { locale: "fr-FR" });
  await fr.page.goto(server.url + "#lang=fr");
  await waitReady(fr.page);
  await fr.page.click("#scene-edit summary");
  // The box shows the view's scene first: a text the page writes into it during the fill would
  // be mixed with the one typed.
  await boxText(fr.page);
  await fr.page.fill("#scene-text", flint.replace('"f2"', '"f3"'));
  await fr.page.waitForFunction(() => !document.getElementById("scene-errors").hidden);
  const said = (await fr.page.locator("#scene-errors li").allTextContents()).join(" ");
  assert.match(said, /« f3 » n'est pas un matériau de la table : vouliez-vous dire 'f2' \?/);
  await fr.context.close();
});

test("the scene file's box on a laptop and a phone, in English and French", async () => {
  const dir = ON_SITE ? path.join(tmpdir(), "shots-edit-site") : "/tmp/shots-edit";
  mkdirSync(dir, { recursive: true });
  for (const [name, viewport, options] of [["laptop", { width: 1500, height: 1000 }, {}], ["phone", { width: 390, height: 844 }, PHONE]]) {
    for (const lang of ["en", "fr"]) {
      const { page, context, problems } = await openPage(browser, server.url, viewport, { ...options, locale: lang === "fr" ? "fr-FR" : "en-US" });
      await page.goto(server.url + "#scene=two-straws&observer=0.25,0,0.17");
      await waitReady(page);
      await page.click("#scene-edit summary");
      const text = await boxText(page);
      assert.match(text, /\[\[straw\]\]/);
      assert.equal(await page.textContent("#scene-save"), lang === "fr" ? "Enregistrer" : "Save");
      // A broken rule, shown under the box.
      await page.fill("#scene-text", text.replace("index = 1.333", "index = 0.8"));
      await page.waitForFunction(() => !document.getElementById("scene-errors").hidden);
      await page.locator("#scene-errors").scrollIntoViewIfNeeded();
      // Every control of the panel a finger can hit on a phone; no sideways scrolling.
      if (name === "phone") {
        const small = await page.evaluate(() => [...document.querySelectorAll("#scene-edit summary, #scene-edit button")]
          .map((el) => [el.id || el.textContent.trim(), el.getBoundingClientRect().height]).filter(([, h]) => h < 44));
        assert.deepEqual(small, []);
        assert.ok(await page.evaluate(() => document.scrollingElement.scrollWidth) <= 390);
        await page.locator("#scene-edit").screenshot({ path: path.join(dir, `${name}-${lang}-panel.png`) });
      }
      await page.screenshot({ path: path.join(dir, `${name}-${lang}.png`) });
      assert.deepEqual(problems.filter((p) => !/status of 400/.test(p)), []);
      await context.close();
    }
  }
});

test("a French browser gets a broken scene's rules in French, naming each key and value; the last good view stays", async () => {
  const dir = ON_SITE ? path.join(tmpdir(), "shots-rules-site") : "/tmp/shots-rules";
  mkdirSync(dir, { recursive: true });
  for (const [name, viewport, options] of [["laptop", { width: 1500, height: 1000 }, {}], ["phone", { width: 390, height: 844 }, PHONE]]) {
    const { page, context, problems } = await openPage(browser, server.url, viewport, { ...options, locale: "fr-FR" });
    await page.goto(server.url + "#scene=two-straws&observer=0.25,0,0.17&points=4000");
    await waitReady(page);
    await page.click("#scene-edit summary");
    const text = await boxText(page);
    const points = await page.evaluate(() => window.bentstraw.points());
    const frames = await page.evaluate(() => window.bentstraw.frames);
    // Two rules broken at once: the liquid's index and the first straw's tilt.
    const broken = text.replace("index = 1.333", "index = 0.8").replace(/tilt = 0(\.0)?\b/, "tilt = 95");
    assert.notEqual(broken, text);
    await page.fill("#scene-text", broken);
    await page.waitForFunction(() => !document.getElementById("scene-errors").hidden);
    assert.deepEqual(await page.locator("#scene-errors li").allTextContents(), [
      "scene.toml : 2 règles ne sont pas respectées :",
      "  liquid[1].index = 0,8 : un indice de réfraction doit être compris entre 1 et 5 (le vide vaut 1 ; les matériaux les plus réfringents connus valent environ 4)",
      "  straw[1].tilt = 95 : l'inclinaison par rapport à la verticale doit vérifier 0 <= tilt < 90 (degrés)",
    ]);
    // The last good view stays: no new frame, the same scene and points.
    assert.equal(await page.evaluate(() => window.bentstraw.frames), frames);
    assert.equal(await page.evaluate(() => window.bentstraw.state.file), "");
    assert.equal(await page.evaluate(() => window.bentstraw.points()), points);
    await page.locator("#scene-errors").scrollIntoViewIfNeeded();
    await page.screenshot({ path: path.join(dir, `${name}-fr.png`) });
    if (name === "laptop") {
      // In English, the same rules are the command line's message, line for line.
      const cli = await simulateText(broken);
      await page.selectOption("#lang", "en");
      assert.deepEqual(await page.locator("#scene-errors li").allTextContents(), cli.message.split("\n").filter((l) => l.trim()));
      await page.selectOption("#lang", "fr");
      // An eye inside the assignment's glass, from the address: the rule in French, its numbers French.
      await page.evaluate(() => { location.hash = "#observer=0,0,0.1&straw=0.02,0.01&water-height=0.15&lang=fr"; });
      await page.waitForFunction(() => !document.getElementById("error").hidden);
      assert.equal(await page.textContent("#error"), "l'observateur (0 ; 0 ; 0,1) est dans le verre ou sur sa paroi : il ne doit pas vérifier 0 <= z <= 0,2 et x² + y² <= 0,04²");
      await page.screenshot({ path: path.join(dir, `${name}-fr-eye.png`) });
    }
    // (The refused texts' answers, 400, are the browser's only complaints.)
    assert.deepEqual(problems.filter((p) => !/status of 400/.test(p)), []);
    await context.close();
  }
});

/** The value of `key` (a line `key = value` under `[table]` or the n-th `[[table]]`) in a scene's text. */
function fileValue(text, table, n, key) {
  const blocks = text.split(/^(?=\[)/m).filter((b) => b.startsWith(`[${table}]`) || b.startsWith(`[[${table}]]`));
  const m = new RegExp(`^${key} = (.+)$`, "m").exec(blocks[n] || "");
  return m ? m[1] : undefined;
}
/** Drags with the mouse from the map's pixel `from` by `(dx, dy)` in `steps` moves. */
async function dragOnMap(page, id, from, [dx, dy], steps = 20) {
  const r = await page.evaluate((id) => { const b = document.getElementById(id).getBoundingClientRect(); return [b.left, b.top]; }, id);
  await page.mouse.move(r[0] + from[0], r[1] + from[1]);
  await page.mouse.down();
  for (let i = 1; i <= steps; i++) { await page.mouse.move(r[0] + from[0] + (dx * i) / steps, r[1] + from[1] + (dy * i) / steps); await page.waitForTimeout(25); }
  await page.mouse.up();
}
/** Waits until the page's scene file is a new one, then until its view is painted. */
async function nextFile(page, before) {
  await page.waitForFunction((t) => window.bentstraw.state.file && window.bentstraw.state.file !== t, before, { timeout: 30000 });
  // A drag's last step may still be on its way: wait for the text to rest.
  let text = await page.evaluate(() => window.bentstraw.state.file);
  for (;;) {
    await page.waitForTimeout(400);
    const again = await page.evaluate(() => window.bentstraw.state.file);
    if (again === text) break;
    text = again;
  }
  await waitReady(page);
  return text;
}

test("the objects' controls and the maps' rings edit the scene: the box and the view follow (simulate's points), broken values are marked", async () => {
  const { page, context, problems } = await openPage(browser, server.url, { width: 1500, height: 1000 });
  await page.goto(server.url + "#scene=coin-in-glass&observer=0.15,0,0.35");
  await waitReady(page);
  await page.click("#scene-objects summary");
  await page.waitForFunction(() => document.querySelectorAll("#objects fieldset").length === 3);
  assert.deepEqual(await page.locator("#objects legend").allTextContents(), ["Container", "Liquid 1 (from the bottom)", "Coin 1"]);
  assert.equal(await page.inputValue('[data-key="liquid[1].top"]'), "0.1");
  // A value typed in a control: the file's text says it, the view is simulate's for that text.
  let file = await page.evaluate(() => window.bentstraw.state.file);
  await page.fill('[data-key="liquid[1].top"]', "0.15");
  await page.press('[data-key="liquid[1].top"]', "Enter");
  file = await nextFile(page, file);
  assert.equal(fileValue(file, "liquid", 0, "top"), "0.15");
  assert.equal(await page.inputValue("#scene-text"), file);
  const sim = await simulateText(file);
  assert.ok(sim.csv, sim.message);
  assert.equal(await page.evaluate(() => window.bentstraw.points()), sim.csv);
  // An object added, then removed.
  await page.click('#objects .add button[data-i18n="obj.add.straw"]');
  file = await nextFile(page, file);
  assert.match(file, /\[\[straw\]\]/);
  await page.waitForFunction(() => document.querySelectorAll("#objects fieldset").length === 4);
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  await page.locator("#objects fieldset", { hasText: "Straw 1" }).locator("button.remove").click();
  file = await nextFile(page, file);
  assert.doesNotMatch(file, /\[\[straw\]\]/);
  // A broken value: its control marked, its rule under the controls in the command line's words;
  // the view stays.
  const frames = await page.evaluate(() => window.bentstraw.frames);
  await page.fill('[data-key="coin[1].radius"]', "-0.01");
  await page.press('[data-key="coin[1].radius"]', "Enter");
  await page.waitForFunction(() => !document.getElementById("objects-errors").hidden);
  const rules = await page.locator("#objects-errors li").allTextContents();
  assert.ok(rules.some((l) => l.includes("coin[1].radius = -0.01")), rules.join("\n"));
  assert.equal(await page.getAttribute('[data-key="coin[1].radius"]', "aria-invalid"), "true");
  assert.equal(await page.evaluate(() => window.bentstraw.state.file), file);
  assert.equal(await page.evaluate(() => window.bentstraw.frames), frames);
  await page.fill('[data-key="coin[1].radius"]', "0.0115");
  await page.press('[data-key="coin[1].radius"]', "Enter");
  await page.waitForFunction(() => document.getElementById("objects-errors").hidden);
  // The coin dragged far out on the map from above: it stops inside the glass, touching its side.
  // (The maps are drawn again once the scene's sketch comes back: wait for the coin's ring.)
  await page.waitForFunction(() => document.getElementById("map-top").handles?.some((h) => h.kind === "coin"));
  const coin = await page.evaluate(() => document.getElementById("map-top").handles.find((h) => h.kind === "coin").at);
  await dragOnMap(page, "map-top", coin, [400, -120]);
  file = await nextFile(page, file);
  const [x, y] = ["x", "y"].map((k) => Number(fileValue(file, "coin", 0, k)));
  const reach = Math.hypot(x, y) + 0.0115;
  assert.ok(reach < 0.04 && reach > 0.039, `the coin's edge ${reach} m from the axis, inside 0.04 m`);
  assert.ok(x > 0 && y > 0, `${x}, ${y}`);
  assert.equal(await page.inputValue('[data-key="coin[1].x"]'), String(x));
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  // The whole drag is one step of the history: undo puts the coin back in the middle, redo
  // where it was dropped.
  let frames2 = await page.evaluate(() => window.bentstraw.frames);
  await page.click("#objects-undo");
  await waitReady(page, frames2);
  const undone = await page.evaluate(() => window.bentstraw.state.file);
  assert.deepEqual(["x", "y"].map((k) => Number(fileValue(undone, "coin", 0, k))), [0, 0]);
  frames2 = await page.evaluate(() => window.bentstraw.frames);
  await page.click("#objects-redo");
  await waitReady(page, frames2);
  assert.equal(await page.evaluate(() => window.bentstraw.state.file), file);
  // The water's surface dragged far up on the side map: it stops at the glass's rim.
  await page.waitForFunction(() => document.getElementById("map-side").handles?.some((h) => h.kind === "liquid"));
  const surface = await page.evaluate(() => document.getElementById("map-side").handles.find((h) => h.kind === "liquid").at);
  await dragOnMap(page, "map-side", surface, [0, -300]);
  file = await nextFile(page, file);
  assert.equal(Number(fileValue(file, "liquid", 0, "top")), 0.2);
  assert.deepEqual(await page.locator("#error").isHidden(), true);
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  await page.screenshot({ path: ON_SITE ? shot("objects.png") : "/tmp/shots-edit/objects-laptop.png" });
  assert.deepEqual(problems.filter((p) => !/status of 400/.test(p)), []);
  await context.close();
});

test("a decimal comma is read in French, refused with its message in English; the arrow keys step a value", async () => {
  for (const locale of ["fr-FR", "en-GB"]) {
    const { page, context, problems } = await openPage(browser, server.url, { width: 1500, height: 1000 }, { locale });
    await page.goto(server.url + "#scene=coin-in-glass&observer=0.15,0,0.35");
    await waitReady(page);
    await page.click("#scene-objects summary");
    await page.waitForFunction(() => document.querySelectorAll("#objects fieldset").length === 3);
    const index = '[data-key="liquid[1].index"]';
    // Shown as the language writes numbers.
    assert.equal(await page.inputValue(index), locale === "fr-FR" ? "1,333" : "1.333");
    let file = await page.evaluate(() => window.bentstraw.state.file);
    await page.fill(index, "1,5");
    await page.press(index, "Enter");
    if (locale === "fr-FR") {
      file = await nextFile(page, file);
      assert.equal(fileValue(file, "liquid", 0, "index"), "1.5");
      assert.equal(await page.inputValue(index), "1,5");
      // The arrow keys step it by a thousandth.
      await page.focus(index);
      await page.keyboard.press("ArrowUp");
      file = await nextFile(page, file);
      assert.equal(fileValue(file, "liquid", 0, "index"), "1.501");
      // An index out of its range: its control marked, the allowed range written under it.
      await page.fill(index, "7");
      await page.press(index, "Enter");
      await page.waitForFunction((sel) => document.querySelector(sel).getAttribute("aria-invalid") === "true", index);
      const note = await page.evaluate((sel) => { const el = document.querySelector(sel); return document.getElementById(el.getAttribute("aria-describedby")).textContent; }, index);
      assert.match(note, /doit être compris entre 1 et 5/);
      // A good value again: the mark and its words go.
      await page.fill(index, "1,4");
      await page.press(index, "Enter");
      file = await nextFile(page, file);
      assert.equal(await page.locator("#objects .field-rule").count(), 0);
      // (The refused text's answer, 400, is the browser's only complaint.)
      problems.splice(0, problems.length, ...problems.filter((p) => !/status of 400/.test(p)));
    } else {
      await page.waitForFunction(() => !document.getElementById("objects-errors").hidden);
      assert.equal(await page.getAttribute(index, "aria-invalid"), "true");
      assert.match(await page.textContent("#objects-errors"), /liquid\[1\]\.index: not a number/);
      assert.equal(await page.evaluate(() => window.bentstraw.state.file), file);
    }
    assert.deepEqual(problems, []);
    await context.close();
  }
});

test("the objects' controls on a phone, in French: a finger can hit each, nothing scrolls sideways", async () => {
  mkdirSync("/tmp/shots-edit", { recursive: true });
  const { page, context, problems } = await openPage(browser, server.url, { width: 390, height: 844 }, { ...PHONE, locale: "fr-FR" });
  await page.goto(server.url + "#scene=reversing-arrow");
  await waitReady(page);
  await page.click("#scene-objects summary");
  await page.waitForFunction(() => document.querySelectorAll("#objects fieldset").length >= 3);
  const legends = await page.locator("#objects legend").allTextContents();
  assert.equal(legends[0], "Récipient");
  assert.ok(legends.includes("Carte 1"), legends.join(", "));
  const small = await page.evaluate(() => [...document.querySelectorAll("#scene-objects summary, #scene-objects button, #objects input, #objects select")]
    .map((el) => [el.dataset.key || el.textContent.trim(), Math.round(el.getBoundingClientRect().height)]).filter(([, h]) => h < 44));
  assert.deepEqual(small, []);
  assert.ok(await page.evaluate(() => document.scrollingElement.scrollWidth) <= 390);
  await page.locator("#scene-objects").scrollIntoViewIfNeeded();
  await page.screenshot({ path: ON_SITE ? shot("objects-phone.png") : "/tmp/shots-edit/objects-phone-fr.png" });
  assert.deepEqual(problems, []);
  await context.close();
});

/** Waits until every step of a drag on a map has been answered (the body's data-drag), then
 * until its view is painted. */
async function dragSettled(page) {
  await page.waitForFunction(() => document.body.dataset.drag !== "1", null, { timeout: 30000 });
  await waitReady(page);
}
/** The pixels of a map within a few levels of the spheres' outline colour. */
const sphereInk = (page, id, at, reach) => page.evaluate(([id, at, reach]) => {
  const c = document.getElementById(id), d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data, k = c.width / c.clientWidth;
  let n = 0;
  for (let i = 0; i < d.length; i += 4) {
    // (Within `reach` CSS pixels of `at` only, when given.)
    if (at && Math.hypot((i / 4) % c.width / k - at[0], Math.floor(i / 4 / c.width) / k - at[1]) > reach) continue;
    if (d[i + 3] > 200 && Math.abs(d[i] - 27) + Math.abs(d[i + 1] - 127) + Math.abs(d[i + 2] - 134) < 40) n++;
  }
  return n;
}, [id, at || null, reach || 0]);

test("a sphere added from the Objects panel is drawn, dragged on the maps where the rules let it go, kept by a link; a broken centre shows its rule", async () => {
  const dir = ON_SITE ? path.join(tmpdir(), "shots-sphere-site") : "/tmp/shots-sphere";
  mkdirSync(dir, { recursive: true });
  const { page, context, problems } = await openPage(browser, server.url, { width: 1500, height: 1000 });
  await page.goto(server.url + "#scene=two-straws&observer=0.25,0,0.17");
  await waitReady(page);
  await page.click("#scene-objects summary");
  await page.waitForFunction(() => document.querySelectorAll("#objects fieldset").length === 4);
  assert.equal(await sphereInk(page, "map-top"), 0);
  // "+ sphere": a glass marble resting on the floor in the water, clear of both straws.
  const frames = await page.evaluate(() => window.bentstraw.frames);
  const before = await pictureDigest(page);
  await page.click('#objects .add button[data-i18n="obj.add.sphere"]');
  await page.waitForFunction(() => /\[\[sphere\]\]/.test(window.bentstraw.state.file), null, { timeout: 30000 });
  await waitReady(page, frames);
  await page.waitForFunction(() => document.querySelectorAll("#objects fieldset").length === 5);
  assert.equal((await page.locator("#objects legend").allTextContents())[4], "Sphere 1");
  await page.waitForFunction(() => document.getElementById("map-top").handles.some((h) => h.kind === "sphere"));
  let file = await page.evaluate(() => window.bentstraw.state.file);
  const centre = () => JSON.parse(fileValue(file, "sphere", 0, "center"));
  assert.equal(fileValue(file, "sphere", 0, "radius"), "0.01");
  assert.equal(fileValue(file, "sphere", 0, "index"), "1.5");
  let [x, y, z] = centre();
  assert.equal(z, 0.01, "resting on the floor");
  assert.ok(Math.hypot(x, y) + 0.01 <= 0.04, `${x}, ${y} inside the glass`);
  for (const [sx, sy] of [[0, 0], [0, 0.024]]) assert.ok(Math.hypot(x - sx, y - sy) > 0.015, `${x}, ${y} clear of the straw at ${sx}, ${sy}`);
  assert.deepEqual(await page.locator('[data-key="sphere[1].center"]').evaluateAll((els) => els.map((e) => Number(e.value))), [x, y, z]);
  // The view shows it: a new picture, simulate's points for the text; both maps draw its disc.
  assert.notEqual(await pictureDigest(page), before);
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  assert.ok(await sphereInk(page, "map-top") >= 8, "the sphere drawn from above");
  assert.ok(await sphereInk(page, "map-side") >= 8, "the sphere drawn from the side");
  // Dragged far out on the map from above: it stops inside the glass, touching its side.
  const handle = (id) => page.evaluate((id) => document.getElementById(id).handles.find((h) => h.kind === "sphere").at, id);
  await dragOnMap(page, "map-top", await handle("map-top"), [300, -60]);
  await dragSettled(page);
  file = await page.evaluate(() => window.bentstraw.state.file);
  [x, y, z] = centre();
  const reach = Math.hypot(x, y) + 0.01;
  assert.ok(reach <= 0.04 && reach > 0.0395, `the sphere's edge ${reach} m from the axis, inside 0.04 m`);
  assert.ok(x > 0 && y > 0 && z === 0.01, `${x}, ${y}, ${z}`);
  assert.ok(await page.locator("#error").isHidden());
  // Dragged across the first straw: it stops against it (the rules' distance), never over it.
  await dragOnMap(page, "map-top", await handle("map-top"), [-300, 0]);
  await dragSettled(page);
  file = await page.evaluate(() => window.bentstraw.state.file);
  [x, y, z] = centre();
  const gap = Math.hypot(x, y);
  assert.ok(x > 0 && gap >= 0.015 && gap < 0.0155, `${x}, ${y}: ${gap} m from the straw's axis`);
  assert.ok(await page.locator("#error").isHidden());
  // Lifted on the side map: only its height changes.
  await dragOnMap(page, "map-side", await handle("map-side"), [0, -25]);
  await dragSettled(page);
  file = await page.evaluate(() => window.bentstraw.state.file);
  const lifted = centre();
  assert.deepEqual(lifted.slice(0, 2), [x, y]);
  assert.ok(lifted[2] > z + 0.01, `${lifted[2]}`);
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  const digest = await pictureDigest(page);
  await page.screenshot({ path: path.join(dir, "laptop.png") });
  // The link: a fresh page, on a laptop and on a phone, shows the same scene, sphere and picture.
  await page.click("#copy-link");
  const link = await page.evaluate(() => document.body.dataset.link);
  for (const [name, viewport, options] of [["laptop", { width: 1500, height: 1000 }, {}], ["phone", { width: 390, height: 844 }, PHONE]]) {
    const fresh = await openPage(browser, server.url, viewport, options);
    await fresh.page.goto(link);
    await waitReady(fresh.page);
    assert.equal(await fresh.page.evaluate(() => window.bentstraw.state.file), file);
    await fresh.page.click("#scene-objects summary");
    await fresh.page.waitForFunction(() => document.querySelectorAll("#objects fieldset").length === 5);
    assert.deepEqual(await fresh.page.locator('[data-key="sphere[1].center"]').evaluateAll((els) => els.map((e) => Number(e.value))), lifted);
    await fresh.page.waitForFunction(() => document.getElementById("map-top").handles.some((h) => h.kind === "sphere"));
    if (name === "laptop") {
      assert.equal(await pictureDigest(fresh.page), digest);
      assert.deepEqual(await handle("map-top"), await fresh.page.evaluate(() => document.getElementById("map-top").handles.find((h) => h.kind === "sphere").at));
    } else {
      assert.ok(await fresh.page.evaluate(() => document.scrollingElement.scrollWidth) <= 390);
      await fresh.page.evaluate(() => window.scrollTo(0, 0));
      await fresh.page.screenshot({ path: path.join(dir, "phone.png") });
      await fresh.page.locator("#map-panel").scrollIntoViewIfNeeded();
      await fresh.page.screenshot({ path: path.join(dir, "phone-maps.png") });
      await fresh.page.locator('#objects fieldset[data-object="sphere[1]"]').scrollIntoViewIfNeeded();
      await fresh.page.screenshot({ path: path.join(dir, "phone-objects.png") });
    }
    assert.deepEqual(fresh.problems, []);
    await fresh.context.close();
  }
  // A centre typed into the wall: the rule's words under the controls (the command line's
  // message), the sphere's box marked; the view stays.
  const framesBefore = await page.evaluate(() => window.bentstraw.frames);
  const broken = file.replace(`center = ${fileValue(file, "sphere", 0, "center")}`, `center = [0.035, ${lifted[1]}, ${lifted[2]}]`);
  const refusal = await simulateText(broken);
  assert.equal(refusal.code, 2);
  await page.fill('[data-key="sphere[1].center"][data-part="0"]', "0.035");
  await page.press('[data-key="sphere[1].center"][data-part="0"]', "Enter");
  await page.waitForFunction(() => !document.getElementById("objects-errors").hidden);
  const rules = await page.locator("#objects-errors li").allTextContents();
  assert.deepEqual(rules, refusal.message.split("\n").filter((l) => l.trim()));
  assert.match(rules.join("\n"), /sphere\[1\]: centred at \(0\.035, .*it cuts the container/);
  assert.equal(await page.getAttribute('#objects fieldset[data-object="sphere[1]"]', "aria-invalid"), "true");
  assert.equal(await page.evaluate(() => window.bentstraw.state.file), file);
  assert.equal(await page.evaluate(() => window.bentstraw.frames), framesBefore);
  await page.locator("#objects-errors").scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(dir, "laptop-refused.png") });
  // (The refused text's answer, 400, is the browser's only complaint.)
  assert.deepEqual(problems.filter((p) => !/status of 400/.test(p)), []);
  await context.close();
});

test("a prism and a lens added from the Objects panel are drawn on both maps, dragged where the rules let them go, and kept by a link", async () => {
  const dir = ON_SITE ? path.join(tmpdir(), "shots-solids-site") : "/tmp/shots-solids";
  mkdirSync(dir, { recursive: true });
  const { page, context, problems } = await openPage(browser, server.url, { width: 1500, height: 1000 });
  await page.goto(server.url + "#scene=two-straws&observer=0.25,0,0.17");
  await waitReady(page);
  await page.click("#scene-objects summary");
  await page.waitForFunction(() => document.querySelectorAll("#objects fieldset").length === 4);
  assert.equal(await sphereInk(page, "map-top"), 0);
  const handle = (p, id, kind) => p.evaluate(([id, kind]) => (document.getElementById(id).handles.find((h) => h.kind === kind) || {}).at, [id, kind]);
  /** Clicks "+ kind", then waits for its table in the file, the frame that shows it and its box. */
  const add = async (kind, boxes) => {
    const frames = await page.evaluate(() => window.bentstraw.frames);
    await page.click(`#objects .add button[data-i18n="obj.add.${kind}"]`);
    await page.waitForFunction((kind) => new RegExp(`\\[\\[${kind}\\]\\]`).test(window.bentstraw.state.file), kind, { timeout: 30000 });
    await waitReady(page, frames);
    await page.waitForFunction((n) => document.querySelectorAll("#objects fieldset").length === n, boxes);
    await page.waitForFunction((kind) => document.getElementById("map-top").handles.some((h) => h.kind === kind), kind);
    return page.evaluate(() => window.bentstraw.state.file);
  };
  // "+ prism": a 60° glass prism standing on the floor inside the glass, clear of both straws.
  const before = await pictureDigest(page);
  let file = await add("prism", 5);
  assert.equal((await page.locator("#objects legend").allTextContents())[4], "Prism 1");
  const corners = () => JSON.parse(fileValue(file, "prism", 0, "corners"));
  let poly = corners();
  assert.equal(poly.length, 3);
  const side = (i) => Math.hypot(poly[i][0] - poly[(i + 1) % 3][0], poly[i][1] - poly[(i + 1) % 3][1]);
  for (const i of [0, 1, 2]) assert.ok(Math.abs(side(i) - 0.02) < 1e-4, `a side of ${side(i)} m`);
  assert.equal(Number(fileValue(file, "prism", 0, "bottom")), 0);
  assert.equal(fileValue(file, "prism", 0, "index"), "1.5");
  for (const [x, y] of poly) assert.ok(Math.hypot(x, y) <= 0.04, `corner ${x}, ${y} inside the glass`);
  assert.equal(await page.inputValue('[data-key="prism[1].corners"]'), poly.map((q) => q.join(", ")).join("; "));
  assert.notEqual(await pictureDigest(page), before);
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  const inkTop = await sphereInk(page, "map-top"), inkSide = await sphereInk(page, "map-side");
  assert.ok(inkTop >= 8, "the prism drawn from above");
  assert.ok(inkSide >= 8, "the prism drawn from the side");
  // "+ lens": a biconvex lens held between the eye and the glass, its axis towards the glass.
  file = await add("lens", 6);
  assert.equal((await page.locator("#objects legend").allTextContents())[5], "Lens 1");
  const lensCentre = () => JSON.parse(fileValue(file, "lens", 0, "center"));
  let [lx, ly, lz] = lensCentre();
  assert.ok(lx > 0.05 && lx < 0.25 && Math.abs(ly) < 1e-9 && lz === 0.1, `${lx}, ${ly}, ${lz}`);
  assert.deepEqual(JSON.parse(fileValue(file, "lens", 0, "axis")), [-1, 0, 0]);
  assert.deepEqual(["radius1", "radius2", "thickness", "diameter", "index"].map((k) => Number(fileValue(file, "lens", 0, k))), [0.04, -0.04, 0.007, 0.03, 1.5]);
  assert.deepEqual(await page.locator('[data-key="lens[1].axis"]').evaluateAll((els) => els.map((e) => Number(e.value))), [-1, 0, 0]);
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  // (The maps widen to take the lens in, so its own ink is counted round its handle.)
  for (const id of ["map-top", "map-side"]) assert.ok(await sphereInk(page, id, await handle(page, id, "lens"), 30) >= 8, `the lens drawn on ${id}`);
  // The prism dragged far out on the map from above: it stops inside the glass, a corner at its
  // side; its shape stays.
  await dragOnMap(page, "map-top", await handle(page, "map-top", "prism"), [0, 300]);
  await dragSettled(page);
  file = await page.evaluate(() => window.bentstraw.state.file);
  const moved = corners();
  const reach = Math.max(...moved.map(([x, y]) => Math.hypot(x, y)));
  assert.ok(reach <= 0.04 && reach > 0.039, `its farthest corner ${reach} m from the axis, inside 0.04 m`);
  for (const i of [0, 1, 2]) for (const j of [0, 1]) assert.ok(Math.abs(moved[i][j] - poly[i][j] - (moved[0][j] - poly[0][j])) < 2e-5, "moved, not turned");
  assert.ok(moved[0][1] < poly[0][1], "towards -y");
  poly = moved;
  assert.ok(await page.locator("#error").isHidden());
  // The lens lifted on the side map: only its height changes.
  await dragOnMap(page, "map-side", await handle(page, "map-side", "lens"), [0, -25]);
  await dragSettled(page);
  file = await page.evaluate(() => window.bentstraw.state.file);
  const lifted = lensCentre();
  assert.deepEqual(lifted.slice(0, 2), [lx, ly]);
  assert.ok(lifted[2] > lz + 0.005, `${lifted[2]}`);
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  const digest = await pictureDigest(page);
  await page.screenshot({ path: path.join(dir, "laptop.png") });
  // Corners typed wrong: the page's own words under the controls, the box marked; the view stays.
  const framesBefore = await page.evaluate(() => window.bentstraw.frames);
  await page.fill('[data-key="prism[1].corners"]', "0.01, 0.02; 0.03");
  await page.press('[data-key="prism[1].corners"]', "Enter");
  await page.waitForFunction(() => !document.getElementById("objects-errors").hidden);
  assert.match((await page.locator("#objects-errors li").allTextContents()).join("\n"), /prism\[1\]\.corners: write the corners as x, y; x, y/);
  assert.equal(await page.getAttribute('[data-key="prism[1].corners"]', "aria-invalid"), "true");
  assert.equal(await page.evaluate(() => window.bentstraw.state.file), file);
  assert.equal(await page.evaluate(() => window.bentstraw.frames), framesBefore);
  // The link: a fresh page shows the same scene, its prism and lens in their boxes and on the maps.
  await page.click("#copy-link");
  const link = await page.evaluate(() => document.body.dataset.link);
  const fresh = await openPage(browser, server.url, { width: 1500, height: 1000 });
  await fresh.page.goto(link);
  await waitReady(fresh.page);
  assert.equal(await fresh.page.evaluate(() => window.bentstraw.state.file), file);
  await fresh.page.click("#scene-objects summary");
  await fresh.page.waitForFunction(() => document.querySelectorAll("#objects fieldset").length === 6);
  assert.deepEqual((await fresh.page.locator("#objects legend").allTextContents()).slice(4), ["Prism 1", "Lens 1"]);
  assert.equal(await fresh.page.inputValue('[data-key="prism[1].corners"]'), poly.map((q) => q.join(", ")).join("; "));
  assert.deepEqual(await fresh.page.locator('[data-key="lens[1].center"]').evaluateAll((els) => els.map((e) => Number(e.value))), lifted);
  await fresh.page.waitForFunction(() => ["prism", "lens"].every((k) => document.getElementById("map-top").handles.some((h) => h.kind === k)));
  assert.equal(await pictureDigest(fresh.page), digest);
  for (const kind of ["prism", "lens"]) assert.deepEqual(await handle(fresh.page, "map-top", kind), await handle(page, "map-top", kind));
  await fresh.page.screenshot({ path: path.join(dir, "reloaded.png") });
  assert.deepEqual(fresh.problems, []);
  await fresh.context.close();
  assert.deepEqual(problems, []);
  await context.close();
});

test("a glass of revolution: its profiles in the Objects panel and on both maps, a point dragged from the side, its shape switched, a broken profile refused in French", async () => {
  const dir = ON_SITE ? path.join(tmpdir(), "shots-revolution-site") : "/tmp/shots-revolution";
  mkdirSync(dir, { recursive: true });
  const { page, context, problems } = await openPage(browser, server.url, { width: 1500, height: 1000 });
  await page.goto(server.url + "#scene=wine-glass&observer=0,-0.15,0.12");
  await waitReady(page);
  await page.click("#scene-objects summary");
  await page.waitForFunction(() => document.querySelectorAll("#objects fieldset").length === 3);
  // The controls hold the file's profiles, written "r, z; r, z; …".
  const gallery = readFileSync(path.join(ROOT, "scenes/wine-glass.toml"), "utf8");
  const pairs = (list) => list.map((q) => q.join(", ")).join("; ");
  const profile = (text, which) => JSON.parse(fileValue(text, "container", 0, which));
  assert.equal(await page.inputValue('[data-key="container.shape"]'), "revolution");
  assert.equal(await page.locator('[data-key="container.shape"] option:checked').textContent(), "of revolution");
  for (const which of ["outer", "inner"]) assert.equal(await page.inputValue(`[data-key="container.${which}"]`), pairs(profile(gallery, which)));
  assert.equal(await page.inputValue('[data-key="container.index"]'), "1.5");
  assert.deepEqual(await page.locator('#objects fieldset[data-object="container"] label > span[data-i18n]').allTextContents(), ["shape", "outer profile (r, z)", "inner profile (r, z)", "index n"]);
  // The side map: a ring on each point of both profiles; the water tinted inside the bowl, not
  // above its surface; from above, the water's disc inside the glass's widest circle.
  const handles = (id = "map-side") => page.evaluate((id) => document.getElementById(id).handles, id);
  const point = async (which, k) => (await handles()).find((h) => h.kind === "profile" && h.which === which && h.k === k).at;
  assert.deepEqual((await handles()).filter((h) => h.kind === "profile").map((h) => h.which[0]).join(""), "o".repeat(11) + "i".repeat(4));
  /** The share of a map's pixels along the row at height `z`, from `s0` to `s1` across (metres),
   * that are tinted (neither white nor clear), and the longest run of them side by side (a
   * liquid's tint fills the row; the wall's lines are a pixel or two each). */
  const tinted = (id, z, s0, s1) => page.evaluate(([id, z, s0, s1]) => {
    const c = document.getElementById(id), d = c.width / c.clientWidth, k = c.clientWidth / 2;
    const inv = c.mapInverse, [a0] = inv(k, 0), [a1, zz] = inv(k + 1, 0), scale = 1 / (a1 - a0);
    const y = Math.round((0 - (z - zz) * scale) * d), xs = [s0, s1].map((s) => Math.round((k + (s - a0) * scale) * d));
    const row = c.getContext("2d").getImageData(xs[0], y, xs[1] - xs[0], 1).data;
    let n = 0, run = 0, longest = 0;
    for (let i = 0; i < row.length; i += 4) {
      if (row[i + 3] > 20 && row[i] + row[i + 1] + row[i + 2] < 3 * 245) { n++; run++; longest = Math.max(longest, run); } else run = 0;
    }
    return { share: n / (row.length / 4), longest };
  }, [id, z, s0, s1]);
  assert.ok((await tinted("map-side", 0.115, 0.006, 0.02)).share > 0.9, "the water in the bowl");
  assert.ok((await tinted("map-side", 0.16, 0.006, 0.02)).longest <= 3, "nothing but the wall's lines above the water");
  assert.ok((await tinted("map-top", 0, 0.006, 0.03)).share > 0.9, "the water from above");
  await page.locator("#map-panel").scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(dir, "laptop.png") });
  // A profile changed in its control: the file says it, the view is simulate's for that text,
  // and the point's ring moves on the side map.
  let file = await boxText(page);
  const frames = await page.evaluate(() => window.bentstraw.frames);
  const before = await pictureDigest(page), ring = await point("inner", 2);
  const narrower = profile(gallery, "inner").map(([r, z]) => [z === 0.13 ? 0.036 : r, z]);
  await page.fill('[data-key="container.inner"]', pairs(narrower));
  await page.press('[data-key="container.inner"]', "Enter");
  file = await nextFile(page, file);
  assert.deepEqual(profile(file, "inner"), narrower);
  assert.equal(await page.inputValue("#scene-text"), file);
  assert.ok(await page.evaluate(() => window.bentstraw.frames) > frames);
  assert.notEqual(await pictureDigest(page), before);
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  await page.waitForFunction((x) => document.getElementById("map-side").handles.some((h) => h.kind === "profile" && h.which === "inner" && h.k === 2 && h.at[0] < x - 1), ring[0]);
  // A point of the inner profile dragged far up on the side map: it rises, the steps the rules
  // refuse (at or above the next point's height) left out, with no banner.
  const refused = await page.evaluate(() => Number(document.body.dataset.dragRefused || 0));
  await dragOnMap(page, "map-side", await point("inner", 1), [0, -60], 60);
  await dragSettled(page);
  file = await page.evaluate(() => window.bentstraw.state.file);
  const [r1, z1] = profile(file, "inner")[1];
  assert.ok(r1 === 0.028 && z1 > 0.1 && z1 < 0.13, `the inner profile's point 2 at ${r1}, ${z1}`);
  assert.ok(await page.evaluate(() => Number(document.body.dataset.dragRefused || 0)) > refused, "steps past the outer wall left out");
  assert.ok(await page.locator("#error").isHidden());
  assert.ok(await page.locator("#objects-errors").isHidden());
  assert.equal(await page.inputValue('[data-key="container.inner"]'), pairs(profile(file, "inner")));
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  // The rim's point dragged up on the outer profile's side: both rims rise together.
  await dragOnMap(page, "map-side", await point("outer", 10), [0, -10], 5);
  await dragSettled(page);
  file = await page.evaluate(() => window.bentstraw.state.file);
  const rim = profile(file, "outer")[10][1];
  assert.ok(rim > 0.195, `the rim at ${rim}`);
  assert.equal(profile(file, "inner")[3][1], rim);
  await page.screenshot({ path: path.join(dir, "laptop-dragged.png") });
  // The shape switched: a glass of the widest radius, the rim's height, the rim's thickness and
  // the floor; then a glass of revolution of that glass's straight profiles; then the glass again.
  const shape = async (value) => {
    const text = await page.evaluate(() => window.bentstraw.state.file);
    await page.selectOption('[data-key="container.shape"]', value);
    return nextFile(page, text);
  };
  file = await shape("glass");
  const glass = ["shape", "radius", "height", "wall", "bottom", "index"].map((k) => fileValue(file, "container", 0, k));
  assert.deepEqual(glass, ['"glass"', "0.041", String(rim), "0.002", "0.082", "1.5"]);
  await page.waitForFunction(() => document.querySelector('[data-key="container.radius"]'));
  assert.equal(await page.inputValue('[data-key="container.radius"]'), "0.041");
  assert.equal((await handles()).filter((h) => h.kind === "profile").length, 0);
  file = await shape("revolution");
  assert.deepEqual([profile(file, "outer"), profile(file, "inner")], [[[0.041, 0], [0.041, rim]], [[0.039, 0.082], [0.039, rim]]]);
  await page.waitForFunction(() => document.getElementById("map-side").handles.filter((h) => h.kind === "profile").length === 4);
  assert.equal(await page.inputValue('[data-key="container.outer"]'), `0.041, 0; 0.041, ${rim}`);
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  file = await shape("glass");
  assert.deepEqual(["shape", "radius", "height", "wall", "bottom", "index"].map((k) => fileValue(file, "container", 0, k)), glass);
  file = await shape("revolution");
  // In French: an inner profile that leaves the outer one is refused with its rule in French, its
  // control marked, the view staying; a list that is not one of points gets the page's own words.
  await page.selectOption("#lang", "fr");
  const framesBefore = await page.evaluate(() => window.bentstraw.frames);
  await page.fill('[data-key="container.inner"]', `0.039, 0.082; 0.045, ${rim}`);
  await page.press('[data-key="container.inner"]', "Enter");
  await page.waitForFunction(() => !document.getElementById("objects-errors").hidden);
  const rules = (await page.locator("#objects-errors li").allTextContents()).join("\n");
  assert.match(rules, /container\.inner.*le profil intérieur sort du profil extérieur vers z = [\d,]+ \(rayons [\d,]+ et 0,041\)/, rules);
  assert.equal(await page.getAttribute('[data-key="container.inner"]', "aria-invalid"), "true");
  assert.equal(await page.evaluate(() => window.bentstraw.state.file), file);
  assert.equal(await page.evaluate(() => window.bentstraw.frames), framesBefore);
  await page.locator("#objects-errors").scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(dir, "laptop-refused-fr.png") });
  await page.fill('[data-key="container.outer"]', "0.041, 0; 0.041");
  await page.press('[data-key="container.outer"]', "Enter");
  await page.waitForFunction(() => /container\.outer : écrivez les points r, z/.test(document.getElementById("objects-errors").textContent));
  assert.equal(await page.getAttribute('[data-key="container.outer"]', "aria-invalid"), "true");
  assert.equal(await page.evaluate(() => window.bentstraw.state.file), file);
  // (The refused text's answer, 400, is the browser's only complaint.)
  assert.deepEqual(problems.filter((p) => !/status of 400/.test(p)), []);
  await context.close();
  // On a phone: the wine glass on both maps, its controls within the screen.
  const phone = await openPage(browser, server.url, { width: 390, height: 844 }, PHONE);
  await phone.page.goto(server.url + "#scene=wine-glass");
  await waitReady(phone.page);
  await phone.page.click("#scene-objects summary");
  await phone.page.waitForFunction(() => document.getElementById("map-side").handles.some((h) => h.kind === "profile"));
  assert.ok(await phone.page.evaluate(() => document.scrollingElement.scrollWidth) <= 390);
  await phone.page.locator("#map-panel").scrollIntoViewIfNeeded();
  await phone.page.screenshot({ path: path.join(dir, "phone-maps.png") });
  await phone.page.locator('#objects fieldset[data-object="container"]').scrollIntoViewIfNeeded();
  await phone.page.screenshot({ path: path.join(dir, "phone-objects.png") });
  assert.deepEqual(phone.problems, []);
  await phone.context.close();
});

test("the maps are framed on the glass: handles a finger apart, a far eye at the edge, a straw leaned by its handle from above", async () => {
  // (A teacher's laptop: the static site's header leaves the maps least room there.)
  const { page, context, problems } = await openPage(browser, server.url, { width: 1366, height: 768 });
  await page.goto(server.url + "#scene=two-straws&observer=0.25,0,0.17");
  await waitReady(page);
  await page.waitForFunction(() => document.getElementById("map-top").handles.some((h) => h.kind === "lean"));
  // The glass (radius 4 cm) is well over a hundred pixels across from above, not a speck.
  const across = await page.evaluate(() => { const inv = document.getElementById("map-top").mapInverse; return 0.08 / (inv(101, 0)[0] - inv(1, 0)[0]) * 100; });
  assert.ok(across >= 100, `the glass is ${across} px across`);
  // Every handle (the straws' feet and leans) and the eye at least 44 px from each other: where
  // the straws stand closer, their handles are drawn apart with a line to where each belongs.
  const points = await page.evaluate(() => { const c = document.getElementById("map-top"); return [...c.handles.map((h) => h.at), c.eyeAt]; });
  for (let i = 0; i < points.length; i++) for (let j = i + 1; j < points.length; j++) {
    const d = Math.hypot(points[i][0] - points[j][0], points[i][1] - points[j][1]);
    assert.ok(d >= 44, `handles ${i} and ${j} are ${d} px apart`);
  }
  // A foot drawn off its straw moves the straw by the finger's path, not to the finger.
  const [feet, grab] = await page.evaluate(() => {
    const c = document.getElementById("map-top"), h = c.handles.find((h) => h.kind === "straw" && h.k === 0 && h.shift);
    return [c.handles.filter((h) => h.kind === "straw").length, h && { at: h.at, k: h.k, per: c.mapInverse(1, 0)[0] - c.mapInverse(0, 0)[0] }];
  });
  assert.equal(feet, 2);
  assert.ok(grab, "the two straws' feet, closer than a fingertip at this size, are drawn apart");
  {
    const before = await page.evaluate(() => window.bentstraw.state.file);
    const start = before || readFileSync(path.join(ROOT, "scenes/two-straws.toml"), "utf8");
    const [x0, y0] = [Number(fileValue(start, "straw", grab.k, "x")), Number(fileValue(start, "straw", grab.k, "y"))];
    // (The straw on the axis, down the map: away from the other.)
    await dragOnMap(page, "map-top", grab.at, [0, 20]);
    const file = await nextFile(page, before);
    const [x1, y1] = [Number(fileValue(file, "straw", grab.k, "x")), Number(fileValue(file, "straw", grab.k, "y"))];
    assert.ok(Math.abs(x1 - x0) < 2 * grab.per && Math.abs(y0 - y1 - 20 * grab.per) < 2 * grab.per, `moved from (${x0}, ${y0}) to (${x1}, ${y1})`);
  }
  // The eye, 25 cm away, is beyond the map's frame: drawn at its edge.
  assert.ok(await page.evaluate(() => document.getElementById("map-top").eyeFar));
  // The upright straw on the axis leaned by its handle (44 px beyond its foot towards +x), moved
  // 30 px further out and 30 px up (+y): its azimuth points at the pointer, and its tilt is
  // the pointer's distance beyond those 44 px over the straw's length (25 cm), as a sine.
  const [lean, foot, perPx] = await page.evaluate(() => {
    const c = document.getElementById("map-top"), h = c.handles.find((h) => h.kind === "lean" && h.k === 0);
    return [h.at, h.from, c.mapInverse(1, 0)[0] - c.mapInverse(0, 0)[0]];
  });
  const [px, py] = [lean[0] + 30 - foot[0], lean[1] - 30 - foot[1]];
  const wantAzimuth = Math.atan2(-py, px) * 180 / Math.PI, wantTilt = Math.asin((Math.hypot(px, py) - 44) * perPx / 0.25) * 180 / Math.PI;
  const before = await page.evaluate(() => window.bentstraw.state.file);
  await dragOnMap(page, "map-top", lean, [30, -30]);
  const file = await nextFile(page, before);
  const tilt = Number(fileValue(file, "straw", 0, "tilt")), azimuth = Number(fileValue(file, "straw", 0, "azimuth"));
  assert.ok(Math.abs(tilt - wantTilt) < 0.3, `tilt ${tilt}, not ${wantTilt}`);
  assert.ok(Math.abs(azimuth - wantAzimuth) < 0.3, `azimuth ${azimuth}, not ${wantAzimuth}`);
  assert.equal((await simulateText(file)).csv, await page.evaluate(() => window.bentstraw.points()));
  await page.locator("#map-panel").screenshot({ path: shot("explorer-maps.png") });
  assert.deepEqual(problems, []);
  await context.close();
});

test("a prism's corner dragged on the map from above, and a lens's axis turned by its handle", async () => {
  const { page, context, problems } = await openPage(browser, server.url, { width: 1500, height: 1000 });
  const handles = () => page.evaluate(() => document.getElementById("map-top").handles);
  const pairs = (list) => list.map((q) => q.join(", ")).join("; ");
  // The prism: a ring on each corner; one dragged outwards from its middle moves that corner alone.
  await page.goto(server.url + "#scene=prism");
  await waitReady(page);
  await page.click("#scene-objects summary");
  await page.waitForFunction(() => document.getElementById("map-top").handles.filter((h) => h.kind === "corner").length === 3);
  let file = await boxText(page);
  const poly = JSON.parse(fileValue(file, "prism", 0, "corners"));
  assert.equal(await page.inputValue('[data-key="prism[1].corners"]'), pairs(poly));
  const middle = (await handles()).find((h) => h.kind === "prism").at;
  const corner = (await handles()).find((h) => h.kind === "corner" && h.k === 0 && h.j === 0).at;
  const out = [corner[0] - middle[0], corner[1] - middle[1]], d = Math.hypot(...out);
  await dragOnMap(page, "map-top", corner, [(12 * out[0]) / d, (12 * out[1]) / d], 6);
  await dragSettled(page);
  file = await page.evaluate(() => window.bentstraw.state.file);
  const moved = JSON.parse(fileValue(file, "prism", 0, "corners"));
  assert.deepEqual(moved.slice(1), poly.slice(1), "the other corners stay");
  const mid = [0, 1].map((i) => poly.reduce((a, q) => a + q[i], 0) / 3), far = (q) => Math.hypot(q[0] - mid[0], q[1] - mid[1]);
  assert.ok(far(moved[0]) > far(poly[0]) + 1e-3, `corner 1 at ${moved[0]}, from ${poly[0]}`);
  assert.equal(await page.inputValue('[data-key="prism[1].corners"]'), pairs(moved));
  assert.ok(await page.locator("#error").isHidden());
  // The lens: its axis's handle 22 px from its centre along the axis (-x); dragged sideways, the
  // axis turns towards the pointer, still level and of length 1.
  await page.goto(server.url + "#scene=magnifying-glass");
  await waitReady(page);
  await page.waitForFunction(() => document.getElementById("map-top").handles.some((h) => h.kind === "axis"));
  const axisHandle = (await handles()).find((h) => h.kind === "axis"), centre = (await handles()).find((h) => h.kind === "lens").at;
  assert.ok(Math.abs(Math.hypot(axisHandle.at[0] - centre[0], axisHandle.at[1] - centre[1]) - 22) < 0.01);
  const along = [(axisHandle.at[0] - centre[0]) / 22, (axisHandle.at[1] - centre[1]) / 22];
  const drop = [axisHandle.at[0] - 15 * along[1], axisHandle.at[1] + 15 * along[0]];
  await dragOnMap(page, "map-top", axisHandle.at, [-15 * along[1], 15 * along[0]], 6);
  await dragSettled(page);
  file = await page.evaluate(() => window.bentstraw.state.file);
  const axis = JSON.parse(fileValue(file, "lens", 0, "axis"));
  assert.equal(axis[2], 0);
  assert.ok(Math.abs(Math.hypot(axis[0], axis[1]) - 1) < 2e-4, `${axis}`);
  assert.ok(axis[0] < -0.6 && Math.abs(axis[1]) > 0.4, `the axis turned: ${axis}`);
  assert.deepEqual(await page.locator('[data-key="lens[1].axis"]').evaluateAll((els) => els.map((e) => Number(e.value))), axis);
  // Its handle now points towards where the pointer left it.
  const turned = (await handles()).find((h) => h.kind === "axis").at;
  const angle = (p) => Math.atan2(p[1] - centre[1], p[0] - centre[0]);
  assert.ok(Math.abs(angle(turned) - angle(drop)) < 0.02, `${angle(turned)} vs ${angle(drop)}`);
  assert.ok(await page.locator("#error").isHidden());
  assert.deepEqual(problems, []);
  await context.close();
});

// ---- predict, then look ----

/** The marks' canvas over the picture (or the side map) is drawn at the window's point [x, y]. */
const markedAt = (page, id, [x, y]) => page.evaluate(([id, x, y]) => {
  const c = document.getElementById(id), r = c.getBoundingClientRect(), d = c.width / r.width;
  const px = c.getContext("2d").getImageData(Math.round((x - r.left) * d), Math.round((y - r.top) * d), 1, 1).data;
  return px[3] > 0;
}, [id, x, y]);

/** Waits until the page in predict mode has the engine's answer for the view it shows. */
const waitAnswer = (page) => page.waitForFunction(() => window.bentstraw.predict.answer && document.body.dataset.predictAnswer);

test("predict, then look: a teacher's link hides the picture; a guess is revealed with the true image and the distance, in English and French", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url + "#predict=1&lang=en");
  await waitReady(page);
  await waitAnswer(page);
  // The picture and the 3D view are hidden; the bar says what to click; nothing to reveal yet.
  assert.equal(await page.evaluate(() => window.bentstraw.predict.phase), "guess");
  assert.equal(await page.getAttribute("#predict", "aria-pressed"), "true");
  assert.ok(await page.locator("#predict-cover").isVisible());
  assert.ok(await page.locator("#predict-cloud-cover").isVisible());
  assert.equal(await page.evaluate(() => getComputedStyle(document.getElementById("picture")).visibility), "hidden");
  assert.equal(await page.evaluate(() => getComputedStyle(document.getElementById("cloud")).visibility), "hidden");
  const [cover, picture] = [await page.locator("#predict-cover").boundingBox(), await page.locator("#picture").boundingBox()];
  for (const k of ["x", "y", "width", "height"]) assert.ok(Math.abs(cover[k] - picture[k]) < 1.5, `${k}: ${cover[k]} vs ${picture[k]}`);
  assert.match(await page.locator("#predict-text").textContent(), /^Click where you expect the bottom of the straw to appear/);
  assert.equal(await page.locator("#predict-question").textContent(), "Where will you see the bottom of the straw?");
  assert.ok(await page.locator("#predict-reveal").isDisabled());
  assert.match(await page.evaluate(() => window.bentstraw.link()), /[#&]predict=1(&|$)/);
  await page.screenshot({ path: shot("explorer-predict-hidden.png") });
  // A guess off the mark, in the picture and on the side map; revealed: both marked, and the distances.
  await page.mouse.click(cover.x + 0.3 * cover.width, cover.y + 0.35 * cover.height);
  const side = await page.locator("#map-side").boundingBox();
  await page.mouse.click(side.x + 0.75 * side.width, side.y + 0.3 * side.height);
  assert.ok(await page.locator("#predict-reveal").isEnabled());
  await page.click("#predict-reveal");
  await page.waitForFunction(() => document.body.dataset.predict === "shown");
  assert.equal(await page.evaluate(() => getComputedStyle(document.getElementById("picture")).visibility), "visible");
  assert.ok(await page.locator("#predict-cover").isHidden());
  const far = await page.evaluate(() => window.bentstraw.predict.results());
  assert.ok(far.picture.degrees > 2 && far.map.metres > 0.01, JSON.stringify(far));
  const said = await page.locator("#predict-text").textContent();
  assert.match(said, new RegExp(`In the picture, your guess is ${far.picture.degrees.toFixed(1)}° away from where the bottom of the straw appears\\.`));
  assert.match(said, new RegExp(`On the side map, your guess is ${(100 * far.map.metres).toFixed(1)} cm away from where (two eyes see|one eye, focusing, sees) the bottom of the straw\\.`));
  const image = await page.evaluate((k) => window.bentstraw.predict.screenOfImage(k), far.picture.image);
  assert.ok(await markedAt(page, "predict-marks", image), "the true image is marked");
  assert.ok(await markedAt(page, "predict-marks", await page.evaluate(() => window.bentstraw.predict.screenOfGuess())), "the guess is marked");
  // Each image's ray reaches the straw's lower end (the engine's answer, red: section 1).
  const answer = await page.evaluate(() => window.bentstraw.predict.answer);
  assert.equal(answer.target.kind, "straw-bottom");
  for (const im of answer.images) assert.equal(im.ray.color, 1);
  // The light's path of that image: the readout's ray reaches the straw's red end.
  await page.click("#predict-path");
  await page.waitForFunction(() => /^px:/.test(document.body.dataset.picked || "") && window.bentstraw.path);
  assert.equal(await page.evaluate(() => window.bentstraw.path.color), 1);
  assert.match(await page.locator("#readout").textContent(), /1 red/);
  // Try again, a guess exactly where it appears: about no distance, in the picture and on the map.
  await page.click("#predict-again");
  await page.waitForFunction(() => document.body.dataset.predict === "guess");
  assert.ok(await page.locator("#predict-cover").isVisible());
  assert.equal(await page.evaluate(() => window.bentstraw.path), null, "the light's path is hidden again");
  // (Nothing of it left on the side map: only the eye's dot is black there.)
  assert.equal(await page.evaluate(() => {
    const c = document.getElementById("map-side"), d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let dark = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i + 3] > 200 && d[i] < 40 && d[i + 1] < 40 && d[i + 2] < 40) dark++;
    return dark < 200 * devicePixelRatio ** 2;
  }), true);
  await waitReady(page);
  const [at, onMap] = await page.evaluate(() => [window.bentstraw.predict.screenOfImage(0), window.bentstraw.predict.screenOfApparent(0)]);
  await page.mouse.click(...at);
  await page.mouse.click(...onMap);
  // The keyboard too: Enter on the hidden picture reveals.
  await page.focus("#predict-cover");
  await page.keyboard.press("Enter");
  await page.waitForFunction(() => document.body.dataset.predict === "shown");
  const near = await page.evaluate(() => window.bentstraw.predict.results());
  assert.equal(near.picture.image, 0);
  // (A click lands on a whole pixel: on the side map one is about 3 mm.)
  assert.ok(near.picture.degrees < 0.15 && near.map.metres < 0.006, JSON.stringify(near));
  assert.match(await page.locator("#predict-text").textContent(), /your guess is 0\.[01]° away/);
  await page.screenshot({ path: shot("explorer-predict.png") });
  // In French, every text of the mode.
  await page.selectOption("#lang", "fr");
  const fr = await page.locator("#predict-text").textContent();
  assert.match(fr, /Dans l'image, votre prédiction est à 0,[01]° de l'endroit où apparaît le bas de la paille\./);
  assert.match(fr, /Sur la vue de côté, votre prédiction est à 0,\d cm de l'endroit où (deux yeux voient|un œil qui accommode voit) le bas de la paille\./);
  assert.equal(await page.locator("#predict-again").textContent(), "Recommencer");
  assert.equal(await page.locator("#predict").textContent(), "Prédire, puis regarder");
  assert.deepEqual(await i18nMismatches(page, "fr"), []);
  // Moving the eye starts a new guess, the picture hidden again; the toggle leaves the mode.
  await page.selectOption("#preset", "4");
  await page.waitForFunction(() => document.body.dataset.predict === "guess");
  assert.ok(await page.locator("#predict-cover").isVisible());
  await page.click("#predict");
  await page.waitForFunction(() => document.body.dataset.predict === "off");
  assert.ok(await page.locator("#predict-cover").isHidden());
  assert.ok(await page.locator("#predict-bar").isHidden());
  assert.equal(await page.evaluate(() => getComputedStyle(document.getElementById("picture")).visibility), "visible");
  assert.doesNotMatch(await page.evaluate(() => window.bentstraw.link()), /predict=/);
  assert.ok(await page.locator("#error").isHidden());
  assert.deepEqual(problems, []);
  await context.close();
});

test("predict, then look on a phone, in French: a tap in the hidden picture, the coin's centre revealed", async () => {
  const { page, context, problems } = await openPage(browser, server.url, { width: 390, height: 844 }, { ...PHONE, locale: "fr-FR" });
  await page.goto(server.url + "#scene=coin-in-glass&observer=0.25,0,0.12&predict=1");
  await waitReady(page);
  await waitAnswer(page);
  assert.equal(await page.evaluate(() => document.documentElement.lang), "fr");
  assert.ok(await page.evaluate(() => document.scrollingElement.scrollWidth) <= 390);
  assert.match(await page.locator("#predict-text").textContent(), /^Touchez l'endroit où vous pensez voir le centre de la pièce/);
  assert.equal(await page.evaluate(() => getComputedStyle(document.getElementById("picture")).visibility), "hidden");
  const answer = await page.evaluate(() => window.bentstraw.predict.answer);
  assert.equal(answer.target.kind, "coin-centre");
  assert.ok(answer.images.length >= 1);
  for (const id of ["#predict", "#predict-reveal"]) assert.ok((await page.locator(id).boundingBox()).height >= 44, id);
  await page.screenshot({ path: path.join(tmpdir(), (ON_SITE ? "bentstraw-site-" : "bentstraw-") + "predict-phone-hidden.png") });
  // A tap exactly where the coin's centre appears.
  const at = await page.evaluate(() => window.bentstraw.predict.screenOfImage(0));
  await page.evaluate(() => document.getElementById("predict-cover").scrollIntoView({ block: "start" }));
  const at2 = await page.evaluate(() => window.bentstraw.predict.screenOfImage(0));
  await page.touchscreen.tap(...at2);
  await page.tap("#predict-reveal");
  await page.waitForFunction(() => document.body.dataset.predict === "shown");
  const r = await page.evaluate(() => window.bentstraw.predict.results());
  assert.ok(r.picture.degrees < 0.3, JSON.stringify({ r, at, at2 }));
  assert.match(await page.locator("#predict-text").textContent(), /Dans l'image, votre prédiction est à 0,\d° de l'endroit où apparaît le centre de la pièce\./);
  assert.ok(await markedAt(page, "predict-marks", await page.evaluate(() => window.bentstraw.predict.screenOfImage(0))));
  assert.ok(await page.evaluate(() => document.scrollingElement.scrollWidth) <= 390);
  await page.locator("#eye-panel").screenshot({ path: path.join(tmpdir(), (ON_SITE ? "bentstraw-site-" : "bentstraw-") + "predict-phone.png") });
  assert.deepEqual(problems, []);
  await context.close();
});

test("apparent depth as the eye moves: the clicked point's plot and its CSV, the current eye's numbers the readout's and the server's, in English and French, on a laptop and a phone", async () => {
  // The same numbers from bentstraw explore's own route: on the site, from a server started here.
  const native = ON_SITE ? await startServer() : server;
  const dir = ON_SITE ? path.join(tmpdir(), "shots-sweep-site") : "/tmp/shots-sweep";
  mkdirSync(dir, { recursive: true });
  try {
    for (const [name, viewport, options] of [["laptop", { width: 1400, height: 900 }, {}], ["phone", { width: 390, height: 844 }, PHONE]]) {
      for (const lang of ["en", "fr"]) {
        const { page, context, problems } = await openPage(browser, server.url, viewport, { ...options, locale: lang === "fr" ? "fr-FR" : "en-US" });
        const view = "observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&points=20000";
        await page.goto(server.url + "#" + view);
        await waitReady(page);
        // Nothing to follow before a point is clicked.
        assert.ok(await page.isHidden("#sweep"));
        await page.evaluate(() => window.bentstraw.pickPoint(1234));
        await page.waitForFunction(() => document.body.dataset.picked === "point:1234");
        await page.waitForSelector("#sweep:not([hidden])");
        assert.equal(await page.inputValue("#sweep-kind"), "off");
        assert.ok(await page.isHidden("#sweep-plot"));
        const p = await page.evaluate(() => window.bentstraw.path);
        for (const kind of ["around", "updown"]) {
          await page.selectOption("#sweep-kind", kind);
          await page.waitForFunction((k) => (document.body.dataset.sweep || "").startsWith(k + ":"), kind);
          const n = Number((await page.evaluate(() => document.body.dataset.sweep)).split(":")[1]);
          // 61 positions of the eye, and the current one if the grid misses it.
          assert.ok(n === 61 || n === 62, String(n));
          const [download] = await Promise.all([page.waitForEvent("download"), page.click("#sweep-csv")]);
          assert.equal(download.suggestedFilename(), `sweep-${kind}.csv`);
          const csv = readFileSync(await download.path(), "utf8");
          const [head, ...lines] = csv.trim().split("\n");
          assert.match(head, /^angle_deg,eye_x_m,eye_y_m,eye_z_m,current,sight,path,course_x_m,/);
          assert.equal(lines.length, n);
          const col = Object.fromEntries(head.split(",").map((c, i) => [c, i]));
          const rows = lines.map((l) => l.split(","));
          const own = rows.filter((r) => r[col.current] === "1");
          assert.equal(own.length, 1);
          const xyz = (r, what) => ["x", "y", "z"].map((a) => Number(r[col[`${what}_${a}_m`]]));
          // The current eye is the observer, and sees the point along the readout's ray: the same
          // numbers, to the bit.
          assert.deepEqual(xyz(own[0], "eye"), p.observer);
          assert.equal(own[0][col.sight], "seen");
          assert.deepEqual(xyz(own[0], "course"), p.image_point);
          assert.deepEqual(xyz(own[0], "stereo"), p.stereo_point);
          assert.equal(Number(own[0][col.s_h_m]), p.s_h.distance);
          assert.equal(Number(own[0][col.s_v_m]), p.s_v.distance);
          // The angles run over the whole sweep, in order; the unseen positions have no numbers.
          const angles = rows.map((r) => Number(r[col.angle_deg]));
          assert.deepEqual(angles.slice().sort((a, b) => a - b), angles);
          assert.deepEqual([angles[0], angles[n - 1]], kind === "around" ? [-180, 180] : [-90, 90]);
          for (const r of rows) if (r[col.sight] !== "seen") assert.equal(r[col.course_z_m], "");
          // The legend gives the readout's height of the course's point here.
          const legend = await page.textContent("#sweep-legend");
          const here = p.image_point[2].toFixed(4);
          assert.ok(legend.includes(lang === "fr" ? here.replace(".", ",") : here), legend);
          // bentstraw explore's route gives the same file, to the byte.
          const query = `${view}&point=${p.straw_point.join(",")}&direction=${p.direction.join(",")}&sweep=${kind}&rows=61&format=csv`;
          const r = await fetch(`${native.url}api/sweep?${query}`);
          assert.equal(r.status, 200);
          assert.equal(await r.text(), csv);
        }
        // Axes labelled with their units, in the page's language.
        const words = await page.textContent("#sweep-plot");
        assert.match(words, lang === "fr" ? /hauteur z \(cm\)/ : /height z \(cm\)/);
        assert.match(words, lang === "fr" ? /élévation de l'œil \(°\)/ : /elevation of the eye \(°\)/);
        // One line per model, the current eye marked on each it places.
        assert.ok(await page.locator("#sweep-plot polyline").count() >= 4);
        assert.ok(await page.locator("#sweep-plot circle.here").count() >= 3);
        if (name === "phone") {
          assert.ok(await page.evaluate(() => document.scrollingElement.scrollWidth) <= 390);
          const small = await page.evaluate(() => ["sweep-kind", "sweep-csv"].map((id) => [id, document.getElementById(id).getBoundingClientRect().height]).filter(([, h]) => h < 44));
          assert.deepEqual(small, []);
        }
        // The panel scrolled to the plot (on a laptop the readout's panel scrolls on its own).
        await page.evaluate(() => document.getElementById("sweep").scrollIntoView({ block: "start" }));
        await page.locator("#readout-panel").screenshot({ path: path.join(dir, `${name}-${lang}.png`) });
        assert.deepEqual(problems, []);
        await context.close();
      }
    }
  } finally {
    if (ON_SITE) native.stop();
  }
});

test("predict, then look: a target the eye cannot see is said to be unseen, in both languages", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  // The marble in front hides the straw's bottom from this eye.
  await page.goto(server.url + "#scene=marble-in-water&observer=0.18,0,0.04&predict=1&lang=en");
  await waitReady(page);
  await waitAnswer(page);
  assert.deepEqual(await page.evaluate(() => window.bentstraw.predict.answer.images), []);
  const cover = await page.locator("#predict-cover").boundingBox();
  await page.mouse.click(cover.x + cover.width / 2, cover.y + cover.height / 2);
  await page.click("#predict-reveal");
  await page.waitForFunction(() => document.body.dataset.predict === "shown");
  assert.equal(await page.locator("#predict-text").textContent(), "From this eye, the bottom of the straw cannot be seen in this picture.");
  assert.ok(await page.locator("#predict-path").isHidden());
  await page.selectOption("#lang", "fr");
  assert.equal(await page.locator("#predict-text").textContent(), "Depuis cet œil, on ne voit pas le bas de la paille dans cette image.");
  assert.deepEqual(problems, []);
  await context.close();
});
