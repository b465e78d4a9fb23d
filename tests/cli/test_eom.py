"""`rigid eom --format text|latex|json`: the same bytes from separate processes, the textbook
forms, labels that cannot be mistaken for symbols, and the same document from the CLI and
from Python."""
import json
import re
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
SCENES = sorted(EXAMPLES.glob("*.toml"))
FORMATS = ["text", "latex", "json"]


@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.stem)
def test_two_processes_print_the_same_bytes(run, scene, fmt):
    # GiNaC orders terms by hashes that change from run to run; the printer may not
    first = run("eom", scene, "--format", fmt, check=True).stdout
    second = run("eom", scene, "--format", fmt, check=True).stdout
    assert first == second
    if fmt == "json":
        json.loads(first)


def test_text_is_the_default_and_latex_an_alias(run):
    scene = EXAMPLES / "double_pendulum.toml"
    assert run("eom", scene, check=True).stdout == run("eom", scene, "--format", "text", check=True).stdout
    assert run("eom", scene, "--latex", check=True).stdout == run("eom", scene, "--format", "latex", check=True).stdout


def test_double_pendulum_mass_matrix_has_cos_of_the_difference(run):
    scene = EXAMPLES / "double_pendulum.toml"
    doc = json.loads(run("eom", scene, "--format", "json", check=True).stdout)
    M = doc["mass_matrix"]["text"]
    assert M == [["(m1 + m2)*l1^2", "m2*l1*l2*cos(theta1 - theta2)"],
                 ["m2*l1*l2*cos(theta1 - theta2)", "m2*l2^2"]]
    assert "\\cos(\\theta_{1} - \\theta_{2})" in doc["mass_matrix"]["latex"][0][1]
    text = run("eom", scene, check=True).stdout
    assert "  [(m1 + m2)*l1^2, m2*l1*l2*cos(theta1 - theta2)]\n" in text
    latex = run("eom", scene, "--format", "latex", check=True).stdout
    assert "\\cos(\\theta_{1} - \\theta_{2})" in latex


@pytest.mark.parametrize("scene", ["physical_pendulum", "cone_pendulum"])
def test_labels_do_not_collide_with_parameters_named_L_or_h(run, scene):
    # physical_pendulum has a parameter L, cone_pendulum a parameter h: no label reads "L =" or
    # "h =" (text headings are words, LaTeX labels \mathcal{L}, \mathcal{H})
    text = run("eom", EXAMPLES / f"{scene}.toml", check=True).stdout
    for line in text.splitlines():
        assert not re.match(r"\s*[A-Za-z_]\w*\s*=", line), line
    latex = run("eom", EXAMPLES / f"{scene}.toml", "--format", "latex", check=True).stdout
    assert "\\mathcal{L} &=" in latex and "\\mathcal{H} &=" in latex
    for line in latex.splitlines():
        assert not re.match(r"\s*[A-Za-z]\s*&?=", line), line


def test_latex_equations_are_in_align_environments(run):
    latex = run("eom", EXAMPLES / "atwood.toml", "--format", "latex", check=True).stdout
    assert latex.count("\\begin{align*}") == latex.count("\\end{align*}") >= 4
    body = latex.split("\\begin{align*}\n", 1)[1].split("\\end{align*}", 1)[0]
    assert len(body.strip().split(" \\\\\n")) == 3  # one equation per coordinate: y1, y2, phi


def test_json_lists_every_quantity(run):
    doc = json.loads(run("eom", EXAMPLES / "atwood.toml", "--format", "json", check=True).stdout)
    assert doc["coordinates"] == ["y1", "y2", "phi"]
    assert [p["name"] for p in doc["parameters"]] == ["g", "m1", "m2", "M", "R"]
    assert doc["constraint_names"] == ["rope1", "rope2"]
    for key in ("lagrangian", "kinetic_energy", "potential_energy", "jacobi_integral"):
        assert set(doc[key]) >= {"text", "latex"}
    assert len(doc["mass_matrix"]["text"]) == 3 and all(len(r) == 3 for r in doc["mass_matrix"]["latex"])
    assert doc["constraint_jacobian"]["text"] == [["1", "0", "-R"], ["0", "1", "R"]]
    assert doc["jacobi_integral"]["conserved"] is True
    units = {s["name"]: s["unit"] for s in doc["symbols"]}
    assert units["t"] == "s"


def test_free_body_scenes_in_every_format(run):
    doc = json.loads(run("eom", EXAMPLES / "heavy_top.toml", "--format", "json", check=True).stdout)
    assert doc["kind"] == "free_bodies" and doc["bodies"][0]["pivot"] is True
    assert any("w1_dot" in line for line in doc["bodies"][0]["text"])


def test_bad_format_is_refused(run):
    p = run("eom", EXAMPLES / "atwood.toml", "--format", "html", check=False)
    assert "--format: unknown equation format 'html'; expected text, latex or json" in p.stderr
    p = run("eom", EXAMPLES / "atwood.toml", "--latex", "--format", "json", check=False)
    assert "--latex and --format json ask for two formats" in p.stderr


def test_python_prints_what_the_cli_prints(run):
    rigid = pytest.importorskip("rigid")
    for scene in (EXAMPLES / "double_pendulum.toml", EXAMPLES / "heavy_top.toml"):
        for fmt in FORMATS:
            assert rigid.Scene(scene).equations(format=fmt) == run("eom", scene, "--format", fmt, check=True).stdout
    with pytest.raises(rigid.Error, match="unknown equation format 'html'"):
        rigid.Scene(EXAMPLES / "atwood.toml").equations(format="html")


def test_python_system_equations_are_an_object():
    rigid = pytest.importorskip("rigid")
    s = rigid.lagrange.System(coordinates=[("theta1", 0, 0), ("theta2", 0, 0)],
                              parameters={"m1": 1.0, "m2": 1.0, "l1": 1.0, "l2": 1.0},
                              lagrangian="(m1 + m2)/2*l1^2*theta1_dot^2 + m2*l1*l2*cos(theta1 - theta2)*theta1_dot*theta2_dot"
                                         " + m2/2*l2^2*theta2_dot^2")
    eq = s.equations()
    assert eq.coordinates == ["theta1", "theta2"]
    assert eq.mass_matrix[0][1].text == "m2*l1*l2*cos(theta1 - theta2)"
    assert "\\frac{1}{2}" in eq.lagrangian.latex
    assert "theta1_ddot" in repr(eq) and eq["text"] == eq.text
    assert json.loads(eq.format("json"))["mass_matrix"]["text"][1][1] == "m2*l2^2"


def test_docs_show_what_the_program_prints(run):
    # docs/lagrange.md pastes the double pendulum in every format: the pasted blocks cannot drift
    root = EXAMPLES.parent
    doc = (root / "docs" / "lagrange.md").read_text()
    blocks = re.findall(r"<!-- rigid eom (\S+) --format (\w+) -->\n```\w*\n(.*?)```\n", doc, re.S)
    assert sorted(b[1] for b in blocks) == sorted(FORMATS)
    for scene, fmt, body in blocks:
        assert body == run("eom", root / scene, "--format", fmt, check=True).stdout, fmt
