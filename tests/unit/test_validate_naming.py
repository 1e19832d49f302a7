"""linkgen.validate.naming: names the generated programs cannot carry are refused where the file gives
them, with the reason and a name that would do (the lists themselves are tests/unit/test_names.py's and
the backends' words tests'): the mechanism's name, and the pairs, points and links, including two names a
program would write alike."""

from __future__ import annotations

import pytest
from mechanism_text import check, fourbar, refused

from linkgen.backends.c import words as c_words
from linkgen.backends.m import words as m_words
from linkgen.names import entity_name_problem, mechanism_name_problem

# -- the mechanism name ---------------------------------------------------------

@pytest.mark.parametrize("name, reason", [
    ("zeros", "is a MATLAB/Octave function, which the script zeros.m would hide"),
    ("size", "is a MATLAB/Octave function, which the script size.m would hide"),
    ("fprintf", "is a MATLAB/Octave function, which the script fprintf.m would hide"),
    ("json", "is a module of Python's standard library, which json.py would hide"),
    ("random", "is a module of Python's standard library, which random.py would hide"),
    ("until", "is a MATLAB/Octave keyword, so the script until.m cannot be run"),
    ("row", "is a variable of the sweep script row.m, which after one run would hide the script"),
    ("None", "is a Python keyword, so the module None.py cannot be imported"),
    ("isinstance", "is a Python built-in, which `import isinstance` would hide in the importing module"),
    ("String", "makes String.h, which would hide the C header <string.h> from a compiler given -I"),
    ("features", "makes features.h, which would hide the C header <features.h> from a compiler given -I"),
    ("Com1", "is a device name on Windows, which cannot create a file named Com1.c"),
])
def test_a_refused_mechanism_name_says_why_and_suggests_one(name: str, reason: str):
    error = refused(fourbar(fourbar=name))
    assert (error.line, error.key) == (2, "name")
    assert error.message == f"{name} {reason}; choose another name for the mechanism, such as {name}_linkage"
    check(fourbar(fourbar=f"{name}_linkage"))


@pytest.mark.parametrize("name", ["auto", "register", "typedef", "NAN", "linux", "EOF", "new", "zeros_linkage",
                                  "solve", "strandbeest"])
def test_c_words_and_near_misses_are_fine_mechanism_names(name: str):
    """The mechanism name is never a C identifier by itself (NAME_state, NAME_solve, ...)."""
    assert check(fourbar(fourbar=name)).mechanism.name == name


# -- pair, point and link names ---------------------------------------------------

ENTITY_REFUSED = {
    "state field": c_words.STATE_FIELDS | m_words.STATE_FIELDS,
    "header name": c_words.header_names("fourbar"),
    "macro of NAME.c": c_words.SOURCE_MACROS,
}


@pytest.mark.parametrize("listed", sorted(ENTITY_REFUSED))
def test_every_name_of_every_refused_list_is_refused_as_a_link_name(listed: str):
    for name in sorted(ENTITY_REFUSED[listed]):
        error = refused(fourbar(rocker=name))
        assert (error.line, error.key) == (14, f"links.{name}")
        assert error.message.startswith(f"{name} is "), error.message
        assert error.message.endswith(f"; call the link {name}_link or similar"), error.message
        check(fourbar(rocker=f"{name}_link"))


def test_a_state_field_names_the_structures_that_have_it():
    assert refused(fourbar(P="sigma")).message == (
        "sigma is a field of the generated state (C fourbar_state, MATLAB/Octave out); "
        "call the point sigma_point or similar")
    assert refused(fourbar(B="status")).message == (
        "status is a field of the generated state (C fourbar_state); call the pair status_pair or similar")
    assert refused(fourbar(crank="columns")).message == (
        "columns is a field of the generated state (MATLAB/Octave out); call the link columns_link or similar")


def test_a_renamed_name_and_its_spelling_cannot_both_be_given():
    error = refused(fourbar(crank="do", rocker="do_"))
    assert (error.line, error.key) == (14, "links.do_")
    assert error.message == ("do_ is written do_ in the generated C program, as is do (line 12), because do is a C "
                             "keyword and gets a trailing _ there; call the link do_link or similar")
    error = refused(fourbar(rocker="until", O2="until_"))
    assert (error.line, error.key) == (14, "links.until")
    assert "until is written until_ in the generated MATLAB/Octave program, as is until_ (line 9)" in error.message


@pytest.mark.parametrize("name, key, reason, better", [
    ("_B", "joints._B", "starts with _, which a MATLAB struct field cannot (out._B) and C reserves", "pair B"),
    ("B__1", "joints.B__1", "contains __, which C++ reserves (the generated header is C++ too)", "pair B_1"),
    ("B" * 64, "joints." + "B" * 64, "has 64 characters; a MATLAB struct field has at most 63", ""),
])
def test_names_no_language_allows_are_refused(name: str, key: str, reason: str, better: str):
    error = refused(fourbar(B=name))
    assert (error.line, error.key) == (8, key)
    advice = f"call the {better} or similar" if better else "choose another name for the pair"
    assert error.message == f"{name} {reason}; {advice}"


def test_names_are_checked_whether_outputs_lists_them_or_not():
    text = fourbar(P="sigma") + "outputs: [B]\n"
    assert refused(text).key == "links.coupler.points.sigma"




@pytest.mark.parametrize("name, better", [
    ("_private", "private"),  # the leading _ dropped
    ("m" * 58, "m" * 40 + "_linkage"),  # too long for MATLAB: cut to 40 characters
    ("pi", "pi_linkage"),
])
def test_the_suggested_mechanism_name_is_the_first_that_would_do(name: str, better: str):
    assert mechanism_name_problem(name) and not mechanism_name_problem(better)
    error = refused(fourbar(fourbar=name))
    assert error.message.endswith(f"; choose another name for the mechanism, such as {better}")
    assert check(fourbar(fourbar=better)).mechanism.name == better


@pytest.mark.parametrize("old, name, what, better", [
    ("P", "sigma", "point", "sigma_point"),  # the name itself is taken, so name_point
    ("B", "B__1", "pair", "B_1"),  # the runs of _ closed up
    ("coupler", "iterations", "link", "iterations_link"),
])
def test_the_suggested_entity_name_is_free_and_allowed(old: str, name: str, what: str, better: str):
    error = refused(fourbar(**{old: name}))
    assert error.message.endswith(f"; call the {what} {better} or similar")
    assert entity_name_problem(name, "fourbar") and not entity_name_problem(better, "fourbar")
    check(fourbar(**{old: better}))


def test_a_name_refused_for_the_mechanism_is_fine_for_a_link_and_back():
    """The two namespaces differ: zeros names a script (refused) but is a fine field; a state field
    (iterations) names no file."""
    assert check(fourbar(rocker="zeros")).mechanism.links[3].name == "zeros"
    assert check(fourbar(fourbar="iterations")).mechanism.name == "iterations"


def test_names_a_language_renames_are_accepted_when_no_other_name_is_written_alike():
    topo = check(fourbar(crank="do", rocker="until"))
    assert [lk.name for lk in topo.mechanism.links] == ["frame", "do", "coupler", "until"]
    assert c_words.WORDS.field("do") == "do_" and m_words.WORDS.field("until") == "until_"
