"""MkDocs hook: every figure of a page links to its own file, so that a click opens it at full
size (the column shrinks a wide, multi-panel figure until its ticks and legends are hard to read)."""

import re

IMAGE = re.compile(r"<img\b[^>]*?\bsrc=\"([^\"]+)\"[^>]*>")


def _inside_link(html: str, position: int) -> bool:
    return html.rfind("<a ", 0, position) > html.rfind("</a>", 0, position)


def link_figures(html: str) -> str:
    """`html` with each image that is not already inside a link wrapped in a link to its file."""

    def wrap(match: re.Match) -> str:
        if _inside_link(html, match.start()):
            return match.group(0)
        return (
            f'<a class="figure-link" href="{match.group(1)}" title="Open the figure at full size">{match.group(0)}</a>'
        )

    return IMAGE.sub(wrap, html)


def on_page_content(html: str, page, config, files) -> str:
    """Link the page's figures to their files."""
    return link_figures(html)
