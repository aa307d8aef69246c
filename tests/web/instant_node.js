// The page's engine (web/instant/kinbook-instant.js) under Node on the answers of tests/web/instant_cases.py:
//   node tests/web/instant_node.js CASES.jsonl MATHJS_DIR > VERDICTS.jsonl
"use strict";
const fs = require("fs");
const path = require("path");
const [cases, mathjsDir] = process.argv.slice(2);
const math = require(path.resolve(mathjsDir));
const engine = require(path.resolve(__dirname, "../../web/instant/kinbook-instant.js"))(math);
const lines = fs.readFileSync(cases, "utf8").trim().split("\n").map((l) => JSON.parse(l));
const { specs, grammar } = lines.pop();
const out = [];
for (const c of lines) {
  if (c.text === null) { out.push(JSON.stringify({ id: c.id, verdict: "not_text" })); continue; }
  let r;
  try {
    r = engine.check(specs[c.spec], grammar, c.text);
  } catch (e) {
    r = { verdict: "error", error: String(e && e.stack || e) };
  }
  out.push(JSON.stringify({ id: c.id, verdict: r.verdict, mistake: r.mistake ? r.mistake.code : null,
    reasons: r.reasons, ms: r.ms, error: r.error }));
}
process.stdout.write(out.join("\n") + "\n");
