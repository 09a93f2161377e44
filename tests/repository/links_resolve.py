#!/usr/bin/python3
"""Fails when a relative link or image of the README or the manual names a
file that is not in the repository (the README links into docs/, the manual
back to the README and to sources; a page moved or renamed breaks them).

  links_resolve.py REPO_ROOT
"""
import glob
import os
import re
import sys

root = sys.argv[1]
pages = [os.path.join(root, "README.md"), os.path.join(root, "python", "README.md")]
pages += sorted(glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True))
link = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
broken = []
for page in pages:
    text = open(page, encoding="utf-8").read()
    # Code blocks show commands and paths, not links.
    text = re.sub(r"(?ms)^```.*?^```", "", text)
    for target in link.findall(text):
        if re.match(r"^(https?:|mailto:|#)", target):
            continue
        if "." not in target and "/" not in target:
            continue  # not a path: a formula such as [σ_0 A, C A](1−D)
        path = os.path.normpath(os.path.join(os.path.dirname(page), target.split("#", 1)[0]))
        if not os.path.exists(path):
            broken.append(f"{os.path.relpath(page, root)}: {target}")
if broken:
    print("\n".join(broken))
    sys.exit(f"FAIL: {len(broken)} link(s) above name no file of the repository")
print(f"OK: every relative link of {len(pages)} pages resolves")
