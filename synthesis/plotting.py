"""The one place synthesis sets matplotlib's backend: files only, no display (Agg).

Imported lazily by whatever draws, so that importing synthesis loads no matplotlib.
"""


def pyplot():
    """Return ``matplotlib.pyplot`` with the non-interactive Agg backend selected."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt
