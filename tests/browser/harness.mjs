// Shared by the browser tests and the latency benchmark: a bentstraw explore server on a free
// port, and headless Chromium.
import { spawn } from "node:child_process";
import { fileURLToPath } from "node:url";
import path from "node:path";
import { chromium } from "playwright-core";

export const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), "../..");
/** The bentstraw binary: $BENTSTRAW, else the release build. */
export const BIN = process.env.BENTSTRAW || path.join(ROOT, "target/release/bentstraw");

/** Starts `command args` and waits until its output names its address (`pattern`'s match, made
 * into a URL by `url`); resolves to { url, child, stop, stderr }. The process never outlives a
 * test run, even one cut short. */
function startListening(command, args, pattern, url, what) {
  // Standard input stays open: a process that waits on it lives until it is stopped.
  const child = spawn(command, args, { stdio: ["pipe", "pipe", "pipe"] });
  let stderr = "";
  child.stderr.on("data", (d) => { stderr += d; });
  process.on("exit", () => child.kill());
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`${what} printed no address: ${stderr}`)), 15000);
    child.stdout.on("data", (d) => {
      const m = pattern.exec(String(d));
      if (m) { clearTimeout(timer); resolve({ url: url(m), child, stop: () => child.kill("SIGINT"), stderr: () => stderr }); }
    });
    child.on("exit", (code) => reject(new Error(`${what} exited with ${code}: ${stderr}`)));
  });
}

/** Starts `bentstraw explore --no-open --port 0 ...args`; resolves to { url, stop }. */
export function startServer(args = []) {
  return startListening(BIN, ["explore", "--no-open", "--port", "0", ...args], /http:\/\/\S+\//, (m) => m[0], "explore");
}

/** The Python that has the bentstraw package installed: $PYTHON, else python3. */
export const PYTHON = process.env.PYTHON || "python3";

/** Runs `bentstraw.explore(ARGS)` (Python's keywords, as code) in a Python process that lives
 * until `stop`; resolves to { url, stop } with the address the call gives. */
export function startPythonExplore(args) {
  const code = `import bentstraw, sys\nprint(bentstraw.explore(${args}).url, flush=True)\nsys.stdin.read()`;
  return startListening(PYTHON, ["-c", code], /http:\/\/\S+/, (m) => m[0], "bentstraw.explore");
}

/** Headless Chromium as the project runs it. */
export function launch() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update", "--no-first-run"],
  });
}

/** A page on `url` that records console errors, failed requests and any request off the server;
 * `options` are the browser context's (a locale, a phone's touch screen…). */
export async function openPage(browser, url, viewport = { width: 1400, height: 900 }, options = {}) {
  const context = await browser.newContext({ viewport, ...options });
  const page = await context.newPage();
  const problems = [];
  const origin = new URL(url).origin;
  // Listening costs the page nothing (intercepting with context.route would pause every request
  // for a round trip to this script, and the latency benchmark would measure that).
  page.on("request", (r) => {
    const u = r.url();
    // The page's own workers are made from its files, as blob: addresses of its origin.
    if (!u.startsWith(origin) && !u.startsWith("data:") && !u.startsWith("blob:" + origin)) problems.push("request off the server: " + u);
  });
  page.on("console", (m) => { if (m.type() === "error") problems.push("console error: " + m.text()); });
  page.on("pageerror", (e) => problems.push("page error: " + e.message));
  page.on("requestfailed", (r) => {
    // The page cancels its own superseded requests by design (a newer view replaces them).
    if (r.failure()?.errorText === "net::ERR_ABORTED" && r.url().includes("/api/")) return;
    problems.push(`failed request: ${r.url()} ${r.failure()?.errorText}`);
  });
  return { page, context, problems };
}

/** Waits until the page has painted a full-quality frame after `since` frames. */
export async function waitReady(page, sinceFrames = -1) {
  await page.waitForFunction((n) => document.body.dataset.ready === "1" && Number(document.body.dataset.frames || 0) > n && !window.bentstraw.busy(), sinceFrames, { timeout: 60000 });
}

/** Runs the bentstraw command line (in the folder `cwd`, if given); resolves to { code, stdout, stderr }. */
export function runCli(args, cwd) {
  return new Promise((resolve) => {
    const child = spawn(BIN, args, { stdio: ["ignore", "pipe", "pipe"], cwd });
    let stdout = "", stderr = "";
    child.stdout.on("data", (d) => { stdout += d; });
    child.stderr.on("data", (d) => { stderr += d; });
    // "close", not "exit": the process may end before its output has all been read.
    child.on("close", (code) => resolve({ code, stdout, stderr }));
  });
}

/** Percentile `p` (0..100) of numbers. */
export function percentile(values, p) {
  const v = [...values].sort((a, b) => a - b);
  if (!v.length) return NaN;
  return v[Math.min(v.length - 1, Math.ceil((p / 100) * v.length) - 1)];
}

/** The static site built by `cargo xtask site`: $SITE, else target/site. */
export const SITE = process.env.SITE || path.join(ROOT, "target/site");

/** Serves `dir` with Python's plain static server on a free port; resolves to { url, stop }.
 * `isolated`: it sends the headers that make a page cross-origin isolated, as a host that can
 * send them does (the page's engine then has threads from the first load on). */
export function startStaticServer(dir = SITE, { isolated = false } = {}) {
  const code = `import functools, http.server, sys
class Isolated(http.server.SimpleHTTPRequestHandler):
    def end_headers(self):
        self.send_header("Cross-Origin-Opener-Policy", "same-origin")
        self.send_header("Cross-Origin-Embedder-Policy", "require-corp")
        super().end_headers()
http.server.test(HandlerClass=functools.partial(Isolated, directory=sys.argv[1]), bind="127.0.0.1", port=0)`;
  const args = isolated ? ["-u", "-c", code, dir] : ["-u", "-m", "http.server", "--bind", "127.0.0.1", "--directory", dir, "0"];
  return startListening("python3", args, /port (\d+)/, (m) => `http://127.0.0.1:${m[1]}/`, "the static server");
}
