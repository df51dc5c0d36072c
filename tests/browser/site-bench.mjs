// The static site against the native explorer, side by side in one run (a benchmark, not a test):
// the same page, its requests answered by the engine in WebAssembly (site, Web Workers) or by
// `bentstraw explore` (native). Prints, for both:
// - the engine's time for the same frames (the four reference views, about 800x600 pictures,
//   course and Fresnel, 20 000 points), native on one thread (RAYON_NUM_THREADS=1), and the ratio;
// - the same for the eye and stereo models' apparent positions of those 20 000 points;
// - input-to-paint latency while dragging (p50/p95) and the quick frames' scales (1: the picture's
//   full resolution), the full-quality frame after the input stops,
//   the first picture after the page starts loading; and the quick frames with the processor
//   slowed four times (Chromium's throttling: about a phone's speed);
// - the first picture of the site opened again once its service worker keeps it.
// The WebAssembly engine is measured twice in the same run: on one thread (the page not
// cross-origin isolated, as at its first load) and on every core (isolated, as from its second).
// Run: node site-bench.mjs (after cargo build --release and cargo xtask site).
import os from "node:os";
import { startServer, startStaticServer, launch, openPage, waitReady, percentile } from "./harness.mjs";

const VIEWPORT = { width: 1500, height: 1180 }; // the picture's panel is about 800x600
const REFS = ["0,0.1,0.1&straw=0.02,0.01&water-height=0.15", "0.1,0,0.1&straw=0.02,0.01&water-height=0.15", "0.1,0,0.3&straw=0.02,0.01&water-height=0.2", "0.1,0,-0.1&straw=0,0&water-height=0.2"];
const REPEAT = Number(process.env.REPEAT || 5);

process.env.RAYON_NUM_THREADS = "1";
const native1 = await startServer(); // one thread: the rays per second of one core
delete process.env.RAYON_NUM_THREADS;
const native = await startServer();
const site = await startStaticServer();
const siteThreads = await startStaticServer(undefined, { isolated: true });
const browser = await launch();
console.log(`machine: ${os.cpus()[0].model}, ${os.cpus().length} cores, load ${os.loadavg().map((x) => x.toFixed(1)).join(" ")}`);

/** Median engine time of `query`'s frame on the page at `url`. */
async function engineTimes(url) {
  const { page, context } = await openPage(browser, url, VIEWPORT);
  await page.goto(url);
  await waitReady(page);
  const out = {};
  for (const mode of ["course", "fresnel"]) {
    for (const [i, ref] of REFS.entries()) {
      const q = `observer=${ref}&mode=${mode}&size=800x600&points=20000`;
      const t = [];
      for (let k = 0; k < REPEAT; k++) t.push((await page.evaluate(([p, q]) => window.bentstraw.request(p, q), ["/api/frame", q])).engineMs);
      out[`${mode} ref ${i + 1}`] = percentile(t, 50);
    }
  }
  for (const model of ["eye", "stereo"]) {
    for (const [i, ref] of REFS.entries()) {
      const q = `observer=${ref}&points=20000&model=${model}&every=1`;
      const t = [];
      for (let k = 0; k < REPEAT; k++) t.push((await page.evaluate(([p, q]) => window.bentstraw.request(p, q), ["/api/model", q])).engineMs);
      out[`${model} model ref ${i + 1}`] = percentile(t, 50);
    }
  }
  await context.close();
  return out;
}

/** Latencies of a scripted drag on the page at `url`, and the page's first picture; `slower`:
 * the processor slowed that many times. */
async function latencies(url, mode, slower = 1) {
  const { page, context } = await openPage(browser, url, VIEWPORT);
  if (slower > 1) await (await context.newCDPSession(page)).send("Emulation.setCPUThrottlingRate", { rate: slower });
  const t0 = Date.now();
  await page.goto(url + `#observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&mode=${mode}&points=20000`);
  await page.waitForFunction(() => window.bentstraw.frames > 0, null, { timeout: 60000 });
  const first = Date.now() - t0;
  await waitReady(page);
  await page.evaluate(() => { window.bentstraw.latencies.length = 0; });
  const box = await page.locator("#picture").boundingBox();
  const x0 = box.x + box.width / 2, y0 = box.y + box.height / 2;
  await page.mouse.move(x0, y0);
  await page.mouse.down();
  for (let i = 1; i <= 120; i++) { await page.mouse.move(x0 + 160 * Math.sin(i / 20), y0 + 60 * Math.sin(i / 33)); await page.waitForTimeout(16); }
  await page.mouse.up();
  const stop = await page.evaluate(() => performance.now());
  await waitReady(page);
  const painted = await page.evaluate(() => window.bentstraw.fullPaintedAt);
  const threads = await page.evaluate(() => window.bentstraw.engine === "wasm" ? window.bentstraw.engineThreads.inUse() : null);
  const { drawn, allowed } = await page.evaluate(async () => ({
    drawn: window.bentstraw.latencies.filter((l) => l.quick),
    allowed: (await import("./quickscale.js")).QUICK_SCALES,
  }));
  const quick = drawn.map((l) => l.ms);
  // How many quick frames were drawn at each of the page's scales (1: full resolution).
  const scales = allowed.map((s) => `${s}:${drawn.filter((l) => l.scale === s).length}`).join(" ");
  const size = await page.evaluate(() => `${window.bentstraw.frame.header.width}x${window.bentstraw.frame.header.height}`);
  await context.close();
  return { first, p50: percentile(quick, 50), p95: percentile(quick, 95), full: painted - stop, frames: quick.length, size, threads, scales };
}

/** The first picture of the site at `url` opened again, its files kept by its service worker
 * (median of REPEAT openings), and the threads its engine then has. */
async function cachedFirst(url) {
  const { page, context } = await openPage(browser, url, VIEWPORT);
  await page.goto(url);
  await waitReady(page);
  await page.evaluate(() => navigator.serviceWorker.ready);
  const t = [];
  let threads = 0;
  for (let k = 0; k < REPEAT; k++) {
    const t0 = Date.now();
    await page.reload();
    await page.waitForFunction(() => window.bentstraw.frames > 0, null, { timeout: 60000 });
    t.push(Date.now() - t0);
    threads = await page.evaluate(() => window.bentstraw.engineThreads.inUse());
    await waitReady(page);
  }
  await context.close();
  return { ms: percentile(t, 50), threads };
}

const [a, t, b] = [await engineTimes(site.url), await engineTimes(siteThreads.url), await engineTimes(native1.url)];
const cores = await (async () => { const { page, context } = await openPage(browser, siteThreads.url, VIEWPORT); await page.goto(siteThreads.url); await waitReady(page); const n = await page.evaluate(() => window.bentstraw.engineThreads.inUse()); await context.close(); return n; })();
console.log("\nengine time per frame (800x600, 20 000 points) and per model (those points), median of " + REPEAT);
console.log(`view               WebAssembly 1 thread ms   WebAssembly ${cores} threads ms   native 1 thread ms   threads / 1 thread speed   WebAssembly 1 thread / native speed`);
for (const k of Object.keys(a)) console.log(`${k.padEnd(18)} ${a[k].toFixed(1).padStart(23)} ${t[k].toFixed(1).padStart(23)} ${b[k].toFixed(1).padStart(20)} ${(a[k] / t[k]).toFixed(2).padStart(25)} ${(b[k] / a[k] * 100).toFixed(0).padStart(36)} %`);
if (process.env.ONLY === "engine") { await browser.close(); site.stop(); siteThreads.stop(); native.stop(); native1.stop(); process.exit(0); }
console.log("\nthe page, dragging in the picture (120 moves at 60 Hz)");
console.log("engine                   mode      processor  picture   first picture ms  quick frames  p50 ms  p95 ms  full frame after the input stops ms  quick frames per scale");
const engines = [["WebAssembly 1 thread", site.url], [`WebAssembly ${cores} threads`, siteThreads.url], ["native (2 threads)", native.url]];
for (const slower of [1, 4]) {
  for (const mode of ["course", "fresnel"]) {
    for (const [name, url] of engines.filter(([n]) => slower === 1 || n.startsWith("WebAssembly"))) {
      const r = await latencies(url, mode, slower);
      console.log(`${name.padEnd(24)} ${mode.padEnd(9)} ${(slower === 1 ? "as is" : slower + "x slower").padEnd(10)} ${r.size.padEnd(9)} ${String(r.first).padStart(16)} ${String(r.frames).padStart(13)} ${r.p50.toFixed(0).padStart(7)} ${r.p95.toFixed(0).padStart(7)} ${r.full.toFixed(0).padStart(8)}                              ${r.scales}`);
    }
  }
}
const again = await cachedFirst(site.url);
console.log(`\nthe site opened again, its files kept by its service worker (isolated, ${again.threads} threads): first picture after ${again.ms} ms (median of ${REPEAT})`);
await browser.close();
site.stop(); siteThreads.stop(); native.stop(); native1.stop();
