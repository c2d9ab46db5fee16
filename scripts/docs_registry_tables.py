"""The docs' tables of the registries: the techniques and the question types.

Written into docs/architecture.md's figure blocks by scripts/docs_figures.py, so a
technique or question type registered in code is in the docs' table without anyone
keeping the two in step (issue 57); tests/test_docs_figures.py fails on drift.
"""

import os

from docs_figure_blocks import _block, _table


def techniques_table() -> str:
    """Return a row per registered technique: its kinds, parameters (with their allowed
    values and units) and the seed it draws from."""
    from synthesis.techniques import REGISTRY

    def parameter(p) -> str:
        extra = ", ".join(p.choices) if p.choices else p.units
        return f"`{p.name}`" + (f" ({extra})" if extra else "")

    body = [
        [
            f"`{t.name}`",
            ", ".join(k.replace("_", " ") for k in REGISTRY.kinds if k in t.kinds),
            ", ".join(parameter(p) for p in t.parameters),
            t.source,
        ]
        for t in REGISTRY.techniques
    ]
    return _block(_table(["technique", "kinds", "parameters", "source"], body))


def questions_table() -> str:
    """Return a row per registered question type: its label, pages, export and scale."""
    import django

    # The labels are translatable (issue 55): their English needs Django's apps loaded.
    os.environ.setdefault("DJANGO_SETTINGS_MODULE", "studyplatform.settings")
    django.setup()
    from studyplatform.questions import QUESTION_TYPES

    body = [
        [
            f"`{kind}`",
            str(t.label),
            ", ".join(sorted(t.trial_kinds)),
            f"`{t.export_kind}`" if t.export_kind else "participant column",
            t.exported_scale,
            f"`{type(t).__module__.rsplit('.', 1)[-1]}.py`",
        ]
        for kind, t in QUESTION_TYPES.items()
    ]
    header = ["kind", "label", "pages", "tidy kind", "scale", "module"]
    return _block(_table(header, body))
