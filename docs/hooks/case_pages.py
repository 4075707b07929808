"""mkdocs hook: one page per validation case, generated from ``cases/<id>/README.md``.

The case folders keep their README (read in the repository, beside the
case's data); the site shows the same text under ``explanation/cases/<id>``,
with the links between cases and to the docs rewritten for the site.
"""

import re
from pathlib import Path

from mkdocs.structure.files import File

_CASE_LINK = re.compile(r"\]\(\.\./([\w-]+)/README\.md\)")


def on_files(files, config):
    root = Path(config.config_file_path).parent
    for readme in sorted((root / "cases").glob("*/README.md")):
        text = _CASE_LINK.sub(r"](\1.md)", readme.read_text(encoding="utf-8"))
        text = text.replace("](../../docs/explanation/", "](../")
        files.append(File.generated(config, f"explanation/cases/{readme.parent.name}.md",
                                    content=text))
    return files
