// The static site against the native explorer, side by side in one run (a benchmark, not a test):
// the same page, its requests answered by the engine in WebAssembly (site, Web Workers) or by
// `bentstraw explore` (native). Prints, for both:
// - the engine's time for the same frames (the four reference views, about 800x600 pictures,
//   course and Fresnel, 20 000 points), native on one thread (RAYON_NUM_THREADS=1), and the ratio;
// - the same for the eye and stereo models' apparent positions of those 20 000 points;
// - input-to-paint latency while dragging (p50/p95), the full-quality frame after the input stops,
//   the first picture after the page starts loading.
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

/** Latencies of a scripted drag on the page at `url`, and the page's first picture. */
async function latencies(url, mode) {
  const { page, context } = await openPage(browser, url, VIEWPORT);
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
  const quick = await page.evaluate(() => window.bentstraw.latencies.filter((l) => l.quick).map((l) => l.ms));
  const size = await page.evaluate(() => `${window.bentstraw.frame.header.width}x${window.bentstraw.frame.header.height}`);
  await context.close();
  return { first, p50: percentile(quick, 50), p95: percentile(quick, 95), full: painted - stop, frames: quick.length, size };
}

const [a, b] = [await engineTimes(site.url), await engineTimes(native1.url)];
console.log("\nengine time per frame (800x600, 20 000 points) and per model (those points), median of " + REPEAT);
console.log("view               WebAssembly ms   native 1 thread ms   WebAssembly / native speed");
for (const k of Object.keys(a)) console.log(`${k.padEnd(18)} ${a[k].toFixed(1).padStart(14)} ${b[k].toFixed(1).padStart(20)} ${(b[k] / a[k] * 100).toFixed(0).padStart(24)} %`);
if (process.env.ONLY === "engine") { await browser.close(); site.stop(); native.stop(); native1.stop(); process.exit(0); }
console.log("\nthe page, dragging in the picture (120 moves at 60 Hz)");
console.log("engine            mode      picture   first picture ms  quick frames  p50 ms  p95 ms  full frame after the input stops ms");
for (const mode of ["course", "fresnel"]) {
  for (const [name, url] of [["WebAssembly", site.url], ["native (2 threads)", native.url]]) {
    const r = await latencies(url, mode);
    console.log(`${name.padEnd(17)} ${mode.padEnd(9)} ${r.size.padEnd(9)} ${String(r.first).padStart(16)} ${String(r.frames).padStart(13)} ${r.p50.toFixed(0).padStart(7)} ${r.p95.toFixed(0).padStart(7)} ${r.full.toFixed(0).padStart(8)}`);
  }
}
await browser.close();
site.stop(); native.stop(); native1.stop();
