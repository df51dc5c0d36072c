// The page's engine against the native one, side by side: the picture tracer on one thread, on
// `bentstraw bench`'s four zoomed views (1024x768, course and Fresnel), built natively and for
// WebAssembly with SIMD (as the site is) and run by Node.js, whose WebAssembly engine is
// Chromium's. Interleaved rounds; the best rays per second of each case; the ratio of
// WebAssembly's to each native compilation's (AVX-512, AVX2 and the baseline, those this
// processor runs).
//
// Run from the repository: node bench/wasm_native.mjs [ROUNDS]   (default 3; it adds the
// wasm32-wasip1 target with rustup and builds both first).
import { execFileSync } from "node:child_process";
import os from "node:os";

const ROUNDS = Number(process.argv[2] || 3);
const WASM_DIR = "target/wasi";
const wasmFile = `${WASM_DIR}/wasm32-wasip1/release/picture-speed.wasm`;
const cargo = (args, env = {}) => execFileSync("cargo", args, { stdio: ["ignore", "ignore", "inherit"], env: { ...process.env, ...env } });

execFileSync("rustup", ["target", "add", "wasm32-wasip1"], { stdio: ["ignore", "ignore", "inherit"] });
cargo(["build", "--release", "-p", "bentstraw-bench", "--bin", "picture-speed"]);
cargo(["build", "--release", "-p", "bentstraw-bench", "--bin", "picture-speed", "--target", "wasm32-wasip1", "--target-dir", WASM_DIR],
  { CARGO_TARGET_WASM32_WASIP1_RUSTFLAGS: "-C target-feature=+simd128" });

/** `INSTRUCTIONS MODE VIEW MRAYS` lines into [key, rays/s]. */
const parse = (text, prefix = "") => text.trim().split("\n").map((l) => l.split(" ")).map(([isa, mode, view, m]) => [`${mode} ${view} ${prefix || isa}`, Number(m)]);

const native = () => parse(execFileSync("target/release/picture-speed", { encoding: "utf8" }));
function wasm() {
  // Each run in a child process, so the two sides start alike and WASI's output is captured.
  const script = `import { WASI } from "node:wasi"; import { readFileSync } from "node:fs";
    const wasi = new WASI({ version: "preview1", args: ["picture-speed"] });
    const m = await WebAssembly.compile(readFileSync(${JSON.stringify(wasmFile)}));
    wasi.start(await WebAssembly.instantiate(m, wasi.getImportObject()));`;
  return parse(execFileSync(process.execPath, ["--no-warnings", "--input-type=module", "-e", script], { encoding: "utf8" }), "wasm");
}

const best = new Map();
for (let round = 1; round <= ROUNDS; round++) {
  const sides = round % 2 ? [native, wasm] : [wasm, native];
  for (const side of sides) for (const [k, v] of side()) best.set(k, Math.max(best.get(k) ?? 0, v));
  console.error(`round ${round}/${ROUNDS} done`);
}

const isas = ["avx512", "avx2", "baseline"].filter((i) => best.has(`course 1 ${i}`));
console.log(`machine: ${os.cpus()[0].model}, load ${os.loadavg().map((x) => x.toFixed(1)).join(" ")}; best of ${ROUNDS} rounds, M rays/s on one thread, 1024x768`);
console.log(["mode   ", "view", "WebAssembly", ...isas.map((i) => `native ${i}`), ...isas.map((i) => `wasm/${i}`)].map((s) => s.padStart(11)).join(" "));
for (const mode of ["course", "fresnel"]) {
  for (const view of [1, 2, 3, 4]) {
    const w = best.get(`${mode} ${view} wasm`);
    const n = isas.map((i) => best.get(`${mode} ${view} ${i}`));
    console.log([mode, String(view), w.toFixed(1), ...n.map((x) => x.toFixed(1)), ...n.map((x) => `${(100 * w / x).toFixed(0)} %`)].map((s) => s.padStart(11)).join(" "));
  }
}
