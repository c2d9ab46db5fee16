"""Statistics and reports on a tidy table of responses (pandas/statsmodels).

Never imports Django or any other SignStudy package; runs on a CSV from the command line
as well as inside the platform.
"""

__all__: list[str] = []
