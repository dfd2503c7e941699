"""What the benchmarks' plot scripts share: their command line (`plot.py CSV OUT.png`) and matplotlib,
which only draws: without it, or without rows, a plot says why and the script exits 0, so that
`make bench` never fails on a plot."""
import sys


def start(argv, doc, load):
    """matplotlib's pyplot, the loaded CSV and the PNG path; exits the script when there is nothing to draw."""
    if len(argv) != 3:
        print(doc.strip().splitlines()[-1].strip(), file=sys.stderr)
        sys.exit(2)
    csv_path, png_path = argv[1], argv[2]
    try:
        import matplotlib

        matplotlib.use("Agg")  # no display: write the file only
        import matplotlib.pyplot as plt
    except ImportError as e:
        print(f"plot.py: matplotlib is not available ({e}); {png_path} not drawn")
        sys.exit(0)
    data = load(csv_path)
    if not data:
        print(f"plot.py: {csv_path} has no rows; {png_path} not drawn")
        sys.exit(0)
    return plt, data, png_path
