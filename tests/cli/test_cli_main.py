import re


def test_version(run):
    p = run("--version", check=True)
    assert re.fullmatch(r"rigid \d+\.\d+\.\d+\n", p.stdout)


def test_help_lists_demo(run):
    p = run("--help", check=True)
    assert "demo" in p.stdout


def test_unknown_subcommand_fails_without_trace(run):
    p = run("frobnicate", check=False)
    assert "frobnicate" in p.stderr
    assert "terminate" not in p.stderr
