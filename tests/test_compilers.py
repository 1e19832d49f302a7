"""The generated C under every compiler a user's project may build it with.

Every sample and test mechanism, gcc and clang at -O0, -O2, -O3 and -Os with
`-std=c99 -Wall -Wextra -Werror -pedantic -Wshadow -Wstrict-prototypes -Wmissing-prototypes`:
no diagnostic at all, and every build writes the same CSV bits.  A C++ host (g++ and clang++,
`-std=c++11 -Wall -Wextra -Werror -pedantic`) includes NAME.h and links the C library; NAME.c
itself also compiles as C++.  AddressSanitizer and UBSan (gcc and clang) find nothing in the
sweep or in refused calls.  `make test` runs a fast subset (NAME.c alone under gcc -O2 and
clang -O3, one C++ host); the full matrix is the long tier.
"""

from __future__ import annotations

import functools
import os
import subprocess
from pathlib import Path

import pytest
from programs import CXXFLAGS, ROOT, SAMPLES, SANITIZE, STRICT, build, compile_step, host_source, need

from linkgen.render.view import build_view

MECHANISMS = SAMPLES + sorted((ROOT / "tests" / "mechanisms").glob("*.yaml"))
LEVELS = ("-O0", "-O2", "-O3", "-Os")
CXX = {"gcc": "g++", "clang": "clang++"}


def _id(path: Path) -> str:
    return f"{path.parent.name}-{path.stem}" if path.parent.name == "mechanisms" else path.stem


@pytest.fixture(scope="module", params=MECHANISMS, ids=_id)
def generated(request, tmp_path_factory):
    outdir = tmp_path_factory.mktemp(_id(request.param))
    log = build(request.param, outdir)
    (outdir / "host.c").write_text(host_source(log, build_view(log).record_order + 1))
    return log, outdir


def _run(exe: Path, cwd: Path) -> str:
    done = subprocess.run([str(exe)], cwd=cwd, capture_output=True, text=True)
    assert done.returncode == 0 and not done.stderr, done.stderr
    return done.stdout


def _sweep(cc: str, flags: list[str], log, outdir: Path, tag: str) -> str:
    """Compile NAME.c and NAME_main.c with cc and flags, link, and return the sweep's CSV."""
    exe = outdir / f"sweep_{tag}"
    for src in (log.name, f"{log.name}_main"):
        compile_step([need(cc), *flags, "-c", f"{src}.c", "-o", f"{src}_{tag}.o"], outdir)
    compile_step([need(cc), *flags, f"{log.name}_{tag}.o", f"{log.name}_main_{tag}.o", "-lm", "-o", exe.name], outdir)
    return _run(exe, outdir)


def _reference(log, outdir: Path) -> str:
    """The sweep built by gcc -O0, once per mechanism."""
    path = outdir / "reference.csv"
    if not path.exists():
        path.write_text(_sweep("gcc", [*STRICT, "-O0"], log, outdir, "gcc-O0"))
    return path.read_text()


def _host(cc: str, cxx: str, lib_flags: list[str], log, outdir: Path, tag: str, lib_as_cxx: bool = False,
          extra: tuple[str, ...] = ()) -> str:
    """The C++ host linked with NAME.c (compiled as C by cc, or as C++ by cxx); its CSV."""
    (outdir / "host.cpp").write_text((outdir / "host.c").read_text())
    lib = [need(cxx), "-x", "c++", *CXXFLAGS] if lib_as_cxx else [need(cc), *lib_flags]
    compile_step([*lib, *extra, "-c", f"{log.name}.c", "-o", f"lib_{tag}.o"], outdir)
    compile_step([need(cxx), *CXXFLAGS, *extra, "-c", "host.cpp", "-o", f"host_{tag}.o"], outdir)
    compile_step([need(cxx), *extra, f"host_{tag}.o", f"lib_{tag}.o", "-lm", "-o", f"host_{tag}"], outdir)
    return _run(outdir / f"host_{tag}", outdir)


# -- make test: the fast subset -------------------------------------------------

def test_library_compiles_strictly_under_gcc_and_clang(generated):
    """NAME.c alone, gcc -O2 and clang -O3 at once (the levels where gcc's flow analysis and clang's
    inlining see most; -O2 is where `w.phi_block.the may be used uninitialized` came from)."""
    log, outdir = generated
    jobs = [subprocess.Popen([need(cc), *STRICT, level, "-c", f"{log.name}.c", "-o", f"fast_{cc}.o"], cwd=outdir,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            for cc, level in (("gcc", "-O2"), ("clang", "-O3"))]
    for job in jobs:
        out, err = job.communicate()
        assert job.returncode == 0 and not err and not out, f"{' '.join(job.args)}\n{err}"


def test_cpp_host_agrees_with_the_c_sweep(tmp_path):
    """A resolver mechanism (the warm start lives in the state the host keeps): g++ host, gcc library."""
    log = build(ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml", tmp_path)
    (tmp_path / "host.c").write_text(host_source(log, build_view(log).record_order + 1))
    assert _host("gcc", "g++", [*STRICT, "-O2"], log, tmp_path, "gxx") == _reference(log, tmp_path)


# -- make test-long: the full matrix -------------------------------------------

@pytest.mark.long
@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_every_level_compiles_strictly_and_writes_the_same_bits(generated, cc):
    log, outdir = generated
    reference = _reference(log, outdir)
    for level in LEVELS:
        assert _sweep(cc, [*STRICT, level], log, outdir, f"{cc}{level}") == reference, (cc, level)


@pytest.mark.long
@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_cpp_host_links_the_c_library(generated, cc):
    log, outdir = generated
    reference = _reference(log, outdir)
    assert _host(cc, CXX[cc], [*STRICT, "-O2"], log, outdir, f"{cc}-host") == reference


@pytest.mark.long
@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_library_compiles_as_cpp(generated, cc):
    """NAME.c itself is also valid C++ (under -pedantic too: no compound literals, no implicit
    conversions from void *), and computes the same bits."""
    log, outdir = generated
    reference = _reference(log, outdir)
    assert _host(cc, CXX[cc], [], log, outdir, f"{cc}-cxx", lib_as_cxx=True) == reference


@functools.cache
def _sanitizer_runtime(cc: str, workdir: str) -> str:
    """Why cc cannot link a sanitized program ('' when it can: clang needs libclang-rt-*-dev)."""
    src = Path(workdir) / "empty.c"
    src.write_text("int main(void) { return 0; }\n")
    done = subprocess.run([need(cc), *SANITIZE, src.name, "-o", f"empty_{cc}"], cwd=workdir, capture_output=True,
                          text=True)
    return done.stderr if done.returncode else ""


@pytest.mark.long
@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_sanitizers_find_nothing(generated, cc, tmp_path_factory):
    """The sweep and the refused calls (the host) under ASan and UBSan; the same CSV as without."""
    missing = _sanitizer_runtime(cc, str(tmp_path_factory.getbasetemp()))
    if missing:
        if os.environ.get("CI"):
            pytest.fail(f"{cc} cannot link sanitized programs in CI: {missing}")
        pytest.skip(f"{cc} cannot link sanitized programs here: {missing}")
    log, outdir = generated
    reference = _reference(log, outdir)
    assert _sweep(cc, [*STRICT, "-O1", *SANITIZE], log, outdir, f"{cc}-san") == reference
    assert _host(cc, CXX[cc], [*STRICT, "-O1"], log, outdir, f"{cc}-host-san", extra=tuple(SANITIZE)) == reference
