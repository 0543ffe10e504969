#!/usr/bin/env python3
"""Mutation checks: each mutation below breaks the code on purpose in a scratch copy of HEAD (a
git worktree under DTLAB_MUTATION_DIR, default /tmp/dtlab-mutations, with its own release build),
builds the test that must catch it, runs it, and prints "caught" (the test failed) or "MISSED"
(it passed); the file is restored before the next mutation. Then the stage histogram's seed sweep.
Exits 1 when a mutation is missed, no longer applies (the code it edits changed: update the list)
or does not build, or when the seed sweep fails.

Usage: tools/mutation_checks.py [NAME...]   (default: every mutation and the seed sweep)
About 25 minutes on the 2-core development VM from nothing, most of it the first build.
"""
import os
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path


@dataclass
class Mutation:
    name: str
    file: str
    old: str  # must occur in the file
    new: str
    target: str  # the CMake target of the test
    binary: str  # under the build folder
    gtest_filter: str
    rc_params: str = "seed=20261121 max_success=300"


MUTATIONS = [
    # Orientation (issue 38, part 1): an inverted tetrahedron in the output, and a canonical form
    # that forgets orientation.
    Mutation("output-inverted", "engine/src/driver/triangulate.cpp",
             "  stats.seconds.output += std::chrono",
             "  if (!result.tetrahedra.empty()) {\n"
             "    std::swap(result.tetrahedra[0][0], result.tetrahedra[0][1]);\n  }\n"
             "  stats.seconds.output += std::chrono",
             "cgal_oracle_test", "tests/cgal_oracle_test",
             "CgalOracle.EveryFamilyIdenticalTetrahedra"),
    Mutation("canonical-drops-orientation", "engine/src/driver/triangulate.cpp",
             "    if (odd) std::swap(t[2], t[3]);", "    (void)odd;",
             "cgal_oracle_test", "tests/cgal_oracle_test",
             "CanonicalTetrahedra.*:CgalOracle.AnInvertedTetrahedronIsADifference"),
    # Answers from CGAL, not from the code under test (part 2).
    Mutation("aux-loss-not-counted", "engine/src/driver/triangulate.cpp",
             "stats.hull_tetrahedra_lost = hull_tetrahedra_lost(",
             "stats.hull_tetrahedra_lost = 0 * hull_tetrahedra_lost(",
             "cgal_oracle_test", "tests/cgal_oracle_test", "AuxTet.*"),
    Mutation("validator-counts-no-non-delaunay-face", "engine/src/validate/validator.cpp",
             "      r.non_delaunay_faces += non_delaunay;",
             "      r.non_delaunay_faces += 0 * non_delaunay;",
             "parallel_test", "tests/parallel_test",
             "ParallelMethods.BurglaryStaysConsistentAndRepairs"),
    Mutation("repair-without-bridges", "engine/src/repair/list_repair.cpp",
             "    if (bridges.empty()) break;", "    break;",
             "repair_properties", "property_tests/repair_properties", "Repair.*"),
    # The fast kernel then star splaying (found by a fresh RapidCheck seed, 2026-11-28).
    Mutation("fast-splay-duplicate-named-high", "engine/src/driver/triangulate.cpp",
             "if (duplicates || inexact_repaired) name_duplicates",
             "if (duplicates) name_duplicates",
             "regressions_test", "property_tests/regressions_test",
             "Regressions.KeptPointSetsValidate"),
    Mutation("scan-misses-reflex-hull-vertex", "engine/src/repair/exact_scan.cpp",
             "if (t.is_infinite() && !exact_mesh) {",
             "if (t.is_infinite() && !exact_mesh && false) {",
             "regressions_test", "property_tests/regressions_test",
             "Regressions.KeptPointSetsValidate"),
    # Checks that could not fail before (part 3).
    Mutation("huge-family-scaled-wrong", "generators/src/generators.cpp",
             "scaled_uniform(n, rng, 1e150)", "scaled_uniform(n, rng, 1e151)",
             "generators_test", "tests/generators_test",
             "Generators.DegenerateFamiliesHaveTheirDefiningProperty"),
    # The packed insphere (last: the header rebuilds most of the engine).
    Mutation("packed-lift-reassociated",
             "predicates/include/dtlab/predicates/detail/float_determinants.hpp",
             "_mm_add_pd(_mm_add_pd(_mm_mul_pd(x, x), _mm_mul_pd(y, y)), _mm_mul_pd(z, z))",
             "_mm_add_pd(_mm_mul_pd(x, x), _mm_add_pd(_mm_mul_pd(y, y), _mm_mul_pd(z, z)))",
             "predicates_test", "tests/predicates_test", "Stages.PackedEvaluationIsTheScalarOne"),
]


def run(cmd, **kwargs):
    return subprocess.run(cmd, check=False, **kwargs)


def main() -> int:
    wanted = set(sys.argv[1:])
    root = Path(subprocess.check_output(
        ["git", "-C", str(Path(__file__).parent), "rev-parse", "--show-toplevel"], text=True).strip())
    work = Path(os.environ.get("DTLAB_MUTATION_DIR", "/tmp/dtlab-mutations"))
    src, build = work / "src", work / "build"
    head = subprocess.check_output(["git", "-C", str(root), "rev-parse", "HEAD"], text=True).strip()
    if not src.is_dir():
        work.mkdir(parents=True, exist_ok=True)
        subprocess.check_call(["git", "-C", str(root), "worktree", "add", "--detach", str(src), head],
                              stdout=subprocess.DEVNULL)
    else:
        subprocess.check_call(["git", "-C", str(src), "checkout", "-q", "--detach", head])
        subprocess.check_call(["git", "-C", str(src), "checkout", "-q", "--", "."])
    subprocess.check_call(["cmake", "-S", str(src), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                           "-DDTLAB_BUILD_TESTS=ON", "-DDTLAB_BUILD_BENCH=OFF"],
                          stdout=subprocess.DEVNULL)
    jobs = str(os.cpu_count() or 1)
    failed = 0
    for m in MUTATIONS:
        if wanted and m.name not in wanted:
            continue
        # The test must pass unmutated first, or a failure would say nothing about the mutation.
        built = run(["cmake", "--build", str(build), "-j", jobs, "--target", m.target],
                    stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT).returncode == 0
        env = dict(os.environ, RC_PARAMS=m.rc_params)
        if not built or run([str(build / m.binary), f"--gtest_filter={m.gtest_filter}"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT,
                            env=env).returncode != 0:
            print(f"mutation {m.name}: {m.gtest_filter} does not pass unmutated", flush=True)
            failed += 1
            continue
        path = src / m.file
        text = path.read_text()
        if m.old not in text:
            print(f"mutation {m.name}: does not apply (its text is not in {m.file})", flush=True)
            failed += 1
            continue
        path.write_text(text.replace(m.old, m.new, 1))
        try:
            with open(work / f"build-{m.name}.log", "w") as log:
                built = run(["cmake", "--build", str(build), "-j", jobs, "--target", m.target],
                            stdout=log, stderr=subprocess.STDOUT).returncode == 0
            if not built:
                verdict = f"does not build (see {work}/build-{m.name}.log)"
            else:
                with open(work / f"run-{m.name}.log", "w") as log:
                    env = dict(os.environ, RC_PARAMS=m.rc_params)
                    code = run([str(build / m.binary), f"--gtest_filter={m.gtest_filter}"],
                               stdout=log, stderr=subprocess.STDOUT, env=env).returncode
                verdict = "caught" if code != 0 else "MISSED"
        finally:
            path.write_text(text)
        print(f"mutation {m.name}: {verdict} by {m.gtest_filter}", flush=True)
        failed += verdict != "caught"

    # Not a mutation: the stage histogram's property reaches every stage whatever the seed.
    if not wanted or "stage-histogram-seeds" in wanted:
        subprocess.check_call(["cmake", "--build", str(build), "-j", jobs, "--target",
                               "predicates_test"], stdout=subprocess.DEVNULL)
        failures = 0
        # At each case count the suites use: 300 (release), 60 (fresh seed), 40 (ASan).
        runs = 0
        for cases in (300, 60, 40):
            for seed in range(1, 101):
                env = dict(os.environ, RC_PARAMS=f"seed={seed} max_success={cases}")
                failures += run([str(build / "tests/predicates_test"),
                                 "--gtest_filter=StageHistogram.PropertyRunReachesEveryStage"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                env=env).returncode != 0
                runs += 1
        print(f"stage histogram: {failures} failures in {runs} runs (seeds 1-100 at 300, 60 and "
              "40 cases)", flush=True)
        failed += failures != 0

    print(f"mutation checks: {failed} missed or failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
