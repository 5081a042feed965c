"""The README's figures are the measurements': every cell of its table "How it compares" must
appear, as written, in the section of docs/measurements/ its row links to, and so must the row's
command and date. And every relative link of the README, CONTRIBUTING.md and docs/ leads to a file
that is there (and, for a link to a Markdown heading, to that heading)."""
import pathlib
import re

REPO = pathlib.Path(__file__).resolve().parents[2]
TABLE_HEADING = "## How it compares"
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
# Written with the command line's errors and limits; until it is in the tree, links to it wait.
PENDING = set()


def anchor(heading):
    """GitHub's anchor of a Markdown heading."""
    text = heading.strip().lstrip("#").strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def section(path, wanted):
    """The text of the section whose heading has the anchor `wanted`, up to the next heading of the
    same or a higher level; None when there is none."""
    lines = path.read_text(encoding="utf-8").splitlines()
    in_code = False
    for i, line in enumerate(lines):
        if line.startswith("```"):
            in_code = not in_code
        m = re.match(r"^(#+) ", line)
        if m and not in_code and anchor(line) == wanted:
            level, body, fenced = len(m.group(1)), [], False
            for rest in lines[i + 1:]:
                if rest.startswith("```"):
                    fenced = not fenced
                n = re.match(r"^(#+) ", rest)
                if n and not fenced and len(n.group(1)) <= level:
                    break
                body.append(rest)
            return "\n".join(body)
    return None


def table_rows(readme_text):
    """The rows of the README's table as dicts by column name."""
    after = readme_text.split(TABLE_HEADING, 1)[1]
    lines = [l for l in after.splitlines() if l.startswith("|")]
    cells = lambda l: [c.strip() for c in l.strip().strip("|").split("|")]
    header = cells(lines[0])
    return [dict(zip(header, cells(l))) for l in lines[2:]]


def mismatches(readme_text):
    """What in the README's table is not in its measurements sections."""
    wrong = []
    rows = table_rows(readme_text)
    if len(rows) < 5:
        wrong.append(f"the table has {len(rows)} rows")
    for row in rows:
        name = row["measure"]
        link = LINK.search(row.get("details", ""))
        if not link or "#" not in link.group(1):
            wrong.append(f"{name}: no link to a measurements section")
            continue
        target, wanted = link.group(1).split("#", 1)
        path = REPO / target
        text = section(path, wanted) if path.is_file() else None
        if text is None:
            wrong.append(f"{name}: {target} has no section #{wanted}")
            continue
        command_date = row.get("command, date", "")
        command = re.search(r"`([^`]+)`", command_date)
        date = re.search(r"\d{4}-\d{2}-\d{2}", command_date)
        if not command or command.group(1) not in text:
            wrong.append(f"{name}: the command {command_date!r} is not in {target}#{wanted}")
        if not date or date.group(0) not in text:
            wrong.append(f"{name}: the date in {command_date!r} is not in {target}#{wanted}")
        for column in ("curvemesh", "TriWild reference", "CGAL CDT"):
            cell = row.get(column, "")
            if cell and cell != "—" and cell not in text:
                wrong.append(f"{name}: {column} {cell!r} is not in {target}#{wanted}")
    return wrong


def test_every_figure_of_the_readmes_table_is_in_its_measurements_section():
    wrong = mismatches((REPO / "README.md").read_text(encoding="utf-8"))
    assert not wrong, "README.md's table and docs/measurements/ disagree:\n" + "\n".join(wrong)


def test_a_figure_changed_in_the_readme_alone_is_found():
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    row = next(r for r in table_rows(readme) if r["curvemesh"] not in ("", "—"))
    line = next(l for l in readme.splitlines() if l.startswith(f"| {row['measure']} |"))
    changed = line.replace(f"| {row['curvemesh']} |", f"| {row['curvemesh']}1 |", 1)
    assert changed != line
    wrong = mismatches(readme.replace(line, changed))
    assert any(row["measure"] in w and "curvemesh" in w for w in wrong), wrong


def test_links_lead_somewhere():
    pages = [REPO / "README.md", REPO / "CONTRIBUTING.md", *sorted((REPO / "docs").rglob("*.md"))]
    broken = []
    for page in pages:
        text = re.sub(r"```.*?```", "", page.read_text(encoding="utf-8"), flags=re.S)
        for target in LINK.findall(text):
            if re.match(r"^[a-z]+:", target):
                continue  # a web address
            file, _, wanted = target.partition("#")
            path = (page.parent / file).resolve() if file else page
            relative = path.relative_to(REPO).as_posix() if path.is_relative_to(REPO) else str(path)
            if relative in PENDING and not path.exists():
                continue
            if not path.exists():
                broken.append(f"{page.relative_to(REPO)}: {target}: no such file")
            elif wanted and path.suffix == ".md" and section(path, wanted) is None:
                broken.append(f"{page.relative_to(REPO)}: {target}: no such heading")
    assert not broken, "\n".join(broken)
