"""Bad config input is refused when the config is loaded (before any job), naming the file,
the key, the value and what is allowed (mechrepro.inputs, mechrepro.config)."""
from pathlib import Path

import pytest
import yaml

from mechrepro.config import ConfigError, load_paper
from mechrepro.inputs import read_yaml

SCENES_LINE = (Path(__file__).resolve().parents[1] / "config/papers/saw_chain.yaml"
               ).read_text().splitlines().index("scenes:") + 1
PITCH = "tie_strap_pitch:        {value: 8.91,  unit: mm,"

# (class, text edit of saw_chain.yaml, what the message must name)
BAD = [
    ("NaN in a parameter without a cross-check",
     lambda t: t.replace("{value: 32,    unit: \"1\", source: \"Sec. 4 (M)\"",
                         "{value: .nan,  unit: \"1\", source: \"Sec. 4 (M)\""),
     ["parameters.tie_straps_tight_side.value", "nan", "finite"]),
    ("infinity in a scene override",
     lambda t: t.replace("parameters: {sprocket_speed: 12000}", "parameters: {sprocket_speed: .inf}"),
     ["scenes.speed_12000.parameters.sprocket_speed", "inf", "finite"]),
    ("duplicate top-level key (a second scenes: block)",
     lambda t: t + "\nscenes:\n  x: {solver: difference_method, effects: []}\n",
     ["'scenes' given twice", f"line {SCENES_LINE}", "each key once"]),
    ("duplicate nested key",
     lambda t: t.replace(PITCH, "tie_strap_pitch:        {value: 8.91, value: 9.0, unit: mm,"),
     ["'value' given twice", "each key once"]),
    ("non-UTF-8 byte",
     lambda t: t.replace("Sec. 4 (p1)", "Sec. 4 (p1) \udce9"),
     ["line 10", "not UTF-8", "b'\\xe9'"]),
    ("a unit of another scale (8.91 m chain pitch)",
     lambda t: t.replace(PITCH, "tie_strap_pitch:        {value: 8.91,  unit: m,"),
     ["parameters.tie_strap_pitch.value = 8.91", "chain pitch between 3 mm and 200 mm"]),
    ("a negative pitch (schema)",
     lambda t: t.replace("value: 8.91,", "value: -8.91,"),
     ["parameters.tie_strap_pitch = -8.91", "must be > 0"]),
]


@pytest.mark.parametrize("name, edit, expect", BAD, ids=[b[0] for b in BAD])
def test_bad_input_is_refused_at_load_with_file_key_value_and_what_is_allowed(
        config_copy, name, edit, expect):
    path = config_copy / "papers" / "saw_chain.yaml"
    text = edit(path.read_text())
    path.write_bytes(text.encode("utf-8", "surrogateescape"))
    with pytest.raises(ConfigError) as err:
        load_paper(path, "ci")
    msg = str(err.value)
    assert str(path) in msg, msg
    for part in expect:
        assert part in msg, (part, msg)


def test_the_committed_configs_read_as_before(config_copy):
    """The strict reader gives the same data as the plain safe loader on valid files."""
    for path in sorted((config_copy / "papers").glob("*.yaml")):
        assert read_yaml(path) == yaml.safe_load(path.read_text()), path


def test_merge_keys_may_override(tmp_path):
    p = tmp_path / "x.yaml"
    p.write_text("a: &a {x: 1, y: 2}\nb:\n  <<: *a\n  y: 3\n")
    assert read_yaml(p) == {"a": {"x": 1, "y": 2}, "b": {"x": 1, "y": 3}}
