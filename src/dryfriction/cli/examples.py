"""``dryfriction examples``: where the shipped examples are, and a copy of them to edit;
``dryfriction model``: the model's description, shipped with the package."""

from __future__ import annotations

import typer

from .common import FORCE_HELP, app, cli_errors, say


@app.command()
@cli_errors
def examples(
    copy: str = typer.Option(None, "--copy", metavar="DIR",
                             help="Copy every example (protocols, data, gallery scripts) "
                                  "into DIR."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
) -> None:
    """Print the folder of the shipped examples, or copy them into DIR (--copy DIR)."""
    from ..io.examples import copy_examples, example_files, examples_path

    if copy is None:
        print(examples_path())
        for rel in example_files():
            print(f"  {rel}")
        return
    files = copy_examples(copy, force=force, report=say)
    say(f"copied {len(files)} example files into {copy}; try: "
        f"dryfriction simulate {copy.rstrip('/')}/velocity_step.toml --out run/")


@app.command("model")
@cli_errors
def model_description(
    path: bool = typer.Option(False, "--path", help="Print where the file is instead."),
) -> None:
    """Print the model's description (Markdown): the equations, the readings the code follows
    and the units; docstrings cite its sections as docs/model.md §N."""
    from ..io.examples import model_description as where

    file = where()
    if path:
        print(file)
        return
    print(file.read_text(encoding="utf-8"), end="")
