/* kinbook's instant check (issue 35): a try-it's answer checked in the page, without Python.
 *
 * The page's JSON (kinbook/book/instant.py, written at build time) holds everything but the answer: the
 * reader's grammar (kinbook/core/reader.py: the same names, functions and bounds), the reference at the
 * checker's own points, the rule (a constant factor per row, the tolerance) and the catalogued mistakes as
 * values at the same points. mathjs (pinned in web/package-lock.json, served by the site) parses the answer;
 * the tree is walked against kinbook's allow-list before anything is evaluated, and evaluated by a closure built
 * here (never mathjs's own evaluate: no complex numbers, no units, nothing outside the grammar).
 *
 * verdict: "pass", "fail" (with a named mistake when the values are a catalogued one's), "refused" (the answer
 * cannot be read: Python refuses it too) or "undecided" (an equivalent formulation, a Newton iteration: the
 * page says so and links to the live notebook). The engine below has no DOM: tests/web run it under Node.
 */
(function (root, factory) {
  if (typeof module === "object" && module.exports) module.exports = factory;
  else root.KinbookInstant = factory(root.math);
})(typeof self !== "undefined" ? self : this, function (math) {
  "use strict";

  // ------------------------------------------------------------------------------------------ reading
  class Refusal extends Error {
    constructor(key, fields) { super(key); this.key = key; this.fields = fields || {}; }
  }

  const NUMBER = /(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?/y;
  const NAME = /[\p{L}\p{Nl}_][\p{L}\p{Nl}\p{Mn}\p{Mc}\p{Nd}\p{Pc}]*/uy;
  const STRING = /"(?:[^"\\]|\\.)*"|'(?:[^'\\]|\\.)*'/y;

  /* Every name becomes a placeholder mathjs cannot misread (π, φ̇2, e01 …: kinbook's names in NFKC, as
   * Python's parser reads them); numbers are kept as written, ** becomes ^ (as kinbook's reader does). */
  function tokenize(text, names) {
    let out = "", i = 0;
    while (i < text.length) {
      let m;
      for (const re of [STRING, NUMBER, NAME]) {
        re.lastIndex = i;
        m = re.exec(text);
        if (m) {
          const end = re.lastIndex;  // before a string's inside is tokenized (the same sticky expressions)
          if (re === NAME) {
            const name = m[0].normalize("NFKC");
            let key = names.byName.get(name);
            if (!key) { key = "_k" + names.list.length; names.byName.set(name, key); names.list.push(name); }
            out += key;
          } else if (re === STRING) {
            out += m[0][0] + tokenize(m[0].slice(1, -1), names) + m[0][0];
          } else {
            out += m[0];
            if (names.numbers) names.numbers.push(m[0]);
          }
          i = end;
          break;
        }
      }
      if (m) continue;
      if (text.startsWith("**", i)) { out += "^"; i += 2; continue; }
      out += text[i];
      i += 1;
    }
    return out;
  }

  const OPS = { add: "+", subtract: "-", multiply: "*", divide: "/", pow: "^", unaryMinus: "-", unaryPlus: "+" };

  /* One entry: the vetted tree compiled to f(point) → number, with its TeX. */
  function entry(node, ctx) {
    const g = ctx.grammar, lim = g.limits;
    let count = 0;
    function walk(n, depth) {
      if (++count > 10 * lim.nodes || depth > 10 * lim.depth) throw new Refusal("too_large");
      switch (n.type) {
        case "ParenthesisNode": return walk(n.content, depth);
        case "ConstantNode": {
          if (typeof n.value !== "number") throw new Refusal("not_allowed", { what: String(n.value) });
          if (!isFinite(n.value) || Math.abs(n.value) > lim.magnitude) throw new Refusal("not_finite");
          const v = ctx.swap && ctx.swap.has(n.value) ? ctx.swap.get(n.value) : n.value;  // the rounding rule
          return { f: () => v, num: v };
        }
        case "SymbolNode": {
          const name = ctx.names.list[Number(n.name.slice(2))];
          if (name in g.constants) { const v = g.constants[name]; return { f: () => v, num: v }; }
          const where = ctx.symbols[name];
          if (!where) {
            if (name in g.functions || name in g.aliases) throw new Refusal("not_allowed", { what: name });
            throw new Refusal("unknown_name", { name });
          }
          const [arr, k] = where;
          if (arr === "t") return { f: (p) => p.t };
          return arr === "q" ? { f: (p) => p.q[k] } : { f: (p) => p.qd[k] };
        }
        case "OperatorNode": {
          if (!(n.fn in OPS)) throw new Refusal("not_allowed", { what: n.op });
          if (n.implicit) throw new Refusal("implicit");
          const args = n.args.map((a) => walk(a, depth + 1));
          return operator(n.fn, args, lim);
        }
        case "FunctionNode": {
          if (!n.fn || n.fn.type !== "SymbolNode") throw new Refusal("not_allowed", { what: "(…)(…)" });
          const written = ctx.names.list[Number(n.fn.name.slice(2))];
          const name = g.aliases[written] || written;
          if (!(name in g.functions)) {
            if (ctx.symbols[written] || written in g.constants) throw new Refusal("implicit");
            throw new Refusal("unknown_function", { name: written });
          }
          if (!g.functions[name].includes(n.args.length)) {
            throw new Refusal("arguments", { name: written, want: g.functions[name].join(" or "), got: n.args.length });
          }
          const args = n.args.map((a) => walk(a, depth + 1));
          return call(name, args);
        }
        default:
          throw new Refusal("not_allowed", { what: n.type.replace("Node", "").toLowerCase() });
      }
    }
    const built = walk(node, 1);
    return { f: built.f, num: built.num, get tex() { return tex(node, ctx); }, node, ctx };  // TeX only for the echo
  }

  function operator(fn, args, lim) {
    const [a, b] = args;
    const num = args.every((x) => x.num !== undefined);
    if (fn === "pow" && b.num !== undefined && Math.abs(b.num) > lim.exponent) throw new Refusal("exponent", { limit: lim.exponent });
    const F = {
      add: (p) => a.f(p) + b.f(p), subtract: (p) => a.f(p) - b.f(p), multiply: (p) => a.f(p) * b.f(p),
      divide: (p) => a.f(p) / b.f(p), pow: (p) => Math.pow(a.f(p), b.f(p)),
      unaryMinus: (p) => -a.f(p), unaryPlus: (p) => a.f(p),
    }[fn];
    if (!num) return { f: F };
    const v = F({});
    if (!isFinite(v) || Math.abs(v) > lim.magnitude) throw new Refusal("not_finite");
    return { f: () => v, num: v };
  }

  const FUNCTIONS = {
    sin: Math.sin, cos: Math.cos, tan: Math.tan, asin: Math.asin, acos: Math.acos, atan: Math.atan,
    atan2: Math.atan2, sqrt: Math.sqrt, exp: Math.exp, Abs: Math.abs, sign: Math.sign,
    log: (x, b) => (b === undefined ? Math.log(x) : Math.log(x) / Math.log(b)),
  };

  function call(name, args) {
    const fn = FUNCTIONS[name];
    const F = args.length === 1 ? (p) => fn(args[0].f(p)) : (p) => fn(args[0].f(p), args[1].f(p));
    if (args.every((x) => x.num !== undefined)) {
      const v = F({});
      if (!isFinite(v)) throw new Refusal("not_finite");
      return { f: () => v, num: v };
    }
    return { f: F };
  }

  // TeX of a name as the book writes it: x1 → x_{1}, phi2 → \varphi_{2}, dphi2 → \dot{\varphi}_{2}
  function nameTex(name) {
    const m = /^(d)?(phi|φ|ϕ|x|y|z|e[0-3]|[A-Za-z]+?)_?(dot)?_?([0-9]+)$/u.exec(name);
    if (!m) return name === "pi" || name === "π" ? "\\pi" : name === "t" ? "t" : "\\mathrm{" + name.replace(/_/g, "\\_") + "}";
    let stem = { phi: "\\varphi", "φ": "\\varphi", "ϕ": "\\varphi" }[m[2]] || m[2];
    if (/^e[0-3]$/.test(m[2])) stem = "e_{" + m[2][1];
    const sub = /^e[0-3]$/.test(m[2]) ? stem + m[4] + "}" : stem + "_{" + m[4] + "}";
    return m[1] || m[3] ? "\\dot{" + sub + "}" : sub;
  }

  function tex(node, ctx) {
    try {
      return node.toTex({
        parenthesis: "auto", implicit: "show",
        handler: (n, options) => {
          if (n.type === "SymbolNode") {
            const name = ctx.names.list[Number(n.name.slice(2))];
            return "{" + (name in ctx.grammar.constants ? (name === "E" ? "e" : "\\pi") : nameTex(name.normalize("NFKC"))) + "}";
          }
          if (n.type === "FunctionNode") {
            const written = ctx.names.list[Number(n.fn.name.slice(2))];
            const name = ctx.grammar.aliases[written] || written;
            const args = n.args.map((a) => a.toTex(options));
            if (name === "sqrt") return "\\sqrt{" + args[0] + "}";
            if (name === "Abs") return "\\left|" + args[0] + "\\right|";
            const op = ["sin", "cos", "tan", "exp", "log"].includes(name) ? "\\" + name : "\\operatorname{" + name + "}";
            return op + "\\left(" + args.join(",") + "\\right)";
          }
          return undefined;
        },
      });
    } catch (e) {
      return "";
    }
  }

  function parse(source) {
    try {
      return math.parse(source);
    } catch (e) {
      throw new Refusal("syntax");
    }
  }

  /* The answer as a matrix of entries (rows × columns): a list ["…", "…"] or [[…], […]] as in the notebook,
   * or one row per line (a line may be a list [a, b, c]). */
  function readAnswer(text, spec, grammar, swap) {
    if (typeof text !== "string" || !text.trim()) throw new Refusal("syntax");
    if (text.length > 20 * grammar.limits.length) throw new Refusal("too_large");
    const ctx = { grammar, symbols: spec.names || {}, names: { byName: new Map(), list: [], numbers: [] }, swap };
    const source = tokenize(text.trim(), ctx.names);
    let top;
    try {
      top = math.parse(source);
    } catch (e) {
      top = null;
    }
    let rows;
    if (top && unwrap(top).type === "ArrayNode") {
      rows = unwrap(top).items.map((item) => (unwrap(item).type === "ArrayNode" ? unwrap(item).items : [item]));
    } else if (top && top.type !== "BlockNode") {
      rows = [[top]];
    } else {
      rows = source.split(/\n/).filter((l) => l.trim()).map((line) => {
        const n = unwrap(parse(line));
        return n.type === "ArrayNode" ? n.items : [n];
      });
    }
    const matrix = rows.map((row) => row.map((n) => {
      n = unwrap(n);
      if (n.type === "ConstantNode" && typeof n.value === "string") n = parse(n.value);
      if (n.type === "ArrayNode") throw new Refusal("not_allowed", { what: "[…]" });
      return entry(n, ctx);
    }));
    const width = matrix[0].length;
    if (matrix.some((r) => r.length !== width)) throw new Refusal("syntax");
    matrix.literals = ctx.names.numbers;
    return matrix;
  }

  function unwrap(n) { return n && n.type === "ParenthesisNode" ? unwrap(n.content) : n; }

  // ------------------------------------------------------------------------------------------ comparing
  const maxAbs = (a) => a.reduce((m, x) => Math.max(m, Math.abs(x)), 0);
  const NICE = [1, -1, 2, -2, 0.5, -0.5, 3, -3];
  function nice(c) {
    for (const r of NICE) if (Math.abs(c - r) < 1e-9 * Math.max(1, Math.abs(c))) return r;
    return c;
  }
  const wrapTo = (x, period) => ((((x + period / 2) % period) + period) % period) - period / 2;

  function same(a, b, rtol, period) {
    const scale = Math.max(maxAbs(a), maxAbs(b));
    const tol = rtol * scale + 1e-12 * Math.max(scale, 1) * rtol;
    return a.every((x, i) => Math.abs(period ? wrapTo(x - b[i], period) : x - b[i]) <= tol);
  }

  /* kinbook.grading.compare.scale_match: the constant c ≠ 0 with a ≈ c·b at every point, or null. */
  function scaleMatch(a, b, rtol, free, period, atol, zeros) {
    atol = atol || 0;
    if (period) {
      for (const c of free ? [1, -1] : [1]) if (same(a, b.map((x) => c * x), rtol, period)) return c;
      return null;
    }
    const sb = maxAbs(b);
    if (sb <= atol) return zeros && maxAbs(a) <= Math.max(atol, 1e-12) ? 1 : null;
    if (!free) {
      const d = maxAbs(a.map((x, i) => x - b[i]));
      return d <= rtol * Math.max(maxAbs(a), sb) + atol ? 1 : null;
    }
    let ab = 0, bb = 0;
    for (let i = 0; i < a.length; i++) { ab += a[i] * b[i]; bb += b[i] * b[i]; }
    const c = ab / bb;
    if (c === 0 || !isFinite(c)) return null;
    const d = maxAbs(a.map((x, i) => x - c * b[i]));
    return d <= rtol * Math.max(maxAbs(a), Math.abs(c) * sb) + atol ? nice(c) : null;
  }

  /* kinbook.grading.compare.turned_multiple, one row: the constant c and the whole number n ≠ 0 of periods with
     a ≈ c·(b + n·period) at every point (c and n the same at all of them), or null. An angle row turned by whole
     turns places the bodies as the row does. */
  function turnedMultiple(a, b, rtol, period) {
    const N = a.length, mean = (v) => v.reduce((x, y) => x + y, 0) / N;
    const ma = mean(a), mb = mean(b);
    let ab = 0, bb = 0;
    for (let i = 0; i < N; i++) { ab += (a[i] - ma) * (b[i] - mb); bb += (b[i] - mb) * (b[i] - mb); }
    const c = ab / bb;
    if (!isFinite(c) || c === 0) return null;
    const d = a.map((x, i) => x - c * b[i]), off = mean(d), n = Math.round(off / (c * period));
    const scale = Math.max(maxAbs(a), Math.abs(c) * maxAbs(b));
    const tol = rtol * scale + 1e-12 * Math.max(scale, 1) * rtol;
    if (!isFinite(n) || n === 0 || d.some((x) => Math.abs(x - off) > tol) || Math.abs(off - c * n * period) > tol) return null;
    return { c: nice(c), n };
  }

  /* scale_matrix's turns: where no multiple of an angle row was found, a multiple of it turned by whole turns. */
  function turnRows(C, S, R, rule) {
    const turned = new Map();
    for (const [key, period] of Object.entries(rule.turns || {})) {
      const j = Number(key);
      if (j >= R.length) continue;
      for (let k = 0; k < S.length; k++) {
        if (C[k][j] !== null) continue;
        const t = turnedMultiple(S[k], R[j], rule.rtol, period);
        if (t) { C[k][j] = t.c; turned.set(`${k},${j}`, { period, c: t.c }); }
      }
    }
    return turned;
  }

  function points(P) {
    return P.t.map((t, i) => ({ q: P.q[i], qd: P.qd[i], t }));
  }

  // values of an entry at every point, flattened over the entries of a row: rows × (points · width)
  function evaluate(matrix, pts) {
    return matrix.map((row) => {
      const out = [];
      for (const p of pts) for (const e of row) out.push(e.f(p));
      if (!out.every(Number.isFinite)) throw new Refusal("not_finite");
      return out;
    });
  }

  // reference rows flattened the same way: R[point][row] (or R[point][row][col] for Φ_q, taking cols)
  function refRows(R, m, cols) {
    const out = [];
    for (let j = 0; j < m; j++) {
      const row = [];
      for (const atPoint of R) {
        if (cols) for (const c of cols) row.push(atPoint[j][c]);
        else row.push(atPoint[j]);
      }
      out.push(row);
    }
    return out;
  }

  // ------------------------------------------------------------------------------------------ rows
  function asVector(matrix, m) {
    if (matrix.length === 1 && matrix[0].length > 1) return matrix[0].map((e) => [e]);
    if (matrix[0].length === 1) return matrix;
    throw new Refusal("shape", { got: matrix.length + "×" + matrix[0].length, want: m });
  }

  function checkRows(spec, grammar, text, swap) {
    const matrix = readAnswer(text, spec, grammar, swap);
    const rule = spec.rule, q = spec.quantity;
    if (rule.refuse) throw new Refusal("not_allowed", { what: "options" });  // an option the checker refuses
    if (!rule.decides) return { verdict: "undecided", reasons: [] };
    if (q === "Phi_q") return checkJacobian(spec, matrix);
    const rows = asVector(matrix, spec.m);
    const pts = points(spec.points.samples);
    const S = evaluate(rows, pts);
    const R = refRows(spec.reference.samples, spec.m);
    return q === "Phi" ? checkPhi(spec, rows, S, R) : checkDerived(spec, rows, S, R, null);
  }

  function named(spec, S, free) {
    // a catalogued mistake: the answer's rows are its rows (in any order, each with a constant factor)
    for (const mk of spec.mistakes) {
      const W = mk.rows ? transposeRows(mk.values) : null;
      if (!W || W.length !== S.length) continue;
      const left = W.map((_, j) => j);
      let ok = true;
      // a mutant is stored at the first mk.points of the checker's points (kinbook/book/instant.py): the answer
      // is compared there, entry for entry (the same width: Φ_q's columns)
      const P = spec.points.samples.t.length;
      const width = S[0].length / P, K = mk.points || P;
      if (W.some((w) => w.length !== K * width)) continue;
      for (const s0 of S) {
        const s = s0.slice(0, K * width);
        const hit = left.find((j) => scaleMatch(s, W[j], 1e-6, free) !== null);
        if (hit === undefined) { ok = false; break; }
        left.splice(left.indexOf(hit), 1);
      }
      if (ok) return mk;
    }
    return null;
  }

  // mistake values are stored as the reference: [point][row](…); as rows × points
  function transposeRows(V) {
    const m = V[0].length, out = [];
    for (let j = 0; j < m; j++) out.push(V.map((p) => (Array.isArray(p[j]) ? p[j] : [p[j]])).flat());
    return out;
  }

  function checkPhi(spec, rows, S, R) {
    const rule = spec.rule, ms = S.length, m = R.length;
    const wrap = rule.wrap || {};
    const C = S.map((s) => R.map((r, j) => scaleMatch(s, r, rule.rtol, true, wrap[j])));
    const vanishing = [];
    for (let k = 0; k < ms; k++) {  // no multiple of a reference row: a form the page can reduce to one?
      if (C[k].some((c) => c !== null) || !spec.blocks) continue;
      const how = reform(spec, rows[k][0], R);
      if (how === null) continue;
      if (how.kind === "vanishing") { vanishing.push(k); continue; }
      rows[k] = [how.entry];
      S[k] = evaluate([rows[k]], points(spec.points.samples))[0];
      C[k] = R.map((r, j) => scaleMatch(S[k], r, rule.rtol, true, wrap[j]));
    }
    const turned = turnRows(C, S, R, rule);
    const status = new Array(ms).fill("wrong"), ref = new Array(ms).fill(null), taken = new Map();
    const book = rule.order === "book";
    if (book) for (let k = 0; k < Math.min(ms, m); k++) if (C[k][k] !== null) { status[k] = "ok"; ref[k] = k; taken.set(k, k); }
    for (let k = 0; k < ms; k++) {
      if (status[k] === "ok") continue;
      const cands = R.map((_, j) => j).filter((j) => C[k][j] !== null);
      const free = cands.filter((j) => !taken.has(j));
      if (free.length) { status[k] = "ok"; ref[k] = free[0]; taken.set(free[0], k); }
      else if (cands.length) status[k] = "dependent";
    }
    const combos = combinations(spec, S, R, status, ref, taken);
    const mk = named(spec, S, true);
    if (mk) return { verdict: "fail", mistake: mk, reasons: [] };
    if (combos.dependent.length) {
      return { verdict: "fail", mistake: spec.diagnoses.dependent_row,
        reasons: combos.dependent.map((k) => ({ key: "row_wrong", fields: { k: k + 1 } })) };
    }
    if (vanishing.length) {
      return { verdict: "fail", mistake: spec.diagnoses.vanishing_factor, reasons: [] };  // its title says it
    }
    // more rows than the constraints have: one at least is dependent (or wrong), whatever its form; fewer: their
    // gradients cannot span the reference's (independent, with the bodies' pᵀp − 1, where the checker samples)
    if (ms !== m) return { verdict: "fail", mistake: lookalike(spec, S, true), reasons: [{ key: "rows_count", fields: { got: ms, want: m } }] };
    const reasons = [];
    let undecided = false, nearOnly = true;
    for (let k = 0; k < ms; k++) {
      if (status[k] !== "wrong") continue;
      const how = formulation(spec, rows[k], maxAbs(S[k]));
      if (how !== "wrong") { undecided = true; reasons.push({ key: "equivalent", fields: { k: k + 1 } }); }
      else reasons.push({ key: "row_wrong", fields: { k: k + 1 } });
      if (how === "maybe") nearOnly = false;
    }
    if (reasons.some((r) => r.key === "row_wrong") || status.includes("dependent")) {
      return { verdict: "fail", mistake: lookalike(spec, S, true), reasons };
    }
    if (undecided) return { verdict: "undecided", reasons, nearOnly };
    if (ms !== m) return { verdict: "fail", reasons: [{ key: "rows_count", fields: { got: ms, want: m } }] };
    if (book && ref.some((j, k) => j !== k)) return { verdict: "fail", reasons: [] };
    const bad = witness(Object.assign({}, spec, { _combos: combos.coef, _turned: turned }), rows, ref, S, R, true);
    if (bad !== null && (rule.turns || {})[ref[bad]] !== undefined) {
      // an angle row whose turns change over the whole domain (atan2 of the row): whether some turn of the bodies
      // places them as the row does is the checker's witness's question, not the page's
      return { verdict: "undecided", reasons: [{ key: "equivalent", fields: { k: bad + 1 } }], nearOnly: false };
    }
    if (bad !== null) return { verdict: "fail", reasons: [{ key: "row_only", fields: { k: bad + 1 } }] };
    return { verdict: "pass", reasons: [] };
  }

  /* Φ rows that are constant combinations of one constraint's reference rows (R₁ + 2R₂ for R₁): with that
   * constraint's other rows they are right when the combination is regular (the same zero set, the same rank), a
   * dependent row when it is not. Marks them in status/ref; returns {coef: Map(k → [[j, c]…]), dependent: [k…]}. */
  function combinations(spec, S, R, status, ref, taken) {
    const out = { coef: new Map(), dependent: [] };
    const rtol = spec.rule.rtol, blocks = spec.row_blocks || [];
    const found = new Map();  // block index → [k…]
    for (let k = 0; k < S.length; k++) {
      if (status[k] !== "wrong") continue;
      for (let b = 0; b < blocks.length; b++) {
        const rowsB = blocks[b].map((j) => R[j]);
        if (rowsB.length < 2) continue;
        const c = solve(rowsB.map((x) => rowsB.map((y) => dot(x, y))), rowsB.map((x) => dot(x, S[k])));
        if (c === null) continue;
        const fit = S[k].map((_, i) => rowsB.reduce((a, r, jj) => a + c[jj] * r[i], 0));
        const size = Math.max(maxAbs(S[k]), ...rowsB.map((r, jj) => Math.abs(c[jj]) * maxAbs(r)));
        if (maxAbs(S[k].map((x, i) => x - fit[i])) > rtol * size) continue;
        out.coef.set(k, blocks[b].map((j, jj) => [j, Math.abs(c[jj]) > 1e-9 * Math.max(...c.map(Math.abs)) ? c[jj] : 0]));
        if (!found.has(b)) found.set(b, []);
        found.get(b).push(k);
        break;
      }
    }
    for (const [b, ks] of found) {
      const block = blocks[b];
      const mine = S.map((_, k) => k).filter((k) => (status[k] === "ok" && block.includes(ref[k])) || ks.includes(k));
      if (mine.length !== block.length) { ks.forEach((k) => out.coef.delete(k)); continue; }
      const M = mine.map((k) => (ks.includes(k) ? out.coef.get(k).map(([, c]) => c) : block.map((j) => (j === ref[k] ? 1 : 0))));
      const scale = M.reduce((a, row) => a * Math.max(Math.sqrt(dot(row, row)), 1e-300), 1);
      if (Math.abs(det(M)) <= 1e-6 * scale) { out.dependent.push(...ks); ks.forEach((k) => out.coef.delete(k)); continue; }
      const free = block.filter((j) => !taken.has(j));
      for (const k of ks) {
        const j = free.includes(k) ? k : free[0];
        free.splice(free.indexOf(j), 1);
        status[k] = "ok"; ref[k] = j; taken.set(j, k);
      }
    }
    return out;
  }

  function det(M) {
    const n = M.length, A = M.map((r) => r.slice());
    let d = 1;
    for (let c = 0; c < n; c++) {
      let p = c;
      for (let i = c + 1; i < n; i++) if (Math.abs(A[i][c]) > Math.abs(A[p][c])) p = i;
      if (A[p][c] === 0) return 0;
      if (p !== c) { [A[c], A[p]] = [A[p], A[c]]; d = -d; }
      d *= A[c][c];
      for (let i = c + 1; i < n; i++) { const f = A[i][c] / A[c][c]; for (let k = c; k < n; k++) A[i][k] -= f * A[c][k]; }
    }
    return d;
  }

  /* A Φ row written in a form the page can reduce to a multiple of a reference row (kinbook.grading.equivalence
   * and factors.py, as far as values at points and the row's own tree decide):
   *   √E − c (c > 0), c − √E: the same zero set and a regular gradient as E − c², compared as that;
   *   g·h₁·…·h_r with g a multiple of a reference row: each hᵢ proved nonzero over the whole domain (interval
   *   arithmetic: translations and angles on the real line, Euler parameters in [−1, 1], t ≥ 0) leaves g's zero set
   *   — the row is compared as g; an hᵢ that changes sign along a line through a sample (one coordinate moving over
   *   factors.py's grid, hᵢ continuous there), where g does not vanish, is a vanishing factor (Python names it).
   * Anything else (a factor neither proved nonzero nor seen to vanish: a touch of zero, a quotient) → null: the
   * checker's zero-set search decides. */
  function reform(spec, e, R) {
    if (!e || !e.node) return null;
    const ctx = e.ctx, pts = points(spec.points.samples), rtol = spec.rule.rtol, wrap = spec.rule.wrap || {};
    const matches = (f) => R.some((r, j) => scaleMatch(evaluate([[f]], pts)[0], r, rtol, true, wrap[j]) !== null);
    const factors = [];
    (function flatten(n) {
      n = unwrap(n);
      if (n.type === "OperatorNode" && n.fn === "multiply" && !n.implicit) n.args.forEach(flatten);
      else if (n.type === "OperatorNode" && (n.fn === "unaryMinus" || n.fn === "unaryPlus")) flatten(n.args[0]);
      else if (n.type === "OperatorNode" && n.fn === "divide" && entry(n.args[1], ctx).num !== undefined) flatten(n.args[0]);
      else factors.push(n);
    })(e.node);
    const live = factors.map((n) => ({ n, e: entry(n, ctx) })).filter((x) => x.e.num === undefined);
    if (live.length === 1) {
      const root = sqrtForm(live[0].n, ctx);
      return root && matches(root) ? { kind: "ok", entry: root } : null;
    }
    if (live.length < 2) return null;
    let vanishing = false;
    for (const g of live) {
      if (!matches(g.e)) continue;
      const others = live.filter((x) => x !== g);
      if (others.every((h) => nonzero(interval(h.n, ctx, spec)))) return { kind: "ok", entry: g.e };
      if (others.some((h) => continuous(h.n, ctx) && signChange(spec, h.e, g.e))) vanishing = true;
    }
    return vanishing ? { kind: "vanishing" } : null;
  }

  function sqrtForm(n, ctx) {
    if (n.type !== "OperatorNode" || !["add", "subtract"].includes(n.fn) || n.args.length !== 2) return null;
    const [a, b] = n.args.map(unwrap);
    const isSqrt = (x) => x.type === "FunctionNode" && x.fn.type === "SymbolNode"
      && (ctx.grammar.aliases[ctx.names.list[Number(x.fn.name.slice(2))]] || ctx.names.list[Number(x.fn.name.slice(2))]) === "sqrt";
    let root, c;
    if (isSqrt(a)) { root = a; c = entry(b, ctx).num; if (c !== undefined && n.fn === "add") c = -c; }
    else if (isSqrt(b) && n.fn === "subtract") { root = b; c = entry(a, ctx).num; }
    if (!root || c === undefined || !(c > 0)) return null;
    const E = entry(root.args[0], ctx);
    return { f: (p) => E.f(p) - c * c, node: null, ctx };
  }

  const FULL = [-Infinity, Infinity];
  function interval(n, ctx, spec) {
    n = unwrap(n);
    const I = (x) => interval(x, ctx, spec);
    const clean = (xs) => xs.map((x) => (Number.isNaN(x) ? 0 : x));
    switch (n.type) {
      case "ConstantNode": return [n.value, n.value];
      case "SymbolNode": {
        const name = ctx.names.list[Number(n.name.slice(2))];
        if (name in ctx.grammar.constants) return [ctx.grammar.constants[name], ctx.grammar.constants[name]];
        const where = ctx.symbols[name];
        if (!where) return FULL;
        if (where[0] === "t") return [0, Infinity];
        return where[0] === "q" && (spec.euler || []).includes(where[1]) ? [-1, 1] : FULL;
      }
      case "OperatorNode": {
        const [a, b] = n.args.map(I);
        switch (n.fn) {
          case "add": return [a[0] + b[0], a[1] + b[1]].map((x) => (Number.isNaN(x) ? NaN : x));
          case "subtract": return [a[0] - b[1], a[1] - b[0]];
          case "unaryMinus": return [-a[1], -a[0]];
          case "unaryPlus": return a;
          case "multiply": {
            const xs = clean([a[0] * b[0], a[0] * b[1], a[1] * b[0], a[1] * b[1]]);
            return [Math.min(...xs), Math.max(...xs)];
          }
          case "divide": {
            if (b[0] <= 0 && b[1] >= 0) return FULL;
            const xs = clean([a[0] / b[0], a[0] / b[1], a[1] / b[0], a[1] / b[1]]);
            return [Math.min(...xs), Math.max(...xs)];
          }
          case "pow": {
            const k = b[0] === b[1] ? b[0] : NaN;
            if (!(Number.isInteger(k) && k >= 0)) return FULL;
            if (k === 0) return [1, 1];
            const lo = Math.pow(a[0], k), hi = Math.pow(a[1], k);
            if (k % 2) return [lo, hi];
            if (a[0] >= 0) return [lo, hi];
            if (a[1] <= 0) return [hi, lo];
            return [0, Math.max(lo, hi)];
          }
          default: return FULL;
        }
      }
      case "FunctionNode": {
        const written = ctx.names.list[Number(n.fn.name.slice(2))];
        const name = ctx.grammar.aliases[written] || written;
        const a = n.args.length === 1 ? I(n.args[0]) : null;
        if (name === "sin" || name === "cos") return [-1, 1];
        if (name === "exp" && a) return [Math.exp(a[0]), Math.exp(a[1])];
        if (name === "sqrt" && a) return [Math.sqrt(Math.max(a[0], 0)), Math.sqrt(Math.max(a[1], 0))];
        if (name === "atan" && a) return [Math.atan(a[0]), Math.atan(a[1])];
        return FULL;
      }
      default: return FULL;
    }
  }
  const nonzero = (iv) => iv[0] > 1e-9 * Math.max(1, Math.abs(iv[1]) === Infinity ? 1 : Math.abs(iv[1])) || iv[1] < -1e-9 * Math.max(1, Math.abs(iv[0]) === Infinity ? 1 : Math.abs(iv[0]));

  /* Built of continuous operations only (no quotient by a variable, no tan, sign, log, atan2): a sign change
   * between two points of a line is a zero between them. */
  function continuous(n, ctx) {
    n = unwrap(n);
    if (n.type === "ConstantNode" || n.type === "SymbolNode") return true;
    if (n.type === "OperatorNode") {
      if (n.fn === "divide") return entry(n.args[1], ctx).num !== undefined && continuous(n.args[0], ctx);
      if (n.fn === "pow") { const k = entry(n.args[1], ctx).num; return Number.isInteger(k) && k >= 0 && continuous(n.args[0], ctx); }
      return ["add", "subtract", "multiply", "unaryMinus", "unaryPlus"].includes(n.fn) && n.args.every((x) => continuous(x, ctx));
    }
    if (n.type === "FunctionNode") {
      const written = ctx.names.list[Number(n.fn.name.slice(2))];
      const name = ctx.grammar.aliases[written] || written;
      return ["sin", "cos", "exp", "atan", "Abs"].includes(name) && n.args.every((x) => continuous(x, ctx));
    }
    return false;
  }

  // factors.py's grid: offsets 10⁻³ … 10⁴ on both sides (translations, angles), t in [0, 10⁴], e in [−1, 1]
  const SIDE = Array.from({ length: 160 }, (_, i) => Math.pow(10, -3 + (7 * i) / 159));
  const GRID = SIDE.slice().reverse().map((x) => -x).concat([0], SIDE);
  const T_GRID = [0].concat(Array.from({ length: GRID.length - 1 }, (_, i) => Math.pow(10, -3 + (7 * i) / (GRID.length - 2))));
  const E_GRID = GRID.map((_, i) => -1 + (2 * i) / (GRID.length - 1));

  function signChange(spec, h, g) {
    const P = spec.points.samples, base = points(P).slice(0, 3);
    const gScale = Math.max(...base.map((p) => Math.abs(g.f(p))), 1e-300);
    const firm = (p) => { const v = g.f(p); return Number.isFinite(v) && Math.abs(v) > 1e-6 * gScale ? Math.sign(v) : 0; };
    const euler = new Set(spec.euler || []);
    const used = new Set();  // the coordinates (and t) h is written in: the only lines along which it changes
    h.node.traverse((n) => {
      const where = n.type === "SymbolNode" && h.ctx.symbols[h.ctx.names.list[Number(n.name.slice(2))]];
      if (where) used.add(where[0] === "q" ? where[1] : where[0] === "t" ? -1 : null);
    });
    for (const b of base) {
      const lines = b.q.map((_, i) => ({ i, grid: euler.has(i) ? E_GRID : GRID.map((d) => b.q[i] + d) }))
        .filter(({ i }) => used.has(i));
      if (used.has(-1)) lines.push({ i: -1, grid: T_GRID });
      for (const { i, grid } of lines) {
        let prev = null;
        for (const x of grid) {
          const q = b.q.slice();
          if (i >= 0) q[i] = x;
          const p = { q, qd: b.qd, t: i >= 0 ? b.t : x };
          const v = h.f(p);
          if (!Number.isFinite(v)) { prev = null; continue; }
          const cur = { v, s: firm(p) };
          if (prev && cur.s !== 0 && cur.s === prev.s && ((v === 0) || prev.v * v < 0)) return true;
          prev = cur;
        }
      }
    }
    return false;
  }

  /* A Φ row that is no constant multiple of a reference row, where each constraint alone holds (its own assembled
   * points): "wrong" when it vanishes where no constraint alone holds (a masked row, or no constraint at all) or
   * when its gradient vanishes there too (Φ_k², a vanishing factor: the rank is lost); "maybe" an equivalent
   * formulation otherwise — the checker decides (its zero-set search, the coverage of every row). */
  function formulation(spec, row, scale) {
    scale = Math.max(scale, 1e-9);
    let maybe = false;
    for (const block of spec.blocks) {
      const pts = points(block.points);
      const values = evaluate([row], pts)[0];
      const size = maxAbs(values);
      if (size > 1e-4 * scale) continue;          // not zero where this constraint holds
      if (size > 1e-6 * scale) return "near";     // nearly: the page cannot say (a constant rounded?)
      for (const p of pts) {
        if (gradientSize(row, p) <= 1e-6 * scale) return "wrong";
      }
      maybe = true;
    }
    return maybe || !spec.blocks_complete ? "maybe" : "wrong";
  }

  function gradientSize(row, p) {
    let g = 0;
    for (let i = 0; i < p.q.length; i++) {
      const h = 1e-6 * Math.max(1, Math.abs(p.q[i]));
      const up = p.q.slice(), down = p.q.slice();
      up[i] += h;
      down[i] -= h;
      const d = (row[0].f({ q: up, qd: p.qd, t: p.t }) - row[0].f({ q: down, qd: p.qd, t: p.t })) / (2 * h);
      g = Math.max(g, Math.abs(d));
    }
    return g;
  }

  function lookalike(spec, S, free) {
    const mk = spec.mistakes.filter((x) => x.code === "wrong_data" && x.rows);
    return named(Object.assign({}, spec, { mistakes: mk }), S, free);
  }

  /* Rows accepted at the checker's points, compared again at the page's witness points with the same factor. */
  function witness(spec, rows, ref, S, R, phi) {
    if (!spec.points.witness) return null;
    const pts = points(spec.points.witness);
    const cols = spec._cols || null;
    const W = evaluate(rows, pts);
    const RW = refRows(spec.reference.witness, spec.m, cols);
    const scaleAll = Math.max(...R.map(maxAbs), 1e-9);
    for (let k = 0; k < rows.length; k++) {
      const j = ref[k];
      if (j === null || j === undefined) continue;
      const combo = spec._combos && spec._combos.get(k);
      const turn = spec._turned && spec._turned.get(`${k},${j}`);
      if (turn) {  // turned by whole turns: the same constant there, by a whole number of turns of its own (_wide)
        const t = turnedMultiple(W[k], RW[j], spec.rule.rtol, turn.period);
        if (!t || Math.abs(t.c - turn.c) > 1e-6 * Math.abs(turn.c)) return k;
        continue;
      }
      const c = combo ? 1 : spec._factors ? spec._factors[k] : scaleMatch(S[k], R[j], spec.rule.rtol, true, (spec.rule.wrap || {})[j]);
      const a = W[k], b = combo ? W[k].map((_, i) => combo.reduce((x, [jj, cc]) => x + cc * RW[jj][i], 0)) : RW[j].map((x) => c * x);
      const rtol = spec.rule.rtol;
      let ok;
      if (phi) ok = scaleMatch(a, b, rtol, false, (spec.rule.wrap || {})[j], rtol * Math.max(Math.abs(c) * maxAbs(R[j]), 1e-9), true) !== null;
      else ok = maxAbs(a.map((x, i) => x - b[i])) <= rtol * Math.max(maxAbs(a), maxAbs(b)) + rtol * scaleAll;
      if (!ok) return k;
    }
    return null;
  }

  function checkDerived(spec, rows, S, R, cols) {
    const rule = spec.rule, ms = S.length, m = R.length;
    const sign = rule.factor === "sign";
    const atol = rule.rtol * Math.max(Math.max(...R.map(maxAbs)), 1e-9);
    const factor = (k, j) => {
      if (j >= m) return null;
      const c = scaleMatch(S[k], R[j], rule.rtol, sign, null, atol, true);
      return c === null ? null : c;
    };
    const mk = named(spec, S, sign);
    const ref = [], factors = [], reasons = [];
    if (ms !== m) return { verdict: "fail", mistake: mk, reasons: [{ key: "rows_count", fields: { got: ms, want: m } }] };
    let wrong = false;
    for (let k = 0; k < ms; k++) {
      let j = k;
      if (rule.order === "any") {
        j = R.findIndex((_, jj) => !ref.includes(jj) && factor(k, jj) !== null);
        if (j < 0) j = k;
      }
      const c = factor(k, j);
      ref.push(j);
      factors.push(c);
      if (c === null) { wrong = true; reasons.push({ key: "row_wrong", fields: { k: k + 1 } }); }
      else if (Math.abs(Math.abs(c) - 1) > 1e-6) {
        wrong = true;
        reasons.push({ key: "scaled_row", fields: { k: k + 1, c: +c.toPrecision(6) } });
      }
    }
    if (wrong) {
      const unmatched = reasons.filter((x) => x.key === "row_wrong");
      if (spec.spatial && spec.quantity === "Phi_q" && egRow(spec, S, R, cols, unmatched)) {
        return { verdict: "fail", mistake: mk || spec.diagnoses.eg_jacobian, reasons };
      }
      if (sign && unmatched.length === reasons.length && spanned(spec, S, unmatched, cols)) return { verdict: "undecided", reasons };
      return { verdict: "fail", mistake: mk || lookalike(spec, S, sign), reasons };
    }
    if (mk) return { verdict: "fail", mistake: mk, reasons: [] };
    const bad = witness(Object.assign({}, spec, { _cols: cols, _factors: factors }), rows, ref, S, R, false);
    if (bad !== null) return { verdict: "fail", reasons: [{ key: "row_only", fields: { k: bad + 1 } }] };
    return { verdict: "pass", reasons: [] };
  }

  // ------------------------------------------------------------------------------------------ rounding
  /* kinbook.grading.rounding: a decimal of the answer that is a correct rounding (to its own significant digits,
   * at least min_digits) of an exact constant of the exercise stands for it; one near a constant (or a rounding
   * with too few digits) is named not_rounded when the answer is right with the constant in its place. Only a
   * failed answer is looked at again (the checker's graded()). */
  function typedDigits(literal) {
    const mantissa = literal.toLowerCase().split("e")[0];
    return mantissa.includes(".") ? mantissa.replace(".", "").replace(/^0+/, "").length : mantissa.replace(/^0+|0+$/g, "").length;
  }

  function roundings(spec, literals) {
    const r = spec.rounding, swap = new Map(), near = [];
    const digits = new Map();
    for (const lit of literals) {
      const x = Number(lit), isInt = !/[.eE]/.test(lit);
      if (x === 0 || (isInt && x < 100)) continue;  // the checker's decimals: floats, and integers from 100
      digits.set(x, Math.max(digits.get(x) || 0, typedDigits(lit)));
    }
    const data = new Set(r.data);
    for (const x of [...digits.keys()].sort((a, b) => a - b)) {
      const isInt = Number.isInteger(x) && literals.some((l) => !/[.eE]/.test(l) && Number(l) === x);
      if (data.has(x)) continue;                                  // the exercise's own datum, as written
      if (isInt && r.integers.includes(x)) continue;
      const d = digits.get(x);
      let best = null;
      for (const n of r.integers) {                               // a decimal near an integer of the exercise
        if (n && !isInt && Math.abs(x - n) <= r.near * n && x !== n && (best === null || Math.abs(x - n) < Math.abs(best[0] - x))) best = [n, String(n)];
      }
      let rounded = false;
      for (const [value, text] of r.constants) {
        if (value === x) continue;
        const isR = Number(value.toPrecision(Math.min(Math.max(d, 1), 100))) === x;
        if (isR && d >= r.min_digits) { swap.set(x, value); rounded = true; break; }
        if (!isR && Math.abs(value - x) > r.near * Math.abs(value)) continue;
        if (best === null || Math.abs(value - x) < Math.abs(best[0] - x)) best = [value, text];
      }
      if (!rounded && best !== null) near.push([x, best[0], best[1], d]);
    }
    return { swap, near };
  }

  function withRounding(spec, grammar, text, first) {
    if (first.verdict === "pass" || first.verdict === "refused" || !spec.rounding) return first;
    let literals;
    try { literals = readAnswer(text, spec, grammar).literals; } catch (e) { return first; }
    const { swap, near } = roundings(spec, literals);
    let result = first;
    const recheck = (sw) => {
      try { return checkRows(spec, grammar, text, sw); } catch (e) { if (e instanceof Refusal) return { verdict: "fail", reasons: [] }; throw e; }
    };
    if (swap.size) {
      const again = recheck(swap);
      if (again.verdict !== "fail") return again;                 // right (or undecided) with the constants
      result = first.verdict === "undecided" ? first : again;
    }
    if (!near.length || (result.verdict === "undecided" && !result.nearOnly)) return result;
    const repaired = new Map(swap);
    for (const [x, value] of near) repaired.set(x, value);
    const fixed = recheck(repaired);
    if (fixed.verdict !== "pass") return result;
    const [x, value, exact, d] = near[0];
    const detail = {};
    for (const lang of Object.keys(spec.diagnoses.not_rounded.title)) detail[lang] = String(x) + " ≠ " + exact + " (" + d + ")";
    return { verdict: "fail", mistake: Object.assign({}, spec.diagnoses.not_rounded, { detail }), reasons: [] };
  }

  // ------------------------------------------------------------------------------------------ Φ_q
  function checkJacobian(spec, matrix) {
    const n = spec.n, roles = spec.cols, r = matrix.length, c = matrix[0].length;
    if (![roles.length, n].includes(c)) {
      if ([roles.length, n].includes(r)) return { verdict: "fail", reasons: [{ key: "shape", fields: { got: r + "×" + c, want: spec.m + "×" + roles.length } }] };  // transposed
      return { verdict: "fail", reasons: [{ key: "shape", fields: { got: r + "×" + c, want: spec.m + "×" + roles.length } }] };
    }
    const pts = points(spec.points.samples);
    const S = evaluate(matrix, pts);
    let cols = c === roles.length ? roles : [...Array(n).keys()];  // evaluate.best_columns
    const sorted = [...roles].sort((a, b) => a - b);
    if (c === roles.length && sorted.some((x, i) => x !== roles[i])) {
      const fit = (cc) => {
        const R = refRows(spec.reference.samples, spec.m, cc);
        let good = 0;
        for (let col = 0; col < cc.length; col++) {
          let all = true;
          for (let k = 0; k < Math.min(S.length, R.length); k++) {
            for (let p = col; p < S[k].length; p += cc.length) {
              let scale = 0;
              for (let kk = 0; kk < Math.min(S.length, R.length); kk++) scale = Math.max(scale, Math.abs(R[kk][p]));
              if (Math.abs(S[k][p] - R[k][p]) > spec.rule.rtol * (scale + 1e-12)) { all = false; break; }
            }
            if (!all) break;
          }
          if (all) good++;
        }
        return good;
      };
      if (fit(sorted) > fit(roles)) cols = sorted;
    }
    const R = refRows(spec.reference.samples, spec.m, cols);
    if (r === c && r > 1) {  // a square matrix given transposed: Python names it
      const T = evaluate(matrix[0].map((_, j) => matrix.map((row) => row[j])), pts);
      const match = (X) => X.length === R.length && X.every((s, k) => scaleMatch(s, R[k], spec.rule.rtol, false, null, spec.rule.rtol * Math.max(...R.map(maxAbs), 1e-9), true) !== null);
      if (match(T) && !match(S)) return { verdict: "fail", reasons: [{ key: "shape", fields: { got: "(" + r + "×" + c + ")ᵀ", want: spec.m + "×" + c } }] };
    }
    return checkDerived(Object.assign({}, spec, { _free: spec.reference.free }), matrix, S, R, cols);
  }

  /* kinbook.grading.aftermatch.eg_rows: a spatial Φ_q row that differs from its reference row only by multiples of
   * the bodies' normalization gradients 2pᵀ in their p-columns (∂(EGᵀa)/∂p = 2Eā where 2(Eā + apᵀ) belongs). */
  function egRow(spec, S, R, cols, unmatched) {
    const w = cols.length, Q = spec.points.samples.q, rtol = spec.rule.rtol;
    const bodies = [...new Set(cols.map((c) => Math.floor(c / 7)))];
    for (const reason of unmatched) {
      const k = reason.fields.k - 1;
      if (k >= R.length) continue;
      const scale = Math.max(maxAbs(R[k]), 1e-300);
      const rest = S[k].map((x, i) => x - R[k][i]);
      if (maxAbs(rest) <= rtol * scale) continue;
      for (let pt = 0; pt < Q.length; pt++) {
        for (const b of bodies) {
          const pc = cols.map((c, i) => [c, i]).filter(([c]) => c >= 7 * b + 3 && c < 7 * b + 7).map(([, i]) => i);
          if (pc.length !== 4) continue;
          const p = Q[pt].slice(7 * b + 3, 7 * b + 7);
          const coef = pc.reduce((a, i, j) => a + rest[pt * w + i] * p[j], 0) / p.reduce((a, x) => a + x * x, 0);
          pc.forEach((i, j) => { rest[pt * w + i] -= coef * p[j]; });
        }
      }
      if (maxAbs(rest) <= 1e2 * rtol * scale) return true;
    }
    return false;
  }

  /* A Φ_q row that is, at every point, a combination of the reference rows (and the rows that hold anyway):
   * an equivalent formulation Python may accept (the Jacobian of M(q)·Φ) — the page leaves it to Python. */
  function spanned(spec, S, reasons, cols) {
    const F = spec.reference.free && spec.reference.free.length && spec.reference.free[0].length
      ? refRows(spec.reference.free, spec.reference.free[0].length, cols) : [];
    const R = refRows(spec.reference.samples, spec.m, cols);
    const w = cols.length, N = spec.points.samples.t.length;
    const blocks = spec.row_blocks || [R.map((_, j) => j)];
    // a combination of the rows of one constraint (the checker's jacobian_equivalents), at every point
    const inBlock = (s, block) => {
      const rows = block.map((j) => R[j]).concat(F);
      for (let p = 0; p < N; p++) {
        const basis = rows.map((row) => row.slice(p * w, p * w + w));
        if (!inSpan(s.slice(p * w, p * w + w), basis, spec.rule.rtol)) return false;
      }
      return true;
    };
    for (const reason of reasons) {
      const s = S[reason.fields.k - 1];
      if (!(maxAbs(s) > 0) || !blocks.some((b) => inBlock(s, b))) return false;
    }
    return reasons.length > 0;
  }

  function inSpan(v, basis, rtol) {
    const Q = [];
    for (const b of basis) {
      let u = b.slice();
      for (const e of Q) { const d = dot(u, e); u = u.map((x, i) => x - d * e[i]); }
      const nu = Math.sqrt(dot(u, u));
      if (nu > 1e-10 * Math.max(1, Math.sqrt(dot(b, b)))) Q.push(u.map((x) => x / nu));
    }
    let r = v.slice();
    for (const e of Q) { const d = dot(r, e); r = r.map((x, i) => x - d * e[i]); }
    return Math.sqrt(dot(r, r)) <= Math.max(1e-6, rtol) * Math.max(Math.sqrt(dot(v, v)), 1e-12);
  }
  const dot = (a, b) => a.reduce((s, x, i) => s + x * b[i], 0);

  // ------------------------------------------------------------------------------------------ numbers
  function shapeOf(v) { return Array.isArray(v) ? [v.length].concat(v.length ? shapeOf(v[0]) : []) : []; }
  const flat = (v) => (Array.isArray(v) ? v.flat(Infinity) : [v]);

  function checkValue(spec, grammar, text) {
    const matrix = readAnswer(text, { names: {} }, grammar);
    for (const row of matrix) for (const e of row) if (e.num === undefined) throw new Refusal("not_finite");
    const a = matrix.flat().map((e) => e.num);
    const eShape = spec.shape, size = eShape.reduce((x, y) => x * y, 1);
    const aShape = matrix.length === 1 ? [matrix[0].length] : [matrix.length, matrix[0].length];
    const squeeze = (s) => s.filter((x) => x !== 1).join("×");
    const r = spec.rule;
    if (a.length !== size || (!r.sizes_only && squeeze(aShape) !== squeeze(eShape))) {
      const transposed = aShape.length === 2 && eShape.length === 2 && aShape[0] === eShape[1] && aShape[1] === eShape[0];
      return { verdict: "fail", mistake: transposed ? spec.diagnoses && spec.diagnoses.transposed : null,
        reasons: [{ key: "shape", fields: { got: aShape.join("×"), want: eShape.join("×") || "1" } }] };
    }
    const e = flat(spec.value);
    const per = new Set(r.periodic);
    const close = (x, y) => {
      const scale = maxAbs(y), tol = r.atol + r.rtol * scale;
      return x.every((v, i) => Math.abs(per.has(i) ? wrapTo(v - y[i], 2 * Math.PI) : v - y[i]) <= tol);
    };
    if (close(a, e)) return { verdict: "pass", reasons: [] };
    for (const eq of spec.equivalents) if (close(a, flat(eq.values))) return { verdict: "pass", reasons: [], why: eq.why };
    const off = a.filter((v, i) => Math.abs(per.has(i) ? wrapTo(v - e[i], 2 * Math.PI) : v - e[i]) > r.atol + r.rtol * maxAbs(e)).length;
    const reasons = size > 1 ? [{ key: "entries_off", fields: { n: off, total: size } }] : [];
    for (const mk of spec.mistakes) {
      const v = flat(mk.values);
      if (v.length === e.length && !close(v, e) && close(a, v)) return { verdict: "fail", mistake: mk, reasons };
    }
    return { verdict: "fail", mistake: null, reasons };
  }

  // ------------------------------------------------------------------------------------------ Newton–Raphson
  /* kinbook.grading.newton.check_iterates: the guess first; every step q_j → q_j+1 must be q_j + Δq with
   * Φ_q(q_j) Δq = −Φ(q_j) (computed here from the student's own q_j); the last iterate converged, to the solution
   * the guess leads to. */
  function checkIterates(spec, grammar, text) {
    const matrix = readAnswer(text, { names: {} }, grammar);
    const a = matrix.map((row) => row.map((e) => {
      if (e.num === undefined) throw new Refusal("not_finite");
      return e.num;
    }));
    const n = spec.n, r = spec.rule;
    const mk = (code) => spec.mistakes.find((m) => m.code === code) || null;
    if (a.length > 200 || a.length < 2 || a[0].length !== n) {
      return { verdict: "fail", reasons: [{ key: "shape", fields: { got: a.length + "×" + a[0].length, want: "k×" + n } }] };
    }
    if (!a[0].every((x, i) => Math.abs(x - spec.guess[i]) <= 1e-9 + 1e-9 * Math.abs(spec.guess[i]))) {
      return { verdict: "fail", mistake: mk("wrong_data"), reasons: [] };
    }
    const compiled = spec._compiled || (spec._compiled = compileMechanism(spec, grammar));
    const at = (q) => ({ q, qd: q, t: spec.t });
    for (let j = 0; j + 1 < a.length; j++) {
      const p = at(a[j]);
      const dq = solve(compiled.J.map((row) => row.map((e) => e.f(p))), compiled.phi.map((e) => -e.f(p)));
      const ok = dq !== null && a[j + 1].every((x, i) => Math.abs(x - (a[j][i] + dq[i])) <= r.rtol * Math.max(1, maxAbs(dq)));
      if (!ok) return { verdict: "fail", mistake: mk("newton_step"), reasons: [{ key: "row_wrong", fields: { k: j + 2 } }] };
    }
    const last = a[a.length - 1];
    const res = maxAbs(compiled.phi.map((e) => e.f(at(last))));
    if (!(res <= r.tol)) return { verdict: "fail", mistake: mk("not_converged"), reasons: [] };
    const d = last.map((x, i) => (spec.angles.includes(i) ? wrapTo(x - spec.solution[i], 2 * Math.PI) : x - spec.solution[i]));
    if (maxAbs(d) > 1e-6 * Math.max(1, maxAbs(spec.solution))) return { verdict: "fail", mistake: mk("assembly_mode"), reasons: [] };
    return { verdict: "pass", reasons: [] };
  }

  function compileMechanism(spec, grammar) {
    const one = (text) => readAnswer(text, spec, grammar)[0][0];
    return { phi: spec.phi.map(one), J: spec.phi_q.map((row) => row.map(one)) };
  }

  /* A x = b by Gaussian elimination with partial pivoting; null when A is singular. */
  function solve(A, b) {
    const n = b.length, M = A.map((row, i) => row.concat([b[i]]));
    for (let c = 0; c < n; c++) {
      let p = c;
      for (let i = c + 1; i < n; i++) if (Math.abs(M[i][c]) > Math.abs(M[p][c])) p = i;
      if (!(Math.abs(M[p][c]) > 1e-300)) return null;
      [M[c], M[p]] = [M[p], M[c]];
      for (let i = c + 1; i < n; i++) {
        const f = M[i][c] / M[c][c];
        for (let k = c; k <= n; k++) M[i][k] -= f * M[c][k];
      }
    }
    const x = new Array(n).fill(0);
    for (let i = n - 1; i >= 0; i--) {
      let s = M[i][n];
      for (let k = i + 1; k < n; k++) s -= M[i][k] * x[k];
      x[i] = s / M[i][i];
    }
    return x.every(Number.isFinite) ? x : null;
  }

  // ------------------------------------------------------------------------------------------ entry point
  function check(spec, grammar, text) {
    const t0 = (typeof performance !== "undefined" ? performance : Date).now();
    let out;
    try {
      if (spec.kind === "value") out = checkValue(spec, grammar, text);
      else if (spec.kind === "rows") out = withRounding(spec, grammar, text, checkRows(spec, grammar, text));
      else if (spec.kind === "iterates") out = checkIterates(spec, grammar, text);
      else out = { verdict: "undecided", reasons: [{ key: "not_typed", fields: {} }] };
    } catch (e) {
      if (!(e instanceof Refusal)) throw e;
      // beyond the page's own bounds the checker's (larger ones for answers) decide: the page does not
      out = { verdict: e.key === "too_large" ? "undecided" : "refused", reasons: [{ key: e.key, fields: e.fields }] };
    }
    out.ms = (typeof performance !== "undefined" ? performance : Date).now() - t0;
    return out;
  }

  /* The TeX of the answer as it was read (null when it cannot be read). */
  function echo(spec, grammar, text) {
    try {
      const matrix = readAnswer(text, spec.kind === "rows" ? spec : { names: {} }, grammar);
      const rows = matrix.map((row) => row.map((e) => e.tex).join(" & "));
      return rows.length === 1 && matrix[0].length === 1 ? rows[0]
        : "\\begin{bmatrix}" + rows.join(" \\\\ ") + "\\end{bmatrix}";
    } catch (e) {
      return null;
    }
  }

  return { check, echo, Refusal, tokenize, scaleMatch };
});
