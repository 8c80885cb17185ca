"""What the figure scripts share: running `penumbra compare --json`, keeping its sheet, and
writing a figure's README.md (the paper's claim, the command, the table, the verdict).

Every figure script takes the same options:
  --penumbra BIN  the binary (default: build/release/penumbra, else build/ci/penumbra)
  --out DIR       where the figure goes (default: docs/figures/<figure>)
  --small         a small, fast run (what the test suite runs): 96x54, 8 samples, 512² maps
"""
import argparse
import json
import os
import shlex
import shutil
import subprocess
import sys
import time

SMALL = ["--size", "96x54", "--samples", "8", "--shadow-map", "1024"]


def options(figure, description):
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--penumbra", default=None, help="the penumbra binary")
    parser.add_argument("--out", default=os.path.join("docs", "figures", figure), help="output folder")
    parser.add_argument("--small", action="store_true", help="a small, fast run (the test suite's)")
    args = parser.parse_args()
    if args.penumbra is None:
        for candidate in ("build/release/penumbra", "build/ci/penumbra"):
            if os.access(candidate, os.X_OK):
                args.penumbra = candidate
                break
    if args.penumbra is None or not os.access(args.penumbra, os.X_OK):
        sys.exit(f"{figure}: no penumbra binary (build first, or pass --penumbra)")
    os.makedirs(args.out, exist_ok=True)
    args.figure = figure
    args.rows = []
    return args


def compare(args, label, compare_args):
    """Runs compare with `compare_args` (+ the small options), keeps its sheet as <label>.png and
    returns its JSON with the command that made it (as a user types it) under "command"."""
    work = os.path.join(args.out, "work-" + label)
    full = list(compare_args) + (SMALL if args.small else [])
    command = ["penumbra", "compare"] + full
    started = time.monotonic()
    print(f"{args.figure}: {label}: {shlex.join(command)}", file=sys.stderr, flush=True)
    result = subprocess.run([args.penumbra, "compare"] + full + ["--json", "--out", work],
                            capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"{args.figure}: {label} failed ({result.returncode}): {result.stderr.strip()}")
    data = json.loads(result.stdout)
    shutil.copyfile(os.path.join(work, "sheet.png"), os.path.join(args.out, label + ".png"))
    shutil.rmtree(work)
    data["label"] = label
    data["command"] = shlex.join(command)
    data["seconds"] = round(time.monotonic() - started, 1)
    args.rows.append(data)
    return data


def fmt(value, digits=4):
    return f"{value:.{digits}g}" if isinstance(value, float) else str(value)


def table(rows, columns):
    """A markdown table: columns are (heading, key or function of a row)."""
    out = ["| " + " | ".join(h for h, _ in columns) + " |", "|" + "---|" * len(columns)]
    for r in rows:
        out.append("| " + " | ".join(fmt(k(r) if callable(k) else r[k]) for _, k in columns) + " |")
    return "\n".join(out)


def write(args, title, claim, setup, columns, verdicts, notes=""):
    """README.md and results.json of the figure. `verdicts`: (statement, holds) pairs computed from
    the numbers: what the paper says, and whether Penumbra's measurement against the reference
    agrees."""
    renderer = args.rows[0].get("gl_renderer", "") if args.rows else ""
    clock = args.rows[0].get("clock", "") if args.rows else ""
    lines = [f"# {title}", "", f"**The paper's claim.** {claim}", "", f"**Penumbra's set-up.** {setup}", "",
             table(args.rows, columns), "",
             "**Against the truth** (the ray-traced reference, `compare`'s metrics):", ""]
    for statement, holds in verdicts:
        lines.append(f"- {'agrees' if holds else 'the truth says otherwise'}: {statement}")
    if notes:
        lines += ["", notes]
    lines += ["", "Images (compare's sheet: the frame, the reference, V − V_ref with its key):", ""]
    for r in args.rows:
        lines.append(f"![{r['label']}]({r['label']}.png)")
    lines += ["", "Made by `python3 scripts/figures/" + args.figure + ".py" + (" --small" if args.small else "") +
              f"` ({'small run' if args.small else 'full size'}; GL_RENDERER {renderer}; times by {clock}; the "
              "reference at the samples each command gives). The commands, one per row:", ""]
    for r in args.rows:
        lines.append(f"    {r['command']}")
    with open(os.path.join(args.out, "README.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump({"figure": args.figure, "small": args.small, "rows": args.rows,
                   "verdicts": [{"statement": s, "agrees": bool(h)} for s, h in verdicts]}, f, indent=1)
    print(f"{args.figure}: wrote {args.out}/README.md", file=sys.stderr)
