// The explorer's latency benchmark (not a test): a scripted drag in the picture, in course and in
// Fresnel mode, and the input-to-paint latency of the frames painted meanwhile.
// Run: node latency.mjs   (after cargo build --release; BENTSTRAW=path to use another binary;
// SCENE=NAME for a scene of the gallery, e.g. SCENE=leaning-straw, seen from its own eye)
import os from "node:os";
import { startServer, launch, openPage, waitReady, percentile } from "./harness.mjs";

const MOVES = Number(process.env.MOVES || 120); // pointer moves, one every 16 ms (60 Hz)
// The window: its picture panel is about 800x600 CSS pixels.
const VIEWPORT = { width: Number(process.env.WIDTH || 1500), height: Number(process.env.HEIGHT || 1180) };
const server = await startServer();
/** The eye of gallery scene `name`, as the server lists it. */
async function sceneEye(page, name) {
  const list = await (await fetch(server.url + "api/scenes")).json();
  const s = list.find((x) => x.name === name);
  if (!s) throw new Error(`no scene ${name}: ${list.map((x) => x.name).join(", ")}`);
  return s.observer.join(",");
}
const browser = await launch();
console.log(`machine: ${os.cpus()[0].model}, ${os.cpus().length} cores, load ${os.loadavg().map((x) => x.toFixed(1)).join(" ")}`);
console.log("mode     picture  points  frames  p50 ms  p95 ms  max ms  fps   (quick frames while dragging)");
for (const mode of ["course", "fresnel"]) {
  // 1000x750 CSS pixels for the picture's panel: full frames about 1000x750, quick frames that or
  // two or four times coarser along each side, as fine as the engine draws them in time.
  const { page, context } = await openPage(browser, server.url, VIEWPORT);
  const scene = process.env.SCENE ? `scene=${process.env.SCENE}&observer=${await sceneEye(page, process.env.SCENE)}` : "observer=0.1,0,0.1";
  await page.goto(server.url + `#${scene}&straw=0.02,0.01&water-height=0.15&mode=${mode}&points=20000`);
  await waitReady(page);
  const size = await page.evaluate(() => `${window.bentstraw.frame.header.width}x${window.bentstraw.frame.header.height}`);
  await page.evaluate(() => { window.bentstraw.latencies.length = 0; });
  const box = await page.locator("#picture").boundingBox();
  const x0 = box.x + box.width / 2, y0 = box.y + box.height / 2;
  await page.mouse.move(x0, y0);
  await page.mouse.down();
  const frames0 = await page.evaluate(() => window.bentstraw.frames);
  const t0 = Date.now();
  for (let i = 1; i <= MOVES; i++) {
    await page.mouse.move(x0 + 160 * Math.sin(i / 20), y0 + 60 * Math.sin(i / 33));
    await page.waitForTimeout(16);
  }
  const seconds = (Date.now() - t0) / 1000;
  const frames = (await page.evaluate(() => window.bentstraw.frames)) - frames0;
  await page.mouse.up();
  const all = await page.evaluate(() => window.bentstraw.latencies.filter((l) => l.quick));
  const lat = all.map((l) => l.ms);
  if (process.env.VERBOSE) {
    const mean = (k) => (all.reduce((a, l) => a + l[k], 0) / all.length).toFixed(1);
    const worst = [...all].sort((a, b) => b.ms - a.ms).slice(0, Math.ceil(all.length / 10));
    console.log("  worst tenth (total/wait/request/server/body/paint): " + worst.map((l) => [l.ms, l.wait, l.request, l.server, l.body, l.paint].map((x) => x.toFixed(0)).join("/")).join(" "));
    console.log(`  mean ms: total ${mean("ms")} = waiting to be sent ${mean("wait")} + request ${mean("request")} (server ${mean("server")}) + body ${mean("body")} + paint ${mean("paint")} + to the screen`);
  }
  await waitReady(page);
  const points = await page.evaluate(() => window.bentstraw.frame.header.n);
  console.log(`${mode.padEnd(8)} ${size.padEnd(8)} ${String(points).padStart(6)}  ${String(lat.length).padStart(6)}  ${percentile(lat, 50).toFixed(0).padStart(6)}  ${percentile(lat, 95).toFixed(0).padStart(6)}  ${Math.max(...lat).toFixed(0).padStart(6)}  ${(frames / seconds).toFixed(1).padStart(4)}`);
  // The eye and stereo models after the drag: time from switching each on to its first points
  // (every 4th) and to all of them.
  for (const model of ["eye", "stereo"]) {
    const [first, all] = await page.evaluate(async (m) => {
      const t1 = performance.now();
      document.getElementById("show-" + m).click();
      const shown = (full) => { const x = window.bentstraw.models[m]; return x && !x.pending && (!full || x.all); };
      while (!shown(false)) await new Promise((r) => setTimeout(r, 2));
      const t2 = performance.now();
      while (!shown(true)) await new Promise((r) => setTimeout(r, 2));
      return [t2 - t1, performance.now() - t1];
    }, model);
    const n = await page.evaluate((m) => window.bentstraw.models[m].color.length, model);
    console.log(`         ${model} model: ${first.toFixed(0)} ms from switching it on to its first points, ${all.toFixed(0)} ms to all ${n}`);
  }
  await context.close();
}
await browser.close();
server.stop();
