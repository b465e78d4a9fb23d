"""docs/architecture.md's module table is the code's: the same modules as the folders of src/,
include/rigid/ and tests/, in the order src/CMakeLists.txt builds them, each linking to the
`rigid::` targets its row names (public, then those after "privately"), only upwards, and
including only the `rigid/` headers of modules it reaches through those links. Reads files
only: it needs no build."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "architecture.md"

_CELL = re.compile(r"(?<!\\)\|")  # a table cell border (an escaped \| is text)
_NAME = re.compile(r"`([a-z_][a-z0-9_]*)`")
_INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]rigid/([a-z_][a-z0-9_]*)[/.]', re.MULTILINE)
# a module's private helpers, src/<module>/detail/, included from src/ as "<module>/detail/..."
_DETAIL = re.compile(r'^\s*#\s*include\s*"([a-z_][a-z0-9_]*)/detail/', re.MULTILINE)
_SOURCES = {".cpp", ".hpp", ".h", ".cc", ".inl"}


def _cells(line):
    return [c.strip() for c in _CELL.split(line.strip())[1:-1]]


def doc_modules():
    """The table of the "## Modules" section: [(module, public links, private links)] in order."""
    text = DOC.read_text()
    start = text.index("## Modules")
    end = text.find("\n## ", start + 1)
    section = text[start:end if end >= 0 else len(text)]
    lines = section.splitlines()
    header = next(i for i, l in enumerate(lines) if l.startswith("| module |"))
    columns = _cells(lines[header])
    assert "links to" in columns, f"the module table has no 'links to' column: {columns}"
    links = columns.index("links to")
    rows = []
    for line in lines[header + 2:]:
        if not line.startswith("|"):
            break
        cells = _cells(line)
        name = re.fullmatch(r"`([a-z_][a-z0-9_]*)`", cells[0])
        assert name, f"a row of the module table does not start with a `module`: {line!r}"
        public, _, private = cells[links].partition("privately")
        rows.append((name.group(1), _NAME.findall(public), _NAME.findall(private)))
    assert rows, "docs/architecture.md's module table has no rows"
    return rows


def folders(path):
    return {p.name for p in path.iterdir() if p.is_dir() and not p.name.startswith((".", "_"))}


def cmake_call(text, function):
    """The arguments of the first `function(...)` call in CMake text, as words."""
    start = text.index(function + "(") + len(function) + 1
    depth, i = 1, start
    while depth:
        depth += {"(": 1, ")": -1}.get(text[i], 0)
        i += 1
    body = re.sub(r"#[^\n]*", "", text[start:i - 1])
    return body.split()


def cmake_links(module):
    """(public, private) rigid:: targets of src/<module>/CMakeLists.txt's rigid_add_module."""
    words = cmake_call((ROOT / "src" / module / "CMakeLists.txt").read_text(), "rigid_add_module")
    assert words[0] == module, f"src/{module}/CMakeLists.txt makes rigid_{words[0]}"
    found = {"PUBLIC_DEPS": [], "PRIVATE_DEPS": []}
    key = None
    for w in words[1:]:
        if w in ("SOURCES", "PUBLIC_DEPS", "PRIVATE_DEPS"):
            key = w
        elif key in found and w.startswith("rigid::"):
            found[key].append(w[len("rigid::"):])
    return found["PUBLIC_DEPS"], found["PRIVATE_DEPS"]


def includes(module, pattern=_INCLUDE):
    """{included module: first file that includes it} over src/<module>/ and its public headers."""
    files = [p for base in (ROOT / "src" / module, ROOT / "include" / "rigid" / module)
             if base.is_dir() for p in sorted(base.rglob("*")) if p.suffix in _SOURCES]
    umbrella = ROOT / "include" / "rigid" / f"{module}.hpp"
    if umbrella.is_file():
        files.append(umbrella)
    out = {}
    for f in files:
        for name in pattern.findall(f.read_text(errors="replace")):
            out.setdefault(name, f.relative_to(ROOT).as_posix())
    return out


def _difference(what, documented, actual):
    missing = sorted(set(actual) - set(documented))
    extra = sorted(set(documented) - set(actual))
    return (f"{what}: missing from docs/architecture.md's module table: {missing}; "
            f"in the table but not there: {extra}")


def test_the_table_lists_the_folders_of_src_include_and_tests():
    modules = [m for m, _, _ in doc_modules()]
    assert len(modules) == len(set(modules)), f"a module is listed twice: {modules}"
    for where in ("src", "include/rigid"):
        actual = folders(ROOT / where)
        assert set(modules) == actual, _difference(f"{where}/", modules, actual)
    # tests/ holds more (cli, browser, support, install): only the modules' folders are checked
    untested = sorted(set(modules) - folders(ROOT / "tests"))
    assert not untested, f"modules without a tests/<module>/ folder: {untested}"


def test_the_table_is_in_the_build_order():
    modules = [m for m, _, _ in doc_modules()]
    text = (ROOT / "src" / "CMakeLists.txt").read_text()
    order = re.search(r"foreach\(module\s+([^)]*)\)", text).group(1).split()
    assert modules == order, (f"docs/architecture.md lists {modules}; src/CMakeLists.txt builds "
                              f"{order}")


def test_each_row_names_the_targets_its_module_links_to():
    wrong = []
    for module, public, private in doc_modules():
        if not (ROOT / "src" / module / "CMakeLists.txt").is_file():
            wrong.append(f"{module}: src/{module}/CMakeLists.txt does not exist")
            continue
        cm_public, cm_private = cmake_links(module)
        if sorted(public) != sorted(cm_public):
            wrong.append(f"{module}: the table says {sorted(public)}, "
                         f"src/{module}/CMakeLists.txt PUBLIC_DEPS {sorted(cm_public)}")
        if sorted(private) != sorted(cm_private):
            wrong.append(f"{module}: the table says privately {sorted(private)}, "
                         f"src/{module}/CMakeLists.txt PRIVATE_DEPS {sorted(cm_private)}")
    assert not wrong, "\n".join(wrong)


def test_modules_link_only_to_modules_above_them():
    rows = doc_modules()
    position = {m: i for i, (m, _, _) in enumerate(rows)}
    wrong = [f"{m} links to {d}, which is not above it" for i, (m, pub, priv) in enumerate(rows)
             for d in pub + priv if position.get(d, len(rows)) >= i]
    assert not wrong, "\n".join(wrong)


def test_modules_include_only_what_their_links_reach():
    rows = doc_modules()
    modules = {m for m, _, _ in rows}
    # what each module reaches: its links (public or private) and, through them, their public
    # links, transitively (CMake's usage requirements)
    public = {}
    for m, pub, _ in rows:  # build order: every link's public closure is known already
        public[m] = set(pub).union(*(public.get(d, set()) for d in pub))
    reach = {m: set(pub) | set(priv) | set().union(*(public.get(d, set()) for d in pub + priv))
             for m, pub, priv in rows}
    wrong = []
    for m, _, _ in rows:
        for name, where in sorted(includes(m).items()):
            if name in modules and name != m and name not in reach[m]:
                wrong.append(f"{where} includes rigid/{name}/, which {m} does not link to "
                             f"(it reaches {sorted(reach[m])})")
    assert not wrong, "\n".join(wrong)


def test_detail_headers_stay_in_their_module():
    modules = [m for m, _, _ in doc_modules()]
    wrong = [f"{where} includes {name}/detail/, private to {name}"
             for m in modules for name, where in sorted(includes(m, _DETAIL).items())
             if name in modules and name != m]
    assert not wrong, "\n".join(wrong)
