"""Leave Thebe out of the book: Jupyter Book 1 always loads the sphinx-thebe extension, which puts a launcher
script, its stylesheet and a configuration naming a public CDN (unpkg.com) and a Binder repository on every
page. The book's live path is JupyterLite (each page's "Open live" link), so Thebe is unused: its event
handlers are disconnected and its stylesheet dropped before the builder collects the pages' assets.
"""


def _without_thebe(app, config):
    for event in ("env-before-read-docs", "doctree-resolved"):
        for listener in list(app.events.listeners.get(event, [])):
            if getattr(listener.handler, "__module__", "").startswith("sphinx_thebe"):
                app.disconnect(listener.id)
    app.registry.css_files = [(name, attrs) for name, attrs in app.registry.css_files
                              if not str(name).startswith("sphinx-thebe")]


def setup(app):
    app.connect("config-inited", _without_thebe)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
