"""The layering checker (scripts/check_layering.py) on made-up trees: it reports exactly the includes
and links a table forbids, passes a tree that follows its table, and refuses a table it cannot read.

python3 check_layering_test.py (ctest: layering_checker_test)
"""

import contextlib
import io
import os
import re
import sys
import tempfile
import textwrap
import unittest

sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import check_layering  # noqa: E402

TABLE = """\
# Architecture

## The layers, bottom up

| layer | folder | what it is | may include |
|---|---|---|---|
{rows}

`test/` may include anything.
"""

# two folders: app/ above base/
TWO_ROWS = """\
| 1 | `base/` | the bottom | — |
| 2 | `app/` | the top (`teleop::app`) | base (its helpers) |"""

BASE_CMAKE = """\
# the bottom
teleop_library(NAME base
  SOURCES src/base.cpp
  DEPENDS Threads::Threads)
"""

APP_CMAKE = """\
teleop_library(NAME app SOURCES src/app.cpp
  DEPENDS teleop::base)
# teleop::nothing in a comment is no link
teleop_executable(NAME app_tool SOURCES src/main.cpp DEPENDS teleop::app)
"""

CLEAN = {
    "base/CMakeLists.txt": BASE_CMAKE,
    "base/include/teleop/base/base.h": "#pragma once\n#include <vector>\n",
    "base/src/base.cpp": '#include "teleop/base/base.h"\n',
    "app/CMakeLists.txt": APP_CMAKE,
    "app/include/teleop/app/app.h": "#pragma once\n#include <teleop/base/base.h>\n",
    "app/src/app.cpp": '#include "teleop/app/app.h"\n',
    "app/src/main.cpp": '#include "teleop/app/app.h"\n  #  include "teleop/base/base.h"\n',
    # test/ and bench/ may include anything; build/ is generated
    "test/base/base_test.cpp": '#include "teleop/app/app.h"\n',
    "build/gen/teleop/x.h": '#include "teleop/app/app.h"\n',
}


def make_tree(root, rows, files):
    os.makedirs(os.path.join(root, "docs"))
    with open(os.path.join(root, "docs", "architecture.md"), "w", encoding="utf-8") as f:
        f.write(TABLE.format(rows=rows))
    for path, text in files.items():
        os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
        with open(os.path.join(root, path), "w", encoding="utf-8") as f:
            f.write(text)


def run_main(root, *args):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = check_layering.main(["--root", root, *args])
    return status, out.getvalue(), err.getvalue()


class LayeringTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def found(self, literal=False):
        result = check_layering.check(self.root, literal=literal)
        return [(v.path, v.line, v.folder, v.verb, v.other, v.name) for v in result.violations]

    def test_a_tree_following_its_table_passes(self):
        make_tree(self.root, TWO_ROWS, CLEAN)
        status, out, _ = run_main(self.root)
        self.assertEqual(status, 0)
        self.assertEqual(out, "5 includes and 2 links in 2 folders follow docs/architecture.md\n")

    def test_an_illegal_include_and_an_illegal_link_are_reported_and_nothing_else(self):
        files = dict(CLEAN)
        files["base/include/teleop/base/base.h"] = "#pragma once\n#include <teleop/app/app.h>\n"
        files["base/CMakeLists.txt"] = BASE_CMAKE.replace("Threads::Threads", "Threads::Threads\n    teleop::app")
        make_tree(self.root, TWO_ROWS, files)
        self.assertEqual(self.found(), [
            ("base/CMakeLists.txt", 5, "base", "links", "app", "teleop::app"),
            ("base/include/teleop/base/base.h", 2, "base", "includes", "app", "teleop/app/"),
        ])
        status, out, err = run_main(self.root)
        self.assertEqual(status, 1)
        self.assertEqual(out.splitlines(), [
            "base/CMakeLists.txt:5: base links app (teleop::app), which docs/architecture.md's "
            "table does not allow (nothing)",
            "base/include/teleop/base/base.h:2: base includes app (teleop/app/), which "
            "docs/architecture.md's table does not allow (nothing)",
        ])
        self.assertIn("2 includes and links break", err)

    def test_target_link_libraries_and_a_target_s_own_name_are_links(self):
        files = dict(CLEAN)
        files["base/CMakeLists.txt"] = BASE_CMAKE + (
            'add_executable(base_tool src/base.cpp)\n'
            'target_link_libraries(base_tool PRIVATE "$<LINK_LIBRARY:WHOLE_ARCHIVE,teleop_app_lib>")\n'
            "# the probe libraries a node executable links whole are the rules' exception\n"
            "teleop_link_registering(base_tool teleop_app_lib)\n")
        make_tree(self.root, TWO_ROWS, files)
        self.assertEqual(self.found(), [("base/CMakeLists.txt", 6, "base", "links", "app", "teleop_app_lib")])

    def test_a_folder_may_include_what_the_folders_it_names_may_include(self):
        rows = TWO_ROWS + "\n| 3 | `top/` | above | app |"
        files = dict(CLEAN)
        files["top/src/top.cpp"] = '#include "teleop/base/base.h"\n#include "teleop/top/top.h"\n'
        files["top/include/teleop/top/top.h"] = "#pragma once\n"
        make_tree(self.root, rows, files)
        self.assertEqual(self.found(), [])
        self.assertEqual(self.found(literal=True),
                         [("top/src/top.cpp", 1, "top", "includes", "base", "teleop/base/")])

    def test_the_table_s_forms(self):
        rows = """\
| 1 | `idl/` | the samples | — |
| 1 | `common/` | plain C++ | - |
| 2 | `runtime/` | the body | common, idl |
| 3 | `one/`, `two/` | the nodes: one, two; `teleop::parts` in two/ | layers 1–2, **never another node** |
| 4 | `study/` | the studies | the nodes' libraries (reasons), layer 2 |
| 5 | `view/` | the view | study (traces), `parts` (names), layers 1-2 |"""
        cmake_msg = "add_library(teleop_msg gen.cxx)\nadd_library(teleop::msg ALIAS teleop_msg)\n"
        files = {
            "idl/CMakeLists.txt": cmake_msg,
            "common/include/teleop/common/c.h": "",
            "runtime/src/r.cpp": '#include "teleop/msg/arm.h"\n#include "teleop/common/c.h"\n',
            "one/src/one.cpp": '#include "teleop/runtime/r.h"\n#include "teleop/two/two.h"\n',
            "runtime/include/teleop/runtime/r.h": "",
            "two/include/teleop/two/two.h": "",
            "two/CMakeLists.txt": "teleop_library(NAME parts SOURCES p.cpp)\nteleop_library(NAME two SOURCES t.cpp)\n",
            "study/CMakeLists.txt": "teleop_library(NAME study SOURCES s.cpp DEPENDS teleop::two teleop::msg\n"
                                    "  teleop::view)\n",
            "view/CMakeLists.txt": "teleop_library(NAME view SOURCES v.cpp DEPENDS teleop::parts teleop::study)\n",
        }
        make_tree(self.root, rows, files)
        # a node never another node; study/ reaches idl/ through the nodes, never view/ above it
        self.assertEqual(self.found(), [
            ("one/src/one.cpp", 2, "one", "includes", "two", "teleop/two/"),
            ("study/CMakeLists.txt", 2, "study", "links", "view", "teleop::view"),
        ])

    def test_a_cell_it_cannot_understand_stops_the_check(self):
        make_tree(self.root, TWO_ROWS.replace("base (its helpers)", "base, whatever is handy"), CLEAN)
        with self.assertRaisesRegex(check_layering.LayeringError,
                                    r"docs/architecture.md:8: cannot understand 'whatever is handy'"):
            check_layering.check(self.root)
        status, out, err = run_main(self.root)
        self.assertEqual((status, out), (2, ""))
        self.assertIn("cannot understand 'whatever is handy'", err)

    def test_a_table_that_lets_a_node_reach_another_stops_the_check(self):
        rows = """\
| 1 | `base/` | the bottom | — |
| 2 | `one/`, `two/` | the nodes | base, app, **never another node** |
| 3 | `above/` | above the nodes | two |
| 2 | `app/` | beside the nodes, including above | above |"""
        make_tree(self.root, rows, {
            "one/a.h": "", "two/b.h": "", "above/c.h": "", "app/d.h": "", "base/e.h": ""})
        with self.assertRaisesRegex(check_layering.LayeringError, "one/ may never include another node"):
            check_layering.check(self.root)

    def test_what_the_check_cannot_place_stops_it(self):
        for files, message in [
            ({"base/src/b.cpp": '#include "teleop/elsewhere/e.h"\n'}, "teleop/elsewhere/e.h"),
            ({"base/CMakeLists.txt": "target_link_libraries(b PRIVATE teleop::gone)\n"}, "teleop::gone"),
            ({"tools/x.cpp": "int x;\n"}, "tools/ holds C++ sources but has no row"),
        ]:
            with self.subTest(message=message), tempfile.TemporaryDirectory() as root:
                make_tree(root, TWO_ROWS, {**CLEAN, **files})
                with self.assertRaisesRegex(check_layering.LayeringError, re.escape(message)):
                    check_layering.check(root)

    def test_a_doc_without_the_table_or_with_a_missing_folder_stops_the_check(self):
        make_tree(self.root, TWO_ROWS, CLEAN)
        with open(os.path.join(self.root, "docs", "architecture.md"), "w", encoding="utf-8") as f:
            f.write(textwrap.dedent("""\
                | layer | folder | what it is |
                |---|---|---|
                | 1 | `base/` | the bottom |
                """))
        with self.assertRaisesRegex(check_layering.LayeringError, "expected one table"):
            check_layering.check(self.root)
        other = os.path.join(self.root, "other")
        make_tree(other, TWO_ROWS + "\n| 3 | `gone/` | above | app |", CLEAN)
        with self.assertRaisesRegex(check_layering.LayeringError, "gone/ does not exist"):
            check_layering.check(other)


if __name__ == "__main__":
    unittest.main()
