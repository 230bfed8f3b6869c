"""Reads the golden numbers out of the C++ test sources, as the compiler would read them.

check_golden.py compares the oracles against these values, so every number is taken from the
file as it is now: editing a golden literal in the C++ makes the check fail. Each literal keeps
its file and line so that a failure names the number where it is written.
"""

import re
import struct
from dataclasses import dataclass
from fractions import Fraction

NUMBER = r"[-+]?(?:0[xX][0-9a-fA-F]+|\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?)[fFuUlL]*"


class GoldenSourceError(Exception):
    """A golden number could not be found or read: the source's layout changed."""


@dataclass
class Literal:
    text: str  # as written, suffix included
    path: str  # relative to the project root
    line: int

    @property
    def where(self):
        return "%s:%d" % (self.path, self.line)

    def as_int(self):
        return int(self.text.rstrip("uUlL"), 0)

    def as_double(self):
        """A double literal (no suffix) is the decimal rounded once to binary64."""
        if self.text[-1] in "fF":
            return self.as_float32()
        return float(self.text.rstrip("uUlL"))

    def as_float32(self):
        """An f-suffixed literal is the decimal rounded once to binary32 (not via a double:
        decimal -> double -> float can round twice); a plain literal stored in a float is the
        double converted to float, as C++ does."""
        if self.text[-1] not in "fF":
            return to_float32(float(self.text))
        return decimal_to_float32(self.text[:-1])


def to_float32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def _float32_neighbours(x):
    bits = struct.unpack("<I", struct.pack("<f", x))[0]
    result = [x]
    for step in (-1, 1):
        neighbour_bits = bits + step
        if 0 <= neighbour_bits < 0xFFFFFFFF:
            value = struct.unpack("<f", struct.pack("<I", neighbour_bits))[0]
            if value == value and abs(value) != float("inf"):
                result.append(value)
    return result


def decimal_to_float32(text):
    """The binary32 nearest to the decimal (ties to the even significand)."""
    exact = Fraction(text)
    candidates = _float32_neighbours(to_float32(float(exact)))

    def distance_then_odd(candidate):
        bits = struct.unpack("<I", struct.pack("<f", candidate))[0]
        return (abs(Fraction(candidate) - exact), bits & 1)

    return min(candidates, key=distance_then_odd)


def read_source(root, relative_path):
    try:
        with open("%s/%s" % (root, relative_path), encoding="utf-8") as handle:
            return handle.read()
    except OSError as error:
        raise GoldenSourceError("cannot read %s: %s" % (relative_path, error)) from error


def _blank_comments(text):
    """Comments replaced by spaces of the same length, so offsets and lines are kept."""
    def blank(match):
        return re.sub(r"[^\n]", " ", match.group(0))
    return re.sub(r"//[^\n]*|/\*.*?\*/", blank, text, flags=re.S)


def _line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def _one_match(text, path, pattern, description):
    """The one match of pattern (comments blanked); an absent or repeated match is an error,
    because a hand-kept pattern that no longer matches must not pass silently."""
    matches = list(re.finditer(pattern, _blank_comments(text), flags=re.S))
    if len(matches) != 1:
        raise GoldenSourceError("%s: expected one match for %s (/%s/), found %d" %
                                (path, description, pattern, len(matches)))
    return matches[0]


def find_literal(text, path, pattern, description):
    """The one literal captured by group 1 of pattern."""
    match = _one_match(text, path, pattern, description)
    return Literal(match.group(1), path, _line_of(text, match.start(1)))


def find_literal_list(text, path, pattern, description):
    """The comma-separated literals inside group 1 of pattern (a C array initialiser)."""
    match = _one_match(text, path, pattern, description)
    return [Literal(number.group(0), path, _line_of(text, match.start(1) + number.start()))
            for number in re.finditer(NUMBER, match.group(1))]


def find_all(text, pattern):
    """Every match of pattern (comments blanked), with the line of each group."""
    clean = _blank_comments(text)
    for match in re.finditer(pattern, clean, flags=re.S):
        yield match, [_line_of(text, match.start(g)) for g in range(1, len(match.groups()) + 1)]


# ---- Designated initialisers of the WorkedCase structs ------------------------------------

_TOKEN = re.compile(r"(?P<designator>\.[A-Za-z_]\w*\s*=)|(?P<open>\{)|(?P<close>\})|(?P<comma>,)"
                    r"|(?P<number>" + NUMBER + r")|(?P<space>\s+)")


class _InitialiserReader:
    """A recursive-descent reader of one braced initialiser: numbers, braces, designators."""

    def __init__(self, text, start, path):
        self.text, self.position, self.path = text, start, path

    def _next(self):
        while True:
            match = _TOKEN.match(self.text, self.position)
            if not match:
                raise GoldenSourceError("%s:%d: unexpected text %r in an initialiser" % (
                    self.path, _line_of(self.text, self.position),
                    self.text[self.position:self.position + 20]))
            self.position = match.end()
            if match.lastgroup != "space":
                return match.lastgroup, match.group(0), _line_of(self.text, match.start())

    def value(self, first=None):
        kind, token, line = first or self._next()
        if kind == "number":
            return Literal(token, self.path, line)
        if kind != "open":
            raise GoldenSourceError("%s:%d: expected a value, found %r" % (self.path, line, token))
        named, positional, name = {}, [], None
        while True:
            kind, token, line = self._next()
            if kind == "close":
                break
            if kind == "comma":
                continue
            if kind == "designator":
                name = token[1:].rstrip("= \t\n")
                continue
            item = self.value((kind, token, line))
            if name is None:
                positional.append(item)
            else:
                named[name], name = item, None
        if named and positional:
            raise GoldenSourceError("%s:%d: mixed designated and positional values" %
                                    (self.path, line))
        return named if named else positional


def parse_worked_cases(text, path):
    """Every `const WorkedCase NAME = {...};` of the file, as nested dicts and lists."""
    clean = _blank_comments(text)
    cases = {}
    for match in re.finditer(r"const\s+WorkedCase\s+(\w+)\s*=\s*(?=\{)", clean):
        cases[match.group(1)] = _InitialiserReader(clean, match.end(), path).value()
    if not cases:
        raise GoldenSourceError("%s: no `const WorkedCase NAME = {...}` found" % path)
    return cases
