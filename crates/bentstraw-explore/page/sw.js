// The static site's service worker: keeps a copy of the site's files, so that a page opened once
// opens again without a network (in a classroom with none). Network first, so a new version of
// the site is picked up whenever the network is there; the copy when it is not.
"use strict";
const CACHE = "bentstraw-site";
// The page's modules: main.js and every module it imports, each a file the page fetches.
const MODULES = ["main.js", "i18n.js", "state.js", "geometry.js", "dom.js", "engine.js", "errors.js", "frames.js", "draw.js", "pointer.js", "sketch.js", "picture.js", "cloud.js", "maps.js", "readout.js", "sweep.js", "controls.js", "scenetext.js", "editor.js", "predict.js"];
const FILES = ["./", "index.html", ...MODULES, "explorer.css", "worker.js", "pkg/bentstraw_web.js", "pkg/bentstraw_web_bg.wasm"];

self.addEventListener("install", (e) => {
  e.waitUntil(caches.open(CACHE).then((c) => c.addAll(FILES)).then(() => self.skipWaiting()));
});
self.addEventListener("activate", (e) => e.waitUntil(self.clients.claim()));
self.addEventListener("fetch", (e) => {
  const url = new URL(e.request.url);
  if (e.request.method !== "GET" || url.origin !== self.location.origin) return;
  e.respondWith(
    fetch(e.request)
      .then((r) => {
        if (r.ok) {
          const copy = r.clone();
          e.waitUntil(caches.open(CACHE).then((c) => c.put(e.request, copy)));
        }
        return r;
      })
      .catch(() => caches.match(e.request, { ignoreSearch: true }).then((r) => r || Response.error())),
  );
});
