"""Load MathJax on every page of the book, not only on pages where Sphinx itself found an equation.

Some notebook outputs are HTML with TeX in it (the errata tables, written for JupyterLab, which typesets HTML
outputs): Sphinx sees no equation on such a page and would leave its one MathJax script out, so the TeX would
show raw. Each document is marked as having equations once it has been read.
"""


def _has_equations(app, doctree):
    app.env.get_domain("math").data["has_equations"][app.env.docname] = True


def setup(app):
    app.connect("doctree-read", _has_equations)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
