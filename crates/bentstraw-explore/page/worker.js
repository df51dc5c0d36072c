// The page's engine in a Web Worker (an ES module): the explorer's API compiled to WebAssembly
// (the same `handle` that `bentstraw explore` serves over HTTP). The page sends it the compiled
// module first, with the build to run it with (`pkg`: one thread; `pkg-threads`: rayon's pool of
// `threads` workers sharing its memory), then one request at a time: { id, path, query }.
"use strict";
let ready = null, engine = null, running = null, stopFlag = null;
/** Starts the engine; if it cannot (a device that cannot reserve the memory threads share),
 * tells the page, which starts its workers again on one thread. */
async function start(m) {
  try {
    await startEngine(m);
  } catch (e) {
    self.postMessage({ failed: String(e && e.message ? e.message : e) });
    await new Promise(() => {}); // the page stops this worker
  }
}
async function startEngine(m) {
  engine = await import(`./${m.pkg}/bentstraw_web.js`);
  const exports = await engine.default({ module_or_path: m.module });
  const started = { threads: 1, memory: null, stopFlag: 0 };
  if (m.running) {
    // One thread: no pool (rayon then runs everything on this worker).
    if (m.threads > 1) await engine.initThreadPool(m.threads);
    running = m.running;
    const at = engine.stopFlag();
    stopFlag = new Uint8Array(exports.memory.buffer, at, 1);
    Object.assign(started, { memory: exports.memory, stopFlag: at });
  }
  started.threads = engine.threads();
  self.postMessage({ started });
}
/** Marks request `id` as running, its stop flag cleared; false if the page gave it up before.
 * The page stops a request by noting its id as given up, then, only if `running` holds that id,
 * setting it to -1 while it sets the stop flag, then to 0. So once `running` is 0 no stop meant for
 * an earlier request can come after the flag is cleared, and a request given up just before it is
 * marked running is seen here as given up. */
function begin(id) {
  while (Atomics.load(running, 0) !== 0) { /* a stop being set: a few instructions */ }
  Atomics.store(stopFlag, 0, 0);
  Atomics.store(running, 0, id);
  return Atomics.load(running, 1) !== id;
}
self.onmessage = async (e) => {
  const m = e.data;
  if (m.module) {
    ready = start(m);
    return;
  }
  await ready;
  const started = performance.now();
  if (running && !begin(m.id)) {
    Atomics.compareExchange(running, 0, m.id, 0);
    return; // given up: the page no longer waits for it
  }
  let reply;
  try {
    reply = engine.handle(m.path, m.query);
  } catch (err) {
    // A panic leaves the instance unusable: say so; the page starts a fresh worker.
    self.postMessage({ id: m.id, status: 500, contentType: "text/plain; charset=utf-8", fileName: null, body: new TextEncoder().encode("internal error while computing this view").buffer, ms: 0, broken: true });
    return;
  } finally {
    if (running) Atomics.compareExchange(running, 0, m.id, 0);
  }
  const body = reply.takeBody();
  const answer = { id: m.id, status: reply.status, contentType: reply.contentType, fileName: reply.fileName ?? null, body: body.buffer, ms: performance.now() - started, reused: reply.reusedPoints };
  reply.free();
  self.postMessage(answer, [body.buffer]);
};
