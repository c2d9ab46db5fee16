"""Command-line flags derived from the technique registry (``python -m synthesis``).

Every registered parameter that applies to an item kind becomes a flag of the command
that renders that kind; a flag left out takes the technique's default, so the command
line and the platform render the same clip for the same parameters.
"""

import argparse
from typing import Any

from synthesis.techniques import REGISTRY


def _flag(name: str) -> str:
    return "--" + name.replace("_", "-")


def _on_off(text: str) -> bool:
    if text not in ("on", "off"):
        raise argparse.ArgumentTypeError(f"use on or off, not {text!r}")
    return text == "on"


def add_technique_flags(command: argparse.ArgumentParser, kind: str) -> None:
    """Add a flag for every registered technique parameter that applies to *kind*.

    A flag left out takes the technique's default, so the command and the platform
    render the same clip for the same parameters.
    """
    for technique in REGISTRY.for_kind(kind):
        group = command.add_argument_group(f"{technique.label} ({technique.source})")
        for parameter in technique.parameters:
            options: dict[str, Any] = {"dest": f"technique_{parameter.name}", "default": None}
            default = parameter.label_of(parameter.default) if parameter.type != "file" else ""
            help_text = parameter.help + (f" Default: {default}." if default else "")
            if parameter.type == "choice":
                options.update(choices=parameter.choices)
            elif parameter.type == "bool":
                options.update(type=_on_off, metavar="on|off")
            elif parameter.type == "file":
                options.update(type=str, metavar="FILE")
            else:
                options.update(
                    type=int if parameter.type == "int" else float,
                    metavar=parameter.units.upper() or "N",
                )
            group.add_argument(_flag(parameter.name), help=help_text.replace("%", "%%"), **options)


def technique_values(args: argparse.Namespace) -> dict:
    """Return the technique parameters given on the command line."""
    prefix = "technique_"
    return {
        name.removeprefix(prefix): value
        for name, value in vars(args).items()
        if name.startswith(prefix) and value is not None
    }


def techniques_help() -> str:
    """Return the registered techniques as the help text lists them."""
    lines = [
        "techniques (from the registry; python -m synthesis techniques --json for the schema):"
    ]
    for technique in REGISTRY.techniques:
        kinds = ", ".join(sorted(technique.kinds))
        names = ", ".join(p.name for p in technique.parameters)
        lines.append(
            f"  {technique.name:<11} {technique.label} [{kinds}; {technique.source}]: {names}"
        )
    return "\n".join(lines)
