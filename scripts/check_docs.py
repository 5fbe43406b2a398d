#!/usr/bin/env python3
"""The docs a newcomer reads stay readable: every relative link of README.md and docs/ names a file
that exists (and, with #anchor, a heading of it), and no page outside docs/log/ is longer than 600
lines (dated investigations belong in docs/log/). Exit 1 with one line per fault."""
import pathlib
import re
import sys

MAX_LINES = 600
root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else '.').resolve()
pages = [root / 'README.md'] + sorted((root / 'docs').rglob('*.md'))
link = re.compile(r'\[[^\]]*\]\(([^)\s]+)\)')


def anchors(page):
    """GitHub's anchors of a page's headings."""
    found = set()
    for line in page.read_text().splitlines():
        if line.startswith('#'):
            text = line.lstrip('#').strip().lower()
            text = re.sub(r'[^\w\- ]', '', text)
            found.add(text.replace(' ', '-'))
    return found


faults = []
for page in pages:
    text = page.read_text()
    name = page.relative_to(root)
    if 'log' not in page.relative_to(root).parts and len(text.splitlines()) > MAX_LINES:
        faults.append(f'{name}: {len(text.splitlines())} lines, more than {MAX_LINES}')
    for target in link.findall(text):
        if re.match(r'[a-z]+:', target) or target.startswith('#'):
            continue
        path, _, anchor = target.partition('#')
        resolved = (page.parent / path).resolve()
        if not resolved.exists():
            faults.append(f'{name}: link to {target}: no such file')
        elif anchor and resolved.suffix == '.md' and anchor not in anchors(resolved):
            faults.append(f'{name}: link to {target}: no such heading')
print('\n'.join(faults) if faults else f'{len(pages)} pages: links resolve, none too long')
sys.exit(1 if faults else 0)
