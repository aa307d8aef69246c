/* The try-its of a book page, answered in the page (issue 35). Each try-it is one element
 * <div data-tryit="13-1/try-1" data-spec="../instant/13-1.json" data-live="…"> holding its input (textarea),
 * its check button and its verdict (data-verdict: pass, fail, refused or undecided). The engine is
 * kinbook-instant.js (window.KinbookInstant, over mathjs), loaded by this script after the page's own load; the
 * page's data is fetched from the site itself once. English and Spanish: the button "Español" / "English" switches every try-it of the page
 * (remembered in localStorage). */
(function () {
  "use strict";
  const pages = new Map();   // JSON url → promise of the page's data
  let lang = "en";
  try {
    lang = localStorage.getItem("kinbook-lang") || ((navigator.language || "").startsWith("es") ? "es" : "en");
  } catch (e) { /* storage off: English */ }

  function data(url) {
    if (!pages.has(url)) pages.set(url, fetch(url).then((r) => r.json()));
    return pages.get(url);
  }

  function fill(template, fields) {
    return template.replace(/\{(\w+)\}/g, (m, k) => (k in (fields || {}) ? String(fields[k]) : m));
  }

  function el(tag, attrs, text) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    return e;
  }

  function render(box, page, spec, result, text) {
    const ui = (k, fields) => fill(page.ui[k][lang], fields);
    const out = box.querySelector("[data-verdict]");
    out.textContent = "";
    out.setAttribute("data-verdict", result.verdict);
    const head = { pass: "correct", fail: "wrong", refused: "refused", undecided: "undecided" }[result.verdict];
    out.appendChild(el("strong", { class: "kinbook-instant-head" }, ui(head)));
    const reasons = result.reasons.map((r) => ui(r.key, r.fields)).filter(Boolean);
    if (result.why && result.why[lang]) reasons.push(result.why[lang]);
    if (reasons.length) out.appendChild(el("span", {}, " " + reasons.join("; ") + "."));
    if (result.mistake) {
      const mk = result.mistake;
      const p = el("div", { class: "kinbook-instant-mistake", "data-mistake": mk.code });
      p.appendChild(el("b", {}, ui("mistake") + " (" + mk.code + "): "));
      p.appendChild(el("span", {}, mk.title[lang] + (mk.detail ? " — " + mk.detail[lang] : "")));
      out.appendChild(p);
      const h = el("div", { class: "kinbook-instant-hint" });
      h.appendChild(el("b", {}, ui("hint") + ": "));
      h.appendChild(el("span", {}, mk.hint[lang]));
      out.appendChild(h);
    }
    if (result.verdict === "undecided") {
      const a = el("a", { href: box.getAttribute("data-live"), class: "kinbook-instant-python" }, ui("python"));
      const p = el("div", {});
      p.appendChild(a);
      out.appendChild(p);
    }
    const echo = box.querySelector("[data-echo]");
    echo.textContent = "";
    setTimeout(() => showEcho(echo, ui, window.KinbookInstant.echo(spec, page.grammar, text)), 0);  // the verdict first
  }

  function showEcho(echo, ui, tex) {
    if (tex) {
      echo.appendChild(el("span", { class: "kinbook-instant-label" }, ui("read_as") + " "));
      echo.appendChild(el("span", {}, "\\(" + tex + "\\)"));
      if (window.MathJax && MathJax.typesetPromise) MathJax.typesetPromise([echo]).catch(() => {});
    }
  }

  function label(box, page) {
    const spec = page.tryits[box.getAttribute("data-tryit")];
    box.querySelector("[data-check]").textContent = page.ui.check[lang];
    box.querySelector("[data-lang]").textContent = page.ui.language[lang];
    box.querySelector("[data-note]").textContent = page.ui.formative[lang];
    box.querySelector("textarea").setAttribute("placeholder",
      page.ui[spec && spec.kind === "rows" ? "placeholder_rows" : "placeholder_value"][lang]);
  }

  function setUp(box) {
    const url = box.getAttribute("data-spec");
    const ready = data(url);
    const button = box.querySelector("[data-check]");
    ready.then((page) => {
      label(box, page);
      // one check of nothing, once the page is idle: the parser and the engine are compiled before the student's
      const idle = window.requestIdleCallback || ((f) => setTimeout(f, 50));
      idle(() => {
        window.KinbookInstant.check(page.tryits[box.getAttribute("data-tryit")], page.grammar, "0");
        box.setAttribute("data-ready", "1");
      });
    });
    button.addEventListener("click", () => {
      ready.then((page) => {
        const t0 = performance.now();
        const spec = page.tryits[box.getAttribute("data-tryit")];
        const text = box.querySelector("textarea").value;
        const result = window.KinbookInstant.check(spec, page.grammar, text);
        render(box, page, spec, result, text);
        box.setAttribute("data-ms", String(performance.now() - t0));
      });
    });
    box.querySelector("[data-lang]").addEventListener("click", () => {
      lang = lang === "en" ? "es" : "en";
      try { localStorage.setItem("kinbook-lang", lang); } catch (e) { /* no storage */ }
      document.querySelectorAll("[data-tryit]").forEach((b) => {
        data(b.getAttribute("data-spec")).then((page) => {
          label(b, page);
          if (b.querySelector("[data-verdict]").getAttribute("data-verdict")) b.querySelector("[data-check]").click();
        });
      });
    });
  }

  function start() {
    window.KinbookInstant = window.KinbookInstant.call ? window.KinbookInstant(window.math) : window.KinbookInstant;
    document.querySelectorAll("[data-tryit]").forEach(setUp);
  }

  // mathjs and the engine are loaded once the page itself has loaded: the book page is interactive as soon as
  // without them (mathjs is some 650 kB to parse)
  const base = document.currentScript.src.replace(/[^/]*$/, "");
  function load(name) {
    return new Promise((resolve, reject) => {
      const s = document.createElement("script");
      s.src = base + name;
      s.onload = resolve;
      s.onerror = reject;
      document.head.appendChild(s);
    });
  }
  function begin() { load("math.js").then(() => load("kinbook-instant.js")).then(start); }
  if (document.readyState === "complete") begin();
  else window.addEventListener("load", begin);
})();
