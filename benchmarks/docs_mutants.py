"""Hand mutants of the documentation site's extension (docs/_ext/asperity_docs.py): one
realistic bug at a time, each run against tests/test_docs_site.py in a scratch worktree of
the committed HEAD (the working tree is never touched). The extension lives outside the
package, so benchmarks/mutants.py (which copies the package) cannot reach it.

    python benchmarks/docs_mutants.py              # every mutant: caught / MISSED
    python benchmarks/docs_mutants.py NAME [...]   # only these

A mutant whose text no longer matches exactly once is reported stale (the code moved).
"""
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
WT = Path(tempfile.gettempdir()) / "asperity-docs-mutants"
F = "docs/_ext/asperity_docs.py"
MUTANTS = {
 "value-format-ignored": ("value = format(_lookup(json.loads(output), key), spec)", "value = str(_lookup(json.loads(output), key))"),
 "returncode-unchecked": ("if proc.returncode != expected:", "if False:"),
 "run-stores-stderr": ("self.options[\"name\"]] = \\\n                proc.stdout", "self.options[\"name\"]] = \\\n                proc.stderr"),
 "regex-group-0": ("value = found.group(1)", "value = found.group(0)"),
 "list-index-as-key": ("data = data[int(part)] if isinstance(data, list) else data[part]", "data = data[part] if isinstance(data, dict) else data[0]"),
 "commands-check-skipped": ("        if name not in documented:", "        if name not in documented and name != \"crawl\":"),
 "public-check-off-by-one": ("    for name in asperity.__all__:", "    for name in asperity.__all__[:40]:"),
 "choices-dropped": ("            extra.append(f\"choices: {listed}\")", "            pass"),
 "default-dropped": ("        extra.append(f\"default: {default}\")", "        pass"),
 "image-unchecked": ("            if not path.is_file():", "            if False:"),
 "folder-shared-across-pages": ("folder = Path(env.srcdir) / RUN_DIR / env.docname.replace(\"/\", \"--\")", "folder = Path(env.srcdir) / RUN_DIR / \"all\""),
 "hidden-run-shown": ("        if \"hide\" in self.options:\n            return []", "        if \"hide\" in self.options:\n            pass"),
 "flag-anchor-dropped": ("term = nodes.term(ids=[nodes.make_id(f\"asperity-{name}-{flag.lstrip('-')}\")])", "term = nodes.term()"),
 "group-help-dropped": ("                definition += nodes.paragraph(text=_text(action, formatter))", "                definition += nodes.paragraph(text=\"\")"),
}


def main() -> int:
    names = sys.argv[1:] or list(MUTANTS)
    unknown = [n for n in names if n not in MUTANTS]
    if unknown:
        print(f"unknown mutant(s): {', '.join(unknown)} (known: {', '.join(MUTANTS)})")
        return 2
    subprocess.run(["git", "-C", str(REPO), "worktree", "remove", "--force", str(WT)],
                   capture_output=True, check=False)
    subprocess.run(["git", "-C", str(REPO), "worktree", "add", "--detach", str(WT), "HEAD"],
                   check=True, capture_output=True)
    try:
        src = (WT / F).read_text()
        res = {}
        for name in names:
            a, b = MUTANTS[name]
            if src.count(a) != 1:
                res[name] = f"stale ({src.count(a)} matches)"
            else:
                (WT / F).write_text(src.replace(a, b))
                p = subprocess.run([sys.executable, "-m", "pytest", "-q", "-x",
                                    "tests/test_docs_site.py"], cwd=WT, capture_output=True,
                                   text=True, check=False)
                res[name] = "caught" if p.returncode else "MISSED"
            print(f"{name:30s} {res[name]}", flush=True)
        print(f"{sum(v == 'caught' for v in res.values())} of {len(res)} caught")
        return 0 if all(v == "caught" for v in res.values()) else 1
    finally:
        subprocess.run(["git", "-C", str(REPO), "worktree", "remove", "--force", str(WT)],
                       capture_output=True, check=False)


if __name__ == "__main__":
    sys.exit(main())
