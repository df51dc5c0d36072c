// The page's engine in a Web Worker: the explorer's API compiled to WebAssembly (the same
// `handle` that `bentstraw explore` serves over HTTP). The page builds this worker from
// wasm-bindgen's script (which defines `wasm_bindgen`) followed by this file, and sends it the
// compiled module first, then one request at a time: { id, path, query }.
"use strict";
let ready = null;
self.onmessage = async (e) => {
  const m = e.data;
  if (m.module) {
    ready = wasm_bindgen({ module_or_path: m.module });
    return;
  }
  await ready;
  const started = performance.now();
  let reply;
  try {
    reply = wasm_bindgen.handle(m.path, m.query);
  } catch (err) {
    // A panic leaves the instance unusable: say so; the page starts a fresh worker.
    self.postMessage({ id: m.id, status: 500, contentType: "text/plain; charset=utf-8", fileName: null, body: new TextEncoder().encode("internal error while computing this view").buffer, ms: 0, broken: true });
    return;
  }
  const body = reply.takeBody();
  const answer = { id: m.id, status: reply.status, contentType: reply.contentType, fileName: reply.fileName ?? null, body: body.buffer, ms: performance.now() - started, reused: reply.reusedPoints };
  reply.free();
  self.postMessage(answer, [body.buffer]);
};
