// kinbook's live site: say in the page what Python is loading and for how long, and when it cannot be downloaded.
//
// The notebooks run on Pyodide (Python compiled to WebAssembly), which the kernel's web worker downloads from
// the address in jupyter-lite.json (pyodideUrl: this site's static/pyodide/, web/pyodide_site.py). When that
// download fails — offline, a firewall or proxy, a site copied without its static/pyodide/ folder — JupyterLite
// shows nothing: the cells stay at [*] forever. This script (added to the pages by web/build.py) fetches the same
// file once when the page opens, and when the kernel later reports itself dead; if Python cannot be had, a banner
// at the foot of the page (the menu bar stays usable above it) says so and what to do.
(function () {
  'use strict';
  var root = new URL('.', document.currentScript.src); // the live site's root (this script sits there)
  var shown = false;

  function banner(host, detail, answered) {
    if (shown) return;
    shown = true;
    var box = document.createElement('div');
    box.id = 'kinbook-no-python';
    box.setAttribute('role', 'alert');
    box.style.cssText = 'position:fixed;bottom:0;left:0;right:0;z-index:10000;padding:10px 44px 10px 16px;' +
      'background:#fdecea;color:#611a15;border-top:2px solid #c62828;' +
      'font:14px/1.45 -apple-system,BlinkMacSystemFont,"Segoe UI",Helvetica,Arial,sans-serif';
    var title = document.createElement('b');
    title.textContent = 'Python could not be downloaded, so the cells of this page cannot run. ';
    var text = document.createElement('span');
    text.textContent = 'The live notebooks download Python (Pyodide, about 70 MB on a first visit) from ' + host +
      ', and that failed (' + detail + '): ' + (answered
        ? 'the site is missing its copy of Python (ask whoever runs it to publish the whole site folder, ' +
          'static/pyodide/ included).'
        : 'the computer may be offline, or a firewall or proxy may block ' + host + '.') +
      ' The notebook and its stored outputs are here to read; to run cells, ' + (answered
        ? 'come back once the site is complete' : 'connect to the internet (or ask whoever runs this site to ' +
          'allow ' + host + ')') + ' and reload the page.';
    var close = document.createElement('button');
    close.textContent = '×';
    close.title = 'Hide this message';
    close.setAttribute('aria-label', 'Hide this message');
    close.style.cssText = 'position:absolute;top:6px;right:10px;border:0;background:none;font-size:20px;' +
      'cursor:pointer;color:#611a15';
    close.onclick = function () { box.remove(); };
    box.append(title, text, close);
    document.body.appendChild(box);
  }

  function pyodideUrl() {
    return fetch(new URL('jupyter-lite.json', root), { cache: 'no-cache' })
      .then(function (r) { return r.json(); })
      .then(function (config) {
        var settings = ((config['jupyter-config-data'] || {}).litePluginSettings || {})[
          '@jupyterlite/pyodide-kernel-extension:kernel'] || {};
        return new URL(settings.pyodideUrl || 'static/pyodide/pyodide.js', root);
      });
  }

  function probe() {
    return pyodideUrl().then(function (url) {
      // the request the kernel's worker makes (no-cors: a host without CORS headers still counts as reached;
      // its answer is opaque, only a network failure rejects)
      return fetch(url.href, { mode: 'no-cors' }).then(function (r) {
        if (r.type !== 'opaque' && !r.ok) banner(url.host, 'the server answered ' + r.status, true);
      }, function (error) {
        banner(url.host, 'no answer: ' + (error && error.message || error), false);
      });
    }).catch(function () { /* no configuration to read: not a live page */ });
  }

  // a kernel that died while starting (JupyterLite marks the execution indicator) is probed again: the
  // download may have failed after the first check (Pyodide's packages, a dropped connection)
  function watchKernel() {
    var timer = setInterval(function () {
      if (shown) return clearInterval(timer);
      var dead = document.querySelector('[data-status="dead"], .jp-KernelStatus-error');
      if (dead) { clearInterval(timer); probe(); }
    }, 2000);
  }

  // While Python starts, a small notice at the foot of the page names what is loading (Pyodide and the packages
  // jupyter-lite.json has the kernel load) and counts the seconds, so that a student is not left wondering why
  // the first cell waits; past `slowAfter` seconds it says that this is slow but still going. It goes away when
  // the kernel answers (its kernel_info reply: Python is ready) or when the banner above says Python cannot be had.
  var KERNEL_OWN = ['micropip', 'piplite', 'pyodide_kernel', 'ipykernel', 'comm', 'ssl', 'sqlite3', 'jedi', 'ipython'];

  function packages() {
    return fetch(new URL('jupyter-lite.json', root), { cache: 'no-cache' })
      .then(function (r) { return r.json(); })
      .then(function (config) {
        var settings = ((config['jupyter-config-data'] || {}).litePluginSettings || {})[
          '@jupyterlite/pyodide-kernel-extension:kernel'] || {};
        return ((settings.loadPyodideOptions || {}).packages || []).filter(function (p) {
          return KERNEL_OWN.indexOf(p) < 0;
        });
      }).catch(function () { return []; });
  }

  function kernelReady() {
    var app = window.jupyterapp;
    var widget = app && app.shell && app.shell.currentWidget;
    var kernel = widget && widget.sessionContext && widget.sessionContext.session &&
      widget.sessionContext.session.kernel;
    if (kernel && !kernel.__kinbookAsked) {
      kernel.__kinbookAsked = true;
      Promise.resolve(kernel.info).then(function () { kernel.__kinbookReady = true; }, function () {});
    }
    if (kernel && kernel.__kinbookReady) return true;
    // without the app (another JupyterLite page): a cell that has run means Python is there
    return !!document.querySelector('.jp-InputPrompt') &&
      /\[\d+\]/.test(Array.prototype.map.call(document.querySelectorAll('.jp-InputPrompt'),
        function (p) { return p.textContent; }).join(' '));
  }

  function startingNotice() {
    if (!/\/(notebooks|lab)\//.test(location.pathname)) return;
    var slowAfter = typeof window.kinbookSlowAfter === 'number' ? window.kinbookSlowAfter : 40;
    var t0 = Date.now();
    var box = document.createElement('div');
    box.id = 'kinbook-starting';
    box.setAttribute('role', 'status');
    box.style.cssText = 'position:fixed;bottom:8px;right:12px;z-index:9999;max-width:560px;padding:6px 12px;' +
      'background:#eef5ff;color:#0b3d91;border-left:4px solid #1f6feb;box-shadow:0 1px 4px rgba(0,0,0,.15);' +
      'font:13px/1.45 -apple-system,BlinkMacSystemFont,"Segoe UI",Helvetica,Arial,sans-serif';
    var what = 'Python (Pyodide)';
    packages().then(function (names) { if (names.length) what = 'Python (Pyodide) with ' + names.join(', '); });
    function update() {
      if (shown || kernelReady()) {
        clearInterval(timer);
        box.remove();
        return;
      }
      var s = Math.round((Date.now() - t0) / 1000);
      box.textContent = 'Starting ' + what + ' in your browser: ' + s + ' s so far. ' + (s >= slowAfter
        ? 'This is slower than usual (a slow connection or a busy computer) but still going; the page stays ' +
          'readable meanwhile.'
        : 'A first visit takes up to a minute; later visits reuse the copy your browser keeps. Cells you run ' +
          'now wait until it is ready.');
      if (!box.isConnected) document.body.appendChild(box);
    }
    var timer = setInterval(update, 1000);
    update();
  }

  function start() {
    probe();
    watchKernel();
    startingNotice();
  }

  if (document.readyState === 'loading') {
    document.addEventListener('DOMContentLoaded', start);
  } else {
    start();
  }
})();
