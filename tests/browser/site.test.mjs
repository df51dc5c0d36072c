// End-to-end tests of the static site (`cargo xtask site`) in headless Chromium, served by a
// plain static server (Python's http.server): no bentstraw process, every number computed by the
// engine compiled to WebAssembly in the page. Run: npm run test:site (after `cargo xtask site`).
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { existsSync, mkdtempSync, readFileSync, readdirSync, statSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import http from "node:http";
import { launch, openPage, waitReady, runCli, SITE, startStaticServer, startPythonExplore } from "./harness.mjs";

let server, browser;
before(async () => {
  assert.ok(existsSync(path.join(SITE, "index.html")), `no site at ${SITE}: run cargo xtask site`);
  server = await startStaticServer();
  browser = await launch();
});
after(async () => { await browser?.close(); server?.stop(); });

/** Runs the bentstraw command line in `dir`; resolves to { code, stdout, stderr }. */
const cli = (args, dir) => runCli(args, dir);

/** The page's points against the bytes `bentstraw simulate` writes for the page's own command
 * (its scene file, if any, written as scene.toml beside it). */
async function assertPointsAreSimulates(page, label) {
  const [csv, args, toml] = await page.evaluate(async () => [await window.bentstraw.points(), await window.bentstraw.command(), window.bentstraw.state.file]);
  const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-site-"));
  if (args.includes("scene.toml")) writeFileSync(path.join(dir, "scene.toml"), toml);
  const r = await cli(args, dir);
  assert.equal(r.code, 0, `${label}: ${args.join(" ")}: ${r.stderr}`);
  const expected = readFileSync(path.join(dir, "view.csv"), "utf8");
  assert.ok(expected.length > 1000, label);
  assert.ok(csv === expected, `${label}: the page's ${csv.length} bytes differ from simulate's ${expected.length} (${args.join(" ")})`);
  return { csv, args };
}

/** Drags the mouse across the eye's picture in `steps` moves. */
async function drag(page, steps, dx, dy) {
  const box = await page.locator("#picture").boundingBox();
  let x = box.x + box.width / 2, y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let i = 0; i < steps; i++) { x += dx; y += dy; await page.mouse.move(x, y); await page.waitForTimeout(16); }
  await page.mouse.up();
}

// A scene of my own: two straws, one leaning, in a thick glass of oil; seen from the front.
const MY_SCENE = `# Two straws in a thick glass of oil.
[container]
shape = "glass"
radius = 0.045
height = 0.18
wall = 0.003
bottom = 0.006
index = 1.52

[[liquid]]
name = "oil"
index = 1.47
top = 0.12

[[straw]]
x = 0.01
y = -0.008
tilt = 8.0
azimuth = 200.0
radius = 0.004
length = 0.22

[[straw]]
x = -0.015
y = 0.012
radius = 0.005
length = 0.2

[observer]
position = [0.18, 0.04, 0.09]
target = [0.0, 0.0, 0.08]
`;

test("the site is plain files within 6 MB, the engine in WebAssembly with SIMD", () => {
  const sizes = (dir) => readdirSync(dir).reduce((n, f) => { const p = path.join(dir, f); return n + (statSync(p).isDirectory() ? sizes(p) : statSync(p).size); }, 0);
  const total = sizes(SITE);
  assert.ok(total < 6e6, `${total} bytes`);
  for (const f of ["index.html", "main.js", "i18n.js", "explorer.css", "worker.js", "pkg/bentstraw_web.js", "pkg/bentstraw_web_bg.wasm"]) assert.ok(existsSync(path.join(SITE, f)), f);
  // SIMD: the compiler's record of the features the module was built with lists simd128.
  const wasm = readFileSync(path.join(SITE, "pkg/bentstraw_web_bg.wasm"));
  assert.ok(WebAssembly.validate(wasm));
  const features = WebAssembly.Module.customSections(new WebAssembly.Module(wasm), "target_features");
  assert.equal(features.length, 1, "no target_features section");
  assert.ok(Buffer.from(features[0]).includes("simd128"), "built without SIMD");
});

test("the page computes in the browser: no request outside the site, none to an API, still working offline", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  const requests = [];
  page.on("request", (r) => requests.push(r.url()));
  await page.goto(server.url);
  await waitReady(page);
  assert.equal(await page.evaluate(() => window.bentstraw.engine), "wasm");
  assert.deepEqual(requests.filter((u) => u.includes("/api/")), []);
  // Offline now: a drag still gives new frames, and the points still come.
  await context.setOffline(true);
  const frames = await page.evaluate(() => window.bentstraw.frames);
  await drag(page, 10, 6, -1);
  await waitReady(page, frames);
  assert.ok((await page.evaluate(() => window.bentstraw.points())).startsWith("x,y,z,color\n"));
  await context.setOffline(false);
  assert.deepEqual(requests.filter((u) => u.includes("/api/")), []);
  assert.deepEqual(problems, []);
  await page.screenshot({ path: path.join(tmpdir(), "bentstraw-site-desktop.png") });
  await context.close();
});

test("a page opened once opens again without a network", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  await page.evaluate(() => navigator.serviceWorker.ready);
  await context.setOffline(true);
  await page.reload();
  await waitReady(page);
  assert.ok((await page.evaluate(() => window.bentstraw.points())).startsWith("x,y,z,color\n"));
  assert.deepEqual(problems, []);
  await context.close();
});

test("from its second load the site is cross-origin isolated and its engine splits frames over every core, with the same bytes; before, one thread, and the page says why", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  const view = "#observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&mode=fresnel&points=20000";
  const q = "observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&mode=fresnel&size=400x300&points=20000";
  /** The page's frame for `q`, as bytes' digest, and what the page says of its engine. */
  const look = () => page.evaluate(async (q) => {
    const r = await window.bentstraw.request("/api/frame", q);
    const f = window.bentstraw.frame;
    let h = 2166136261;
    for (let i = 0; i < f.rgba.length; i++) h = Math.imul(h ^ f.rgba[i], 16777619);
    const points = await window.bentstraw.points();
    return { isolated: self.crossOriginIsolated, threads: window.bentstraw.engineThreads, inUse: await window.bentstraw.engineThreads.inUse(),
      status: document.getElementById("status").textContent, status200: r.status, picture: `${f.header.width}x${f.header.height}:${h >>> 0}`, points };
  }, q);
  // The first load: the service worker is not yet in charge, so the page is not isolated.
  await page.goto(server.url + view);
  await waitReady(page);
  const first = await look();
  assert.equal(first.isolated, false);
  assert.deepEqual([first.threads.threads, first.threads.why, first.inUse], [1, "engine.first-load", 1]);
  assert.match(first.status, /WebAssembly on one thread: every core is used from the page's next load/);
  await page.evaluate(() => navigator.serviceWorker.ready);
  // The second: every answer now carries the isolation's headers.
  const workers = [];
  page.on("worker", (w) => workers.push(w.url()));
  await page.reload();
  await waitReady(page);
  const second = await look();
  assert.equal(second.isolated, true);
  assert.equal(second.threads.why, null);
  assert.ok(second.threads.threads > 1 && second.inUse === second.threads.threads, JSON.stringify(second));
  assert.match(second.status, new RegExp(`WebAssembly on ${second.inUse} threads`));
  assert.equal(second.status200, 200);
  // The same picture and the same points, to the bit, on one thread and on several.
  assert.equal(second.picture, first.picture);
  assert.ok(second.points === first.points && second.points.length > 100000);
  await assertPointsAreSimulates(page, "isolated");
  // A drag abandons frame after frame: each stops in place (its flag in the shared memory) and
  // its worker goes on; no worker is started afresh, as one is without threads. (The first drag
  // starts the quick frames' worker.)
  const engines = () => workers.filter((u) => u.endsWith("/worker.js")).length;
  let frames = await page.evaluate(() => window.bentstraw.frames);
  await drag(page, 5, 5, -1);
  await waitReady(page, frames);
  const before = engines(), stopped = await page.evaluate(() => ({ ...window.bentstraw.engineStops }));
  frames = await page.evaluate(() => window.bentstraw.frames);
  // Each move comes once the page is computing a full frame: the move abandons it while it runs.
  const box = await page.locator("#picture").boundingBox();
  let x = box.x + box.width / 2;
  const y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let i = 0; i < 6; i++) {
    x += 5;
    await page.mouse.move(x, y);
    await page.waitForFunction(() => window.bentstraw.computing === "full");
  }
  await page.mouse.up();
  await waitReady(page, frames);
  const stops = await page.evaluate(() => ({ ...window.bentstraw.engineStops }));
  assert.ok(stops.inPlace > stopped.inPlace, JSON.stringify(stops));
  assert.equal(stops.restarts, 0);
  assert.equal(engines(), before, `workers started: ${workers.join(" ")}`);
  await assertPointsAreSimulates(page, "after a drag, isolated");
  assert.deepEqual(problems, []);
  await page.screenshot({ path: path.join(tmpdir(), "bentstraw-site-isolated.png") });
  await context.close();
});

test("where the engine with threads cannot start, the page starts it again on one thread and says so", async () => {
  const isolated = await startStaticServer(undefined, { isolated: true });
  try {
    const { page, context, problems } = await openPage(browser, isolated.url);
    // As on a device that cannot reserve the memory threads share: the threaded build fails.
    await context.route("**/pkg-threads/bentstraw_web.js", (route) => route.fulfill({ contentType: "text/javascript", body: "throw new Error('no shared memory here');" }));
    await page.goto(isolated.url + "#observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&mode=fresnel&points=20000");
    await waitReady(page);
    const seen = await page.evaluate(async () => ({ isolated: self.crossOriginIsolated, threads: { ...window.bentstraw.engineThreads }, inUse: await window.bentstraw.engineThreads.inUse(), status: document.getElementById("status").textContent }));
    assert.equal(seen.isolated, true);
    assert.deepEqual([seen.threads.threads, seen.threads.why, seen.inUse], [1, "engine.threads-failed", 1]);
    assert.match(seen.status, /WebAssembly on one thread: the engine with threads could not start here/);
    await assertPointsAreSimulates(page, "one thread after all");
    assert.deepEqual(problems, []);
    await context.close();
  } finally {
    isolated.stop();
  }
});

test("while the engine downloads its progress is shown, in the page's language; it goes with the first picture", async () => {
  for (const locale of ["en-GB", "fr-FR"]) {
    const { page, context, problems } = await openPage(browser, server.url, undefined, { locale });
    // What the indicator said while it was shown, noted as it changed.
    await page.addInitScript(() => {
      window.loadingSeen = [];
      new MutationObserver(() => {
        const box = document.getElementById("loading");
        if (box && !box.hidden) window.loadingSeen.push([document.getElementById("loading-text").textContent, document.getElementById("loading-bar").value]);
      }).observe(document, { subtree: true, childList: true, characterData: true, attributes: true });
    });
    await page.goto(server.url);
    await waitReady(page);
    const seen = await page.evaluate(() => window.loadingSeen);
    assert.ok(seen.length > 0, "the progress was never shown");
    const last = seen[seen.length - 1];
    assert.match(last[0], locale === "fr-FR" ? /^Chargement du moteur .*100 %$/ : /^Loading the engine .*100 %$/);
    assert.equal(last[1], 100);
    assert.ok(await page.locator("#loading").isHidden());
    assert.deepEqual(problems, []);
    await context.close();
  }
});

/** The site served by a server that can be made to hang (connect, never answer) or to answer
 * every request with a captive portal's page, as a school's or a café's network does. */
async function unreliableServer(dir) {
  const types = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css", ".wasm": "application/wasm" };
  let mode = "serve";
  const server = http.createServer((req, res) => {
    if (mode === "hang") return;
    if (mode === "portal") { res.writeHead(200, { "Content-Type": "text/html" }); res.end("<h1>Welcome to the school's network: log in</h1>"); return; }
    let name = decodeURIComponent(new URL(req.url, "http://x").pathname).slice(1) || "index.html";
    const file = path.join(dir, name);
    if (name.includes("..") || !existsSync(file) || statSync(file).isDirectory()) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { "Content-Type": types[path.extname(name)] || "application/octet-stream" });
    res.end(readFileSync(file));
  });
  await new Promise((done) => server.listen(0, "127.0.0.1", done));
  return {
    url: `http://127.0.0.1:${server.address().port}/`,
    set mode(m) { mode = m; },
    close() { server.closeAllConnections(); server.close(); },
  };
}

test("once ready offline, the page opens at once on a network that hangs, and a captive portal's page never replaces it", async () => {
  const site = await unreliableServer(SITE);
  try {
    const { page, context, problems } = await openPage(browser, site.url);
    await page.goto(site.url);
    await waitReady(page);
    // Said once every file is kept and checked.
    await page.waitForFunction(() => document.body.dataset.offline === "ready");
    assert.equal(await page.textContent("#offline"), "✓ ready offline");
    assert.ok(await page.locator("#offline").isVisible());
    const digest = await page.evaluate(() => window.bentstraw.points());
    // The network connects and never answers: the page comes from the copy, at once.
    site.mode = "hang";
    const started = Date.now();
    await page.reload();
    await waitReady(page);
    const ms = Date.now() - started;
    assert.ok(ms < 10000, `the page took ${ms} ms on a hanging network`);
    assert.equal(await page.evaluate(() => window.bentstraw.points()), digest);
    // A captive portal answers everything with its own page: the site's copy is kept and used.
    site.mode = "portal";
    await page.reload();
    await waitReady(page);
    assert.equal(await page.evaluate(() => window.bentstraw.points()), digest);
    const kept = await page.evaluate(async () => {
      const names = await caches.keys();
      const cache = await caches.open(names.find((n) => n.startsWith("bentstraw-site-")));
      return (await (await cache.match("index.html")).text()).includes("bentstraw");
    });
    assert.ok(kept, "the kept index.html is not the site's");
    // In French, the mark says so.
    await page.selectOption("#lang", "fr");
    assert.equal(await page.textContent("#offline"), "✓ disponible hors ligne");
    assert.deepEqual(problems, []);
    await context.close();
  } finally {
    site.close();
  }
});

test("the points are simulate's to the byte: at the start, after a long drag", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  const first = await assertPointsAreSimulates(page, "default view");
  const frames = await page.evaluate(() => window.bentstraw.frames);
  await drag(page, 60, 5, 1.5);
  await waitReady(page, frames);
  const { args } = await assertPointsAreSimulates(page, "after a long drag");
  assert.notDeepEqual(args, first.args);
  assert.deepEqual(problems, []);
  await context.close();
});

test("a scene file set through the hook: simulate's points; its link reopens the view in a fresh browser", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  await page.evaluate((t) => window.bentstraw.setScene(t), MY_SCENE);
  await waitReady(page);
  const { csv, args } = await assertPointsAreSimulates(page, "my scene file");
  assert.ok(args.includes("scene.toml"));
  assert.deepEqual(args.slice(args.indexOf("--observer"), args.indexOf("--observer") + 2), ["--observer", "0.18,0.04,0.09"]);
  // The scene written back is a scene file of the same scene.
  const written = await page.evaluate(() => window.bentstraw.scene());
  assert.match(written, /index = 1\.47/);
  const link = await page.evaluate(() => window.bentstraw.link());
  assert.ok(link.length < 2000, `${link.length} characters`);
  await page.screenshot({ path: path.join(tmpdir(), "bentstraw-site-scene.png") });
  assert.deepEqual(problems, []);
  await context.close();
  // A new browser, as a student's: the same view, the same points.
  const other = await launch();
  try {
    const fresh = await openPage(other, server.url);
    await fresh.page.goto(link);
    await waitReady(fresh.page);
    assert.equal(await fresh.page.evaluate(() => window.bentstraw.points()), csv);
    assert.equal(await fresh.page.evaluate(() => window.bentstraw.state.file), MY_SCENE);
    assert.deepEqual(fresh.problems, []);
  } finally {
    await other.close();
  }
});

// The page's engine traces pictures with WebAssembly's SIMD registers, the command line with
// the processor's widest (AVX-512 or AVX2 here): the same operations in the same order, so the
// same bytes, in both modes, from above, beside and below, and in a scene file of the gallery.
test("the exported picture is render's PNG to the byte", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  const views = [
    "observer=0.1,0,0.3&straw=0.02,0.01&water-height=0.2&mode=fresnel",
    "observer=0.1,0,0.3&straw=0.02,0.01&water-height=0.2&mode=course",
    "observer=0,0.1,0.1&straw=0.02,0.01&water-height=0.15&mode=course",
    "observer=0.1,0,-0.1&straw=0,0&water-height=0.2&mode=fresnel",
    "scene=vanishing-glass&mode=fresnel",
  ];
  for (const view of views) {
    await page.goto(server.url + "#" + view);
    await page.reload();
    await waitReady(page);
    const [png, render] = await page.evaluate(async () => {
      const h = window.bentstraw.frame.header;
      // Asked through the page's own modules: its engine, its state's query.
      const { engineFetch } = await import(new URL("engine.js", document.baseURI).href);
      const { state, viewQuery } = await import(new URL("state.js", document.baseURI).href);
      const r = await engineFetch("test", "/api/export", viewQuery(state, { format: "png", size: `${h.width}x${h.height}` }));
      const bytes = new Uint8Array(await r.arrayBuffer());
      let bin = "";
      for (const b of bytes) bin += String.fromCharCode(b);
      return [btoa(bin), h.render];
    });
    const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-site-"));
    const args = render.split(" ").slice(1);
    const r = await cli(args, dir);
    assert.equal(r.code, 0, r.stderr);
    const expected = readFileSync(path.join(dir, "view.png"));
    assert.ok(Buffer.from(png, "base64").equals(expected), `${view}: the page's PNG differs from ${render}`);
  }
  assert.deepEqual(problems, []);
  await context.close();
});

test("a gallery scene's link is short and reopens it", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  await page.waitForFunction(() => Number(document.body.dataset.scenes || 0) >= 6);
  await page.selectOption("#scene", "leaning-straw");
  await waitReady(page);
  const link = await page.evaluate(() => window.bentstraw.link());
  assert.ok(link.length < 300, `${link.length} characters: ${link}`);
  await assertPointsAreSimulates(page, "leaning straw");
  const again = await openPage(browser, server.url);
  await again.page.goto(link);
  await waitReady(again.page);
  assert.equal(await again.page.evaluate(() => window.bentstraw.state.scene), "leaning-straw");
  assert.deepEqual(problems, []);
  assert.deepEqual(again.problems, []);
  await context.close();
  await again.context.close();
});

test("a broken rule is refused with the command line's message, shown on the page", async () => {
  const { page, context } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  const broken = MY_SCENE.replace("index = 1.47", "index = 0.8");
  const message = await page.evaluate((t) => window.bentstraw.setScene(t).then(() => "accepted", (e) => e.message), broken);
  const dir = mkdtempSync(path.join(tmpdir(), "bentstraw-site-"));
  writeFileSync(path.join(dir, "scene.toml"), broken);
  const r = await cli(["simulate", "--scene", "scene.toml", "--points", "100", "--output", "view.csv"], dir);
  assert.notEqual(r.code, 0);
  assert.ok(message !== "accepted" && r.stderr.includes(message), `page: ${message}\ncommand line: ${r.stderr}`);
  await page.waitForFunction(() => !document.getElementById("error").hidden);
  assert.equal(await page.locator("#error").textContent(), message);
  // The view stays the assignment's.
  assert.equal(await page.evaluate(() => window.bentstraw.state.file), "");
  await page.screenshot({ path: path.join(tmpdir(), "bentstraw-site-refusal.png") });
  await context.close();
});

test("Python's explore() opens the page its package carries, on the view asked: simulate's points", async () => {
  // The package installed in $PYTHON, its page built with it; nothing of the repository served.
  const explorer = await startPythonExplore(`"leaning-straw", observer=(0.25, -0.06, 0.17), mode="course", lang="fr"`);
  try {
    const { page, context, problems } = await openPage(browser, explorer.url);
    await page.goto(explorer.url);
    await waitReady(page);
    const state = await page.evaluate(() => window.bentstraw.state);
    assert.equal(state.scene, "leaning-straw");
    assert.deepEqual(state.observer, [0.25, -0.06, 0.17]);
    assert.equal(state.mode, "course");
    assert.equal(await page.evaluate(() => document.documentElement.lang), "fr");
    const { args } = await assertPointsAreSimulates(page, "opened from Python");
    assert.ok(args.join(" ").includes("--observer 0.25,-0.06,0.17"), args.join(" "));
    await page.screenshot({ path: path.join(tmpdir(), "bentstraw-python-explore.png") });
    assert.deepEqual(problems, []);
    await context.close();
  } finally {
    explorer.stop();
  }
});

test("a long drag down never puts the eye into the glass: it slides round it", async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  const frames = await page.evaluate(() => window.bentstraw.frames);
  await drag(page, 50, 0, 5); // 250 px down: the eye orbits up over the glass
  await waitReady(page, frames);
  const o = await page.evaluate(() => window.bentstraw.state.observer);
  assert.ok(!(Math.hypot(o[0], o[1]) <= 0.04 && o[2] >= 0 && o[2] <= 0.2), `eye at ${o}`);
  assert.equal(await page.locator("#error").isHidden(), true);
  assert.equal(await page.evaluate(() => window.bentstraw.frame.quick), false);
  await assertPointsAreSimulates(page, "after a drag over the glass");
  assert.deepEqual(problems, []);
  await context.close();
});

test("on a phone's screen the page works", async () => {
  const { page, context, problems } = await openPage(browser, server.url, { width: 390, height: 844 });
  await page.goto(server.url);
  await waitReady(page);
  assert.ok(await page.evaluate(() => window.bentstraw.frame.header.n) > 1000);
  await page.screenshot({ path: path.join(tmpdir(), "bentstraw-site-phone.png"), fullPage: true });
  assert.deepEqual(problems, []);
  await context.close();
});

/** The largest peak memory (resident, MB) of the browser's page processes so far (Linux's /proc). */
/** The renderer processes running now, by pid. */
function rendererPids() {
  return readdirSync("/proc").filter((d) => /^\d+$/.test(d)).filter((pid) => {
    try { return readFileSync(`/proc/${pid}/cmdline`, "utf8").includes("--type=renderer"); } catch { return false; }
  });
}

/** The highest peak memory (MB) of the renderer processes not among `before`: those of the
 * page's own browser context (a context shares no renderer with another), whatever earlier
 * tests' pages used. */
function pagePeakMB(before) {
  let peak = 0;
  for (const pid of rendererPids().filter((p) => !before.includes(p))) {
    try {
      const hwm = /VmHWM:\s+(\d+) kB/.exec(readFileSync(`/proc/${pid}/status`, "utf8"));
      if (hwm) peak = Math.max(peak, Number(hwm[1]) / 1024);
    } catch { /* a process that ended meanwhile */ }
  }
  return peak;
}

test("a link whose scene file unpacks to 300 MB is refused, the page unpacking no more than it needs", async () => {
  const { deflateRawSync } = await import("node:zlib");
  // 300 MB of spaces pack into 300 kilobytes: a link a chat could carry.
  const packed = deflateRawSync(Buffer.alloc(300 << 20, 0x20), { level: 9 }).toString("base64url");
  // The page's own peak without the link, in a context of its own: the baseline.
  let others = rendererPids();
  const plain = await openPage(browser, server.url);
  await plain.page.goto(server.url);
  await waitReady(plain.page);
  const baseline = pagePeakMB(others);
  await plain.context.close();
  others = rendererPids();
  const { page, context, problems } = await openPage(browser, server.url);
  await page.goto(server.url);
  await waitReady(page);
  const before = await page.evaluate(() => window.bentstraw.state.file);
  await page.evaluate((code) => { location.hash = `file=${code}`; }, packed);
  await page.waitForFunction(() => /larger than 1 MB/.test(document.body.innerText), null, { timeout: 30000 });
  // No other scene took its place, and no page process held the unpacked text (300 MB).
  assert.equal(await page.evaluate(() => window.bentstraw.state.file), before);
  // The unpacked text alone would take 300 MB (twice that as a string).
  const peak = pagePeakMB(others);
  assert.ok(baseline > 0 && peak > 0 && peak < baseline + 100, `a page process peaked at ${peak.toFixed(0)} MB, ${baseline.toFixed(0)} MB without the link`);
  assert.deepEqual(problems.filter((p) => !p.includes("larger than 1 MB")), []);
  await context.close();
});
