"""Math as plain, monospaced text: the site must work with no network (no MathJax CDN) and
without LaTeX on the machine (imgmath needs ``latex`` and ``dvipng``)."""

from __future__ import annotations

from html import escape
from typing import Any

from docutils import nodes


def _inline(self: Any, node: nodes.Element) -> None:
    self.body.append(f'<code class="math">{escape(node.astext())}</code>')
    raise nodes.SkipNode


def _block(self: Any, node: nodes.Element) -> None:
    self.body.append(f'<pre class="math">{escape(node.astext())}</pre>\n')
    raise nodes.SkipNode


def setup(app: Any) -> dict[str, Any]:
    app.add_html_math_renderer("plainmath", (_inline, None), (_block, None))
    return {"parallel_read_safe": True, "parallel_write_safe": True}
