"""The core's stages depend on each other as docs/design.md says, without cycles: a file of a
stage includes headers of its own stage and of the stages listed for it, nothing else.

Usage: python3 check_stage_dependencies.py <Filters/Core>"""

import pathlib
import re
import sys

ALLOWED = {
    "Common": set(),
    "Mesh": {"Common"},
    "Conformal": {"Common", "Mesh"},
    "Transport": {"Common"},
    "Sampling": {"Common", "Transport"},  # sample masses are power-cell integrals
    "Composition": {"Common", "Mesh"},
    "Pipeline": {"Common", "Mesh", "Conformal", "Sampling", "Transport", "Composition"},
}

core = pathlib.Path(sys.argv[1])
include = re.compile(r'^\s*#\s*include\s+"([A-Za-z]+)/')
problems, files = [], 0
for path in sorted(core.glob("*/*")):
    if path.suffix not in (".h", ".cxx"):
        continue
    stage = path.parent.name
    if stage not in ALLOWED:
        problems.append(f"{path}: folder {stage} is not a stage of the core")
        continue
    files += 1
    for number, line in enumerate(path.read_text().splitlines(), 1):
        match = include.match(line)
        if match and match.group(1) != stage and match.group(1) not in ALLOWED[stage]:
            problems.append(f"{path}:{number}: {stage} includes {match.group(1)}/")
print("\n".join(problems) or f"{files} core files include only the stages they may")
sys.exit(1 if problems or files == 0 else 0)
