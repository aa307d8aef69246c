// kinbook's live site: say in the page when Python cannot be downloaded.
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

  if (document.readyState === 'loading') {
    document.addEventListener('DOMContentLoaded', function () { probe(); watchKernel(); });
  } else {
    probe();
    watchKernel();
  }
})();
