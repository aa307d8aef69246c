// Compile Python sources to bytecode with Pyodide's own Python 3.12 (web/pyodide_site.py, compile_wheels):
//
//     node compile.mjs RUNTIME COMPILE_PY JOBS_JSON
//
// RUNTIME is npm's pyodide package; COMPILE_PY (web/pyodide/compile.py) does the work, inside Pyodide, on the
// files JOBS_JSON names (the host's file system is mounted at /host).
import { pathToFileURL } from "node:url";
import { readFileSync } from "node:fs";
import path from "node:path";

const [runtime, script, jobs] = process.argv.slice(2);
const { loadPyodide } = await import(pathToFileURL(path.join(runtime, "pyodide.mjs")).href);
const pyodide = await loadPyodide({ indexURL: runtime + path.sep });
pyodide.FS.mkdirTree("/host");
pyodide.FS.mount(pyodide.FS.filesystems.NODEFS, { root: "/" }, "/host");
pyodide.runPython(readFileSync(script, "utf8"));
pyodide.globals.get("main")("/host" + path.resolve(jobs));
