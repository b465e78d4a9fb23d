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
