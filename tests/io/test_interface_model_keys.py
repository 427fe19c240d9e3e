"""An ``[interface]`` protocol's refusal of a ``[model]`` key names it as the user wrote it:
``model.direct``, not ``in interface: direct`` (found by a second new user's trial)."""

from __future__ import annotations

from pathlib import Path

import pytest

from dryfriction.io.protocol import parse_protocol

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "interface_side_loaded.toml"


def test_direct_in_an_interface_protocol_is_refused_as_model_direct() -> None:
    # mistake: the InterfaceModel's check reached through the [interface] table's build, which
    # prefixes "in interface:" (the wrong table) and says "direct" without its table
    text = EXAMPLE.read_text()
    assert "eps = 0.04\n" in text
    with pytest.raises(ValueError) as e:
        parse_protocol(text.replace("eps = 0.04\n", "eps = 0.04\ndirect = 0.035\n"), "i6.toml")
    msg = str(e.value)
    assert msg.startswith("i6.toml: model.direct = 0.035 is not allowed with an [interface] "
                          "table: allowed 0"), msg
    assert "in interface" not in msg
