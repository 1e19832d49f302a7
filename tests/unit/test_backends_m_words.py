"""linkgen.backends.m.words: the names MATLAB and Octave give a meaning to. The keywords are this Octave's
iskeyword(); a field renamed with a trailing _ is set and read back by Octave; the function list is what this
Octave makes with the data file's own script; the generated .m files use only the names the lists hold; and
each rule's reason, with MATLAB's 63 characters."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest
from generated_samples import ROOT, SAMPLES, generated, outputs
from programs import need

from linkgen import names
from linkgen.backends.m import words as m_words


def octave(script: str, folder: Path) -> str:
    done = subprocess.run([need("octave-cli"), "--no-gui", "--no-init-file", "--quiet", "--eval", script], cwd=folder,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_the_keywords_are_octaves_and_their_spelling_is_a_field(tmp_path: Path):
    listed = sorted(m_words.KEYWORDS)
    said = octave("k = iskeyword(); printf('%s\\n', k{:});", tmp_path).split()
    assert listed == sorted(k for k in said if not k.startswith("_"))  # __FILE__ and __LINE__: no user name
    sets = " ".join(f"s.{m_words.WORDS.field(k)} = {i};" for i, k in enumerate(listed))
    reads = " ".join(f"printf('%d\\n', s.{m_words.WORDS.field(k)});" for k in listed)
    assert octave(f"s = struct(); {sets} {reads}", tmp_path).split() == [str(i) for i in range(len(listed))]
    assert all(m_words.WORDS.field(k) == f"{k}_" for k in listed)


@pytest.mark.parametrize("name, problem", [
    ("_x", "starts with _, which MATLAB does not allow in a file name"),
    ("m" * 58, "has 58 characters, but MATLAB allows 57 (63 for the function mmmmmmmm..._solve)"),
    ("end", "is a MATLAB/Octave keyword, so the script end.m cannot be run"),
    ("disp", "is a MATLAB/Octave function, which the script disp.m would hide"),
    ("row", "is a variable of the sweep script row.m, which after one run would hide the script"),
    ("crank", ""), ("End", ""),
])
def test_why_the_m_files_cannot_carry_a_mechanism_name(name: str, problem: str):
    assert m_words.mechanism_problem(name) == problem


def test_a_field_is_refused_only_where_its_spelling_is_too_long():
    assert m_words.entity_problem("B" * 63, "fourbar") == ""
    assert m_words.entity_problem("B" * 64, "fourbar") == "has 64 characters; a MATLAB struct field has at most 63"
    assert m_words.word("until") == "a MATLAB/Octave keyword" and m_words.word("untill") == ""


def test_no_octave_function_ends_in_solve():
    """So NAME_solve.m hides none (the data file says so)."""
    assert [f for f in m_words.FUNCTIONS if f.endswith("_solve")] == []


def test_the_longest_mechanism_name_leaves_room_for_the_solve_function():
    """MATLAB's namelengthmax is 63: NAME_solve must fit."""
    longest = "m" * m_words.MAX_NAME
    assert names.mechanism_name_problem(longest) == ""
    assert len(f"{longest}_solve") == 63
    assert names.mechanism_name_problem(longest + "m").startswith(f"has {m_words.MAX_NAME + 1} characters")


def test_a_field_has_at_most_63_characters_as_matlab_writes_it():
    assert names.entity_name_problem("B" * 63, "fourbar") == ""
    assert names.entity_name_problem("B" * 64, "fourbar").startswith("has 64 characters")
    # end_ is what MATLAB writes for end: a 62-character keyword would need 63 (none is that long)
    assert max(len(k) for k in m_words.KEYWORDS) + 1 <= 63


@pytest.mark.parametrize("json", SAMPLES, ids=lambda p: p.stem)
def test_the_matlab_programs_use_only_the_names_the_lists_hold(json: Path):
    solve = generated(json, "_solve.m")
    own = set(re.findall(r"\bout\.(\w+)\s*=", solve)) - {m_words.WORDS.field(o) for o in outputs(json)}
    assert own and own <= m_words.STATE_FIELDS
    script = generated(json, ".m")
    assigned = set(re.findall(r"^\s*(?:for\s+)?(\w+)\s*=[^=]", script, re.M))
    assigned |= {v.strip() for group in re.findall(r"^\s*\[([^\]]*)\]\s*=", script, re.M) for v in group.split(",")}
    assert assigned and assigned <= m_words.SCRIPT_VARIABLES
    # every function the two files call is a function of the list (or one of NAME_solve.m's own)
    calls, local, variables = set(), set(), set()
    for text in (solve, script):
        code = re.sub(r"(?<=[(,={\s])'[^'\n]*'", "''", text)
        code = re.sub(r"%.*", "", code)
        calls |= set(re.findall(r"(?<![.\w@])([A-Za-z]\w*)\s*\(", code))
        for head in re.findall(r"^function\s+(.*)", code, re.M):
            out, _, rest = head.rpartition("=")
            local.add(rest.split("(")[0].strip())
            variables |= set(re.findall(r"\w+", out + rest.partition("(")[2]))
        variables |= set(re.findall(r"(\w+)\s*(?:\([^()]*\))?\s*=[^=]", code))
        variables |= {v for group in re.findall(r"\[([^\]]*)\]\s*=[^=]", code) for v in re.findall(r"\w+", group)}
    called = calls - local - variables - {f"{json.stem}_solve"}
    assert {"fprintf", "zeros", "size", "atan2"} <= called
    assert called <= m_words.FUNCTIONS, called - m_words.FUNCTIONS


def test_the_octave_list_is_what_this_octave_gives(tmp_path: Path):
    """The data file says how it was made; with that Octave version, making it again gives the same."""
    octave = shutil.which("octave-cli")
    if octave is None:
        pytest.skip("octave-cli is not installed")
    data = (ROOT / "linkgen" / "backends" / "m" / "functions.txt").read_text(encoding="utf-8").splitlines()
    version = re.search(r"GNU Octave (\S+)", data[0])[1]
    script = "\n".join(line[4:] for line in data if line.startswith("#   "))
    here = subprocess.run([octave, "--norc", "--no-init-file", "--quiet", "--eval", "disp(OCTAVE_VERSION)"],
                          capture_output=True, text=True).stdout.strip()
    if here != version:
        pytest.skip(f"the list was made with Octave {version}, this is {here}")
    made = subprocess.run([octave, "--norc", "--no-init-file", "--quiet", "--eval", script], cwd=tmp_path,
                          capture_output=True, text=True).stdout.split()
    assert made == sorted(m_words.FUNCTIONS)

