"""Every public name has a docstring: the names `import vofdem` exports (the C++ extension's classes,
enums and functions, and the Python functions beside them) and the public classes and functions of each
module of the package. The API reference (docs/api.md, `make docs`) is made from these docstrings.

A pybind11 enum's generated docstring lists its members only; it counts when it says first what the enum
chooses. A pybind11 function's generated docstring is its signature; it counts when text follows it.
The test lists every name that lacks one.

Every field of the option structs that holds a quantity (a number, or a list of numbers) names its unit
in brackets: [m], [kg/m^3], [-] for a pure number; bit flags say `bits`. A choice (an enum), a switch
(a bool), a name, a struct or a list of structs needs a docstring only. The test lists every field that
lacks its unit."""
from __future__ import annotations

import importlib
import inspect
import pkgutil
import re

import vofdem
from vofdem import _core


def own_text(obj, name: str) -> str:
    """The docstring's own text: without the signature lines pybind11 writes for a function, and without
    the member list it writes for an enum."""
    doc = obj.__doc__ if isinstance(getattr(obj, "__doc__", None), str) else ""
    lines = [line for line in doc.strip().splitlines()
             if not line.startswith(name + "(") and line.strip() != "Overloaded function."]
    text = "\n".join(lines).strip()
    if text.startswith("Members:"):  # a pybind11 enum without a doc of its own
        return ""
    return text.split("\n\nMembers:")[0].strip()


def public_modules():
    return [m.name for m in pkgutil.iter_modules(vofdem.__path__) if not m.name.startswith("_")]


def exported_names() -> list[str]:
    """What `import vofdem` offers: its curated __all__ and every public name of the C++ core."""
    return sorted(set(vofdem.__all__) | {n for n in dir(_core) if not n.startswith("_")})


def undocumented_exports() -> list[str]:
    bad = []
    for name in exported_names():
        obj = getattr(vofdem, name)
        if (inspect.isclass(obj) or callable(obj)) and not own_text(obj, name):
            bad.append(f"vofdem.{name}")
    return bad


def undocumented_module_names() -> list[str]:
    bad = []
    for module_name in public_modules():
        module = importlib.import_module(f"vofdem.{module_name}")
        if not own_text(module, module_name):
            bad.append(f"vofdem.{module_name} (the module)")
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
                continue
            if (inspect.isclass(obj) or inspect.isfunction(obj)) and not own_text(obj, name):
                bad.append(f"vofdem.{module_name}.{name}")
    return bad


def test_every_exported_name_has_a_docstring():
    assert len(exported_names()) > 50
    assert undocumented_exports() == []


def test_import_vofdem_offers_a_short_curated_list_and_reaches_the_rest():
    assert vofdem.__all__ == ["Scene", "load_scene", "run_scene", "VOFGrid", "DEMSystem", "Coupler", "set_threads",
                              "__version__"]
    assert vofdem.Scene is importlib.import_module("vofdem.scene").Scene
    assert vofdem.run_scene is importlib.import_module("vofdem.run").run_scene
    assert vofdem.DEMParams is _core.DEMParams  # the rest of the core by name
    assert "DEM_GRAVITY" not in dir(vofdem)
    try:
        vofdem.no_such_name
    except AttributeError as e:
        assert "no attribute 'no_such_name'" in str(e)
    else:
        raise AssertionError("vofdem.no_such_name did not raise AttributeError")


def test_every_public_name_of_every_module_has_a_docstring():
    assert len(public_modules()) > 20
    assert undocumented_module_names() == []


def test_every_bound_class_has_a_docstring():
    classes = [(n, c) for n, c in vars(_core).items() if inspect.isclass(c) and not n.startswith("_")]
    assert len(classes) > 30
    assert [n for n, c in classes if not own_text(c, n)] == []


def test_the_check_sees_a_missing_docstring():
    class Fake:
        def __init__(self, doc):
            self.__doc__ = doc

    assert own_text(Fake("Water level [m]."), "level") == "Water level [m]."
    assert own_text(Fake(None), "level") == ""
    assert own_text(Fake("level(x: float) -> float\n"), "level") == ""  # pybind11's signature alone
    assert own_text(Fake("level(x: float) -> float\n\nWater level [m].\n"), "level") == "Water level [m]."
    assert own_text(Fake("Members:\n\n  SLIP : a\n\n  NO_SLIP : b"), "Wall") == ""  # an enum's members alone
    assert own_text(Fake("Wall condition.\n\nMembers:\n\n  SLIP : a"), "Wall") == "Wall condition."


def undocumented_members() -> list[str]:
    bad = []
    for cname, cls in vars(_core).items():
        if not inspect.isclass(cls) or cname.startswith("_"):
            continue
        enum = hasattr(cls, "__members__")
        for name, member in vars(cls).items():
            if name.startswith("_") or (enum and name in ("name", "value")) or (enum and name in cls.__members__):
                continue
            if not own_text(member, name):
                bad.append(f"{cname}.{name}")
    return bad


def test_every_method_and_property_of_a_bound_class_has_a_docstring():
    assert undocumented_members() == []


# the structs of options (each field one option of a solver)
OPTION_STRUCTS = ["FlowParams", "DEMParams", "CouplerParams", "PorosityParams", "WeirSpec", "Medium"]
# a unit in brackets: [-] or one that starts with a letter ([m], [kg/m^3], [m^2/s], [deg]); not a range
_UNIT = re.compile(r"\[(?:-|[A-Za-z][^\[\],]*)\]")


def is_quantity(value) -> bool:
    """A number (not a bool or an enum member) or a non-empty list of numbers."""
    if isinstance(value, bool) or hasattr(type(value), "__members__"):  # a switch, an enum's member
        return False
    if isinstance(value, (int, float)):
        return True
    if isinstance(value, (list, tuple)):
        return len(value) > 0 and all(is_quantity(v) for v in value)
    return False


def fields_without_unit(classes) -> list[str]:
    """The properties of the (name, class) pairs with no docstring, or holding a quantity by default with
    no unit in brackets (and no `bits`)."""
    bad = []
    for cname, cls in classes:
        obj = cls()
        for name, prop in vars(cls).items():
            if name.startswith("_") or not isinstance(prop, property):
                continue
            doc = own_text(prop, name)
            if not doc:
                bad.append(f"{cname}.{name} (no docstring)")
            elif is_quantity(getattr(obj, name)) and not _UNIT.search(doc) and "bits" not in doc:
                bad.append(f"{cname}.{name}")
    return bad


def test_every_option_field_names_its_unit():
    classes = [(n, getattr(_core, n)) for n in OPTION_STRUCTS]
    assert sum(1 for _, c in classes for p in vars(c).values() if isinstance(p, property)) > 100
    assert fields_without_unit(classes) == []


def test_the_unit_check_sees_a_missing_unit():
    def field(doc, value):
        return property(lambda self: value, doc=doc)

    class Options:
        length = field("flume length [m], default 2.0", 2.0)
        ratio = field("k_t / k_n [-]", 0.3)
        gravity = field("gravity (x, z) [m/s^2]", [0.0, -9.81])
        flags = field("FlowEffect bits", 7)
        on = field("the effect is on", True)
        bare = field("flume length, default 2.0", 2.0)
        ranged = field("restitution, [0, 1]", 0.5)
        listed = field("stage discharges", [1.0, 2.0])
        undocumented = field(None, "disc")

    assert fields_without_unit([("Options", Options)]) == [
        "Options.bare", "Options.ranged", "Options.listed", "Options.undocumented (no docstring)"]
