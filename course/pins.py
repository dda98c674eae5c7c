"""Write requirements/constraints.txt from the package versions of two tested environments.

    python -m course.pins FREEZE_311 FREEZE_310

Each FREEZE file is ``pip freeze --exclude-editable`` of a ``.venv`` with every extra
installed (``pip install -e ".[test,book,lab,bench]"``) whose ``make test`` passed: the
first on Python 3.11 (its pins also serve 3.12 and later), the second on Python 3.10,
where some of the newest releases (NumPy 2.3+, SciPy 1.16+, IPython 9) no longer install.
A version both share is pinned once; the others get an environment marker.  See
CONTRIBUTING.md, "Pinned versions".
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HEADER = """\
# Tested versions of every package shapelab's extras install, 2026-11.
# Unmarked and `>= "3.11"` lines: Python 3.11 (also tested on 3.12); `< "3.11"` lines: Python 3.10.
# Regenerate with course/pins.py (see CONTRIBUTING.md, "Pinned versions").
"""


def _read(path: str) -> dict[str, tuple[str, str]]:
    pins = {}
    for n, line in enumerate(Path(path).read_text().splitlines(), 1):
        line = line.split("#")[0].strip()
        if not line:
            continue
        if "==" not in line or ";" in line:
            raise SystemExit(f"{path}:{n}: expected 'name==version' from pip freeze, got {line!r}")
        name, version = (s.strip() for s in line.split("==", 1))
        if name.lower() == "shapelab":
            continue
        pins[name.lower().replace("_", "-")] = (name, version)
    return pins


def merge(new: dict, old: dict) -> list[str]:
    out = []
    for key in sorted(set(new) | set(old)):
        if key in new and key in old and new[key][1] == old[key][1]:
            out.append(f"{new[key][0]}=={new[key][1]}")
            continue
        if key in new:
            out.append(f'{new[key][0]}=={new[key][1]} ; python_version >= "3.11"')
        if key in old:
            out.append(f'{old[key][0]}=={old[key][1]} ; python_version < "3.11"')
    return out


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 2:
        raise SystemExit(__doc__)
    lines = merge(_read(argv[0]), _read(argv[1]))
    target = ROOT / "requirements" / "constraints.txt"
    target.write_text(HEADER + "\n".join(lines) + "\n")
    print(f"{target.relative_to(ROOT)}: {len(lines)} pins, {sum(';' in l for l in lines)} with a marker")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
