"""Every fenced block of README.md and docs/*.md runs as written.

Each block is run in a scratch directory (pytest's tmp_path) that holds a copy of examples/ and
a link build/ci to the build that RIGID_EXE names, with `rigid` (RIGID_EXE) and `python3`
(/usr/bin/python3, RIGID_PYTHON_DIR on PYTHONPATH) first on PATH and HOME set to the scratch
directory:

- ```sh: the commands (a line, or lines joined by a trailing `\\`; comment lines skipped) run in
  order in one bash, as typed into a terminal (a `cd` holds for the lines after it); the first
  non-zero exit stops the block and fails the test with the command's file:line.
- ```python: the block runs as a script under /usr/bin/python3.
- ```toml: the block is a whole scene, written to scene.toml and checked by `rigid check`.
- ```cpp: the blocks that start `// FILE.cpp: build and run with` are built and run by
  tests/cli/test_docs_robots.py; any other cpp block must be marked (below).
- A block of output (```text, ```json, ```latex or an unlabelled one) is compared with the
  program's output when the command that printed it is known: an unlabelled block whose lines
  start `$ COMMAND` followed by that command's output, or any of these blocks preceded by an
  HTML comment `<!-- rigid ... -->` naming the command. Words must match; a number matches when
  the program's value rounds to the digits printed in the docs (one unit of the last digit).
  Other output blocks are prose (error messages quoted as examples) and are not run.

A block is marked with one HTML comment line directly above its opening fence:

    <!-- fragment: REASON -->       not run (an excerpt, or a command that installs, builds the
                                    whole project or runs for minutes); counted per language
    <!-- continues -->              python: runs after the file's previous python block, in the
                                    same process (the page's example goes on)
    <!-- file: PATH -->             the block's text is written to PATH (relative to the scratch
                                    directory) before it runs; a TOML block is checked there

Every sh, python, toml, cpp and cmake block is either run or marked; test_every_block_is_run
prints the counts per language.
"""
import collections
import os
import pathlib
import re
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
PYTHON = "/usr/bin/python3"
CODE = {"sh", "python", "toml", "cpp", "cmake"}
OUTPUT = {"", "text", "json", "latex"}
# A command's wall time in the docs is small; this is a hang guard, not a measurement.
TIMEOUT_S = 120


class Block:
    def __init__(self, page, line, language, text, mark, previous):
        self.page, self.line, self.language, self.text = page, line, language, text
        self.mark, self.previous = mark, previous  # previous: the comment line above, if any

    @property
    def where(self):
        return f"{self.page.relative_to(ROOT)}:{self.line}"

    def kind(self):
        return self.mark[0] if self.mark else None


def parse_mark(comment):
    m = re.fullmatch(r"<!--\s*(fragment|continues|file)(?::\s*(.*?))?\s*-->", comment.strip())
    if m is None:
        return None
    return (m[1], (m[2] or "").strip())


def read_blocks():
    blocks = []
    for page in PAGES:
        lines = page.read_text().splitlines()
        i = 0
        while i < len(lines):
            m = re.match(r"^\s*```(\S*)\s*$", lines[i])
            if m is None:
                i += 1
                continue
            j = i + 1
            while j < len(lines) and not re.match(r"^\s*```\s*$", lines[j]):
                j += 1
            indent = len(lines[i]) - len(lines[i].lstrip())
            body = "\n".join(l[indent:] for l in lines[i + 1:j]) + "\n"
            above = lines[i - 1].strip() if i > 0 else ""
            mark = parse_mark(above) if above.startswith("<!--") else None
            blocks.append(Block(page, i + 1, m[1], body, mark,
                                above if above.startswith("<!--") else ""))
            i = j + 1
    return blocks


BLOCKS = read_blocks()
RAN = collections.Counter()


def runnable(language):
    return [b for b in BLOCKS if b.language == language and b.kind() != "fragment"]


def ids(blocks):
    return [b.where for b in blocks]


@pytest.fixture()
def scratch(tmp_path):
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    exe = pathlib.Path(os.environ.get("RIGID_EXE", ROOT / "build" / "ci" / "bin" / "rigid")).resolve()
    (tmp_path / "build").mkdir()
    (tmp_path / "build" / "ci").symlink_to(exe.parents[1])
    tools = tmp_path / ".bin"
    tools.mkdir()
    (tools / "rigid").symlink_to(exe)
    (tools / "python3").symlink_to(PYTHON)
    env = dict(os.environ)
    env["PATH"] = f"{tools}{os.pathsep}{env.get('PATH', '')}"
    env["PYTHONPATH"] = os.environ.get("RIGID_PYTHON_DIR", str(exe.parents[1] / "python"))
    env["HOME"] = str(tmp_path)
    env["OMP_NUM_THREADS"] = "1"
    return tmp_path, env


def write_marked_file(block, cwd):
    if block.kind() == "file":
        path = cwd / block.mark[1]
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(block.text)
        return path
    return None


def commands(block):
    """(line, command) for each command of an sh block: `\\` joins lines; comments skipped."""
    out, pending, start = [], "", 0
    for k, raw in enumerate(block.text.splitlines()):
        if not pending and (not raw.strip() or raw.lstrip().startswith("#")):
            continue
        if not pending:
            start = block.line + 1 + k
        if raw.rstrip().endswith("\\"):
            pending += raw.rstrip()[:-1] + " "
            continue
        out.append((start, pending + raw))
        pending = ""
    assert not pending, f"{block.where}: a command ends with '\\'"
    return out


def bash(command, cwd, env):
    return subprocess.run(["bash", "-c", command], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=TIMEOUT_S)


FAILED = "docs-block-failed"


@pytest.mark.parametrize("block", runnable("sh"), ids=ids(runnable("sh")))
def test_sh_block_runs(scratch, block):
    cwd, env = scratch
    write_marked_file(block, cwd)
    script = []
    for line, command in commands(block):
        script += [command, f"rc=$?; if [ $rc -ne 0 ]; then echo '{FAILED} {line}' $rc >&2; exit $rc; fi"]
    r = bash("\n".join(script), cwd, env)
    failed = re.search(rf"^{FAILED} (\d+) (\d+)$", r.stderr, re.M)
    where = f"{block.page.relative_to(ROOT)}:{failed[1]}" if failed else block.where
    command = dict(commands(block)).get(int(failed[1])) if failed else ""
    assert r.returncode == 0, f"{where}: exit {r.returncode}: {command}\n{r.stdout}\n{r.stderr}"
    RAN["sh"] += 1


def python_source(block):
    if block.kind() != "continues":
        return block.text
    before = [b for b in BLOCKS if b.page == block.page and b.language == "python"
              and b.line < block.line]
    assert before, f"{block.where}: '<!-- continues -->' with no python block above"
    return python_source(before[-1]) + block.text


@pytest.mark.parametrize("block", runnable("python"), ids=ids(runnable("python")))
def test_python_block_runs(scratch, block):
    cwd, env = scratch
    script = cwd / "block.py"
    script.write_text(python_source(block))
    r = subprocess.run([PYTHON, str(script)], cwd=cwd, env=env, capture_output=True, text=True,
                       timeout=TIMEOUT_S)
    assert r.returncode == 0, f"{block.where}: exit {r.returncode}\n{r.stdout}\n{r.stderr}"
    RAN["python"] += 1


@pytest.mark.parametrize("block", runnable("toml"), ids=ids(runnable("toml")))
def test_toml_block_is_a_scene(scratch, block):
    cwd, env = scratch
    path = write_marked_file(block, cwd)
    if path is None:
        path = cwd / "scene.toml"
        path.write_text(block.text)
    r = bash(f"rigid check '{path}'", cwd, env)
    assert r.returncode == 0, f"{block.where}: rigid check: exit {r.returncode}\n{r.stdout}\n{r.stderr}"
    RAN["toml"] += 1


@pytest.mark.parametrize("block", [b for b in BLOCKS if b.language == "toml"],
                         ids=ids([b for b in BLOCKS if b.language == "toml"]))
def test_every_toml_block_parses(block):
    """Fragments too: an excerpt of a scene is still TOML."""
    import tomllib
    try:
        tomllib.loads(block.text)
    except tomllib.TOMLDecodeError as e:
        pytest.fail(f"{block.where}: not TOML: {e}")


def test_cpp_blocks_are_built_or_marked():
    """The cpp blocks that build and run are test_docs_robots.py's (docs/robots.md); every other
    cpp block is a marked fragment (a declaration list or statements without main())."""
    for block in runnable("cpp"):
        built = (block.page == ROOT / "docs" / "robots.md"
                 and re.match(r"// \S+\.cpp: build and run with\n", block.text))
        assert built, f"{block.where}: a cpp block is built (docs/robots.md's form) or marked"
        RAN["cpp"] += 1


# ---------------------------------------------------------------- shown output

NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")


def tokens(text):
    """Words and numbers: a number is (value, its last printed digit's unit)."""
    out = []
    for piece in re.split(f"({NUMBER.pattern})", text):
        if not piece:
            continue
        if NUMBER.fullmatch(piece):
            mantissa, _, exponent = piece.lower().partition("e")
            decimals = len(mantissa.partition(".")[2])
            unit = 10.0 ** (int(exponent or 0) - decimals)
            out.append((float(piece), unit))
        else:
            out.extend(w for w in piece.split() if w)
    return out


def same_output(shown, printed):
    a, b = tokens(shown), tokens(printed)
    if len(a) != len(b):
        return False
    for x, y in zip(a, b):
        if isinstance(x, tuple) != isinstance(y, tuple):
            return False
        if isinstance(x, tuple):
            # the docs print fewer digits than the program: one unit of the docs' last digit
            if abs(x[0] - y[0]) > x[1] * (1 + 1e-9):
                return False
        elif x != y:
            return False
    return True


def shown_outputs():
    """(block, command, shown text) for every output block whose command is known."""
    out = []
    for block in BLOCKS:
        if block.language not in OUTPUT:
            continue
        m = re.fullmatch(r"<!--\s*(rigid .*?)\s*-->", block.previous)
        if m:
            out.append((block, m[1], block.text))
            continue
        lines = block.text.splitlines()
        if block.language == "" and lines and lines[0].startswith("$ "):
            current = None
            for line in lines:
                if line.startswith("$ "):
                    current = [line[2:], []]
                    out.append((block, current[0], current[1]))
                else:
                    current[1].append(line)
    return [(b, c, t if isinstance(t, str) else "\n".join(t)) for b, c, t in out]


@pytest.mark.parametrize("block,command,shown", shown_outputs(),
                         ids=[f"{b.where}:{c}" for b, c, _ in shown_outputs()])
def test_shown_output_is_the_programs(scratch, block, command, shown):
    cwd, env = scratch
    r = bash(command, cwd, env)
    assert r.returncode == 0, f"{block.where}: {command}: exit {r.returncode}\n{r.stderr}"
    assert same_output(shown, r.stdout), (
        f"{block.where}: the docs show\n{shown}\n--- but `{command}` prints\n{r.stdout}")
    RAN["output"] += 1


def test_the_comparison_can_fail():
    assert same_output("omega = 2.3972 rad/s", "omega = 2.397199398 rad/s")
    assert not same_output("omega = 2.3974 rad/s", "omega = 2.397199398 rad/s")
    assert not same_output("omega = 2.3972 rad", "omega = 2.397199398 rad/s")
    assert same_output("[1e-3, 5]", "[0.001, 5.0]")


# ---------------------------------------------------------------- the shipped files

def test_the_docs_meshes_are_make_files_output(tmp_path):
    """examples/docs/make_files.py writes the shipped meshes byte for byte, and they measure
    what its docstring says (closed forms of the prisms and the L bracket)."""
    import rigid
    docs = ROOT / "examples" / "docs"
    shutil.copy(docs / "make_files.py", tmp_path)
    subprocess.run([PYTHON, str(tmp_path / "make_files.py")], check=True, timeout=60)
    written = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*.stl"))
    assert written == sorted(p.relative_to(docs) for p in docs.rglob("*.stl"))
    for name in written:
        assert (tmp_path / name).read_bytes() == (docs / name).read_bytes(), name
    # 1e-12 relative: sums of a few dozen products of numbers printed to 9 digits, exact here
    # because every vertex of the bracket is an integer number of millimetres
    bracket, _ = rigid.mesh.mass_from_file(str(docs / "bracket.stl"), density=1.0, units="mm")
    assert abs(bracket.mass - (40 * 5 + 35 * 5) * 30 * 1e-9) <= 1e-12 * bracket.mass
    # a regular 12-gon of circumradius r has area 3 r^2; its vertices are printed to 9
    # significant digits, so the volume agrees to ~1e-8 relative
    arm, _ = rigid.mesh.mass_from_file(str(docs / "meshes" / "upper_arm.stl"), density=1.0)
    assert abs(arm.mass - 3 * 0.04**2 * 0.3) <= 1e-8 * arm.mass


# ---------------------------------------------------------------- the count

def test_every_block_is_run_or_marked(capsys):
    """Every code block is run by a test above or marked a fragment with a reason; the counts
    per language are printed (and are in the message when this fails)."""
    fragments = collections.Counter(b.language for b in BLOCKS if b.kind() == "fragment")
    run = collections.Counter(b.language for b in BLOCKS
                              if b.language in CODE and b.kind() != "fragment")
    unknown = [f"{b.where} ```{b.language}" for b in BLOCKS
               if b.language not in CODE | OUTPUT and b.kind() != "fragment"]
    unexplained = [b.where for b in BLOCKS if b.kind() == "fragment" and not b.mark[1]]
    stray = [b.where for b in BLOCKS if b.kind() == "continues" and b.language != "python"]
    cmake = [b.where for b in BLOCKS if b.language == "cmake" and b.kind() != "fragment"]
    summary = ("docs blocks run: " + ", ".join(f"{k} {run[k]}" for k in sorted(run))
               + f", shown outputs compared {len(shown_outputs())}"
               + "; fragments: " + ", ".join(f"{k} {fragments[k]}" for k in sorted(fragments)))
    with capsys.disabled():
        print(f"\n{summary}")
    assert not unknown, f"{summary}\nblocks in a language this test cannot run: {unknown}"
    assert not unexplained, f"{summary}\nfragments without a reason: {unexplained}"
    assert not stray, f"{summary}\n'continues' marks on non-python blocks: {stray}"
    assert not cmake, f"{summary}\ncmake blocks cannot run here: mark them: {cmake}"
    assert run["sh"] and run["python"] and run["toml"], summary
    if RAN:  # the block tests ran in this session: every runnable block passed
        for language in ("sh", "python", "toml"):
            assert RAN[language] == run[language], (
                f"{summary}\n{language}: {RAN[language]} of {run[language]} blocks ran and passed")
