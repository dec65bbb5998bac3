"""tumble.model_check: the audit of a robot description as a dict, the same report `tumble model check
--json` prints (one writer for both)."""
import json
import os
import subprocess

import pytest

import tumble

SOURCE = os.environ.get("TUMBLE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
MODELS = os.path.join(SOURCE, "tests", "robot", "models")


def test_model_check_finds_each_planted_defect_and_matches_the_command_line():
    audit = tumble.model_check(os.path.join(MODELS, "arm_flawed.urdf"))
    assert audit["format"] == "urdf" and audit["model"] == "flawed"
    codes = {link["name"]: sorted({f["code"] for f in link["findings"]}) for link in audit["links"]}
    assert codes["clean"] == [] and codes["mesh_scale"] == ["mesh_scale"]
    assert codes["product_sign"] == ["tensor_mismatch"] and codes["open_mesh"] == ["open_mesh"]
    assert audit["errors"] == 9 and audit["warnings"] == 3
    clean = next(link for link in audit["links"] if link["name"] == "clean")
    # A 0.1 m cube of 2 kg: m a^2 / 6 about every axis (closed form), to rounding.
    assert clean["computed"]["inertia"]["ixx"] == pytest.approx(2 * 0.01 / 6, rel=1e-14)
    assert clean["computed"]["volume"] == pytest.approx(1e-3, rel=1e-15)
    cli = os.environ.get("TUMBLE_CLI")
    if cli:
        out = subprocess.run([cli, "model", "check", "--json", os.path.join(MODELS, "arm_flawed.urdf")],
                             capture_output=True, text=True)
        assert out.returncode == 1  # error findings
        assert json.loads(out.stdout) == audit


def test_model_check_refuses_bad_arguments_and_files():
    with pytest.raises(ValueError, match="choose 'collision' or 'visual'"):
        tumble.model_check(os.path.join(MODELS, "arm.urdf"), geometry="both")
    with pytest.raises(OSError):
        tumble.model_check(os.path.join(MODELS, "no_such_model.urdf"))
    audit = tumble.model_check(os.path.join(MODELS, "arm.urdf"), lump_fixed=True)
    assert audit["errors"] == 0 and audit["links"][-1]["lumped"] == ["fore", "tool"]
