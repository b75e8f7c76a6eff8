"""The ctypes mirrors (python/mvr/_native.py) against the C headers: every
struct's size, every field's offset and size, every enum value the package
uses, as py_reference (compiled against include/mvr) prints them."""
import ctypes

import pytest

from mvr import _native as N


@pytest.fixture(scope="module")
def c_layout(reference):
    structs, fields, enums = {}, {}, {}
    for line in reference("layout").stdout.splitlines():
        kind, *rest = line.split()
        if kind == "S":
            structs[rest[0]] = int(rest[1])
        elif kind == "F":
            fields.setdefault(rest[0], {})[rest[1]] = (int(rest[2]), int(rest[3]))
        elif kind == "E":
            enums[rest[0]] = int(rest[1])
    return structs, fields, enums


@pytest.mark.parametrize("cls", N.STRUCTS, ids=lambda c: c.c_name)
def test_struct_matches_c(c_layout, cls):
    structs, fields, _ = c_layout
    assert cls.c_name in structs, "py_reference does not print %s" % cls.c_name
    c_fields = fields[cls.c_name]
    py_fields = cls.field_names()
    # the same fields in the same order (a field added in C and not here, or
    # the other way round, fails even where the size happens to agree)
    assert py_fields == sorted(c_fields, key=lambda f: c_fields[f][0]), cls.c_name
    for name in py_fields:
        d = getattr(cls, name)
        assert (d.offset, d.size) == c_fields[name], "%s.%s: offset/size %s in Python, %s in C" % (
            cls.c_name, name, (d.offset, d.size), c_fields[name])
    assert ctypes.sizeof(cls) == structs[cls.c_name], "sizeof(%s)" % cls.c_name


def test_enums_match_c(c_layout):
    _, _, enums = c_layout
    checked = 0
    for enum in N.ENUMS:
        for py, c_name in enum.c_names.items():
            assert c_name in enums, "py_reference does not print %s" % c_name
            assert enum.values[py] == enums[c_name], "%s: %d in Python, %d in C" % (
                c_name, enum.values[py], enums[c_name])
            checked += 1
    assert checked > 100
    assert N.ERROR_MESSAGE_SIZE == enums["MVR_ERROR_MESSAGE_SIZE"]
    assert N.CAPS_STRING_SIZE == enums["MVR_CAPS_STRING_SIZE"]
    assert N.IMAGE_MAX_LEVELS == enums["MVR_IMAGE_MAX_LEVELS"]


def test_outputs_read_back_as_the_library_says():
    """Each output's array holds mvr_output_pixel_size bytes a pixel, and
    the package's names are mvr_output_name's."""
    for name, (channels, dtype) in N.OUTPUT_PIXEL.items():
        size = channels * (1 if dtype == "uint8" else 4)
        assert N.C.mvr_output_pixel_size(N.OUTPUT(name)) == size, name
        assert N.text(N.C.mvr_output_name(N.OUTPUT(name))) == name
