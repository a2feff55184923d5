"""The README as a user reads it: its length, its figure on the first screen, its Python example run as
it stands, and every number it quotes found in the results file it links to.

A number is quoted from a results file when the paragraph or table row it sits in links to a file under
benchmarks/results/, validation/results/ or studies/results/ (a table row without a link of its own takes the links of the paragraph just above
the table). Every such number must appear, as a number, in one of the linked files, and every paragraph
or table of the README's "Results" section that holds a number must link its file."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
RESULTS = ("benchmarks/results/", "validation/results/", "studies/results/")

# a number as a reader sees it: 19.62, 16,968, 2.5e-3; not the digits inside a name (maeno2008, v1912, L1)
NUMBER = re.compile(r"(?<![\w.])(\d{1,3}(?:,\d{3})+|\d+(?:\.\d+)?(?:e[-+]?\d+)?)(?![\d]|\.\d)")
LINK = re.compile(r"!?\[([^\]]*)\]\(([^)\s]+)\)")


def blocks(text: str):
    """(heading, kind, lines) for each paragraph or table outside fenced code; a table's lines are its rows."""
    heading, kind, cur, out, fenced = "", None, [], [], False

    def flush():
        nonlocal cur, kind
        if cur:
            out.append((heading, kind, cur))
        cur, kind = [], None

    for line in text.splitlines():
        if line.startswith("```"):
            flush()
            fenced = not fenced
            continue
        if fenced:
            continue
        if line.startswith("#"):
            flush()
            heading = line.lstrip("#").strip()
            continue
        if not line.strip():
            flush()
            continue
        k = "table" if line.lstrip().startswith("|") else "text"
        if kind is not None and k != kind:
            flush()
        kind = k
        cur.append(line)
    flush()
    return out


def result_links(text: str) -> list[str]:
    """The results files a piece of text links to (README-relative paths)."""
    return [target for _, target in LINK.findall(text) if target.startswith(RESULTS)]


def numbers(text: str) -> list[str]:
    """The numbers a piece of text quotes, outside link targets and inline code."""
    text = LINK.sub(lambda m: m.group(1), text)
    text = re.sub(r"`[^`]*`", " ", text)
    return NUMBER.findall(text)


def found_in(number: str, source: str) -> bool:
    """Whether `number` appears in `source` as a number (16,968 also as 16968)."""
    return number.replace(",", "") in {n.replace(",", "") for n in NUMBER.findall(source)}


def quoted(text: str):
    """(number, [results files], where) for every number the README quotes next to a results link;
    and the blocks of its Results section that hold numbers but link no results file."""
    checks, unsourced = [], []
    caption_links: list[str] = []
    for heading, kind, lines in blocks(text):
        if kind == "text":
            para = " ".join(lines)
            caption_links = result_links(para)
            if caption_links:
                checks += [(n, caption_links, para[:80]) for n in numbers(para)]
            elif heading == "Results" and numbers(para):
                unsourced.append(para[:80])
            continue
        for row in lines[2:]:  # the header row's numbers are column names; the second row is the rule
            links = result_links(row) or caption_links
            if links:
                checks += [(n, links, row[:80]) for n in numbers(row)]
            elif heading == "Results" and numbers(row):
                unsourced.append(row[:80])
    return checks, unsourced


def missing(text: str, root: Path = ROOT) -> list[str]:
    """Every quoted number not found in its linked files, and every unsourced Results block."""
    checks, unsourced = quoted(text)
    bad = [f"no results file linked: {u!r}" for u in unsourced]
    for number, links, where in checks:
        files = [root / link for link in links]
        absent = [str(f) for f in files if not f.is_file()]
        if absent:
            bad.append(f"{absent} (linked from {where!r}) does not exist")
            continue
        if not any(found_in(number, f.read_text(encoding="utf-8")) for f in files):
            bad.append(f"{number} (in {where!r}) is not in {', '.join(links)}")
    return bad


def test_readme_is_short_with_its_figure_on_the_first_screen():
    lines = README.read_text(encoding="utf-8").splitlines()
    assert len(lines) <= 200
    figure = [i for i, line in enumerate(lines) if line.startswith("![")]
    assert figure and figure[0] < 40, "the fragility figure within the first 40 lines"
    path = LINK.search(lines[figure[0]]).group(2)
    assert (ROOT / path).is_file() and "fragility" in path


def test_every_quoted_number_is_in_its_results_file():
    text = README.read_text(encoding="utf-8")
    checks, _ = quoted(text)
    # the three headline tables and their captions: far more numbers than this
    assert len(checks) >= 60, f"only {len(checks)} numbers checked: are the README's results links gone?"
    assert not missing(text), "\n".join(missing(text))


def test_each_linked_results_file_names_a_committed_script():
    for link in sorted({f for _, links, _ in quoted(README.read_text(encoding="utf-8"))[0] for f in links}):
        head = (ROOT / link).read_text(encoding="utf-8")[:2000]
        named = [s for s in re.findall(r"(?:benchmarks|validation|studies)/[\w./-]+\.py", head) if (ROOT / s).is_file()]
        writers = [p for d in ("benchmarks", "validation", "studies") for p in (ROOT / d).glob("*.py")
                   if Path(link).name in p.read_text(encoding="utf-8")]
        assert named or writers, f"{link}: no committed script writes it"


def test_the_check_finds_a_number_that_is_not_in_its_file(tmp_path):
    (tmp_path / "benchmarks" / "results").mkdir(parents=True)
    (tmp_path / "benchmarks" / "results" / "r.md").write_text("| 16,968 | 19.62 [10.06 to > 25.00] |\n")
    good = "## Results\n\nA median of 19.62 l/s ([r](benchmarks/results/r.md)).\n"
    assert missing(good, tmp_path) == []
    table = "## Results\n\nSee [r](benchmarks/results/r.md):\n\n| a | b |\n|---|---|\n| 16968 steps | 10.06 |\n"
    assert missing(table, tmp_path) == []
    assert missing(good.replace("19.62", "19.6"), tmp_path)          # a rounded copy is not the file's number
    assert missing(table.replace("10.06", "10.6"), tmp_path)
    assert missing("## Results\n\nA median of 19.62 l/s.\n", tmp_path)  # a number with no source
    assert missing("## Results\n\nA median of 19.62 ([r](benchmarks/results/none.md)).\n", tmp_path)


def python_example() -> str:
    text = README.read_text(encoding="utf-8")
    section = text.split("## From Python", 1)[1]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_the_python_example_runs(tmp_path):
    code = python_example()
    assert 15 <= len(code.splitlines()) <= 30
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    first = out.stdout.splitlines()[0]
    assert re.match(r"80 stones carry \d+\.\d{2} N downstream \(the most loaded \d+\.\d{2} N\); \d+ cells of water "
                    r"after \d+ flow steps", first)
    assert "fluid" in out.stdout.splitlines()[1]


@pytest.mark.parametrize("name", ["LICENSE", "CHANGELOG.md", "CITATION.cff"])
def test_the_house_files_exist(name):
    assert (ROOT / name).is_file() and (ROOT / name).stat().st_size > 200
