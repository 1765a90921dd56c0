"""Checks that every relative link of the given Markdown documents leads to a file inside
the repository, and that its #anchor, if any, is a heading of the Markdown file it names
(headings turned into anchors as GitHub does). Links to web addresses are not followed.

    /usr/bin/python3 tests/docs/check_doc_links.py README.md docs/*.md
"""
import pathlib
import re
import sys

SOURCE = pathlib.Path(__file__).resolve().parents[2]
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
FENCE = re.compile(r"^```.*?^```", re.S | re.M)
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$", re.M)


def anchors(path):
    """GitHub's anchors: lower case, punctuation dropped, spaces to hyphens, -1 … for repeats."""
    seen = {}
    text = FENCE.sub("", path.read_text(encoding="utf-8"))
    for title in HEADING.findall(text):
        title = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", title)
        slug = re.sub(r"[^\w\- ]", "", title.lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        yield slug if n == 0 else f"{slug}-{n}"


def problems(doc):
    text = FENCE.sub(lambda m: "\n" * m.group(0).count("\n"), doc.read_text(encoding="utf-8"))
    for match in LINK.finditer(text):
        target = match.group(1)
        if re.match(r"[a-z][a-z0-9+.-]*:", target):
            continue
        line = text.count("\n", 0, match.start()) + 1
        name, _, anchor = target.partition("#")
        path = (doc.parent / name).resolve() if name else doc.resolve()
        if SOURCE not in path.parents and path != SOURCE:
            yield f"{doc}:{line}: {target} leaves the repository"
        elif not path.exists():
            yield f"{doc}:{line}: {target}: no such file"
        elif anchor and path.suffix == ".md" and anchor not in set(anchors(path)):
            yield f"{doc}:{line}: {target}: no heading with anchor #{anchor} in {path.name}"


if __name__ == "__main__":
    found = [p for d in sys.argv[1:] for p in problems(pathlib.Path(d))]
    print("\n".join(found) or f"{len(sys.argv) - 1} documents: every relative link resolves")
    sys.exit(1 if found else 0)
