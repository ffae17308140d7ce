// wasi-run.mjs WASM [ARGS...] — runs a wasm32-wasi program under node's WASI
// (the emulator of cmake/toolchains/wasm32-wasi.cmake): arguments and the
// environment passed through, the host's "/" preopened as "/", the program's
// exit status returned. Works with Debian 12's node 18 (WASI behind
// --experimental-wasi-unstable-preview1, no getImportObject()) and node 20.
import { WASI } from 'node:wasi';
import { readFile } from 'node:fs/promises';

const [wasmPath, ...args] = process.argv.slice(2);
const wasi = new WASI({ version: 'preview1', args: [wasmPath, ...args], env: process.env,
                        preopens: { '/': '/' }, returnOnExit: true });
const module = await WebAssembly.compile(await readFile(wasmPath));
// node 18 has no getImportObject(); wasiImport exists in both.
const imports = typeof wasi.getImportObject === 'function' ? wasi.getImportObject()
                                                           : { wasi_snapshot_preview1: wasi.wasiImport };
const instance = await WebAssembly.instantiate(module, imports);
process.exitCode = wasi.start(instance);
