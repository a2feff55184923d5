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
    with pytest.raises(ValueError, match="'cube' is not one of the registered stone models 'disc', 'polygon'"):
        s.set_model("cube")
