"""The forms of ``asperity serve`` as a browser sees them, read from the pages' HTML with
:mod:`html.parser` (no knowledge of the server's code): each form's action, method and
fields (inputs, selects, textareas with their names, types, defaults, options, and the
``data-when``/``data-values`` conditions of the fieldsets around them), and where a page
puts its one-line errors.  The hostile-input walker of ``test_web_forms.py`` fills a form
from these, so a field added to a page later is walked without a new test."""
from __future__ import annotations

import itertools
import re
from dataclasses import dataclass, field
from html.parser import HTMLParser

VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "param",
        "source", "track", "wbr"}
BUTTONS = {"submit", "button", "reset", "image"}
UPLOAD_ID = re.compile(r"^[0-9a-f]{32}(\.[a-z0-9]{1,10}){1,2}$")


@dataclass
class Field:
    name: str
    kind: str                       # text, hidden, file, select, textarea, ...
    value: str = ""                 # the default the page fills in (a select: the chosen)
    options: list = field(default_factory=list)
    multiple: bool = False
    when: list = field(default_factory=list)     # [(controlling field, allowed values)]
    label: int | None = None        # the node id of the <label> around it
    label_text: str = ""            # the words of that label's name


@dataclass
class Form:
    action: str
    method: str
    enctype: str
    id: str
    fields: list = field(default_factory=list)
    #: one-line errors inside the form: (node id of the <label> around them, text)
    errors: list = field(default_factory=list)
    page_text: str = ""             # every word of the page the form is on

    def by_name(self, name: str) -> list:
        return [f for f in self.fields if f.name == name]

    @property
    def key(self) -> tuple:
        return (self.action, self.id)


class Page(HTMLParser):
    """The forms, links and page-level error line of one HTML page."""

    def __init__(self, html: str):
        super().__init__(convert_charrefs=True)
        self.forms: list[Form] = []
        self.links: list[str] = []
        self.page_errors: list[str] = []
        self._stack: list[dict] = []
        self._ids = itertools.count()
        self._form: Form | None = None
        self._select: Field | None = None
        self._text: list | None = None
        self._names: dict = {}          # label node id -> [Field] inside it
        self._words: list = []
        self.feed(html)
        self.close()
        self.text = " ".join(" ".join(self._words).split())
        for f in self.forms:
            f.page_text = self.text

    def _innermost(self, tag: str):
        for node in reversed(self._stack):
            if node["tag"] == tag:
                return node
        return None

    def handle_starttag(self, tag, attrs):
        a = {k: (v if v is not None else "") for k, v in attrs}
        node = {"tag": tag, "id": next(self._ids), "attrs": a, "error": None}
        classes = a.get("class", "").split()
        if tag == "a" and a.get("href"):
            self.links.append(a["href"])
        if tag == "form":
            self._form = Form(a.get("action", ""), a.get("method", "get").lower(),
                              a.get("enctype", ""), a.get("id", ""))
            self.forms.append(self._form)
        elif tag in ("input", "select", "textarea") and self._form is not None \
                and a.get("name") and a.get("type", "text") not in BUTTONS:
            kind = tag if tag != "input" else a.get("type", "text").lower()
            label = self._innermost("label")
            when = [(n["attrs"]["data-when"], n["attrs"].get("data-values", "").split())
                    for n in self._stack if "data-when" in n["attrs"]]
            f = Field(a["name"], kind, a.get("value", ""), multiple="multiple" in a,
                      when=when, label=label["id"] if label else None,
                      label_text=label.get("name", "") if label else "")
            self._form.fields.append(f)
            if tag == "select":
                self._select = f
        elif tag == "option" and self._select is not None:
            self._select.options.append(a.get("value", ""))
            if "selected" in a:
                self._select.value = a.get("value", "")
        if tag == "span" and "name" in classes:
            node["name_of"] = self._innermost("label")
            self._words_at = len(self._words)
        if "field-error" in classes or (a.get("id") == "error" and "error" in classes):
            node["error"] = "field" if "field-error" in classes else "page"
            self._text = []
        if tag not in VOID:
            self._stack.append(node)

    def handle_endtag(self, tag):
        while self._stack:
            node = self._stack.pop()
            if node.get("name_of") is not None:
                node["name_of"]["name"] = " ".join("".join(
                    self._words[self._words_at:]).split())
            if node["error"] is not None and self._text is not None:
                text = " ".join("".join(self._text).split())
                if node["error"] == "page":
                    self.page_errors.append(text)
                elif self._form is not None:
                    label = self._innermost("label")
                    self._form.errors.append((label["id"] if label else None, text))
                self._text = None
            if node["tag"] == "select":
                if self._select is not None and not self._select.value and \
                        self._select.options:
                    self._select.value = self._select.options[0]
                self._select = None
            if node["tag"] == "form":
                self._form = None
            if node["tag"] == tag:
                break

    def handle_data(self, data):
        if not self._stack or self._stack[-1]["tag"] not in ("script", "style"):
            self._words.append(data)
        if self._text is not None:
            self._text.append(data)


def forms_of(html: str) -> list[Form]:
    return Page(html).forms


def active(f: Field, values: dict) -> bool:
    """Is field ``f`` shown (its conditions met) when the form holds ``values``?"""
    return all(values.get(ctl) in allowed for ctl, allowed in f.when)


def activate(form: Form, target: Field, values: dict) -> dict:
    """``values`` with the selects that show ``target`` set to the first value that does."""
    out = dict(values)
    for ctl, allowed in target.when:
        if out.get(ctl) not in allowed and allowed:
            out[ctl] = allowed[0]
    return out
