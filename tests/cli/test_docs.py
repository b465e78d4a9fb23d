"""The documentation lists what the code has: every name, alias and size of the primitive
catalogue appears in docs/mass.md's catalogue table."""
import pathlib

import rigid

DOCS = pathlib.Path(__file__).resolve().parents[2] / "docs"


def test_the_catalogue_table_lists_every_name_alias_and_size():
    text = (DOCS / "mass.md").read_text()
    table = text[text.index("## The primitive catalogue"):text.index("## URDF, MJCF and SDF")]
    rows = {line.split("|")[1].strip().strip("`"): line for line in table.splitlines()
            if line.startswith("| `")}
    for entry in rigid.mass.primitives():
        assert entry["name"] in rows, entry["name"]
        row = rows[entry["name"]]
        for word in entry["aliases"] + [s["name"] for s in entry["sizes"]] + entry["points"]:
            assert f"`{word}`" in row or word in row, (entry["name"], word)


def test_the_schema_example_is_the_tennis_rackets():
    """docs/scene-format.md's summary.json schema example is what rigid.Scene publishes for
    examples/tennis_racket.toml (the columns it shows, its count of columns, every other field)."""
    import json
    import re
    text = (DOCS / "scene-format.md").read_text()
    block = re.search(r"For examples/tennis_racket.toml, with two of its (\d+) columns:\n\n```json\n(.*?)```",
                      text, re.S)
    assert block, "the schema example is missing from docs/scene-format.md"
    shown = json.loads(block.group(2))
    schema = rigid.Scene(str(DOCS.parent / "examples" / "tennis_racket.toml")).schema
    assert len(schema["columns"]) == int(block.group(1))
    for column in shown["columns"]:
        assert column in schema["columns"], column
    for key in ("kind", "parameters", "diagnostics", "metrics"):
        assert shown[key] == schema[key], key
