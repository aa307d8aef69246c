"""Page titles without TeX: a browser tab (and a bookmark, a search result) shows the ``<title>`` as plain text,
where a chapter heading's math — "13-6 · Velocity analysis: $\\boldsymbol\\Phi_{\\mathbf q}\\,\\dot{\\mathbf q} = \\nu$" —
arrived as raw TeX. The math of a title is written in Unicode instead ("Φ_q q̇ = ν"); the page itself, typeset
by MathJax, is unchanged."""

import html
import re

_SYMBOLS = {r"\Phi": "Φ", r"\nu": "ν", r"\gamma": "γ", r"\varphi": "φ", r"\phi": "φ", r"\psi": "ψ",
            r"\theta": "θ", r"\omega": "ω", r"\alpha": "α", r"\cdot": "·", r"\times": "×", r"\to": "→"}
_ACCENTS = {r"\dot": "\u0307", r"\ddot": "\u0308"}
_STYLES = (r"\boldsymbol", r"\mathbf", r"\mathrm", r"\text", r"\operatorname")
_MATH = re.compile(r"\\\((.+?)\\\)|\$(.+?)\$", re.S)


def _group(tex, k):
    """The argument starting at ``tex[k]``: a {…} group or one token; (text, end)."""
    if tex[k] == "{":
        depth = 0
        for j in range(k, len(tex)):
            depth += {"{": 1, "}": -1}.get(tex[j], 0)
            if depth == 0:
                return tex[k + 1:j], j + 1
    m = re.match(r"\\[A-Za-z]+|.", tex[k:])
    return m.group(0), k + len(m.group(0))


def plain_math(tex):
    """TeX of a title's formula as Unicode: ``\\boldsymbol\\Phi_{\\mathbf q}\\,\\ddot{\\mathbf q} = \\gamma`` → "Φ_q q̈ = γ"."""
    out, k = [], 0
    tex = tex.replace(r"\,", " ").replace(r"\;", " ").replace(r"\ ", " ")
    while k < len(tex):
        c = tex[k]
        m = re.match(r"\\[A-Za-z]+", tex[k:])
        if m:
            name = m.group(0)
            k += len(name)
            if name in _STYLES:
                while k < len(tex) and tex[k] == " ":
                    k += 1
                arg, k = _group(tex, k)
                out.append(plain_math(arg))
            elif name in _ACCENTS:
                while k < len(tex) and tex[k] == " ":
                    k += 1
                arg, k = _group(tex, k)
                out.append(plain_math(arg) + _ACCENTS[name])
            else:
                out.append(_SYMBOLS.get(name, name.lstrip("\\")))
        elif c in "_^":
            arg, k = _group(tex, k + 1)
            out.append(c + plain_math(arg))
        elif c in "{}":
            k += 1
        else:
            out.append(c)
            k += 1
    return re.sub(r" {2,}", " ", "".join(out)).strip()


def plain_title(title):
    """A page title with each TeX formula written in Unicode (HTML entities kept as they are)."""
    if not title:
        return title
    text = html.unescape(re.sub(r"<[^>]+>", "", title))
    return html.escape(_MATH.sub(lambda m: plain_math(m.group(1) or m.group(2)), text), quote=False)


def _page_context(app, pagename, templatename, context, doctree):
    for key in ("title", "pagetitle"):
        if isinstance(context.get(key), str) and ("\\" in context[key] or "$" in context[key]):
            context[key] = plain_title(context[key])


def setup(app):
    app.connect("html-page-context", _page_context)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
