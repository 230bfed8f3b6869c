#!/usr/bin/env python3
"""Checks the golden numbers of the C++ tests against implementations written from the docs.

    python3 tests/oracles/check_golden.py [PROJECT_ROOT] [--verbose]

tests/core/lattice_test.cc pins the noise lattice's test vectors and golden hash, and
tests/core/terrain_spec_cases.h, tests/core/terrain_spec_exact_case.h and
tests/core/terrain_spec_test.cc pin the worked numbers of docs/terrain-spec.md. Both pages say
the numbers were reproduced by an independent Python implementation; noise_lattice.py and
terrain_spec.py are that implementation, written from the pages alone, and this script
recomputes every such number and compares it with the literal as it is written in the C++ (so
editing one makes this fail).
Doubles and floats must match bit for bit (C++ ==), except where the pages say a C library may
differ in the last bit (pow for a_n, hypot for r0): those allow 1 ulp and say so in the table.
Exit status: 0 when every number matches, 1 otherwise. Standard library only; writes nothing.
"""

import sys

sys.dont_write_bytecode = True  # run from the source tree: leave no __pycache__ behind

import os  # noqa: E402
import re  # noqa: E402
import struct  # noqa: E402
import time  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import golden_sources as sources  # noqa: E402
import noise_lattice  # noqa: E402
import sketch_basis_spec  # noqa: E402
import terrain_spec  # noqa: E402
from golden_sources import NUMBER  # noqa: E402

LATTICE_TEST = "tests/core/lattice_test.cc"
CASES_HEADER = "tests/core/terrain_spec_cases.h"
EXACT_CASE_HEADER = "tests/core/terrain_spec_exact_case.h"
SPEC_TEST = "tests/core/terrain_spec_test.cc"
SKETCH_BASIS_HEADER = "tests/core/terrain_spec_sketch_basis_cases.h"

# Each worked case's terrain (changes from the default terrain), camera and point (dx, dz, nu),
# as the headings of docs/terrain-spec.md's "Worked numbers" state them. The headers' inputs are
# checked against these too, so an edited input is named rather than showing up as 100 outputs.
CASE_SETTINGS = {
    "kCaseA": ({}, (0.0, 700.0, 0.0), (1234.5, -2345.25, 5.375)),
    "kCaseB": ({"r": 2.17}, (1e9, 700.0, 2.5e8), (-4321.75, 987.625, 4.625)),
    "kCaseC": ({}, (1e12, 700.0, -1e12), (2000.5, -1500.25, 6.5)),
    "kCaseD": ({"warp": True, "r0": (3.0, 4.0), "t0": (0.5, -0.25)}, (0.0, 2200.0, 0.0),
               (-850.5, 3100.75, 6.625)),
    "kCaseE": ({"H": 0.05, "last_octave": 23}, (0.0, 700.0, 0.0), (45678.25, -31234.5, 23.5)),
}

# Field order of the structs in tests/core/terrain_spec_cases.h.
PLAN_FIELDS = ("frequency", "amplitude", "scale", "omega_x", "omega_z")
CELL_FIELDS = ("i0", "j0", "i1", "j1", "fx", "fz", "tx", "tz", "v00", "v10", "v01", "v11")
OCTAVE_FIELDS = ("exact", "offset_x", "offset_z", "gx", "gz", "wx", "wz", "px", "pz", "s", "h",
                 "height")


def ordered_bits(x):
    bits = struct.unpack("<q", struct.pack("<d", x))[0]
    return bits if bits >= 0 else -(bits & 0x7FFFFFFFFFFFFFFF)


def shortest_float32(x):
    for digits in range(1, 10):
        text = "%.*g" % (digits, x)
        if sources.to_float32(float(text)) == x:
            return text + "f"
    return repr(x) + "f"


class Report:
    """Every comparison made, grouped for the summary table."""

    def __init__(self, verbose):
        self.verbose, self.groups, self.failures = verbose, {}, []
        self.literals, self.within_ulp = {}, 0  # distinct golden literals; 1-ulp passes

    def compare(self, group, literal, label, computed, kind, ulps_allowed=0):
        if kind == "int":
            golden = literal.as_int()
            hexadecimal = literal.text.lower().startswith("0x")
            ok, shown = golden == computed, ("0x%x" if hexadecimal else "%d") % computed
        elif kind == "float32":
            golden = literal.as_float32()
            ok, shown = golden == computed, shortest_float32(computed)
        else:
            golden = literal.as_double()
            ok, shown = golden == computed, repr(computed)
        note = ""
        if ulps_allowed and not ok:
            ok = abs(ordered_bits(golden) - ordered_bits(computed)) <= ulps_allowed
            note = " (within the 1 ulp a C library may differ by)" if ok else ""
            self.within_ulp += ok
        elif ulps_allowed:
            note = " (exact; 1 ulp would be allowed)"
        self.literals[id(literal)] = literal  # kept alive, so no id is reused
        line = "%-4s %-36s %-46s golden %-24s computed %s%s" % (
            "ok" if ok else "FAIL", literal.where, "%s %s" % (group, label),
            literal.text, shown, note)
        passed, checked = self.groups.get(group, (0, 0))
        self.groups[group] = (passed + ok, checked + 1)
        if not ok:
            self.failures.append(line)
        if self.verbose:
            print(line)

    def error(self, group, message):
        passed, checked = self.groups.get(group, (0, 0))
        self.groups[group] = (passed, checked + 1)
        self.failures.append("FAIL %s" % message)

    def totals(self):
        passed = sum(p for p, _ in self.groups.values())
        return passed, sum(c for _, c in self.groups.values()) - passed


class Lattices:
    """Lattices by (seed, P), computed once each (the seed-1, P = 256 one serves everything)."""

    def __init__(self):
        self.cache = {}

    def get(self, seed, size):
        if (seed, size) not in self.cache:
            start = time.monotonic()
            print("computing the seed-%d, P = %d lattice (%d values) ..." % (seed, size, size * size),
                  end="", flush=True)

            def progress(rows, total):
                if rows % max(1, total // 4) == 0:
                    print(" %d%%" % (100 * rows // total), end="", flush=True)

            self.cache[(seed, size)] = noise_lattice.make_lattice(seed, size, progress)
            print(" %.1f s" % (time.monotonic() - start), flush=True)
        return self.cache[(seed, size)]


def check_lattice_test(root, report, lattices):
    """tests/core/lattice_test.cc: mix64 and counter_hash vectors, and the lattice's golden hash,
    against docs/noise-lattice.md ("Test vectors"). Every such CHECK in the file is found, so a
    vector added there is checked here too."""
    text = sources.read_source(root, LATTICE_TEST)
    group = "lattice_test.cc: hash test vectors"
    names = {"kGoldenGamma": noise_lattice.GOLDEN_GAMMA}
    streams = {"kLattice": noise_lattice.STREAM_LATTICE,
               "kOctaveOffset": noise_lattice.STREAM_OCTAVE_OFFSET}

    def argument(token):
        return names[token] if token in names else int(token.rstrip("uUlL"), 0)

    found = 0
    for match, lines in sources.find_all(text, r"mix64\(\s*(\w+)\s*\)\s*==\s*(%s)" % NUMBER):
        literal = sources.Literal(match.group(2), LATTICE_TEST, lines[1])
        report.compare(group, literal, "mix64(%s)" % match.group(1),
                       noise_lattice.mix64(argument(match.group(1))), "int")
        found += 1
    pattern = (r"counter_hash\(\s*(\w+)\s*,\s*HashStream::(\w+)\s*,\s*(\w+)\s*,\s*(\w+)\s*\)"
               r"\s*==\s*(%s)" % NUMBER)
    for match, lines in sources.find_all(text, pattern):
        seed, stream, a, b, value = match.groups()
        literal = sources.Literal(value, LATTICE_TEST, lines[4])
        computed = noise_lattice.counter_hash(argument(seed), streams[stream], argument(a),
                                              argument(b))
        report.compare(group, literal, "counter_hash(%s, %s, %s, %s)" % (seed, stream, a, b),
                       computed, "int")
        found += 1
    if found == 0:
        report.error(group, "%s: no mix64/counter_hash test vector found" % LATTICE_TEST)
    group = "lattice_test.cc: lattice golden hash"
    pattern = (r"make_noise_lattice\(\s*(\w+)\s*,\s*(\w+)\s*\)\s*;\s*CHECK\(\s*lattice_hash\("
               r"\s*\w+\s*\)\s*==\s*(%s)" % NUMBER)
    found = 0
    for match, lines in sources.find_all(text, pattern):
        seed, size = argument(match.group(1)), argument(match.group(2))
        literal = sources.Literal(match.group(3), LATTICE_TEST, lines[2])
        computed = noise_lattice.fnv1a64_of_floats(lattices.get(seed, size))
        report.compare(group, literal, "FNV-1a 64 of lattice(%d, %d)" % (seed, size),
                       computed, "int")
        found += 1
    if found == 0:
        report.error(group, "%s: no lattice_hash(...) == golden found" % LATTICE_TEST)


def case_terrain(name):
    changes, camera, point = CASE_SETTINGS[name]
    return terrain_spec.Terrain(**changes), camera, point


def check_rows(report, group, golden_rows, fields, computed_rows, kinds):
    if len(golden_rows) > len(computed_rows):
        report.error(group, "%s: %d rows in the header, %d octaves summed by the oracle" % (
            golden_rows[0][0].where if golden_rows and golden_rows[0] else group,
            len(golden_rows), len(computed_rows)))
    for n, (golden, computed) in enumerate(zip(golden_rows, computed_rows)):
        for field_name, literal, value in zip(fields, golden, computed):
            report.compare(group, literal, "[%d].%s" % (n, field_name), value,
                           kinds.get(field_name, "double"),
                           1 if field_name == "amplitude" else 0)


def check_worked_case(report, name, golden, lattice):
    """One WorkedCase: inputs, plan, octave 0's cell and every octave row, both precisions."""
    terrain, camera, point = case_terrain(name)
    group = "%s inputs" % name
    for label, literal, value in (("dx", golden["dx"], point[0]), ("dz", golden["dz"], point[1]),
                                  ("nu", golden["nu"], point[2])):
        report.compare(group, literal, label, value, "double")
    for axis, literal, value in zip("xyz", golden["camera"][0], camera):
        report.compare(group, literal, "camera." + axis, value, "double")

    plan = terrain_spec.make_plan(terrain, camera)
    plan_rows = list(zip(plan.frequency, plan.amplitude, plan.scale, plan.omega_x, plan.omega_z))
    check_rows(report, "%s plan (double)" % name, golden["plan"], PLAN_FIELDS, plan_rows, {})

    for precision, rnd, is_float in (("double", float, False),
                                     ("float", sources.to_float32, True)):
        kind = "float32" if is_float else "double"
        params = terrain_spec.Params(plan, terrain, rnd, is_float)
        dx, dz, nu = (rnd(v) for v in point)
        height, trace = terrain_spec.fbm_point(params, lattice, dx, dz, nu)
        height_key = "height_float" if is_float else "height"
        report.compare("%s height (%s)" % (name, precision), golden[height_key],
                       "fbm_height(dx, dz, nu)", height, kind)

        cell = trace[0].cell
        cell_values = (cell.i0, cell.j0, cell.i1, cell.j1, cell.t_x, cell.t_z, cell.fade_x,
                       cell.fade_z) + cell.corners
        cell_kinds = dict.fromkeys(("i0", "j0", "i1", "j1"), "int")
        cell_kinds.update(dict.fromkeys(("v00", "v10", "v01", "v11"), "float32"))
        if is_float:
            cell_kinds.update(dict.fromkeys(("fx", "fz", "tx", "tz"), "float32"))
        check_rows(report, "%s octave-0 cell (%s)" % (name, precision),
                   [golden["cell_" + precision]], CELL_FIELDS, [cell_values], cell_kinds)

        # The height column is what fbm_height returns with octave n the last one summed:
        # nu = n + 1 for whole octaves, nu itself on the last (fractional) row.
        rows = []
        golden_rows = golden["octaves_" + precision]
        for n, octave in enumerate(trace):
            last_nu = rnd(float(n + 1)) if n + 1 < len(golden_rows) else nu
            rows.append((octave.exact, octave.offset_x, octave.offset_z, octave.g_x, octave.g_z,
                         octave.w_x, octave.w_z, octave.p_x, octave.p_z, octave.cell.value,
                         octave.partial_sum,
                         terrain_spec.fbm_point(params, lattice, dx, dz, last_nu)[0]))
        row_kinds = dict.fromkeys(OCTAVE_FIELDS, kind)
        row_kinds["exact"] = "int"
        check_rows(report, "%s octaves (%s)" % (name, precision), golden_rows, OCTAVE_FIELDS,
                   rows, row_kinds)
        # The same column as relative_base_height + height_scale · h_n (section 6's return).
        check_rows(report, "%s octaves (%s)" % (name, precision),
                   [[row[-1]] for row in golden_rows], ("height from h_n",),
                   [[octave.height] for octave in trace], {"height from h_n": kind})


def check_spec_test_extras(root, report, lattice):
    """The literals tests/core/terrain_spec_test.cc holds itself (hand-kept patterns, one each)."""
    text = sources.read_source(root, SPEC_TEST)
    group = "terrain_spec_test.cc literals"

    def one(pattern, description):
        return sources.find_literal(text, SPEC_TEST, pattern, description)

    terrain, camera, _ = case_terrain("kCaseB")
    plan = terrain_spec.make_plan(terrain, camera)
    report.compare(group, one(r"plan\.octaves\.frequency\[3\]\s*==\s*(%s)" % NUMBER, "r^3"),
                   "case B r^3 by products", plan.frequency[3], "double")
    terrain, camera, _ = case_terrain("kCaseC")
    plan = terrain_spec.make_plan(terrain, camera)
    report.compare(group, one(r"world_period\s*==\s*(%s)" % NUMBER, "P*s"),
                   "case C world period P*s", plan.world_period, "double")

    terrain, camera, _ = case_terrain("kCaseD")
    plan = terrain_spec.make_plan(terrain, camera)
    params = terrain_spec.Params(plan, terrain, sources.to_float32, True)
    for axis, index in (("x", 0), ("z", 1)):
        report.compare(group, one(r"plan\.warp\.r0%s\s*==\s*(%s)" % (axis, NUMBER), "r0"),
                       "case D r0%s (double, hypot)" % axis, plan.r0[index], "double", 1)
        report.compare(group, one(r"make_fbm_params<float>\(plan\)\.r0%s\s*==\s*(%s)" %
                                  (axis, NUMBER), "float r0"),
                       "case D r0%s (float)" % axis, params.r0[index], "float32")

    terrain, camera, point = case_terrain("kCaseE")
    params = terrain_spec.Params(terrain_spec.make_plan(terrain, camera), terrain,
                                 sources.to_float32, True)
    for column, name in enumerate(("piece", "hi", "lo")):
        literals = sources.find_literal_list(
            text, SPEC_TEST, r"const float %s\[3\]\s*=\s*\{([^}]*)\}" % name, name + "[3]")
        for q, literal in enumerate(literals):
            report.compare(group, literal, "case E %s[%d] of g_23" % (name, q),
                           params.scale_pieces[23][q][column], "float32")
    d_hi, d_lo = params.split(sources.to_float32(point[0]))
    report.compare(group, one(r"d_hi\s*==\s*(%s)" % NUMBER, "d_hi"), "case E split(dx).hi",
                   d_hi, "float32")
    report.compare(group, one(r"d_lo\s*==\s*(%s)" % NUMBER, "d_lo"), "case E split(dx).lo",
                   d_lo, "float32")

    bounds = terrain_spec.height_bounds(terrain_spec.Terrain(), min(lattice), max(lattice))
    for index, side in enumerate(("world_min", "world_max")):
        report.compare(group, one(r"bounds\.%s\s*==\s*(%s)" % (side, NUMBER), side),
                       "default height bounds %s" % side, bounds[index], "double")


def check_sketch_basis_cases(root, report):
    """Cases F and G (tests/core/terrain_spec_sketch_basis_cases.h) against sketch_basis_spec.py:
    every constant the oracle computes must be in the header, and nothing else."""
    text = sources.read_source(root, SKETCH_BASIS_HEADER)
    golden = sketch_basis_spec.golden()
    declared = set(re.findall(r"inline constexpr \w+ (k\w+)", text))
    if declared != set(golden):
        raise sources.GoldenSourceError("%s declares %s, the oracle computes %s" % (
            SKETCH_BASIS_HEADER, sorted(declared ^ set(golden)), "the others"))
    group = "cases F, G (sketch, basis images)"
    for name, (value, kind) in golden.items():
        if isinstance(value, list):
            literals = sources.find_literal_list(
                text, SKETCH_BASIS_HEADER, r"\b%s\[\d+\]\s*=\s*\{([^}]*)\}" % name, name)
            if len(literals) != len(value):
                raise sources.GoldenSourceError("%s: %s has %d values, the oracle %d" % (
                    SKETCH_BASIS_HEADER, name, len(literals), len(value)))
            for k, (literal, computed) in enumerate(zip(literals, value)):
                report.compare(group, literal, "%s[%d]" % (name, k), computed, kind)
        else:
            literal = sources.find_literal(
                text, SKETCH_BASIS_HEADER, r"\b%s\s*=\s*(%s);" % (name, NUMBER), name)
            report.compare(group, literal, name, value, kind)


def main(argv):
    verbose = "--verbose" in argv
    arguments = [a for a in argv[1:] if a != "--verbose"]
    if len(arguments) > 1:
        print(__doc__)
        return 1
    root = arguments[0] if arguments else os.path.join(os.path.dirname(__file__), "..", "..")
    start = time.monotonic()
    report, lattices = Report(verbose), Lattices()
    lattice = lattices.get(1, 256)  # every worked case and the bounds use seed 1, P = 256
    steps = [("lattice", lambda: check_lattice_test(root, report, lattices))]
    for header in (CASES_HEADER, EXACT_CASE_HEADER):
        def check_header(header=header):
            cases = sources.parse_worked_cases(sources.read_source(root, header), header)
            for name, golden in cases.items():
                if name not in CASE_SETTINGS:
                    raise sources.GoldenSourceError(
                        "%s: no settings for %s in check_golden.py's CASE_SETTINGS" % (header, name))
                check_worked_case(report, name, golden, lattice)
        steps.append((header, check_header))
    steps.append((SPEC_TEST, lambda: check_spec_test_extras(root, report, lattice)))
    steps.append((SKETCH_BASIS_HEADER, lambda: check_sketch_basis_cases(root, report)))
    for name, step in steps:
        try:
            step()
        except (sources.GoldenSourceError, KeyError, IndexError, ValueError) as error:
            report.error(name, "%s: %s: %s" % (name, type(error).__name__, error))

    print("\n%-44s %7s %7s" % ("golden numbers of", "checked", "passed"))
    for group, (passed, checked) in report.groups.items():
        print("%-44s %7d %7d%s" % (group, checked, passed, "" if passed == checked else "  <--"))
    if report.failures:
        print("\nFailures (golden as written in the C++, computed by tests/oracles from the docs):")
        for line in report.failures:
            print(line)
    passed, failed = report.totals()
    print("\n%d golden literals, %d comparisons (row heights are compared twice), %d of them "
          "passing only within 1 ulp" % (len(report.literals), passed + failed, report.within_ulp))
    print("%d passed, %d failed (%.1f s)" % (passed, failed, time.monotonic() - start))
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
