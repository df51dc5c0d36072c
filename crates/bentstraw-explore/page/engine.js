// The engine's transport: bentstraw explore's server over HTTP, or the WebAssembly engine in Web
// Workers; the same requests, the same answers (as `Response`s). Channels keep one request each
// in flight, a newer one aborting the older; refusals are read here too.
import { t, localNumber } from "./i18n.js";

export const ENGINE = document.body.dataset.engine === "wasm" ? "wasm" : "server";
/** How the page's engine runs: on `threads` threads sharing one memory, when the page is
 * cross-origin isolated (the site's service worker makes it so from its second load on), else on
 * one thread per worker, with `why` (a key of the page's words) it cannot share memory. */
export const ENGINE_THREADS = (() => {
  const cores = Math.max(1, Math.min(navigator.hardwareConcurrency || 1, 8));
  if (self.crossOriginIsolated && typeof SharedArrayBuffer === "function" && cores > 1) return { threads: cores, why: null };
  const firstLoad = "serviceWorker" in navigator && !navigator.serviceWorker.controller;
  return { threads: 1, why: cores === 1 ? "engine.one-core" : firstLoad ? "engine.first-load" : "engine.not-isolated" };
})();

/** Requests stopped while they ran: in place (with threads) and by starting their worker afresh. */
export const stops = { inPlace: 0, restarts: 0 };
let threadsStarted;
/** How many threads the engine splits its full frames over, once their worker has started. */
export const threadsInUse = new Promise((resolve) => { threadsStarted = resolve; });

export const wasm = ENGINE === "wasm" ? wasmEngine() : null;
// The site keeps a copy of itself, to open again without a network; once every file is kept
// (and checked), the page says it is ready offline.
if (wasm && "serviceWorker" in navigator) {
  navigator.serviceWorker.register("sw.js")
    .then(() => navigator.serviceWorker.ready)
    .then(() => { document.body.dataset.offline = "ready"; document.getElementById("offline").hidden = false; })
    .catch(() => {});
}

/** The engine compiled to WebAssembly in Web Workers, each named by the page (by default one per
 * channel): quick frames have a worker of their own, so a drag never waits for the rest; full
 * frames and the models share the one that holds the frame's points, which the models start from
 * (each worker's engine remembers only what it computed itself). Everything it needs is fetched
 * once, at the start: afterwards the page needs no network. A request superseded while it waits
 * is only taken out of its worker's queue; one superseded while it runs stops: with threads, by
 * its stop flag in the engine's shared memory (every thread stops at its next row, and the worker
 * goes on with what it remembers); without, by stopping its worker, a fresh one taking over. */
function wasmEngine() {
  let threaded = ENGINE_THREADS.threads > 1;
  let pkg = threaded ? "pkg-threads" : "pkg";
  /** The engine of build `pkg`, compiled while it downloads, its progress shown; a host that
   * does not call it application/wasm gets it compiled after. */
  const compile = (pkg) => {
    const wasmFile = `${pkg}/bentstraw_web_bg.wasm`;
    return WebAssembly.compileStreaming(counted(fetch(wasmFile))).catch(() =>
      fetch(wasmFile).then((r) => r.arrayBuffer()).then((b) => WebAssembly.compile(b)));
  };
  let files = compile(pkg);
  // The compiled engine the workers start from (the one-thread build's after a fallback).
  let module = null;
  const compiled = () => files.then((m) => { module = m; });
  /** Waits for the engine the workers start from (the new one, if a fallback replaced it). */
  async function engineReady() {
    let f;
    do { f = files; await compiled(); } while (f !== files);
  }
  /** The engine with threads could not start (a device short of memory cannot reserve what it
   * shares): every worker starts again on one thread. */
  async function oneThreadAfterAll() {
    threaded = false;
    pkg = "pkg";
    Object.assign(ENGINE_THREADS, { threads: 1, why: "engine.threads-failed" });
    files = compile(pkg);
    await engineReady();
    for (const name of Object.keys(workers)) {
      const w = workers[name];
      if (w.current) w.queue.unshift(w.current);
      w.current = null;
      restart(name);
    }
  }
  const workers = {};
  // Workers whose requests are small enough for one thread (then no pool to start).
  const oneThread = new Set();
  let nextId = 1;
  function spawn(name) {
    // With threads, shared with the worker: [the id of the request running (0: none, -1: the
    // page is stopping it), the id of the last request given up], so that a stop meant for one
    // request never reaches the next, and one given up just before it begins never runs.
    const running = threaded ? new Int32Array(new SharedArrayBuffer(8)) : null;
    const w = { worker: new Worker("worker.js", { type: "module" }), current: null, queue: [], running, stopFlag: null, threaded };
    w.worker.postMessage({ module, pkg, threads: oneThread.has(name) ? 1 : ENGINE_THREADS.threads, running });
    w.worker.onmessage = (e) => {
      const m = e.data;
      if (m.failed) {
        // The first worker with threads to fail starts the fallback, which restarts the others.
        if (w.threaded) { if (threaded) oneThreadAfterAll(); return; }
        // Not even on one thread: each request says so.
        for (const job of [w.current, ...w.queue]) if (job) job.reject(new Error(m.failed));
        w.current = null;
        w.queue = [];
        return;
      }
      if (m.started) {
        if (m.started.memory) w.stopFlag = new Uint8Array(m.started.memory.buffer, m.started.stopFlag, 1);
        if (m.started.threads === ENGINE_THREADS.threads) threadsStarted(m.started.threads);
        return;
      }
      const job = w.current;
      if (!job || job.id !== m.id) return;
      w.current = null;
      const headers = { "Content-Type": m.contentType };
      if (m.fileName) headers["Content-Disposition"] = `attachment; filename="${m.fileName}"`;
      // As the server says it: this model's answer started from the frame's points.
      if (m.reused) headers["X-Points"] = "reused";
      // A crash's message is the page's own, in the page's language.
      const r = new Response(m.broken ? t("error.engine-broken") : m.body, { status: m.status, headers });
      r.engineMs = m.ms;
      if (m.broken) restart(name);
      job.resolve(r);
      pump(name);
    };
    w.worker.onerror = (e) => {
      const job = w.current;
      w.current = null;
      restart(name);
      if (job) job.reject(new Error(e.message || t("error.engine-stopped")));
    };
    return w;
  }
  function restart(name) {
    const old = workers[name];
    if (old) old.worker.terminate();
    const w = spawn(name);
    if (old) w.queue = old.queue;
    workers[name] = w;
    pump(name);
  }
  /** Gives up worker `w`'s current request `job` in place: true if the worker shares its memory
   * (then `job` stops where it is, or never begins). */
  function stopInPlace(w, job) {
    if (!w.stopFlag) return false;
    Atomics.store(w.running, 1, job.id);
    if (Atomics.compareExchange(w.running, 0, job.id, -1) === job.id) {
      Atomics.store(w.stopFlag, 0, 1);
      Atomics.store(w.running, 0, 0);
    }
    return true;
  }
  function pump(name) {
    const w = workers[name];
    if (!w || w.current || !w.queue.length) return;
    w.current = w.queue.shift();
    w.worker.postMessage({ id: w.current.id, path: w.current.path, query: w.current.query });
  }
  return {
    ready: files.then(() => true),
    /** Starts the workers `names` now rather than at their first request (a worker with
     * threads takes a moment to start its pool); those named in `oneThread` have none. */
    async start(names, { oneThread: single = [] } = {}) {
      for (const name of single) oneThread.add(name);
      await engineReady();
      for (const name of names) if (!workers[name]) workers[name] = spawn(name);
    },
    async request(name, path, query, signal) {
      await engineReady();
      if (!workers[name]) workers[name] = spawn(name);
      return new Promise((resolve, reject) => {
        const job = { id: nextId++, path, query, resolve, reject };
        if (signal) {
          signal.addEventListener("abort", () => {
            const w = workers[name];
            if (w.current === job) {
              w.current = null;
              // Its answer, stale, is then ignored: the worker goes on to the next request.
              if (stopInPlace(w, job)) { stops.inPlace++; pump(name); }
              else { stops.restarts++; restart(name); }
            } else w.queue = w.queue.filter((j) => j !== job);
            resolve(null);
          });
        }
        workers[name].queue.push(job);
        pump(name);
      });
    },
  };
}

/** The engine's download as it comes, its progress shown under the picture's heading until the
 * first picture is drawn (a phone on a slow network waits seconds for it). */
function counted(response) {
  const box = document.getElementById("loading"), bar = document.getElementById("loading-bar"), text = document.getElementById("loading-text");
  box.hidden = false;
  const show = (got, total) => {
    const amount = total ? `${Math.round((100 * got) / total)} %` : `${(got / 1e6).toFixed(1)} MB`;
    text.textContent = t("loading.engine", { amount: localNumber(amount) });
    if (total) bar.value = Math.round((100 * got) / total); else bar.removeAttribute("value");
    document.body.dataset.loaded = String(total ? Math.round((100 * got) / total) : got);
  };
  show(0, 0);
  return response.then((r) => {
    if (!r.body) return r;
    const total = Number(r.headers.get("Content-Length")) || 0;
    let got = 0;
    const body = r.body.pipeThrough(new TransformStream({ transform(chunk, c) { got += chunk.length; show(got, total); c.enqueue(chunk); } }));
    return new Response(body, { status: r.status, headers: r.headers });
  });
}

/** Asks the engine for `route?query` on channel `name`: a `Response`, or null if aborted. */
export function engineFetch(name, route, query, signal) {
  if (wasm) return wasm.request(name, route, query, signal);
  return serverFetch(route, query, signal);
}

// The server's addresses are short: a scene file's text is sent to it once (POST /api/keep) and
// named by its key in each view's address. The last few texts' keys are remembered here; a key
// the server has forgotten (410) is sent again.
const keys = new Map(); // text → promise of its key (one request per text, however many ask)
function sceneKey(text) {
  if (!keys.has(text)) {
    const key = fetch("/api/keep", { method: "POST", body: text, headers: { "Content-Type": "text/plain; charset=utf-8" } })
      .then(async (r) => { if (!r.ok) throw new Error(await r.text()); return (await r.json()).key; });
    key.catch(() => keys.delete(text));
    keys.set(text, key);
    if (keys.size > 8) keys.delete(keys.keys().next().value);
  }
  return keys.get(text);
}
async function serverFetch(route, query, signal) {
  const p = new URLSearchParams(query);
  const text = p.get("scene-file");
  if (text === null) return fetch(`${route}?${query}`, { signal });
  for (let attempt = 0; ; attempt++) {
    p.delete("scene-file");
    p.set("scene-key", await sceneKey(text));
    const r = await fetch(`${route}?${p}`, { signal });
    if (r.status !== 410 || attempt > 0) return r;
    keys.delete(text);
  }
}

// At most one request per channel in flight; newer input waits for it and is then sent as
// one request for the latest state (intermediate states are dropped).
const clientId = Math.random().toString(36).slice(2, 10);
const channels = {};
function channel(name) {
  return channels[name] || (channels[name] = { seq: 0, controller: null, busy: false, pending: null });
}

/** Asks for `route?query` on channel `name`, aborting what that channel had in flight; resolves
 * to the response or null when superseded. In the page's own engine, `worker` names the worker
 * that computes it (the channel's by default). */
export async function ask(name, route, query, worker) {
  const ch = channel(name);
  if (ch.controller) ch.controller.abort();
  const controller = new AbortController();
  ch.controller = controller;
  ch.seq += 1;
  try {
    const r = await engineFetch(worker || name, route, `${query}&chan=${clientId}-${name}&seq=${ch.seq}`, controller.signal);
    if (r === null) return null;
    if (r.status === 409 || controller.signal.aborted) return null;
    return r;
  } catch (e) {
    if (e.name === "AbortError") return null;
    throw e;
  } finally {
    if (ch.controller === controller) ch.controller = null;
  }
}

/** Gives up what channel `name` has in flight or waiting (its `ask` resolves to null). In the
 * page's engine a request already running stops its worker, and the fresh worker remembers
 * nothing: for the models, whose worker holds the full frame's points, that costs nothing, since
 * the view has changed and the next full frame brings its own. */
export function cancel(name) {
  const ch = channels[name];
  if (ch && ch.controller) ch.controller.abort();
}

/** A refusal's answer: its broken rules as data ({ refusal, message }) when the engine sends
 * them, else its message as text. */
export async function refusalOf(r) {
  const text = await r.text();
  if (/^application\/json/.test(r.headers.get("Content-Type") || "")) {
    try { const refusal = JSON.parse(text); return { refusal, message: refusal.message }; } catch (_) { /* text, then */ }
  }
  return text;
}

/** The engine's answer as text, or a rejection with its message (the command line's; `shown`:
 * what the page shows of it, its broken rules in the page's language). */
export async function answerText(r) {
  if (r.ok) return r.text();
  const why = await refusalOf(r);
  const e = new Error(typeof why === "string" ? why : why.message);
  e.shown = why;
  throw e;
}
