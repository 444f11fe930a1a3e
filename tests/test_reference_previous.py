"""`make reference` keeps the committed value of a row made from the same inputs as one more
observation: the tolerance then covers the machines the reference was ever made on, not
only the platform variants of the machine that regenerates it (issue #25: a committed value
made on another CPU differed by 1.7e-7 where this machine's variants spread 1.45e-8)."""
import pytest
import yaml

from mechrepro import reference as ref
from mechrepro.config import load_paper
from mechrepro.validation import read_table
from mechrepro.inputs import read_yaml

Q, OTHER = "dynamic_load_max", "exact_load_max"          # both read fig07_fig08 only


def tables(tmp_path, name, values):
    """One machine's variant runs: {variant: results dir} with the validation tables given
    as {variant: {quantity: (value, status)}}."""
    out = {}
    for variant, rows in values.items():
        res = tmp_path / name / variant
        path = res / "saw_chain" / "tables" / "validation.csv"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text("quantity,reproduced_value,status\n"
                        + "".join(f"{q},{v!r},{s}\n" for q, (v, s) in rows.items()))
        out[variant] = res
    return out


def machine(tmp_path, name, q_value, spread=1.45e-8, status="info"):
    return tables(tmp_path, name, {
        "native": {Q: (q_value, status), OTHER: (2.0, "info")},
        "old_cpu": {Q: (q_value + spread, status), OTHER: (2.0, "info")}})


def committed(tmp_path):
    return {r["quantity"]: r for r in read_table(tmp_path / "ref" / "ci" / "saw_chain.csv")}


def test_a_regeneration_keeps_the_other_machines_value_as_an_observation(config_copy, tmp_path):
    safety = ref.settings(config_copy)["safety"]
    # machine A makes the reference: its variants spread 1.45e-8
    ref.derive(machine(tmp_path, "A", 51.18139345), tmp_path / "ref", config_copy, ["saw_chain"], "ci")
    a = committed(tmp_path)[Q]
    assert a["inputs"] and a["variants"] == "native old_cpu"
    assert float(a["spread"]) == pytest.approx(1.45e-8, rel=1e-6)
    # machine B's native value differs by 1.7e-7, ten times more than the variants' spread:
    # the committed value of A (same inputs) is an observation, and A's check passes on B's
    ref.derive(machine(tmp_path, "B", 51.18139345 + 1.7e-7), tmp_path / "ref", config_copy,
               ["saw_chain"], "ci")
    b = committed(tmp_path)[Q]
    assert b["inputs"] == a["inputs"] and b["variants"] == "native old_cpu previous"
    assert float(b["spread"]) == pytest.approx(1.7e-7, rel=1e-6)
    assert float(b["tolerance"]) == pytest.approx(safety * 1.7e-7, rel=1e-6)
    ref.check(tmp_path / "A" / "native", tmp_path / "ref", ["saw_chain"], "ci", config_copy)
    # B regenerates again: A's value is no longer committed, but its spread is kept
    ref.derive(machine(tmp_path, "B2", 51.18139345 + 1.7e-7), tmp_path / "ref", config_copy,
               ["saw_chain"], "ci")
    assert float(committed(tmp_path)[Q]["spread"]) == pytest.approx(1.7e-7, rel=1e-6)
    ref.check(tmp_path / "A" / "native", tmp_path / "ref", ["saw_chain"], "ci", config_copy)


def test_changed_inputs_drop_the_previous_value(config_copy, tmp_path):
    ref.derive(machine(tmp_path, "A", 51.0), tmp_path / "ref", config_copy, ["saw_chain"], "ci")
    before = committed(tmp_path)
    # a parameter of the scene the row reads: another computation, its old value says nothing
    path = config_copy / "papers" / "saw_chain.yaml"
    raw = read_yaml(path)
    raw["profiles"]["ci"]["scenes"]["fig07_fig08"]["resolution"]["K"] = 400
    path.write_text(yaml.safe_dump(raw))
    ref.derive(machine(tmp_path, "B", 52.0), tmp_path / "ref", config_copy, ["saw_chain"], "ci")
    after = committed(tmp_path)
    assert after[Q]["inputs"] != before[Q]["inputs"]
    assert after[Q]["variants"] == "native old_cpu"
    assert float(after[Q]["spread"]) == pytest.approx(1.45e-8, rel=1e-6)


def test_the_digest_names_what_the_row_reads_and_nothing_else(config_copy):
    path = config_copy / "papers" / "saw_chain.yaml"
    code = ref.code_digest("saw_chain")
    digest = lambda q: ref.row_inputs(load_paper(path, "ci"), q, code)  # noqa: E731
    q0, c0 = digest(Q), digest("observed_order_load")     # reads cost_of_accuracy
    raw = read_yaml(path)
    raw["reported"]["observed_order_load"]["why"] += " (edited)"
    path.write_text(yaml.safe_dump(raw))
    assert digest(Q) == q0 and digest("observed_order_load") != c0     # another row's entry
    sweep = raw["profiles"]["ci"]["studies"]["cost_of_accuracy"]["sweep"]
    sweep["K"] = sweep["K"][:-1]                                          # a study it reads
    path.write_text(yaml.safe_dump(raw))
    c1 = digest("observed_order_load")
    assert c1 != c0 and digest(Q) == q0
    raw["profiles"]["ci"]["scenes"]["fig07_fig08"]["resolution"]["K"] = 400   # a scene
    path.write_text(yaml.safe_dump(raw))
    assert digest("observed_order_load") == c1 and digest(Q) != q0
    raw["parameters"]["teeth"]["value"] += 1                              # a parameter: all
    path.write_text(yaml.safe_dump(raw))
    assert digest("observed_order_load") != c1
    # the code a row is computed by, not the code that presents it
    assert ref.code_digest("saw_chain") != ref.code_digest("chain_drive")
    assert "report.py" in ref.PRESENTATION and "validation.py" not in ref.PRESENTATION


def test_a_previous_verdict_that_differs_with_the_same_inputs_is_refused(config_copy, tmp_path):
    ref.derive(machine(tmp_path, "A", 51.0, status="pass"), tmp_path / "ref", config_copy,
               ["saw_chain"], "ci")
    with pytest.raises(ref.DriftError, match=f"{Q}: fail natively, pass under previous"):
        ref.derive(machine(tmp_path, "B", 51.0, status="fail"), tmp_path / "ref", config_copy,
                   ["saw_chain"], "ci")


def test_a_committed_file_without_digests_adds_no_observation(config_copy, tmp_path):
    old = tmp_path / "ref" / "ci" / "saw_chain.csv"
    old.parent.mkdir(parents=True)
    old.write_text("quantity,reproduced_value,status,basis,spread,tolerance,variants,evidence\n"
                   f"{Q},50.0,info,value,0.0,1e-8,native,independent\n")
    ref.derive(machine(tmp_path, "B", 51.0), tmp_path / "ref", config_copy, ["saw_chain"], "ci")
    assert committed(tmp_path)[Q]["variants"] == "native old_cpu"
