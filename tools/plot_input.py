"""What the plotting tools share: the command line (a CSV, an optional PNG beside it) and
reading the CSV with the columns a plot needs, with a message and exit code 2 for bad input."""
import os
import sys

import pandas as pd


def read_input(argv, doc, tool, default_png, needed, kind):
    """(data, target PNG path) or (None, exit code) after printing why."""
    if len(argv) not in (2, 3) or argv[1] in ("-h", "--help"):
        print(doc.strip(), file=sys.stderr)
        return None, 2
    source = argv[1]
    target = argv[2] if len(argv) == 3 else os.path.join(os.path.dirname(source), default_png)
    try:
        data = pd.read_csv(source)
    except (OSError, pd.errors.ParserError, pd.errors.EmptyDataError) as error:
        print(f"{tool}: {source}: {error}", file=sys.stderr)
        return None, 2
    missing = [c for c in needed if c not in data.columns]
    if missing or data.empty:
        print(f"{tool}: {source}: not {kind} (missing {', '.join(missing) or 'rows'})",
              file=sys.stderr)
        return None, 2
    return data, target
