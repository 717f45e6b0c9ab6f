"""Every Python snippet of README.md and docs/*.md runs as written (issue 32, item 5): the blocks
of one page run in order in one namespace, from the top of the source tree, as a reader would
paste them. A snippet that stops working fails here, naming its page and line."""
import os
import re

import pytest

from conftest import SOURCE

PAGES = [SOURCE / "README.md"] + sorted((SOURCE / "docs").rglob("*.md"))
BLOCK = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)


def snippets(page):
    text = page.read_text(encoding="utf-8")
    return [(text.count("\n", 0, m.start()) + 2, m.group(1)) for m in BLOCK.finditer(text)]


PAGES_WITH_PYTHON = [p for p in PAGES if snippets(p)]


def test_the_pages_hold_python_snippets():
    names = {p.relative_to(SOURCE).as_posix() for p in PAGES_WITH_PYTHON}
    assert {"README.md", "docs/python.md"} <= names


@pytest.mark.parametrize("page", PAGES_WITH_PYTHON, ids=[p.relative_to(SOURCE).as_posix() for p in PAGES_WITH_PYTHON])
def test_every_snippet_runs_as_written(page, monkeypatch):
    monkeypatch.chdir(SOURCE)
    namespace = {"__name__": "__snippet__"}
    for line, code in snippets(page):
        where = f"{page.relative_to(SOURCE)}:{line}"
        try:
            exec(compile(code, where, "exec"), namespace)
        except Exception as e:  # the page and line of the snippet, then what it raised
            pytest.fail(f"{where}: the snippet raised {type(e).__name__}: {e}")
