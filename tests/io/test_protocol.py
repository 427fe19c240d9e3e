"""Protocol files: TOML -> validated parameters; every bad input is one clear error."""

from __future__ import annotations

import tracemalloc
from pathlib import Path

import numpy as np
import pytest

from dryfriction.ensemble.driving import ForceDrive, Output, SpringDrive, VelocityDrive, simulate
from dryfriction.ensemble.population import Initial, Track, TrapModel
from dryfriction.ensemble.resources import estimate_run
from dryfriction.io.protocol import InterfaceProtocol, RSFProtocol, load_protocol, parse_protocol
from dryfriction.program import Segment, VelocityProgram
from dryfriction.validation import memory_limit, parse_bytes

# sweep protocols ([sweep] table) are checked point by point in test_stickslip.py
EXAMPLES = sorted(p for p in (Path(__file__).parents[2] / "examples").glob("*.toml")
                  if "\n[sweep]" not in p.read_text())

GOOD = """
[model]
alpha = 0.13
eps = 0.04
creep = "log"
mu_el = 0.5

[ensemble]
traps_per_a0 = 100
layout = "random"
seed = 3
initial = "loaded"
initial_force = 0.4

[drive]
kind = "velocity"
segments = [{velocity = 1.0, slip = 2.0}, {velocity = 0, duration = 10}]

[output]
every_slip = 0.01
snapshots = [1, 2.5]
"""


def test_good_protocol_round_trip() -> None:
    p = parse_protocol(GOOD, "good.toml")
    assert p.model.mu_el == 0.5 and p.track.layout == "random" and p.track.seed == 3
    assert p.initial.kind == "loaded" and p.initial.force == 0.4
    assert isinstance(p.drive, VelocityDrive)
    assert p.drive.program.total_time == pytest.approx(12.0)
    assert p.output.snapshots == (1.0, 2.5)


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_examples_are_valid(path: Path) -> None:
    p = load_protocol(path)
    if isinstance(p, RSFProtocol):  # model.law = "rsf": SI, rsf.driving.simulate
        assert p.program.total_time > 0
        return
    if isinstance(p, InterfaceProtocol):  # an [interface] table: a chain of blocks (issue 29)
        assert p.drive.loading in ("uniform", "side") and p.model.n_elements >= 1
        return
    assert isinstance(p.drive, (VelocityDrive, ForceDrive, SpringDrive))


def _edit(old: str, new: str) -> str:
    assert old in GOOD
    return GOOD.replace(old, new)


BAD = [
    ("[model", "malformed TOML"),  # unterminated table header
    (_edit("mu_el = 0.5", "mu_el = 0.5\nfriction = 1"), r"unknown key\(s\) model.friction"),
    (_edit("eps = 0.04\n", ""), r"model.eps is missing"),
    (_edit("eps = 0.04", 'eps = "small"'), r"model.eps = 'small' has the wrong type"),
    (_edit("eps = 0.04", "eps = true"), r"model.eps = True has the wrong type"),
    (_edit("eps = 0.04", "eps = -0.04"), r"in model: eps = -0.04 is out of range"),
    (_edit('creep = "log"', 'creep = "power"'), r"in model: creep = 'power' is not allowed"),
    (_edit("traps_per_a0 = 100", "traps_per_a0 = -100"),
     r"in ensemble: traps_per_a0 = -100 is out of range"),
    (_edit("seed = 3\n", ""), r"in ensemble: seed is required"),
    (_edit("seed = 3", "seed = 3.5"), r"ensemble.seed = 3.5 has the wrong type"),
    (_edit("initial_force = 0.4\n", ""), r"in ensemble: initial_force is required"),
    (_edit("initial_force = 0.4", "initial_force = 0.4\ninitial_velocity = 1"),
     r"initial_velocity applies only"),
    (_edit("duration = 10", "duration = -10"),
     r"in drive.segments\[1\]: duration = -10 is out of range"),
    (_edit("slip = 2.0", "slip = 2.0, duration = 1"),
     r"drive.segments\[0\]: a segment needs exactly one"),
    (_edit("segments = [", "rate = 1\nsegments = ["), r"drive key\(s\) rate applies to another"),
    (_edit('kind = "velocity"', 'kind = "push"'), r"drive.kind = 'push' is not allowed"),
    (_edit("every_slip = 0.01", "every_slip = 0.01\nevery = 1"), r"in output: give exactly one"),
    (_edit("every_slip = 0.01", "every_slip = 0"), r"in output: every_slip = 0 is out of range"),
    (GOOD + "\n[extra]\nx = 1\n", r"unknown table\(s\) extra"),
    # a misspelt table is answered with the name meant, and a sweep's table with where it
    # belongs (a new user's [modle] got a list without the other kinds' tables)
    (GOOD.replace("[model]", "[modle]"),
     r"unknown table\(s\) modle: allowed model, ensemble, drive, output "
     r"\(\[modle\]: did you mean \[model\]\?; an \[interface\] table makes it an "
     r"extended-interface protocol\)$"),
    (GOOD + "\n[interfase]\nx = 1\n", r"\[interfase\]: did you mean \[interface\]\?\)$"),
    (GOOD + "\n[stickslip]\nx = 1\n",
     r"\[stickslip\] belongs to a sweep protocol, run with dryfriction sweep"),
    (GOOD.replace("[output]\nevery_slip = 0.01\nsnapshots = [1, 2.5]\n", ""),
     r"table 'output' is missing"),
]


@pytest.mark.parametrize("text, match", BAD)
def test_bad_protocols_name_file_and_key(text: str, match: str) -> None:
    with pytest.raises(ValueError, match=r"^bad\.toml: .*" + match):
        parse_protocol(text, "bad.toml")


SPRING = """
[model]
eps = 0.04
[ensemble]
traps_per_a0 = 100
initial = "rest"
[drive]
kind = "spring"
stiffness = {K}
mass = {M}
damping = {eta}
segments = [{{velocity = 1.0, slip = 1.0}}]
[output]
every = 0.1
"""


@pytest.mark.parametrize(
    "K, M, eta, match",
    [
        (0.0, 0.0, 0.0, r"in drive: stiffness = 0 is out of range: allowed finite and > 0"),
        (-1.0, 1.0, 0.0, r"in drive: stiffness = -1 is out of range"),
        (1.0, -1.0, 0.0, r"in drive: mass = -1 is out of range"),
        (1.0, 0.0, 0.5, r"in drive: damping = 0.5 is not allowed with mass = 0"),
    ],
)
def test_spring_checks(K: float, M: float, eta: float, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        parse_protocol(SPRING.format(K=K, M=M, eta=eta), "s.toml")


def test_force_drive_needs_a_growing_force() -> None:
    text = """
[model]
eps = 0.0
[ensemble]
traps_per_a0 = 100
initial = "rest"
[drive]
kind = "force"
rate = 0
[output]
every = 0.1
"""
    with pytest.raises(ValueError, match=r"in drive: rate = 0 is out of range"):
        parse_protocol(text, "f.toml")
    with pytest.raises(ValueError, match=r"drive.rate is missing"):
        parse_protocol(text.replace("rate = 0\n", ""), "f.toml")


def test_unreadable_file(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="cannot read"):
        load_protocol(tmp_path / "nope.toml")
    bad = tmp_path / "bin.toml"
    bad.write_bytes(b"a = \x80\x81")
    with pytest.raises(ValueError, match="bin.toml: malformed TOML"):
        load_protocol(bad)
    bad.write_bytes(b"\xff\xfe\x00")  # a UTF-16 byte-order mark: said as such (issue 24)
    with pytest.raises(ValueError, match="bin.toml is UTF-16 text: save it as UTF-8"):
        load_protocol(bad)


def test_protocol_from_dict_matches_text() -> None:
    import tomllib

    from dryfriction.io.protocol import protocol_from_dict

    assert protocol_from_dict(tomllib.loads(GOOD), "good.toml") == parse_protocol(GOOD, "good.toml")


# ---------------------------------------------------------------- resource checks (issue 13)


@pytest.mark.parametrize(
    "make, key",
    [
        (lambda: dict(initial=Initial("rest", track=Track(1e10))), "traps_per_a0 = 1e+10"),
        (lambda: dict(initial=Initial("rest", track=Track(1e308))), "traps_per_a0 = 1e+308"),
        (lambda: dict(output=Output(every=1e-300)), "every = 1e-300"),
        (lambda: dict(drive=VelocityDrive(VelocityProgram([Segment(1.0, slip=1e300)]))),
         "every_slip = 0.01"),
        (lambda: dict(drive=ForceDrive(rate=1e-6), output=Output(every=1e-3)), "every = 0.001"),
        # within the run's 1 t0 (snapshots after its end are refused since issue 24)
        (lambda: dict(output=Output(every_slip=0.01, snapshots=tuple(np.arange(1, 5001) * 2e-4)),
                      initial=Initial("rest", track=Track(1e5))), "snapshots"),
    ],
)
def test_simulate_refuses_what_the_machine_cannot_hold(monkeypatch: pytest.MonkeyPatch, make,
                                                       key: str) -> None:
    monkeypatch.setenv("DRYFRICTION_MEMORY_LIMIT", "8GiB")
    args = dict(model=TrapModel(eps=0.04), initial=Initial("rest", track=Track(100.0)),
                drive=VelocityDrive(VelocityProgram([Segment(1.0, slip=1.0)])),
                output=Output(every_slip=0.01))
    args.update(make())
    with pytest.raises(ValueError, match="more than the limit 8.0 GiB") as exc:
        simulate(**args)
    assert key in str(exc.value) and "DRYFRICTION_MEMORY_LIMIT" in str(exc.value)
    assert "output." not in str(exc.value)  # API names, not protocol keys


@pytest.mark.slow
def test_the_estimate_bounds_what_a_run_holds() -> None:
    # the per-sample and per-pair costs against tracemalloc's peak: a bound, not far above it
    model, drive = TrapModel(eps=0.04), VelocityDrive(VelocityProgram([Segment(1.0, slip=3.0)]))
    simulate(model, drive, Initial("rest", track=Track(10.0)),
             Output(every_slip=1.0))  # load the kernel
    for track, output in [(Track(10.0), Output(every_slip=1e-4)),     # samples dominate
                          (Track(1e5), Output(every_slip=0.5))]:     # pairs dominate
        est = estimate_run(model, track, Initial("rest"), drive, output)
        tracemalloc.start()
        res = simulate(model, drive, Initial("rest", track=track), output)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        assert len(res.t) <= est.samples <= len(res.t) + 5
        assert peak <= est.total_bytes <= 3.0 * peak


@pytest.mark.parametrize(
    "text, value",
    [("8GiB", 8 * 2**30), ("512 MB", 512e6), ("1e9", 1e9), ("100kib", 102400.0)],
)
def test_memory_sizes(text: str, value: float) -> None:
    assert parse_bytes(text) == value


@pytest.mark.parametrize("text", ["lots", "-1GiB", "0", "inf", "8 GiBs", "nan"])
def test_bad_memory_sizes_name_the_variable(text: str) -> None:
    with pytest.raises(ValueError, match="DRYFRICTION_MEMORY_LIMIT"):
        parse_bytes(text)


def test_default_limit_is_half_the_available_memory(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("DRYFRICTION_MEMORY_LIMIT", raising=False)
    avail = next(int(ln.split()[1]) * 1024 for ln in Path("/proc/meminfo").read_text().splitlines()
                 if ln.startswith("MemAvailable:"))
    assert memory_limit() == pytest.approx(0.5 * avail, rel=0.2)  # it moves while we read


def test_continue_spring_refuses_what_the_machine_cannot_hold(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from dryfriction.ensemble.driving import continue_spring
    from dryfriction.ensemble.population import Ensemble

    monkeypatch.setenv("DRYFRICTION_MEMORY_LIMIT", "8GiB")
    ens = Ensemble(TrapModel(eps=0.04), Track(100.0), Initial("rest"))
    drive = SpringDrive(stiffness=1.0, mass=0.0,
                        program=VelocityProgram([Segment(1.0, slip=1e300)]))
    with pytest.raises(ValueError, match="every_slip = 0.01 gives 1.0e\\+302 samples"):
        continue_spring(ens, drive, Output(every_slip=0.01))
    assert ens.t == 0.0 and ens.x == 0.0  # nothing was run


def test_too_many_samples_refused_before_any_work() -> None:
    """1e7 samples fit in memory at 5 traps/a0 but take minutes to record and a ~1 GB CSV: the
    run is refused at once, naming the key (a fuzz case that ran for over two minutes)."""
    from dryfriction.ensemble.driving import VelocityDrive, simulate
    from dryfriction.ensemble.population import Initial, Track
    from dryfriction.ensemble.resources import MAX_SAMPLES

    drive = VelocityDrive(VelocityProgram([Segment(0.5, duration=1e6)]))
    with pytest.raises(ValueError, match=r"every = 0.1 gives 1.0e\+07 samples, over the 2e\+06"):
        simulate(TrapModel(eps=0.04), drive, Initial("steady", velocity=0.5, track=Track(5.0)),
                 Output(every=0.1))
    # just under the cap it is not refused for its samples
    ok = VelocityDrive(VelocityProgram([Segment(0.5, duration=0.5 * MAX_SAMPLES * 0.1)]))
    from dryfriction.ensemble.resources import check_run
    est = check_run(TrapModel(eps=0.04), Track(5.0), Initial("steady", velocity=0.5), ok,
                    Output(every=0.1))
    assert est.samples <= MAX_SAMPLES
