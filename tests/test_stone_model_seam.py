"""The stone-model seam (docs/stone_models.md): outside the models' own files the C++ library never
asks which stone model it holds. A branch on the shape (an enum of shapes, a comparison with a model's
name) anywhere else fails this test, naming the file and line."""
import re
from pathlib import Path

import pytest

import vofdem.scene
from vofdem import _core

ROOT = Path(__file__).resolve().parents[1]
CPP = [p for d in ("cpp/include", "cpp/src", "cpp/bindings") for p in sorted((ROOT / d).rglob("*")) if p.is_file()]
# a model's name compared, a shape enum, or a shape query: the forms a branch on the stone model takes
BRANCH = re.compile(r'\bStoneShape\b|\bkPolygon\b|\bkDisc\b|polygons\(\)|shape\(\)|[=!]=\s*"(disc|polygon)"|'
                    r'"(disc|polygon)"\s*[=!]=|name\(\)\s*[=!]=')
# the models' own files
OWN = {"disc_model", "polygon_model", "polygon", "polygon_contact", "polygon_kernels", "polygon_porosity",
       "polygon_packing", "stone_model"}


def branches(text):
    for k, line in enumerate(text.splitlines(), 1):
        code = line.split("//")[0]
        if BRANCH.search(code):
            yield k, line.strip()


def test_no_branch_on_the_stone_model_outside_the_models():
    found = [f"{p.relative_to(ROOT)}:{k}: {line}" for p in CPP if p.stem not in OWN
             for k, line in branches(p.read_text())]
    assert not found, "branches on the stone model outside its files:\n" + "\n".join(found)


def test_the_search_finds_a_branch():
    text = 'if (shape_ == StoneShape::kPolygon) x();\nif (s.model().name() == "polygon") y();\n// "disc" == x\n'
    assert [k for k, _ in branches(text)] == [1, 2]


def test_the_scene_and_the_binding_take_the_names_from_the_registry():
    names = _core.stone_model_names()
    assert names[:2] == ["disc", "polygon"]
    field = {f.name: f for f in vofdem.scene.Stones.__dataclass_fields__.values()}["shape"]
    assert tuple(field.metadata["choices"]) == tuple(names)
    s = _core.DEMSystem(_core.DEMParams(), 2)
    assert s.shape == "disc"
    s.set_model("polygon")
    assert s.shape == "polygon"
    with pytest.raises(ValueError, match="'cube' is not one of the registered stone models 'disc', 'polygon', 'sphere'"):
        s.set_model("cube")


# the Python front: a model's name compared with the scene's or a system's shape
PY = sorted((ROOT / "python/vofdem").glob("*.py"))
PY_BRANCH = re.compile(r'shape\s*[=!]=\s*["\']|["\']\s*[=!]=\s*\S*shape\b|is_polygon_system')
PY_OWN = {"stone_models", "polygon_output"}


def test_the_python_front_asks_the_model_front_not_the_name():
    found = [f"{p.relative_to(ROOT)}:{k}: {line.strip()}" for p in PY if p.stem not in PY_OWN
             for k, line in enumerate(p.read_text().splitlines(), 1) if PY_BRANCH.search(line.split("#")[0])]
    assert not found, "branches on the stone model in the Python front:\n" + "\n".join(found)
    assert PY_BRANCH.search('if scene.stones.shape == "polygon":') and PY_BRANCH.search("if s.shape != 'disc'")


def test_every_registered_model_has_a_python_front():
    from vofdem import stone_models

    for name in _core.stone_model_names():
        assert stone_models.front(name).name == name
    with pytest.raises(ValueError, match="stones.shape = 'cube' is not one of the stone models with a Python front"):
        stone_models.front("cube")
    with pytest.raises(ValueError, match="not taken"):
        stone_models.register_front(stone_models.StoneFront())
