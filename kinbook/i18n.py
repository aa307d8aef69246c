"""The language of kinbook's messages: the standard library's :mod:`gettext`, catalogues managed with Babel.

English is written in the code, where each message is made; every other language is a catalogue,
``kinbook/locale/<lang>/LC_MESSAGES/kinbook.po`` (what a translator edits), compiled to ``kinbook.mo`` (shipped
with the package and read at run time by :mod:`gettext`; Babel is only needed to update the catalogues).

A message is *marked* where it is written and translated when it is shown, in the language of that moment
(:func:`set_language`), so a result made in English reads in Spanish after ``set_language("es")``:

* ``N_("the sign of {what}")`` — a sentence (fields in braces, filled after translation);
* ``Np_("your {n} row", "your {n} rows")`` — a sentence with plural forms, chosen by its field ``n``
  (:func:`gettext.ngettext`: Spanish and English both have two, the catalogue's Plural-Forms header says so);
* ``pN_("verdict on a row", "correct")`` — where one English word has two translations (correcta / correcto).

:class:`Message` keeps a marked message with its fields and writes it when shown: the expression reader's refusals
are made of them, and any :class:`~kinbook.errors.KinbookError` may carry one (its ``str`` follows the language;
its ``args[0]`` is the English).

After changing a marked message: ``make translations`` (Babel's extract, update and compile: the new or changed
message appears untranslated in the .po; translate it and run it again). tests/test_i18n.py fails on any marked
message the Spanish catalogue lacks, leaves fuzzy or translates with other fields, and on a stale ``.mo``.
"""

from __future__ import annotations

import gettext as _gettext
from functools import lru_cache
from pathlib import Path
from typing import NamedTuple

from .errors import InputError

__all__ = ["N_", "Np_", "pN_", "Plural", "Contextual", "Message", "translate", "set_language", "get_language", "LANGUAGES",
           "DOMAIN", "LOCALE_DIR", "KEYWORDS"]

DOMAIN = "kinbook"
LOCALE_DIR = Path(__file__).with_name("locale")
LANGUAGES = ("en", "es")
"""English (the messages as written) and the languages with a catalogue."""
KEYWORDS = {"N_": None, "Np_": (1, 2), "pN_": ((1, "c"), 2)}
"""The marking functions, as Babel's extractor reads them (``pybabel extract -k N_ -k Np_:1,2 -k pN_:1c,2``)."""

_state = {"lang": "en"}


class Plural(NamedTuple):
    """A message with plural forms; the field ``n`` of the message chooses the form."""

    singular: str
    plural: str


class Contextual(NamedTuple):
    """A message with a context (gettext's msgctxt): the same English, translated apart."""

    context: str
    message: str


def N_(message):
    """Mark ``message`` for translation (it is translated when shown)."""
    return message


def Np_(singular, plural):
    """Mark a message with plural forms; the message's field ``n`` chooses the form when it is shown."""
    return Plural(singular, plural)


def pN_(context, message):
    """Mark a message whose English is shared with another of a different translation."""
    return Contextual(context, message)


class Message:
    """A marked message and its fields: a sentence written in the language of the moment when it is shown.

    ``str(m)`` (or :meth:`render`) translates the template, then fills its fields; a field that is itself a
    :class:`Message` is written in the same language. The errors of kinbook's reader carry one
    (:class:`kinbook.errors.ExpressionError`), so a refused expression reads in Spanish after ``set_language("es")``.

    Examples
    --------
    >>> m = Message(N_("{where} is empty"), where=Message(N_("the answer")))
    >>> str(m), m.render("es")
    ('the answer is empty', 'la respuesta está vacía')
    """

    __slots__ = ("template", "fields")

    def __init__(self, template, **fields):
        self.template, self.fields = template, fields

    def render(self, lang=None):
        """The sentence in ``lang`` (default: the current language)."""
        lang = lang or _state["lang"]
        text = translate(self.template, lang, self.fields.get("n"))
        return text.format(**{k: v.render(lang) if isinstance(v, Message) else v for k, v in self.fields.items()})

    def __str__(self):
        return self.render()

    def __repr__(self):
        return f"{type(self).__name__}({self.render('en')!r})"

    def __eq__(self, other):
        return type(other) is type(self) and (self.template, self.fields) == (other.template, other.fields)

    __hash__ = None


def set_language(lang):
    """Choose the language of kinbook's feedback and messages.

    Parameters
    ----------
    lang : {"en", "es"}
        English or Spanish.

    Examples
    --------
    >>> set_language("es"); get_language()
    'es'
    >>> set_language("en")
    """
    if lang not in LANGUAGES:
        raise InputError(f"`lang` must be one of {', '.join(LANGUAGES)}, got {lang!r}")
    translations(lang)  # a missing catalogue is an installation error: say so now, not when a message is shown
    _state["lang"] = lang


def get_language():
    """The current language, "en" or "es"."""
    return _state["lang"]


@lru_cache(maxsize=None)
def translations(lang):
    """The :class:`gettext.NullTranslations` of ``lang`` (English: the messages as written)."""
    if lang == "en":
        return _gettext.NullTranslations()
    return _gettext.translation(DOMAIN, LOCALE_DIR, languages=[lang])


def translate(text, lang=None, n=None):
    """A marked message in ``lang`` (default: the current language); ``n`` chooses a plural form."""
    tr = translations(lang or _state["lang"])
    if isinstance(text, Plural):
        return tr.ngettext(text.singular, text.plural, 1 if n is None else int(n))
    if isinstance(text, Contextual):
        return tr.pgettext(text.context, text.message)
    return tr.gettext(text)
