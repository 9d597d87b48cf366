#!/usr/bin/env python3
"""Check the docs against the tree (tests/test_docs.sh).

    python3 tests/tools/doc_paths.py REPO

1. Every repository path that README.md, docs/*.md and the folders' README.md files name
   (scripts/..., bench/..., tests/..., src/..., input/..., docs/..., figures/..., app/...)
   exists.
2. Every script (scripts/, scripts/lib, scripts/paper, scripts/scans, scripts/slurm,
   bench/*.sh|py, tests/tools/) has its line in the index scripts/README.md.
Exit 1 naming each missing path or script.
"""
import glob
import os
import re
import sys

PATH = re.compile(r"(?<![\w/.$-])((?:scripts|bench|tests|src|input|docs|figures|app)/[\w./*<>{}-]*[\w*>}])")


def docs(repo):
    files = ["README.md", "scripts/README.md"] + sorted(glob.glob(os.path.join(repo, "docs", "*.md")))
    files += sorted(os.path.relpath(p, repo) for p in glob.glob(os.path.join(repo, "src", "*", "README.md")))
    return [os.path.relpath(os.path.join(repo, f), repo) for f in files]


def missing_paths(repo):
    bad = []
    for doc in docs(repo):
        with open(os.path.join(repo, doc), encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                for path in PATH.findall(line):
                    if any(c in path for c in "*<>{}") or path.startswith(("tests/reference/", "docs/uses")):
                        continue
                    if not os.path.exists(os.path.join(repo, path)):
                        bad.append(f"{doc}:{number}: names '{path}', which is not in the repository")
    return bad


def unindexed(repo):
    with open(os.path.join(repo, "scripts", "README.md"), encoding="utf-8") as f:
        index = f.read()
    patterns = ["scripts/*.sh", "scripts/*.py", "scripts/lib/*", "scripts/paper/*.sh", "scripts/scans/*",
                "scripts/slurm/*", "bench/*.sh", "bench/*.py", "tests/tools/*"]
    bad = []
    for pattern in patterns:
        for path in sorted(glob.glob(os.path.join(repo, pattern))):
            name = os.path.relpath(path, repo)
            base = os.path.basename(name)
            if name.endswith(".pyc") or "__pycache__" in name:
                continue
            if name not in index and f"`{base}`" not in index:
                bad.append(f"scripts/README.md: no line for {name}")
    return bad


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    bad = missing_paths(argv[1]) + unindexed(argv[1])
    for line in bad:
        print(line, file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
