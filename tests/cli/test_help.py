"""``--help`` of every command lists the choices of its word options and the unit of its
numbers; one option name has one meaning and one unit system across commands (the renamed
names warn for one release); no reStructuredText markup or development jargon in help."""

from __future__ import annotations

import re

import pytest
from typer.testing import CliRunner

from dryfriction.app.options import OPTIONS
from dryfriction.cli import COMMAND_MODULES, app
from dryfriction.fit.lawchoice import INITIAL_CHOICES
from dryfriction.fit.laws import FIT_LAWS
from dryfriction.fit.loadpoint import DRIVES
from dryfriction.fit.steps import ERRORS
from dryfriction.records.labsteps import SEGMENTS_SYNTAX
from dryfriction.theory.creep import CREEP_LAWS
from dryfriction.validation import FIGURE_FORMATS

runner = CliRunner()
COMMANDS = sorted(COMMAND_MODULES)


def _help(command: str) -> str:
    r = runner.invoke(app, [command, "--help"], terminal_width=400)
    assert r.exit_code == 0, r.output
    return r.stdout


def _option_lines(text: str) -> dict[str, str]:
    """Option flag -> its help (the lines up to the next option), from plain Click help."""
    out: dict[str, str] = {}
    current = None
    for line in text.splitlines():
        m = re.match(r"^  (--[\w-]+)", line)
        if m:
            current = m.group(1)
            out[current] = line
        elif current and line.startswith("    "):
            out[current] += " " + line.strip()
        else:
            current = None
    return out


@pytest.mark.parametrize("command", COMMANDS)
def test_no_markup_or_jargon_in_help(command: str) -> None:
    text = _help(command)
    assert "`" not in text and not re.search(r"issue \d|spec §", text), text


@pytest.mark.parametrize("command", [c for c in COMMANDS if c in OPTIONS])
def test_choices_are_listed(command: str) -> None:
    lines = _option_lines(_help(command))
    for opt in OPTIONS[command].values():
        flag = opt.flag.split("/")[0]
        if opt.choices and flag in lines:
            assert "[" + "|".join(opt.choices) + "]" in lines[flag], (command, flag)


def test_declared_choices_are_the_librarys() -> None:
    fit = OPTIONS["fit"]
    assert fit["creep"].choices == OPTIONS["static"]["creep"].choices == CREEP_LAWS
    assert fit["state_law"].choices == (*FIT_LAWS, "auto")
    assert set(fit["initial_state"].choices) == set(INITIAL_CHOICES)
    assert set(fit["drive"].choices) == set(DRIVES)
    assert fit["errors"].choices == ERRORS
    assert fit["fmt"].choices == FIGURE_FORMATS


UNIT = re.compile(r"\[[^\]]*[A-Za-z0-9][^\]]*\]|\b(m/s|1/m|s/m|s\^2/m|m|s|a0/t0|t0|a0|F_el"
                  r"|Pa)\b|, s\b|(?i:\b(dimensionless|seconds|dots per inch)\b)")
"""A unit in an option's help: ``[a0/t0]``, ``m/s``, ``, s``, ``dimensionless``."""
CLICK_NOTES = re.compile(r"\[(default|required)[^\]]*\]")


@pytest.mark.parametrize("command", COMMANDS)
def test_every_number_option_gives_its_unit(command: str) -> None:
    lines = _option_lines(_help(command))
    missing = [flag for flag, line in lines.items()
               if re.search(r"<float>|<int>|FLOAT|V1,V2", line)
               and flag != "--workers"  # a count of processes
               and not UNIT.search(CLICK_NOTES.sub("", line.split(None, 2)[-1]))]
    assert missing == [], (command, [lines[f] for f in missing])


def test_segments_syntax_in_help() -> None:
    for command in ("fit", "record"):
        assert "START:VELOCITY" in " ".join(_help(command).split()), command
    assert "START:VELOCITY" in SEGMENTS_SYNTAX


def test_one_name_one_unit_system() -> None:
    # --hold: position|force in static only; rsf's hold time is --hold-time (s)
    assert "--hold" not in _option_lines(_help("rsf")) and "--hold-time" in _help("rsf")
    # --v-ref is m/s (fit); the theory commands' reduced one is --u-ref
    # --mass and --damping are SI (rsf); stability's reduced ones are --M and --eta
    for command in ("static", "steady", "stability"):
        lines = _option_lines(_help(command))
        assert "--v-ref" not in lines and "--u-ref" in lines, command
    lines = _option_lines(_help("stability"))
    assert "--mass" not in lines and "--damping" not in lines
    assert {"--M", "--eta"} <= set(lines)


def test_old_names_warn_and_still_work(tmp_path) -> None:
    new = runner.invoke(app, ["stability", "--eps", "0.04", "--u", "0.3", "--M", "0.2",
                              "--eta", "0.7", "--direct", "0.01", "--u-ref", "2.5", "--json"])
    old = runner.invoke(app, ["stability", "--eps", "0.04", "--u", "0.3", "--mass", "0.2",
                              "--damping", "0.7", "--direct", "0.01", "--v-ref", "2.5",
                              "--json"])
    assert new.exit_code == old.exit_code == 0, old.output
    assert new.stdout == old.stdout
    assert "warning: --mass is deprecated here, use --M" in old.stderr
    assert "warning: --v-ref is deprecated here, use --u-ref" in old.stderr
    assert "deprecated" not in new.stderr
    r = runner.invoke(app, ["rsf", "--case", "shs", "--hold", "7", "--json"])
    assert r.exit_code == 0 and "use --hold-time" in r.stderr, r.output
    both = runner.invoke(app, ["stability", "--eps", "0.04", "--u", "0.3", "--M", "0.2",
                               "--mass", "0.3", "--eta", "1"])
    assert both.exit_code == 2 and "--mass and --M are one option" in both.stderr


def test_a_refusal_names_the_new_option() -> None:
    r = runner.invoke(app, ["stability", "--eps", "0.04", "--u", "0.3", "--M", "-1",
                            "--eta", "1"])
    assert r.exit_code == 2 and r.stderr.count("\n") == 1 and "--M" in r.stderr, r.output
    r = runner.invoke(app, ["rsf", "--hold-time", "-1"])
    assert r.exit_code == 2 and "--hold-time" in r.stderr, r.output


def test_reproduce_lists_every_file_it_wrote(tmp_path, monkeypatch) -> None:
    # the files from the workflow, extra_*.png included; no unexplained C_inf/C_LS
    from dryfriction.app import runs
    from dryfriction.app.outcome import RunOutcome
    from dryfriction.plots.report import DATA_FILES, EXTRA_FILES, FIGURE_FILES

    files = [*FIGURE_FILES, *EXTRA_FILES, *DATA_FILES]
    monkeypatch.setattr(runs, "reproduce", lambda out, **kw: RunOutcome(out, files, {}))
    r = runner.invoke(app, ["reproduce", "--out", str(tmp_path / "o")], terminal_width=300)
    assert r.exit_code == 0, r.output
    text = " ".join(r.stdout.split())
    assert all(f in text for f in files) and "extra_*" in text
    assert "C_inf" not in text and "C_LS" not in text


def test_stability_help_explains_every_column() -> None:
    """Every column ``stability`` prints is explained in its help (a column such as
    forward_stiffness reached users unexplained)."""
    import json

    out = runner.invoke(app, ["stability", "--eps", "0.03", "--u", "0.07", "--json"])
    assert out.exit_code == 0, out.output
    cols = [k for k, v in json.loads(out.output).items() if isinstance(v, list)]
    assert {"K_c", "forward_stiffness", "backward_stiffness"} <= set(cols)
    text = " ".join(runner.invoke(app, ["stability", "--help"],
                                  env={"COLUMNS": "200"}).output.split())
    words = text.split("Options:")[0]
    for c in cols:
        assert f"{c}," in words or f"{c} " in words, (c, words)


def test_the_commands_defaults_load_no_scipy() -> None:
    """``dryfriction --help`` reads the commands' defaults (``app.options`` -> ``theory.model``
    -> ``theory.creep``) but computes nothing: ``scipy.special`` imported there cost ~0.13 s of
    its ~0.2 s of CPU (bench_cli: 0.195 -> 0.337 s). Mistake caught: creep.py importing exp1
    at the top."""
    import subprocess
    import sys

    code = ("import sys\nimport dryfriction.app.options\n"
            "print('SCIPY', 'scipy' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120).stdout
    assert "SCIPY False" in out


def test_the_whole_command_loads_no_scipy_stats() -> None:
    """Every command runs after the whole command line is imported, ``--help`` too:
    ``scipy.stats`` costs ~0.4 s of import there (``records.placement`` took its chi-square
    quantile from it). Mistake caught: ``from scipy.stats import chi2`` at placement's top."""
    import subprocess
    import sys

    code = ("import sys\nimport dryfriction.cli.commands\n"
            "print('STATS', 'scipy.stats' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120).stdout
    assert "STATS False" in out


def test_the_chi_square_quantile_is_the_squared_normal_one() -> None:
    """``records.placement``'s one-degree chi-square quantile against SciPy's own at generic
    levels (mistake: the normal quantile at ``level`` rather than ``(1 + level)/2``)."""
    from scipy.stats import chi2

    from dryfriction.records.placement import _chi2_1

    for level in (0.37, 0.9, 0.95, 0.995):
        assert abs(_chi2_1(level) - chi2.ppf(level, 1)) < 1e-10 * chi2.ppf(level, 1)
