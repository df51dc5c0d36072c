// The static site's service worker: keeps a copy of the site's files, so that a page opened once
// opens again at once, with or without a network (in a classroom with none, or one that connects
// and never answers). The site's build writes the list of its files with each one's SHA-256 below
// (MANIFEST): a copy is made only of the files the build wrote, each checked against its hash, all
// of them or none (a captive portal's page or a half-downloaded file is never kept). The copy is
// served first; a new build of the site (a new list, so a new worker) is fetched and checked in
// the background and takes over at the next visit. Anything else goes to the network, given
// NETWORK_MS before the copy (if any) answers instead.
// Every answer it gives carries the headers that make the page cross-origin isolated, which a
// static host such as GitHub Pages cannot send: an isolated page may share memory between
// threads, and its engine then splits each frame over the cores. A page is isolated from the
// first load this worker controls, so from the second visit on; until then the engine runs on
// one thread per worker, and the page says so.
"use strict";
const MANIFEST = null; // { version, files: { "index.html": "<sha-256, hex>", … } }: the site's build fills it in
const CACHE = "bentstraw-site-" + (MANIFEST ? MANIFEST.version : "unbuilt");
const NETWORK_MS = 3000;

/** A file's name as the list has it, for a request of this site (`./` is index.html). */
function fileOf(request) {
  const scope = new URL(self.registration.scope);
  const url = new URL(request.url);
  if (url.origin !== scope.origin || !url.pathname.startsWith(scope.pathname)) return null;
  const name = url.pathname.slice(scope.pathname.length);
  return name === "" ? "index.html" : name;
}

async function sha256(bytes) {
  const digest = new Uint8Array(await crypto.subtle.digest("SHA-256", bytes));
  return [...digest].map((b) => b.toString(16).padStart(2, "0")).join("");
}

self.addEventListener("install", (e) => {
  e.waitUntil((async () => {
    if (!MANIFEST) return self.skipWaiting();
    // Every file fetched afresh and checked before any is kept: one that differs from what the
    // build wrote fails the whole install, and the copy made before stays in use.
    const checked = await Promise.all(Object.entries(MANIFEST.files).map(async ([name, hash]) => {
      const r = await fetch(name, { cache: "no-store" });
      const body = await r.arrayBuffer();
      if (!r.ok || (await sha256(body)) !== hash) throw new Error(`${name} is not the site's own file`);
      return [name, new Response(body, { headers: { "Content-Type": r.headers.get("Content-Type") || "" } })];
    }));
    const cache = await caches.open(CACHE);
    await Promise.all(checked.map(([name, response]) => cache.put(name, response)));
    await self.skipWaiting();
  })());
});

self.addEventListener("activate", (e) => {
  e.waitUntil((async () => {
    for (const name of await caches.keys()) if (name.startsWith("bentstraw-site") && name !== CACHE) await caches.delete(name);
    await self.clients.claim();
  })());
});

/** The network's answer within NETWORK_MS, else null. */
function network(request) {
  const controller = new AbortController();
  const timer = setTimeout(() => controller.abort(), NETWORK_MS);
  return fetch(request, { signal: controller.signal }).catch(() => null).finally(() => clearTimeout(timer));
}

/** `r` with the isolation's headers: the page opens no other site's window and embeds nothing
 * that has not agreed to be embedded (the site embeds only its own files). */
function isolated(r) {
  if (!r || r.type === "error" || r.type === "opaque" || r.type === "opaqueredirect") return r;
  const headers = new Headers(r.headers);
  headers.set("Cross-Origin-Opener-Policy", "same-origin");
  headers.set("Cross-Origin-Embedder-Policy", "require-corp");
  headers.set("Cross-Origin-Resource-Policy", "same-origin");
  return new Response(r.body, { status: r.status, statusText: r.statusText, headers });
}

self.addEventListener("fetch", (e) => {
  if (e.request.method !== "GET") return;
  const name = fileOf(e.request);
  if (name === null) return;
  e.respondWith((async () => isolated(await answer(e.request, name)))());
});

let opened = null;
/** The site's copy (opened once: a page's start asks for every file at once). */
function siteCopy() {
  if (!opened) opened = caches.open(CACHE);
  return opened;
}

/** The answer to `request`, for the site's file `name`. */
async function answer(request, name) {
  const cache = await siteCopy();
  // The site's own files: the checked copy first.
  if (MANIFEST && name in MANIFEST.files) {
    const kept = await cache.match(name);
    if (kept) return kept;
  }
  const r = await network(request);
  return r || (await cache.match(name)) || Response.error();
}
