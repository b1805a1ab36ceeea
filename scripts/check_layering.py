"""Checks the layering of docs/architecture.md against the code: python3 check_layering.py [--root DIR]

The table "The layers, bottom up" (columns layer | folder | what it is | may include) is the single
source of truth: this script reads it, not a copy of it. For every folder of the table it reports

- each `#include "teleop/<x>/..."` or `#include <teleop/<x>/...>` in the folder's .h and .cpp
  files whose <x> belongs to a folder the table does not allow, and
- each `teleop::<x>` (or a teleop target's own name) the folder's CMakeLists.txt files link
  (target_link_libraries, the DEPENDS of teleop_library and teleop_executable) that belongs to a
  folder the table does not allow.

A folder may always include itself. The table names what a folder builds on directly; a folder may
also include what those may include (runtime/ may include transport/, which may include idl/: so
runtime/ may include teleop/msg/, transport's samples), except that a cell saying "never another
node" forbids every node's folder but its own however it is reached. --literal reads each cell
alone. What <x> belongs to: the folder holding `include/teleop/<x>/`, else the folder defining the
target teleop::<x> (teleop/msg/ is idl/'s generated teleop::msg). Links through
teleop_link_registering are the probe libraries a node executable links whole, which the rules
below the table allow; they are not checked.

Exit status: 0 when everything follows the table (one line of counts), 1 with one line per
violation, 2 when the table or a name in the code cannot be understood (the message says which):
a change to the doc can make the check fail, never silently pass. The functions take the root of
the tree as a parameter (test/layering/check_layering_test.py runs them on made-up trees).
"""

from __future__ import annotations

import argparse
import os
import re
import sys
from dataclasses import dataclass, field

DOC = os.path.join("docs", "architecture.md")
# not layers: test/ and bench/ may include anything, build/ is generated
NOT_LAYERS = {"build", "test", "bench"}
SOURCE_SUFFIXES = (".h", ".hpp", ".cpp", ".cc", ".cxx", ".h.in", ".cpp.in")
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]teleop/([^">]*)[">]')
TELEOP_TARGET = re.compile(r"teleop::[A-Za-z0-9_]+")
WORD = re.compile(r"[A-Za-z0-9_.+-]+")
# the commands that link, and the keywords of teleop_library's and teleop_executable's arguments
LINK_KEYWORDS = {"DEPENDS", "PRIVATE_DEPENDS"}
TELEOP_KEYWORDS = {"NAME", "SOURCES"} | LINK_KEYWORDS


class LayeringError(Exception):
    """The table, or a name the code uses, cannot be understood: the check cannot run."""


@dataclass
class Row:
    line: int
    layer: int
    folders: list[str]
    what: str
    may_include: str


@dataclass
class Violation:
    path: str  # relative to the root
    line: int
    folder: str
    verb: str  # "includes" or "links"
    other: str  # the folder included or linked
    name: str  # what the line names: teleop/<x>/ or the target
    allowed: list[str]

    def message(self, doc: str = DOC) -> str:
        allowed = ", ".join(self.allowed) if self.allowed else "nothing"
        return (f"{self.path}:{self.line}: {self.folder} {self.verb} {self.other} ({self.name}), "
                f"which {doc}'s table does not allow ({allowed})")


@dataclass
class Result:
    folders: list[str]
    includes: int = 0
    links: int = 0
    violations: list[Violation] = field(default_factory=list)

    def summary(self, doc: str = DOC) -> str:
        return (f"{self.includes} includes and {self.links} links in {len(self.folders)} folders "
                f"follow {doc}")


# --- the table -----------------------------------------------------------------------------------

def split_cells(line: str) -> list[str]:
    """The cells of a markdown table row (pipes escaped as \\| stay in their cell)."""
    text = line.strip()
    if text.startswith("|"):
        text = text[1:]
    if text.endswith("|") and not text.endswith("\\|"):
        text = text[:-1]
    return [cell.strip().replace("\\|", "|") for cell in re.split(r"(?<!\\)\|", text)]


def read_table(root: str, doc: str = DOC) -> list[Row]:
    """The rows of the doc's table whose header has the columns layer, folder, may include."""
    path = os.path.join(root, doc)
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise LayeringError(f"{doc}: cannot read it ({e.strerror})") from e
    tables = []
    for i, line in enumerate(lines):
        if not line.lstrip().startswith("|"):
            continue
        header = [c.lower() for c in split_cells(line)]
        if "layer" in header and "folder" in header and "may include" in header:
            tables.append((i, header))
    if len(tables) != 1:
        raise LayeringError(f"{doc}: expected one table with the columns 'layer', 'folder' and 'may "
                            f"include' (the layers, bottom up), found {len(tables)}")
    start, header = tables[0]
    col = {name: header.index(name) for name in ("layer", "folder", "may include")}
    what_col = header.index("what it is") if "what it is" in header else None
    if start + 1 >= len(lines) or not re.fullmatch(r"[\s|:-]+", lines[start + 1]):
        raise LayeringError(f"{doc}:{start + 2}: the layers' table has no |---| line under its header")
    rows = []
    for i in range(start + 2, len(lines)):
        if not lines[i].lstrip().startswith("|"):
            break
        cells = split_cells(lines[i])
        where = f"{doc}:{i + 1}"
        if len(cells) != len(header):
            raise LayeringError(f"{where}: {len(cells)} cells in a table of {len(header)} columns")
        if not re.fullmatch(r"\d+", cells[col["layer"]]):
            raise LayeringError(f"{where}: the layer '{cells[col['layer']]}' is not a number")
        folders = []
        for item in cells[col["folder"]].split(","):
            name = item.strip().strip("`").strip().rstrip("/")
            if not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
                raise LayeringError(f"{where}: cannot understand the folder '{item.strip()}' "
                                    "(expected `name/`, several separated by commas)")
            folders.append(name)
        rows.append(Row(i + 1, int(cells[col["layer"]]), folders,
                        cells[what_col] if what_col is not None else "", cells[col["may include"]]))
    if not rows:
        raise LayeringError(f"{doc}:{start + 1}: the layers' table has no rows")
    seen = {}
    for row in rows:
        for folder in row.folders:
            if folder in seen:
                raise LayeringError(f"{doc}:{row.line}: {folder}/ has a row already (line {seen[folder]})")
            seen[folder] = row.line
            if not os.path.isdir(os.path.join(root, folder)):
                raise LayeringError(f"{doc}:{row.line}: the table's folder {folder}/ does not exist")
    return rows


def strip_remarks(cell: str, where: str) -> str:
    """The cell without its parenthesised remarks: "experiment (traces)" is "experiment"."""
    out, depth = [], 0
    for c in cell:
        if c == "(":
            depth += 1
        elif c == ")":
            depth -= 1
            if depth < 0:
                raise LayeringError(f"{where}: unbalanced parentheses in '{cell}'")
        elif depth == 0:
            out.append(c)
    if depth != 0:
        raise LayeringError(f"{where}: unbalanced parentheses in '{cell}'")
    return "".join(out)


@dataclass
class Allowance:
    folders: set[str]
    no_other_node: bool = False


def node_folders(rows: list[Row], doc: str) -> list[str]:
    """The nodes' folders: the row whose 'what it is' starts with "the nodes"."""
    matches = [row for row in rows if re.match(r"\s*the nodes\b", row.what, re.IGNORECASE)]
    if len(matches) != 1:
        raise LayeringError(f"{doc}: the 'may include' column speaks of the nodes, but {len(matches)} "
                            "rows' 'what it is' starts with 'the nodes' (expected one)")
    return list(matches[0].folders)


def parse_cell(row: Row, rows: list[Row], names: dict[str, str], doc: str) -> Allowance:
    """What one 'may include' cell allows. names maps an include directory's or a target's name
    (hand_canopen, box_task, msg) to its folder. Anything not understood raises LayeringError."""
    where = f"{doc}:{row.line}"
    cell = strip_remarks(row.may_include.replace("**", "").replace("`", ""), where).strip()
    allowance = Allowance(set())
    if cell.lower() in ("", "—", "–", "-", "none", "nothing"):
        return allowance
    folders = {f for r in rows for f in r.folders}
    items = [item.strip() for part in cell.split(",") for item in re.split(r"\s+and\s+", part)]
    for item in items:
        text = re.sub(r"\s+", " ", item.replace("’", "'")).strip().rstrip("/")
        lower = text.lower()
        span = re.fullmatch(r"layers? (\d+)(?: ?(?:–|—|-|to) ?(\d+))?", lower)
        if span:
            low, high = int(span.group(1)), int(span.group(2) or span.group(1))
            chosen = {f for r in rows if low <= r.layer <= high for f in r.folders}
            if low > high or not chosen:
                raise LayeringError(f"{where}: '{text}' in {'/, '.join(row.folders)}/'s 'may include' "
                                    "names no layer of the table")
            allowance.folders |= chosen
        elif re.fullmatch(r"the nodes'?( librar(y|ies)| folders?)?", lower):
            allowance.folders |= set(node_folders(rows, doc))
        elif lower == "never another node":
            allowance.no_other_node = True
        elif text in folders:
            allowance.folders.add(text)
        elif text.removeprefix("teleop::") in names:
            allowance.folders.add(names[text.removeprefix("teleop::")])
        else:
            raise LayeringError(
                f"{where}: cannot understand '{text}' in {'/, '.join(row.folders)}/'s 'may include' "
                f"cell '{row.may_include}': expected a folder of the table, a teleop target or "
                "include directory (hand_canopen), 'layers N–M', 'the nodes' libraries', "
                "'never another node' or '—' (parenthesised remarks are ignored)")
    return allowance


def allowed_folders(rows: list[Row], names: dict[str, str], doc: str = DOC,
                    literal: bool = False) -> dict[str, set[str]]:
    """For each folder, the folders it may include and link: itself, what its cell names and
    (unless literal) what those may include, never another node's folder if its cell says so."""
    direct: dict[str, Allowance] = {}
    for row in rows:
        allowance = parse_cell(row, rows, names, doc)
        for folder in row.folders:
            direct[folder] = allowance
    allowed = {folder: {folder} | a.folders for folder, a in direct.items()}
    if not literal:
        changed = True
        while changed:
            changed = False
            for folder, reach in allowed.items():
                more = set().union(*(allowed[f] for f in reach)) - reach
                if more:
                    reach |= more
                    changed = True
    for row in rows:
        for folder in row.folders:
            if direct[folder].no_other_node:
                others = sorted((allowed[folder] & set(node_folders(rows, doc))) - {folder})
                if others:
                    raise LayeringError(
                        f"{doc}:{row.line}: {folder}/ may never include another node, but its 'may "
                        f"include' reaches {', '.join(f + '/' for f in others)} through the table")
    return allowed


# --- CMake ---------------------------------------------------------------------------------------

@dataclass
class Command:
    name: str
    line: int
    args: list[tuple[str, int]]  # each argument with its line


def cmake_commands(text: str) -> list[Command]:
    """The command invocations of a CMake file, comments dropped, arguments with their lines."""
    commands, i, line, n = [], 0, 1, len(text)

    def skip_comment(i: int, line: int) -> tuple[int, int]:
        bracket = re.match(r"#\[(=*)\[", text[i:])
        if bracket:
            end = text.find("]" + bracket.group(1) + "]", i)
            end = n if end < 0 else end + len(bracket.group(1)) + 2
        else:
            end = text.find("\n", i)
            end = n if end < 0 else end
        return end, line + text.count("\n", i, end)

    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif c == "#":
            i, line = skip_comment(i, line)
        elif c.isalpha() or c == "_":
            m = re.match(r"[A-Za-z_][A-Za-z0-9_]*[ \t]*\(", text[i:])
            if not m:
                i += 1
                continue
            command = Command(m.group(0).split("(")[0].strip(), line, [])
            i += m.end()
            depth = 1
            while i < n and depth > 0:
                c = text[i]
                if c == "\n":
                    line += 1
                    i += 1
                elif c in " \t\r":
                    i += 1
                elif c == "#":
                    i, line = skip_comment(i, line)
                elif c == "(":
                    depth += 1
                    i += 1
                elif c == ")":
                    depth -= 1
                    i += 1
                elif c == '"':
                    j = i + 1
                    while j < n and text[j] != '"':
                        j += 2 if text[j] == "\\" else 1
                    command.args.append((text[i + 1:j], line))
                    line += text.count("\n", i, j)
                    i = j + 1
                else:
                    m = re.match(r'(?:[^\s()#"\\]|\\.)+', text[i:])
                    if not m:  # a lone backslash
                        i += 1
                        continue
                    command.args.append((m.group(0), line))
                    i += m.end()
            commands.append(command)
        else:
            i += 1
    return commands


def cmake_files(root: str, folder: str) -> list[str]:
    return [p for p in walk(root, folder) if os.path.basename(p) == "CMakeLists.txt"]


def walk(root: str, folder: str) -> list[str]:
    """The files under root/folder, relative to root, sorted; hidden and build directories skipped."""
    found = []
    for dirpath, dirnames, filenames in os.walk(os.path.join(root, folder)):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith(".") and d != "build")
        found += [os.path.relpath(os.path.join(dirpath, f), root) for f in sorted(filenames)]
    return found


def read(root: str, path: str) -> str:
    with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
        return f.read()


def check_target_helper(root: str) -> None:
    """teleop_library(NAME x) defines teleop_x_lib with the alias teleop::x (cmake/TeleopTarget.cmake):
    targets() relies on it, so a change of the helper's naming stops the check."""
    helper = os.path.join(root, "cmake", "TeleopTarget.cmake")
    if not os.path.exists(helper):
        return
    with open(helper, encoding="utf-8") as f:
        text = f.read()
    if ("set(target teleop_${ARG_NAME}_lib)" not in text
            or "add_library(teleop::${ARG_NAME} ALIAS ${target})" not in text):
        raise LayeringError("cmake/TeleopTarget.cmake: teleop_library(NAME x) no longer defines "
                            "teleop_x_lib and its alias teleop::x, which scripts/check_layering.py "
                            "expects")


def targets(root: str, folders: list[str]) -> dict[str, str]:
    """Each target the folders' CMakeLists.txt define (teleop::x and teleop_x_lib of
    teleop_library(NAME x), add_library's and add_executable's names and aliases) -> its folder."""
    check_target_helper(root)
    defined: dict[str, tuple[str, str]] = {}

    def define(name: str, folder: str, where: str) -> None:
        if name in defined and defined[name][0] != folder:
            raise LayeringError(f"{where}: {name} is defined in {folder}/ and in "
                                f"{defined[name][0]}/ ({defined[name][1]})")
        defined[name] = (folder, where)

    for folder in folders:
        for path in cmake_files(root, folder):
            for command in cmake_commands(read(root, path)):
                name = command.name.lower()
                args = [a for a, _ in command.args]
                where = f"{path}:{command.line}"
                if name in ("teleop_library", "teleop_executable") and "NAME" in args[:-1]:
                    target = args[args.index("NAME") + 1]
                    if name == "teleop_library":
                        define(f"teleop::{target}", folder, where)
                        define(f"teleop_{target}_lib", folder, where)
                    else:
                        define(target, folder, where)
                elif name in ("add_library", "add_executable") and args:
                    define(args[0], folder, where)
    return {name: folder for name, (folder, _) in defined.items()}


def linked(command: Command) -> list[tuple[str, int]]:
    """The arguments of a command that name what it links."""
    name = command.name.lower()
    if name == "target_link_libraries":
        return command.args[1:]
    if name in ("teleop_library", "teleop_executable"):
        out, section = [], None
        for arg, line in command.args:
            if arg in TELEOP_KEYWORDS:
                section = arg
            elif section in LINK_KEYWORDS:
                out.append((arg, line))
        return out
    # teleop_link_registering(<executable> <probe library>): a node executable links a probe
    # library whole, as the rules below the table allow; everything else links nothing
    return []


def link_names(arg: str, known: dict[str, str]) -> list[str]:
    """The teleop targets one argument names: teleop::x, or a target's own name (teleop_x_lib)."""
    names = TELEOP_TARGET.findall(arg)
    rest = TELEOP_TARGET.sub(" ", arg)
    names += [w for w in WORD.findall(rest) if w in known and not w.startswith("teleop::")]
    return names


# --- the check -----------------------------------------------------------------------------------

def unlisted_folders(root: str, folders: list[str]) -> list[str]:
    """Top-level folders holding C++ sources without a row in the table (a build tree is none)."""
    out = []
    for entry in sorted(os.listdir(root)):
        path = os.path.join(root, entry)
        if (entry in folders or entry in NOT_LAYERS or entry.startswith(".") or not os.path.isdir(path)
                or os.path.exists(os.path.join(path, "CMakeCache.txt"))):
            continue
        if any(p.endswith(SOURCE_SUFFIXES) for p in walk(root, entry)):
            out.append(entry)
    return out


def include_dirs(root: str, folders: list[str]) -> dict[str, str]:
    """Each include directory's name (x of <folder>/.../include/teleop/x/) -> its folder."""
    found: dict[str, str] = {}
    for folder in folders:
        for dirpath, dirnames, _ in os.walk(os.path.join(root, folder)):
            dirnames[:] = [d for d in dirnames if not d.startswith(".") and d != "build"]
            parts = os.path.relpath(dirpath, root).split(os.sep)
            if len(parts) >= 3 and parts[-3:-1] == ["include", "teleop"]:
                name = parts[-1]
                if found.get(name, folder) != folder:
                    raise LayeringError(f"include/teleop/{name}/ is in {found[name]}/ and in {folder}/")
                found[name] = folder
    return found


def check(root: str, doc: str = DOC, literal: bool = False) -> Result:
    """Every include and link of the table's folders against the table. Raises LayeringError when
    the table or a name cannot be understood."""
    rows = read_table(root, doc)
    folders = [f for row in rows for f in row.folders]
    unlisted = unlisted_folders(root, folders)
    if unlisted:
        one = len(unlisted) == 1
        raise LayeringError(f"{', '.join(f + '/' for f in unlisted)} {'holds' if one else 'hold'} C++ "
                            f"sources but {'has' if one else 'have'} no row in {doc}'s table, so "
                            "nothing would check their includes and links")
    known = targets(root, folders)
    headers = include_dirs(root, folders)
    # a name in a cell or an include: an include directory's, else a target's (msg: teleop::msg)
    names = {n.removeprefix("teleop::"): f for n, f in known.items() if n.startswith("teleop::")}
    names.update(headers)
    allowed = allowed_folders(rows, names, doc, literal)
    order = {f: i for i, f in enumerate(folders)}

    def listing(folder: str) -> list[str]:
        return sorted(allowed[folder] - {folder}, key=order.get)

    result = Result(folders)
    for folder in folders:
        for path in walk(root, folder):
            if not path.endswith(SOURCE_SUFFIXES):
                continue
            for number, line in enumerate(read(root, path).splitlines(), 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                first = m.group(1).split("/")[0]
                if "/" not in m.group(1) or first not in names:
                    raise LayeringError(f"{path}:{number}: cannot tell which folder teleop/{m.group(1)} "
                                        "belongs to (no include/teleop/<x>/ directory, no target "
                                        "teleop::<x> in the table's folders)")
                result.includes += 1
                other = names[first]
                if other not in allowed[folder]:
                    result.violations.append(Violation(path, number, folder, "includes", other,
                                                       f"teleop/{first}/", listing(folder)))
        for path in cmake_files(root, folder):
            for command in cmake_commands(read(root, path)):
                for arg, number in linked(command):
                    for name in link_names(arg, known):
                        if name not in known:
                            raise LayeringError(f"{path}:{number}: cannot tell which folder defines "
                                                f"{name} (no teleop_library(NAME x) or add_library of "
                                                "it in the table's folders)")
                        result.links += 1
                        other = known[name]
                        if other not in allowed[folder]:
                            result.violations.append(Violation(path, number, folder, "links", other,
                                                               name, listing(folder)))
    result.violations.sort(key=lambda v: (v.path, v.line))
    return result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Checks every folder's includes and links against "
                                     "the layers' table of docs/architecture.md.")
    parser.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                        help="the source tree (default: the one holding this script)")
    parser.add_argument("--literal", action="store_true",
                        help="read each 'may include' cell alone, without what the folders it "
                        "names may include")
    args = parser.parse_args(argv)
    try:
        result = check(args.root, literal=args.literal)
    except LayeringError as e:
        print(f"check_layering: {e}", file=sys.stderr)
        return 2
    for violation in result.violations:
        print(violation.message())
    if result.violations:
        print(f"check_layering: {len(result.violations)} includes and links break {DOC}'s table "
              "(change the code, or the table if the layering changed on purpose)", file=sys.stderr)
        return 1
    print(result.summary())
    return 0


if __name__ == "__main__":
    sys.exit(main())
